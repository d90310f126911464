"""TrueShape nesting in an anytime host (the app, ``torsal run --nesting-time``): the rows
at once, the true-shape layout when the background search has found it
(torsal/engine/improve.py)."""

from __future__ import annotations

import numpy as np

from tests.support.io_helpers import random_panels
from tests.support.node_helpers import Source, tree
from torsal.engine.graph import Graph
from torsal.engine.improve import run_improvements
from torsal.engine.solver import OK, Solver
from torsal.engine.types import encode_value
from torsal.nodes.io.cutting import ExportCutSheet
from torsal.nodes.io.formats import cutfiles


def _solver(**settings):  # type: ignore[no-untyped-def]
    graph = Graph()
    graph.add_node(ExportCutSheet(), "cut")
    graph.add_node(Source(tree({(0,): random_panels(24, seed=2)})), "panels")
    graph.connect("panels", "Tree", "cut", "Panels")
    for name, value in {"Nesting": "TrueShape", "TimeBudget": 2.0, **settings}.items():
        graph.set_input_value("cut", name, encode_value(value))
    solver = Solver(graph, anytime=True)
    solver.solve()
    return solver


def _layout(solver):  # type: ignore[no-untyped-def]
    return solver.result("cut").output("Layout").all_items()[0]


def test_the_rows_come_at_once_and_the_true_shape_layout_replaces_them():
    solver = _solver()
    first = _layout(solver)
    assert first.nesting == cutfiles.SHELF and solver.result("cut").state == OK
    assert any("searches in the background" in m.text for m in solver.result("cut").messages)
    assert run_improvements(solver) == ["cut"]
    better = _layout(solver)
    assert better.nesting == cutfiles.TRUE_SHAPE
    assert better.stock_usage > first.stock_usage
    texts = [m.text for m in solver.result("cut").messages]
    assert any(t.startswith("TrueShape nesting: ") and "% of the stock" in t for t in texts), texts
    (preview,) = solver.result("cut").output("Preview").all_items()
    assert preview.layout is better  # the viewport draws the better one


def test_the_same_seed_gives_the_same_final_layout():
    finals = []
    for _ in range(2):
        solver = _solver(Seed=3)
        run_improvements(solver)
        finals.append(_layout(solver))
    a, b = finals
    assert [p.sheet for p in a.parts] == [p.sheet for p in b.parts]
    assert all(np.array_equal(p.outline, q.outline) for p, q in zip(a.parts, b.parts, strict=True))


def test_a_node_that_writes_files_waits_for_its_layout(tmp_path):
    from tests.support.node_helpers import allowed

    graph = Graph()
    graph.add_node(ExportCutSheet(), "cut")
    graph.add_node(Source(tree({(0,): random_panels(8, seed=2)})), "panels")
    graph.connect("panels", "Tree", "cut", "Panels")
    for name, value in {"Nesting": "TrueShape", "TimeBudget": 1.0, "Write": True, "Path": "a.dxf"}.items():
        graph.set_input_value("cut", name, encode_value(value))
    solver = Solver(graph, allowed(tmp_path), anytime=True)
    solver.solve()
    assert solver.improvers() == {}
    assert _layout(solver).nesting in (cutfiles.TRUE_SHAPE, cutfiles.SHELF)
    assert (tmp_path / "a.dxf").exists()
