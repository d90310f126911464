"""RuledSurface.area and area_and_centroid: Gauss rules per rail span, not adaptive cubature.

The lofts every developable node outputs have cubic spline rails (smooth between ruling
parameters) and are linear in v, so their area is a sum of small Gauss rules; the
generic adaptive cubature refines towards every knot and took seconds for a loft of
a hundred rulings.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import simpson

from torsal.nodes.geometry.curves import Circle
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.geometry.surface_base import Surface
from torsal.nodes.geometry.vectors import Plane


def circle_loft(radius: float, height: float, rulings: int, sweep: float = 2 * math.pi) -> RuledSurface:
    """The loft through ``rulings`` vertical rulings of a cylinder (closed when the sweep is 2π)."""
    angle = np.linspace(0.0, sweep, rulings)
    base = np.column_stack([radius * np.cos(angle), radius * np.sin(angle), 0 * angle])
    if sweep == 2 * math.pi:
        base[-1] = base[0]
    return RuledSurface.from_rulings(base, base + np.array([0.0, 0.0, height]))


def test_ruled_cylinder_loft_has_area_2_pi_r_h():
    """How fast, against scipy's Simpson rule in the same run: bench_areas.py."""
    surface = circle_loft(2.0, 3.0, 97)
    assert surface.closed_u
    area, centroid = surface.area_and_centroid()
    # the periodic cubic rails stand in for the circle to ~1e-8 with 96 segments
    assert area == pytest.approx(2 * math.pi * 2.0 * 3.0, rel=1e-6)
    np.testing.assert_allclose(centroid, [0.0, 0.0, 1.5], atol=1e-9)


def test_loft_area_agrees_with_the_adaptive_cubature():
    surface = circle_loft(2.0, 3.0, 13, sweep=1.5)
    exact_loft = Surface.area(surface, rtol=1e-12)  # the generic rule: seconds, but sure
    assert surface.area() == pytest.approx(exact_loft, rel=1e-11)


def twisted_loft() -> RuledSurface:
    """The loft through a hundred rulings that twist along a curved, climbing rail."""
    u = np.linspace(0.0, 4.0, 100)
    starts = np.column_stack([u, np.sin(u), 0.2 * u**2])
    ends = starts + np.column_stack([0.3 * np.cos(2 * u), 1.0 + 0 * u, 1.0 + 0.1 * u])
    return RuledSurface.from_rulings(starts, ends)


def simpson_area(surface: Surface, nu: int, nv: int) -> float:
    """Simpson's rule on an ``nu`` × ``nv`` grid of the surface's own area element."""
    uu, vv = np.meshgrid(np.linspace(0, 1, nu), np.linspace(0, 1, nv), indexing="ij")
    _, su, sv = surface.derivatives(uu.ravel(), vv.ravel(), 1)
    element = np.linalg.norm(np.cross(su, sv), axis=1).reshape(uu.shape)
    return float(simpson(simpson(element, x=vv[0], axis=1), x=uu[:, 0]))


def test_loft_of_a_hundred_twisted_rulings_agrees_with_simpsons_rule_on_a_fine_grid():
    """How fast, against that Simpson rule in the same run: bench_areas.py."""
    surface = twisted_loft()
    assert surface.area() == pytest.approx(simpson_area(surface, 3961, 33), rel=1e-8)


def test_ruled_surface_between_two_circles_is_a_frustum_by_its_breakpoints():
    lower = Circle(Plane.from_normal([0, 0, 0], [0, 0, 1]), 1.0)
    upper = Circle(Plane.from_normal([0, 0, 2], [0, 0, 1]), 3.0)
    area, centroid = RuledSurface(lower, upper).area_and_centroid()
    slant = math.hypot(2.0, 2.0)
    assert area == pytest.approx(math.pi * (1.0 + 3.0) * slant, rel=1e-12)
    # centroid of a frustum's lateral surface: h (r1 + 2 r2) / (3 (r1 + r2))
    np.testing.assert_allclose(centroid, [0.0, 0.0, 2.0 * 7.0 / 12.0], atol=1e-12)


def test_rulings_through_the_axis_make_a_double_cone_whose_kink_is_integrated_exactly():
    """Each ruling joins a point of the lower circle to the opposite point of the upper
    one, so all pass through the axis at v = 1/2: two cones tip to tip, the area element
    vanishes there (a kink in v that a rule across it would smear)."""
    radius, height = 1.0, 2.0
    lower = Circle(Plane.from_normal([0, 0, 0], [0, 0, 1]), radius)
    opposite = Plane([0, 0, height], [-1, 0, 0], [0, -1, 0], [0, 0, 1])
    surface = RuledSurface(lower, Circle(opposite, radius))
    half_slant = math.hypot(radius, height / 2)
    assert surface.area() == pytest.approx(2 * math.pi * radius * half_slant, rel=1e-12)


RULING_CASES = ["generic", "developable kink inside", "kink at an end", "near-cylinder", "flat"]


