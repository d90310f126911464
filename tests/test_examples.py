"""Every shipped example and test fixture: byte-identical round trip, and a clean solve."""

from __future__ import annotations

from pathlib import Path

import pytest

from engine import graphfile
from engine.solver import ERROR, Solver
from nodes.catalogue import default_registry

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = sorted((ROOT / "resources" / "examples").glob("*.graph"))
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
    solver = Solver(graph)
    solver.solve()
    errors = {n: r.messages for n, r in solver.results.items() if r.state == ERROR}
    assert errors == {}
    assert len(solver.results) == len(graph.nodes)


def test_there_are_examples_to_check():
    assert len(EXAMPLES) >= 1
