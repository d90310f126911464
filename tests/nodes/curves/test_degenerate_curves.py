"""A curve that is a single point says so: "CurveA has zero length", naming the input —
never "CurveA is empty: connect a curve" — in every toolbox node that takes curves.

The degenerate curves are made as a user would: a Line node from a point to itself, an
Interpolate node through one point given three times, a Polyline whose vertices all
coincide, and an expression curve that does not move (C(t) = (1, 2, 3)).
"""

from __future__ import annotations

import pytest

from tests.support.direct_graphs import Chain
from torsal.engine.values import Domain, Point, Vector
from torsal.nodes.curves.primitives import Line, Polyline
from torsal.nodes.curves.splines import Interpolate, ParametricCurve
from torsal.nodes.developable.conical import ConicalSurface
from torsal.nodes.developable.cylindrical import CylindricalSurface
from torsal.nodes.developable.parametric_ruled import ParametricRuledSurface
from torsal.nodes.developable.ruling_developable import RulingDevelopable
from torsal.nodes.developable.spline_approximation import SplineApproximation
from torsal.nodes.developable.tangent import TangentDevelopable
from torsal.nodes.surfaces.freeform import Loft

P = Point(1.0, 2.0, 3.0)

MAKERS = {
    "line": lambda chain: (chain.add("degenerate", Line(), Start=P, End=P), "Line"),
    "interpolate": lambda chain: (chain.add("degenerate", Interpolate(), Vertices=[P, P, P]), "Curve"),
    "polyline": lambda chain: (chain.add("degenerate", Polyline(), Vertices=[P, P]), "Polyline"),
    "expression": lambda chain: (
        chain.add("degenerate", ParametricCurve(), X="1", Y="2", Z="3", Domain=Domain(0.0, 1.0)), "Curve"
    ),
}

#: (node, the input the degenerate curve goes to, other inputs wired from a good line)
CONSUMERS = [
    (RulingDevelopable, "CurveA", ["CurveB"]),
    (RulingDevelopable, "CurveB", ["CurveA"]),
    (CylindricalSurface, "Curve", []),
    (ConicalSurface, "Curve", []),
    (TangentDevelopable, "Curve", []),
    (ParametricRuledSurface, "Directrix", []),
]


def _solve(maker: str, node_type, port: str, others: list[str]) -> Chain:
    chain = Chain()
    source, out_port = MAKERS[maker](chain)
    chain.add("good", Line(), Start=Point(0, 5, 0), End=Point(4, 5, 1))
    values = {"Direction": [Vector(0, 0, 1)]} if node_type is ParametricRuledSurface else {}
    chain.add("node", node_type(), **values)
    chain.wire(source, out_port, "node", port)
    for other in others:
        chain.wire("good", "Line", "node", other)
    return chain.solve()


@pytest.mark.parametrize("maker", sorted(MAKERS))
@pytest.mark.parametrize(("node_type", "port", "others"), CONSUMERS,
                         ids=[f"{n.__name__}-{p}" for n, p, _ in CONSUMERS])
def test_a_curve_that_is_one_point_is_named_as_having_zero_length(maker, node_type, port, others):
    chain = _solve(maker, node_type, port, others)
    texts = chain.texts("node")
    assert any(text.startswith(f"{port} has zero length") for text in texts), texts
    assert not any("is empty" in text for text in texts)
    assert chain.result("node").state in ("warning", "error")


def test_the_curve_nodes_warn_and_hand_on_the_zero_length_curve():
    for maker in sorted(MAKERS):
        chain = Chain()
        source, out_port = MAKERS[maker](chain)
        chain.solve()
        (curve,) = chain.items(source, out_port)
        assert curve.length == pytest.approx(0.0, abs=1e-12)
        if maker != "expression":
            assert chain.result(source).state == "warning"
            assert any("zero length" in text for text in chain.texts(source))


def test_spline_approximation_names_its_zero_length_curve():
    chain = Chain()
    chain.add("a", Line(), Start=Point(0, 0, 0), End=Point(4, 0, 0))
    chain.add("b", Line(), Start=Point(0, 2, 1), End=Point(4, 2, -1))
    chain.add("loft", Loft())
    chain.wire("a", "Line", "loft", "Curves")
    chain.wire("b", "Line", "loft", "Curves")
    source, out_port = MAKERS["line"](chain)
    chain.add("node", SplineApproximation())
    chain.wire("loft", "Surface", "node", "Surface")
    chain.wire(source, out_port, "node", "Curve")
    chain.solve()
    assert chain.texts("node") == ["Curve has zero length, so no rulings can be spaced along it"]
