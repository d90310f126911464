"""The ``torsal sweep`` / ``torsal optimise`` command lines: exit codes, messages, ``--json``."""

from __future__ import annotations

import csv
import json

import pytest

from tests.support.explore_graphs import formula_graph
from torsal.app.cli import main


@pytest.fixture
def bowl(tmp_path):
    return formula_graph(tmp_path / "bowl.graph", {"x": (-5, 5, 4), "y": (-5, 5, -3)},
                         {"f": "(x - 1.3)**2 + 2*(y + 0.7)**2"})


def test_a_range_outside_the_sliders_limits_exits_2_naming_them(bowl, tmp_path, capsys):
    out = str(tmp_path / "o")
    code = main(["sweep", str(bowl), "--vary", "x=-6:5:3", "--collect", "f.Result", "--out", out])
    assert code == 2
    assert "-6:5 is outside the limits of slider 'x', -5 to 5" in capsys.readouterr().err


def test_optimise_rejects_an_unknown_output_with_exit_2(bowl, capsys):
    assert main(["optimise", str(bowl), "--vary", "x=-5:5", "--minimise", "f.Nope"]) == 2
    assert "'f' has no output 'Nope' (outputs: Result)" in capsys.readouterr().err


def test_a_grid_step_count_beyond_an_integer_sliders_values_exits_2(tmp_path, capsys):
    path = formula_graph(tmp_path / "n.graph", {"n": (0, 4, 1)}, {"f": "n * 2"}, integers=("n",))
    out = str(tmp_path / "o")
    code = main(["sweep", str(path), "--vary", "n=0:4:9", "--collect", "f.Result", "--out", out])
    assert code == 2
    assert "has only 5 distinct values from 0 to 4: give N up to 5" in capsys.readouterr().err


def test_optimise_json_gives_best_values_objective_and_evaluations(bowl, cluster, capsys):
    code = main(["optimise", str(bowl), "--vary", "x=-5:5", "--vary", "y=-5:5", "--minimise", "f.Result",
                 "--budget", "300", "--seed", "2", "--json", "--scheduler", cluster.scheduler_address])
    assert code == 0
    data = json.loads(capsys.readouterr().out)
    assert set(data["best"]) >= {"values", "objective"} and set(data["best"]["values"]) == {"x", "y"}
    assert data["best"]["values"]["x"] == pytest.approx(1.3, abs=1e-3)
    assert data["best"]["objective"] == pytest.approx(0.0, abs=1e-6)
    assert 0 < data["evaluations"] <= 300 and data["method"] == "cma-es"


def test_sweep_on_the_cluster_writes_the_grid_and_reports_progress(bowl, cluster, tmp_path, capsys):
    code = main(["sweep", str(bowl), "--vary", "x=0:1:2", "--vary", "y=0:1:3", "--collect", "f.Result",
                 "--out", str(tmp_path / "o"), "--scheduler", cluster.scheduler_address])
    assert code == 0
    captured = capsys.readouterr()
    assert "sweep: 6/6" in captured.err and "ETA" in captured.err
    with (tmp_path / "o" / "results.csv").open(newline="") as handle:
        rows = list(csv.reader(handle))
    assert len(rows) == 1 + 6 and rows[0] == ["in:x", "in:y", "out:f.Result", "status"]


def test_the_pareto_front_csv_is_written_for_two_objectives(tmp_path, cluster):
    path = formula_graph(tmp_path / "two.graph", {"x": (-2, 2, 1.5)}, {"f1": "x**2", "f2": "(x - 1)**2"})
    code = main(["optimise", str(path), "--vary", "x=-2:2", "--minimise", "f1.Result", "f2.Result",
                 "--budget", "120", "--out", str(tmp_path / "o"), "--scheduler", cluster.scheduler_address])
    assert code == 0
    with (tmp_path / "o" / "front.csv").open(newline="") as handle:
        rows = list(csv.reader(handle))
    assert rows[0] == ["in:x", "out:f1.Result", "out:f2.Result", "status"]
    assert len(rows) > 5 and all(-0.01 <= float(r[0]) <= 1.01 for r in rows[1:])  # the front is 0 ≤ x ≤ 1


def test_the_torsal_command_starts_its_own_local_workers(bowl, tmp_path):
    import subprocess
    import sys

    out = tmp_path / "o"
    done = subprocess.run(
        [sys.executable, "-m", "torsal.app.cli", "sweep", str(bowl), "--vary", "x=0:1:3",
         "--collect", "f.Result", "--out", str(out), "--workers", "1"],
        capture_output=True, text=True, timeout=180,
    )
    assert done.returncode == 0, done.stderr
    assert "3 variants — 3 solved" in done.stdout
    assert len((out / "results.csv").read_text().splitlines()) == 1 + 3
