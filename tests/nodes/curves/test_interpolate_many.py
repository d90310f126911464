"""Interpolate.solve_many: the vertices of all calls checked as one array, then the very
curves solve makes (the solver's batch of calls, see engine Node.solve_many)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.benchmarks.check_gaps import check_gaps
from tests.support.node_helpers import Source, out, run, tree
from torsal.engine.graph import Graph
from torsal.engine.node import Node
from torsal.engine.values import Point, Vector
from torsal.nodes.curves.splines import FREE_END, Interpolate

RNG = np.random.default_rng(3)


def _rows(calls: int, count: int) -> list[list[Point]]:
    return [[Point(*p) for p in RNG.normal(size=(count, 3)) * 20 + 100] for _ in range(calls)]


def _arrays(curve):
    return [curve.control_points, curve.knots, curve.weights, curve.points, curve.parameters]


def _same_curves(many, alone):
    assert len(many) == len(alone)
    for a, b in zip(many, alone, strict=True):
        assert type(a) is type(b) and a.degree == b.degree and a.closed == b.closed
        assert all(x.dtype == y.dtype and x.tobytes() == y.tobytes()
                   for x, y in zip(_arrays(a), _arrays(b), strict=True))


@pytest.mark.parametrize("count, degree", [(2, 1), (3, 2), (5, 2), (4, 3), (9, 3), (6, 5)])
def test_all_at_once_gives_the_curves_of_the_calls(count, degree):
    rows = _rows(8, count)
    node = Interpolate()
    args = ([degree] * 8, [False] * 8, [FREE_END] * 8, [FREE_END] * 8)
    many = node.solve_many(rows, *args)
    assert many is not None and not node.messages
    _same_curves(many, [node.solve(v, *a) for v, *a in zip(rows, *args, strict=True)])


def _declined(rows, degree=3, closed=False, start=FREE_END, end=FREE_END):
    n = len(rows)
    return Interpolate().solve_many(rows, [degree] * n, [closed] * n, [start] * n, [end] * n) is None


def test_what_solve_would_warn_about_or_make_otherwise_is_left_to_it():
    rows = _rows(3, 4)
    assert not _declined(rows)
    assert _declined(rows, closed=True)
    assert _declined(rows, start=Vector(1, 0, 0))
    assert _declined(rows, end=Vector(0, 0, 1e-14))
    assert _declined(rows, degree=4)  # too few vertices: solve lowers the degree and warns
    assert _declined(rows, degree=0)
    assert _declined(_rows(2, 4) + _rows(1, 5))
    assert _declined([rows[0], [rows[1][0]] * 4, rows[2]])  # one point: solve hands on a line
    assert _declined([rows[0], [rows[1][0], *rows[1][:3]], rows[2]])  # a point twice in a row
    assert _declined([rows[0], [*rows[1][:3], None], rows[2]])
    assert _declined([rows[0], [None] * 4, rows[2]])
    assert _declined([rows[0], [*rows[1][:3], Point(math.inf, 0, 0)], rows[2]])
    assert _declined([[p] for p in rows[0]], degree=1)


def test_a_solve_through_the_graph_matches_the_calls_row_by_row():
    class RowByRow(Interpolate):
        solve_many = Node.solve_many

    rows = _rows(5, 4)
    vertices = tree({(0, i): row for i, row in enumerate(rows)})
    batched, plain = run(Interpolate(), Vertices=vertices), run(RowByRow(), Vertices=vertices)
    assert not batched.messages and not plain.messages
    assert list(out(batched, "Curve")) == [(0, i) for i in range(5)]
    _same_curves([c for b in out(batched, "Curve").values() for c in b],
                 [c for b in out(plain, "Curve").values() for c in b])
    rows[2][2] = rows[2][1]
    vertices = tree({(0, i): row for i, row in enumerate(rows)})
    batched, plain = run(Interpolate(), Vertices=vertices), run(RowByRow(), Vertices=vertices)
    assert batched.messages and [m.text for m in batched.messages] == [m.text for m in plain.messages]
    assert out(batched, "Curve")[(0, 2)] == [None]


def test_the_token_is_checked_before_each_spline():
    graph = Graph()
    graph.add_node(Source(tree({(0, i): row for i, row in enumerate(_rows(20, 5))})), "v")
    graph.add_node(Interpolate(), "curves")
    graph.connect("v", "Tree", "curves", "Vertices")
    assert check_gaps(graph)["curves"].checks >= 20
