"""WarpAngles is the turn of the tangent plane along a ruling, 0 to π, in every node.

On the hyperbolic paraboloid z = xy the ruling x = const from y = −L to y = L is
R ∝ (0, 1, x), with edge tangents (1, 0, ∓L) at its ends, so its end normals are
(∓L, x, −1) and make the angle 2·atan(L/√(1 + x²)): 2·atan(L) along x = 0 — past π/2 for
L > 1 (folded into [0, π/2] it would read π − 2·atan(L)).
The graphs are built as a user would: Range → Expressions → Point and Vector →
ParametricRuledSurface (C(u) = (u, 0, 0), a(u) = (0, 1, u), two-sided to v = ±L), and that
surface with its edge y = −L (a Line node) → SplineApproximation with no rotation.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support.direct_graphs import Chain
from torsal.engine.values import Domain, Point
from torsal.nodes.curves.primitives import Line
from torsal.nodes.developable.parametric_ruled import ParametricRuledSurface
from torsal.nodes.developable.spline_approximation import SplineApproximation
from torsal.nodes.maths.expression import Expression
from torsal.nodes.maths.sequences import Range
from torsal.nodes.params.points import Point as PointNode
from torsal.nodes.params.vectors import Vector as VectorNode

HALF_LENGTHS = [0.5, 1.0, 2.0, 5.0]


def hyperbolic_paraboloid(half: float) -> Chain:
    """z = xy for x in [−1, 1], y in [−L, L], ruled along y, and SplineApproximation on it."""
    chain = Chain()
    chain.add("u", Range(), Domain=Domain(-1.0, 1.0), Steps=16)
    chain.add("point", PointNode(), Y=0.0, Z=0.0)
    chain.add("vector", VectorNode(), X=0.0, Y=1.0)
    for target, axis, formula in (("point", "X", "u"), ("vector", "Z", "u")):
        node_id = f"{target}_{axis}"
        chain.add(node_id, Expression({"expression": formula, "variables": ["u"]}))
        chain.wire("u", "Range", node_id, "u")
        chain.wire(node_id, "Result", target, axis)
    chain.add("prs", ParametricRuledSurface(), VValues=[half], TwoSided=True)
    chain.wire("point", "Point", "prs", "Directrix")
    chain.wire("vector", "Vector", "prs", "Direction")
    chain.add("edge", Line(), Start=Point(-1.0, -half, half), End=Point(1.0, -half, -half))
    chain.add("approx", SplineApproximation(), Segments=12)
    chain.wire("prs", "Surface", "approx", "Surface")
    chain.wire("edge", "Line", "approx", "Curve")
    return chain.solve()


@pytest.fixture(scope="module", params=HALF_LENGTHS, ids=lambda h: f"L={h:g}")
def solved(request) -> tuple[float, Chain]:
    return request.param, hyperbolic_paraboloid(request.param)


def closed_form(chain: Chain, node: str, half: float) -> np.ndarray:
    """2·atan(L/√(1 + x²)) for each output ruling, x read from its start."""
    x = np.array([ruling.start[0] for ruling in chain.items(node, "Rulings")])
    return 2 * np.arctan(half / np.sqrt(1 + x * x))


def test_parametric_ruled_surface_warp_on_the_hyperbolic_paraboloid_is_twice_atan_L(solved):
    half, chain = solved
    warp = np.array(chain.items("prs", "WarpAngles"))
    assert chain.result("prs").state == "ok"
    assert len(warp) == 17
    assert warp[8] == pytest.approx(2 * math.atan(half), abs=1e-12)  # the ruling along x = 0
    np.testing.assert_allclose(warp, closed_form(chain, "prs", half), rtol=0, atol=1e-12)


def test_spline_approximation_warp_on_the_hyperbolic_paraboloid_is_twice_atan_L(solved):
    half, chain = solved
    warp = np.array(chain.items("approx", "WarpAngles"))
    assert chain.result("approx").state == "ok"
    assert len(warp) == 13
    assert warp[6] == pytest.approx(2 * math.atan(half), abs=1e-12)  # the ruling along x = 0
    exact = closed_form(chain, "approx", half)
    np.testing.assert_allclose(warp, exact, rtol=0, atol=1e-12)
    assert chain.item("approx", "Fitness") == pytest.approx(exact.sum(), abs=1e-8)


def test_spline_approximation_normals_make_the_reported_warp(solved):
    _, chain = solved
    n1 = np.array(chain.items("approx", "NormalsA"), dtype=float)
    n2 = np.array(chain.items("approx", "NormalsB"), dtype=float)
    angle = np.arctan2(np.linalg.norm(np.cross(n1, n2), axis=1), np.einsum("ij,ij->i", n1, n2))
    np.testing.assert_allclose(angle, chain.items("approx", "WarpAngles"), rtol=0, atol=1e-12)
