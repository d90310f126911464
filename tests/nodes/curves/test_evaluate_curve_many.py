"""EvaluateCurve.solve_many: every parameter of a curve in one evaluation, with the very
bits of evaluating each alone (the solver's batch of item calls, see engine Node.solve_many)."""

from __future__ import annotations

import numpy as np
import pytest

from tests.benchmarks.check_gaps import check_gaps
from tests.support.node_helpers import Source, out, run, tree
from torsal.engine.graph import Graph
from torsal.engine.node import Node
from torsal.engine.values import Point
from torsal.nodes.curves.analysis import _ROW_BY_ROW, EvaluateCurve
from torsal.nodes.geometry import curves as kernel
from torsal.nodes.geometry.vectors import Plane

RNG = np.random.default_rng(7)
CONTROL = RNG.normal(size=(7, 3)) * 30 + 500.0

CURVES = {
    "nurbs": kernel.NurbsCurve(CONTROL, degree=3),
    "rational": kernel.NurbsCurve(CONTROL, degree=2, weights=RNG.uniform(0.5, 2.0, 7)),
    "periodic": kernel.NurbsCurve(CONTROL, degree=3, periodic=True),
    "domain": kernel.NurbsCurve(CONTROL, degree=3, knots=[0, 0, 0, 0, 2, 3, 5, 9, 9, 9, 9]),
    "interpolated": kernel.InterpolatedCurve(CONTROL, degree=3),
    "interpolated2": kernel.InterpolatedCurve(CONTROL[:3], degree=2),
    "circle": kernel.Circle(Plane.from_axes([3, 1, 2], [1, 1, 0], [0, 1, 1]), radius=4.5),
    "arc": kernel.Arc(radius=2.0, start_angle=0.3, end_angle=2.5),
    "line": kernel.Line([1, 2, 3], [4, -5, 6.5]),
    "polyline": kernel.Polyline(CONTROL),
}
PARAMETERS = [0.0, 1.0, 0.5, 1 / 3, *RNG.uniform(0, 1, 40).tolist()]


def _bits(results):
    return np.array([[*p, *t, k, *kv] for p, t, k, kv in results]).tobytes()


def test_every_kind_taken_is_listed_here():
    kinds = {type(c) for c in CURVES.values()}
    assert kinds == set(_ROW_BY_ROW)


@pytest.mark.parametrize("name", sorted(CURVES))
def test_all_at_once_gives_each_call_its_own_bits(name):
    node, curve = EvaluateCurve(), CURVES[name]
    many = node.solve_many([curve] * len(PARAMETERS), PARAMETERS)
    alone = [node.solve(curve, t) for t in PARAMETERS]
    assert many is not None
    assert _bits(many) == _bits(alone)
    assert all(type(p) is Point and type(k) is float for p, _, k, _ in many)


def test_rows_of_several_curves_are_grouped_and_kept_in_order():
    node = EvaluateCurve()
    curves = [CURVES["circle"], CURVES["line"], CURVES["circle"], CURVES["nurbs"], CURVES["line"]]
    ts = [0.1, 0.2, 0.3, 0.4, 0.5]
    alone = [node.solve(c, t) for c, t in zip(curves, ts, strict=True)]
    assert _bits(node.solve_many(curves, ts)) == _bits(alone)


@pytest.mark.parametrize("curves, ts", [
    ([kernel.TransformedCurve(CURVES["line"], np.diag([2.0, 1.0, 1.0, 1.0])), CURVES["line"]], [0.5, 0.5]),
    ([CURVES["line"]] * 2, [0.5, 1.0 + 1e-13]),  # solve clamps it
    ([CURVES["line"]] * 2, [0.5, 2.0]),  # solve refuses it
    ([CURVES["line"]] * 2, [0.5, 1]),  # an int: solve converts it
    ([CURVES["line"], None], [0.5, 0.5]),
])
def test_what_solve_would_refuse_clamp_or_convert_is_left_to_it(curves, ts):
    assert EvaluateCurve().solve_many(curves, ts) is None


def test_a_solve_through_the_graph_matches_the_calls_row_by_row():
    class RowByRow(EvaluateCurve):
        solve_many = Node.solve_many

    curves = tree({(0,): [CURVES["circle"], CURVES["rational"]]})
    ts = tree({(0,): [0.25, 0.75, 0.5], (1,): [0.0, 1.0, 2.0]})
    batched = run(EvaluateCurve(), Curve=curves, Parameter=ts)
    plain = run(RowByRow(), Curve=curves, Parameter=ts)
    assert plain.messages and [m.text for m in batched.messages] == [m.text for m in plain.messages]
    for port in ("Point", "Tangent", "Curvature", "CurvatureVector"):
        assert out(batched, port) == out(plain, port)
    grafted = run(EvaluateCurve(), modifiers={"Parameter": ["graft"]}, Curve=curves, Parameter=ts)
    assert list(out(grafted, "Point")) == [(0, 0), (0, 1), (0, 2), (1, 0), (1, 1), (1, 2)]


def test_many_parameters_are_evaluated_in_pieces_with_the_token_checked_between():
    graph = Graph()
    graph.add_node(Source(tree({(0,): [CURVES["nurbs"]]})), "curve")
    graph.add_node(Source(tree({(0,): np.linspace(0, 1, 10_000)})), "t")
    graph.add_node(EvaluateCurve(), "eval")
    graph.connect("curve", "Tree", "eval", "Curve")
    graph.connect("t", "Tree", "eval", "Parameter")
    assert check_gaps(graph)["eval"].checks >= 3  # 4,096 at once
