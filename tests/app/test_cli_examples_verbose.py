"""torsal examples, torsal gui --example and torsal run --verbose."""

from __future__ import annotations

from pathlib import Path

from torsal.app.cli import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "torsal" / "resources" / "examples"
FIRST_STEPS = EXAMPLES / "first-steps.graph"


def test_torsal_examples_lists_every_bundled_graph_by_name_and_path(capsys):
    assert main(["examples"]) == 0
    # a line of name and path per example, its description indented on the next
    rows = [line.split() for line in capsys.readouterr().out.splitlines() if not line.startswith(" ")]
    assert [row[0] for row in rows] == sorted(p.stem for p in EXAMPLES.glob("*.graph"))
    assert [Path(row[1]) for row in rows] == sorted(EXAMPLES.glob("*.graph"))


def test_gui_with_an_unknown_example_names_the_examples_there_are(capsys):
    assert main(["gui", "--example", "no-such-roof"]) == 2
    err = capsys.readouterr().err
    assert "there is no example 'no-such-roof'" in err and "first-steps" in err


def test_gui_refuses_a_file_and_an_example_together(capsys):
    assert main(["gui", str(FIRST_STEPS), "--example", "first-steps"]) == 2
    assert "not both" in capsys.readouterr().err


def test_run_verbose_prints_one_timing_line_per_node(capsys):
    assert main(["run", str(FIRST_STEPS), "--verbose"]) == 0
    out = capsys.readouterr().out
    header, *rows = out[out.index("per-node time"):].splitlines()
    assert header.startswith("per-node time (8 nodes")
    assert len(rows) == 8
    assert all(row.split()[1] == "ms" for row in rows)
    times = [float(row.split()[0]) for row in rows]
    assert times == sorted(times, reverse=True)


def test_run_without_verbose_prints_no_timings(capsys):
    assert main(["run", str(FIRST_STEPS)]) == 0
    assert "per-node time" not in capsys.readouterr().out
