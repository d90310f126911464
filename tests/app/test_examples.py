"""Every shipped example and test fixture: byte-identical round trip, and a clean solve."""

from __future__ import annotations

from pathlib import Path

import pytest

from torsal.engine import graphfile
from torsal.engine.solver import ERROR, Solver
from torsal.engine.writes import WriteAccess
from torsal.nodes.catalogue import default_registry

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((ROOT / "torsal" / "resources" / "examples").glob("*.graph"))
FIXTURES = sorted((ROOT / "tests" / "fixtures").glob("*.graph"))
REGISTRY = default_registry(plugins=False)


@pytest.mark.parametrize("path", EXAMPLES + FIXTURES, ids=lambda p: p.name)
def test_graph_file_loads_and_saves_byte_identically(path: Path):
    text = path.read_text(encoding="utf-8")
    graph = graphfile.loads(text, REGISTRY)
    assert graphfile.dumps(graph) == text


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_example_solves_with_no_node_in_error(path: Path):
    graph = graphfile.read_graph(path, REGISTRY)
    solver = Solver(graph, WriteAccess(path.parent))  # files it reads are beside it
    solver.solve()
    errors = {n: r.messages for n, r in solver.results.items() if r.state == ERROR}
    assert errors == {}
    assert len(solver.results) == len(graph.nodes)


def test_there_are_examples_to_check():
    assert len(EXAMPLES) >= 1


@pytest.mark.parametrize("path", EXAMPLES, ids=lambda p: p.name)
def test_example_results_summarise_as_json(path: Path):
    """What ``torsal run FILE --json`` prints: every value summarised (a surface by its
    area, which once sent strips with fans of rulings to the slow generic cubature)."""
    from torsal.app.headless import run_file

    run = run_file(path)
    summary = run.to_json()
    assert set(summary["nodes"]) == set(run.graph.nodes)


def test_kaohsiung_strip_areas_in_the_json_match_a_fine_mesh_of_each_strip():

    from torsal.app.headless import run_file

    run = run_file(ROOT / "torsal" / "resources" / "examples" / "kaohsiung-stadium.graph")
    listed = run.to_json()["nodes"]["strip"]["outputs"]["Surface"]
    areas = [item["area"] for branch in listed.values() for item in branch]
    strips = run.solver.results["strip"].outputs["Surface"].all_items()
    assert len(areas) == len(strips) == 24 + 2 * 2
    # a fine grid in u and v: the strips cross their edge of regression, where a mesh of
    # whole rulings would fold over itself, so v is divided too; u is divided at every
    # ruling, where a rail may turn (at a fan's apex, it stands still between rulings), so
    # the mesh converges as h²
    for index in (0, 6, 9, 14, 27):
        spans = len(strips[index].ruling_lines) - 1
        mesh = strips[index].to_mesh(spans * (2048 // spans) + 1, 257)
        assert areas[index] == pytest.approx(float(mesh.area), rel=1e-6)
