"""``torsal run --set CLUSTER/ID=VALUE`` as a CI user runs it: a slider inside a cluster's
definition is reached through an instance's id (or the definition's), and, the definition
being shared, every instance gets the value.

Expected values are first-steps' closed forms: ``total = width · count``, and ``count``
heights ``2.5 + wave · sin(2π · width · i / 6)``.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

from torsal.app.cli import main
from torsal.engine.cluster_edits import add_cluster_instance, make_cluster
from torsal.engine.graphfile import read_graph, write_graph
from torsal.nodes.catalogue import default_registry

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "torsal" / "resources" / "examples" / "first-steps.graph"
WIDTH, COUNT, WAVE = 1.2, 12, 0.5  # first-steps' slider values


@pytest.fixture(scope="module")
def two_instances(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """first-steps with width, count and the three computing nodes in a cluster ``panels``
    (definition ``panel_row``), and a second instance ``panels2`` whose total feeds
    ``show_total2``."""
    registry = default_registry()
    graph = read_graph(EXAMPLE, registry)
    make_cluster(graph, ["width", "count", "edges", "total", "heights"], name="Panels", node_id="panels",
                       definition_id="panel_row")
    total_port = next(w.source_port for w in graph.wires_into("show_total"))
    add_cluster_instance(graph, "panel_row", "panels2", position=(300.0, 400.0))
    graph.add_node(registry.create("params.Panel"), "show_total2", position=(600.0, 400.0))
    graph.connect("wave", "Value", "panels2", "a")
    graph.connect("panels2", total_port, "show_total2", "Input")
    path = tmp_path_factory.mktemp("clusters") / "two-instances.graph"
    write_graph(graph, path)
    return path


def run(capsys: pytest.CaptureFixture[str], path: Path, *sets: str) -> tuple[int, dict, str]:
    code = main(["run", str(path), "--json", *(a for s in sets for a in ("--set", s))])
    captured = capsys.readouterr()
    return code, json.loads(captured.out) if code != 2 else {}, captured.err


def single(data: dict, node_id: str, port: str = "Output") -> list:
    (items,) = data["nodes"][node_id]["outputs"][port].values()
    return items


def test_set_through_an_instance_reaches_a_slider_in_its_definition(two_instances, capsys):
    code, data, _ = run(capsys, two_instances, "panels/count=4")
    assert code == 0
    assert single(data, "show_total") == [pytest.approx(WIDTH * 4)]
    heights = single(data, "show_heights")
    assert heights == pytest.approx([2.5 + WAVE * math.sin(2 * math.pi * WIDTH * i / 6) for i in range(4)])


def test_set_inside_a_definition_changes_every_instance_of_it(two_instances, capsys):
    _, data, _ = run(capsys, two_instances, "panels/width=2")
    assert single(data, "show_total2") == [pytest.approx(2.0 * COUNT)]


def test_set_inside_a_shared_definition_says_so_on_stderr(two_instances, capsys):
    _, _, err = run(capsys, two_instances, "panels/width=2")
    assert "panel_row" in err and "panels, panels2" in err and "all of them" in err


def test_set_by_the_definitions_id_reaches_the_same_slider(two_instances, capsys):
    _, data, _ = run(capsys, two_instances, "panel_row/count=5")
    assert single(data, "show_total") == [pytest.approx(WIDTH * 5)]
    assert single(data, "show_total2") == [pytest.approx(WIDTH * 5)]


def test_set_of_an_inner_input_reaches_it(two_instances, capsys):
    _, data, _ = run(capsys, two_instances, "panels/edges.Start=100")
    assert single(data, "show_heights")[0] == pytest.approx(2.5 + WAVE * math.sin(2 * math.pi * 100 / 6))


def test_two_instances_given_different_values_for_one_slider_exit_2(two_instances, capsys):
    code, _, err = run(capsys, two_instances, "panels/count=4", "panels2/count=5")
    assert code == 2
    assert "same node 'count'" in err and "every instance shares" in err


@pytest.mark.parametrize(("assignment", "needle"), [
    ("panels/nothing=1", "cluster definition 'panel_row' (Panels) has no node 'nothing'"),
    ("show_total/count=1", "no cluster or cluster definition 'show_total' at the top level"),
    ("nowhere/count=1", "no cluster or cluster definition 'nowhere'"),
])
def test_a_path_that_reaches_nothing_exits_2_naming_it(two_instances, capsys, assignment, needle):
    code, _, err = run(capsys, two_instances, assignment)
    assert code == 2
    assert needle in err and "Traceback" not in err


def test_the_help_tells_how_to_reach_a_slider_in_a_cluster():
    done = subprocess.run([sys.executable, "-m", "torsal.app.cli", "run", "--help"], capture_output=True,
                          text=True, cwd=ROOT, check=True, timeout=60)
    assert "CLUSTER/ID=VALUE" in " ".join(done.stdout.split())


def test_the_command_sets_a_slider_in_a_cluster_as_a_ci_user_would(two_instances):
    command = [sys.executable, "-m", "torsal.app.cli", "run", str(two_instances), "--set", "panels/count=3",
               "--json"]
    done = subprocess.run(command, capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert done.returncode == 0, done.stderr
    assert single(json.loads(done.stdout), "show_total2") == [pytest.approx(WIDTH * 3)]