@pytest.mark.parametrize("case", RULING_CASES)
def test_integrals_along_a_ruling_match_quadrature_across_the_kink(case):
    from scipy.integrate import quad

    from torsal.nodes.geometry.ruled import ruling_integrals

    rng = np.random.default_rng(RULING_CASES.index(case))
    c0 = rng.normal(size=(6, 3))
    c1 = {
        "generic": rng.normal(size=(6, 3)),
        "developable kink inside": -rng.uniform(1.2, 4.0, size=(6, 1)) * c0,  # zero at v = 1/k
        "kink at an end": -c0,  # zero exactly at v = 1
        "near-cylinder": 1e-5 * rng.normal(size=(6, 3)),
        "flat": np.zeros((6, 3)),
    }[case]
    i0, i1 = ruling_integrals(c0, c1)
    for k in range(6):
        def element(v, k=k):
            return float(np.linalg.norm(c0[k] + v * c1[k]))

        cc = float(c1[k] @ c1[k])
        kink = [min(max(-(c0[k] @ c1[k]) / cc, 0.0), 1.0)] if cc > 0 else None
        exact0 = quad(element, 0, 1, points=kink, epsabs=0, epsrel=1e-13, limit=200)[0]
        exact1 = quad(lambda v: v * element(v), 0, 1, points=kink, epsabs=0, epsrel=1e-13, limit=200)[0]
        assert i0[k] == pytest.approx(exact0, rel=1e-12)
        assert i1[k] == pytest.approx(exact1, rel=1e-12)


def test_a_cone_whose_apex_crosses_the_strips_edge_is_integrated_span_by_span(monkeypatch):
    """Rulings t·A(θ) of the cone over the circle A(θ) = (cos θ, sin θ, 1), from t = 1 to
    t = −s(θ), s running from −1/2 to 1/2: for s > 0 each ruling passes the apex, so the
    area element's kink enters the strip halfway round and the integrand in u is only C¹
    there. Area: √2 ∫ (1/2 + sign(s)·s²/2) dθ = π/√2 over the turn, exactly (the s² terms
    cancel by symmetry). No fallback to the generic cubature is allowed."""
    from torsal.nodes.geometry.curves import ParametricCurve

    def circle(u):
        return np.column_stack([np.cos(u), np.sin(u), np.ones_like(u)])

    def far_end(u):
        s = u / (2 * np.pi) - 0.5
        return -s[:, None] * circle(u)

    turn = (0.0, 2 * np.pi)
    surface = RuledSurface(ParametricCurve(circle, turn), ParametricCurve(far_end, turn))

    def no_fallback(*_args, **_kwargs):
        raise AssertionError("fell back to the generic cubature")

    monkeypatch.setattr(Surface, "area_and_centroid", no_fallback)
    area, _ = surface.area_and_centroid()
    assert area == pytest.approx(math.pi * math.sqrt(2), rel=1e-10)


def test_only_rails_whose_derivatives_are_differences_stop_at_their_rounding_noise():
    """Far from the origin an integral of a rail's derivatives stops at their rounding
    noise only where they may be differences of positions (a function of world
    coordinates, differentiated numerically): exact rails (NURBS, a design's parameter
    lines, anything wrapping them) are integrated as at the origin. It once stopped on
    every kind: rationalise-canopy's strips at 1e6 m came out 3.9e-8 of their area off."""
    from torsal.nodes.geometry.curve_rail import CurveRail
    from torsal.nodes.geometry.curves import NurbsCurve, ParametricCurve
    from torsal.nodes.geometry.nurbs_surface import NurbsSurface
    from torsal.nodes.geometry.surface_base import IsoCurve
    from torsal.nodes.geometry.transforms import translation
    from torsal.nodes.geometry.vec_ops import differenced

    nurbs = NurbsCurve(np.array([[0, 0, 0], [1, 2, 0], [3, 1, 1], [4, 0, 0]], float), 3)
    grid = np.stack([*np.meshgrid(np.arange(4.0), np.arange(4.0), indexing="ij"), np.zeros((4, 4))], axis=2)
    design = NurbsSurface.from_points(grid)
    given = ParametricCurve(lambda t: (np.cos(t), np.sin(t), 0 * t), (0.0, 1.0),
                            derivatives=[lambda t: (-np.sin(t), np.cos(t), 0 * t)])
    function = ParametricCurve(lambda t: (np.cos(t), np.sin(t), 0 * t), (0.0, 1.0))
    exact = [nurbs, Circle(Plane.from_normal([0, 0, 0], [0, 0, 1]), 1.0), IsoCurve(design, "u", 0.5), given,
             CurveRail(nurbs, [0.0, 1.0], [0.0, 1.0]), nurbs.reversed(),
             IsoCurve(design, "v", 0.2).transformed(translation([1e6, 0.0, 0.0]))]
    assert [differenced(c) for c in exact] == [False] * len(exact)
    noisy = [function, CurveRail(function, [0.0, 1.0], [0.0, 1.0]), function.reversed()]
    assert [differenced(c) for c in noisy] == [True] * len(noisy)
