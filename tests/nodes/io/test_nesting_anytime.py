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


def test_each_better_layout_is_published_as_the_search_finds_it():
    """The search publishes every layout that takes less stock than the last one shown (the
    strip of every part cut into sheets, as sparrow shortens it) before its final one: the
    usages rise, the ones on the way say so, and every one keeps its gap (shapely)."""
    import itertools

    import shapely

    solver = _solver(TimeBudget=3.0)
    rows = _layout(solver).stock_usage
    (improver,) = solver.improvers().values()
    published = []
    improver(lambda: False, lambda values, remarks: published.append((values[1], remarks)), lambda f: None)
    usages = [layout.stock_usage for layout, _ in published]
    assert len(published) >= 2, usages
    assert usages[0] > rows and all(b >= a for a, b in itertools.pairwise(usages))
    assert all("searching" in remarks[0] for _, remarks in published[:-1])
    assert published[-1][1][0].startswith("TrueShape nesting: ")
    for layout, _ in published:
        for sheet in range(layout.sheets):
            cuts = [shapely.Polygon(p.outline) for p in layout.parts if p.sheet == sheet]
            gaps = [a.distance(b) for a, b in itertools.combinations(cuts, 2)]
            assert min(gaps, default=10.0) >= 10.0 - 1e-6
