"""NURBS surfaces, grid interpolation and lofts; hypothesis property tests."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st
from scipy.interpolate import BSpline

from torsal.nodes.geometry.nurbs_surface import (
    Loft,
    NurbsSurface,
    SpanBasis,
    basis_functions,
    clamped_knots,
    find_spans,
)
from torsal.nodes.geometry.parametric_surface import ParametricSurface, cylinder

SQRT_HALF = np.sqrt(0.5)


def quarter_cylinder(radius=2.0, height=3.0):
    """Exact rational quadratic × linear quarter cylinder around z."""
    arc = np.array([[radius, 0, 0], [radius, radius, 0], [0, radius, 0]], dtype=float)
    control = np.stack([arc, arc + np.array([0, 0, height])], axis=1)  # (3, 2, 3)
    weights = np.array([[1, 1], [SQRT_HALF, SQRT_HALF], [1, 1]])
    return NurbsSurface(control, 2, 1, weights=weights)


# ---------------------------------------------------------------- exact shapes


def test_rational_quarter_cylinder_has_exact_radius_at_ten_thousand_parameters():
    surface = quarter_cylinder(2.0)
    rng = np.random.default_rng(0)
    pts = surface.point_at(rng.random(10_000), rng.random(10_000))
    assert np.abs(np.hypot(pts[:, 0], pts[:, 1]) - 2.0).max() < 1e-12
    assert surface.is_rational


def test_rational_cylinder_curvature_is_exactly_minus_one_over_radius():
    surface = quarter_cylinder(2.0)
    u = np.linspace(0, 1, 21)
    curv = surface.curvature(u, 0.4)
    # Su (along the arc, counter-clockwise) × Sv (+z) points outwards: k = −1/r across.
    np.testing.assert_allclose(curv.k1, 0.0, atol=1e-12)
    np.testing.assert_allclose(curv.k2, -0.5, rtol=1e-12)
    np.testing.assert_allclose(np.abs(curv.direction1[:, 2]), 1.0, rtol=1e-12)
    np.testing.assert_allclose(curv.gaussian, 0.0, atol=1e-12)


def test_bilinear_patch_evaluates_as_the_docstring_says():
    grid = np.array([[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]], float)
    np.testing.assert_allclose(NurbsSurface(grid, 1, 1).point_at(0.5, 0.5), [0.5, 0.5, 0.25])


def test_grid_interpolation_passes_through_every_point():
    rng = np.random.default_rng(4)
    x, y = np.meshgrid(np.linspace(0, 5, 9), np.linspace(0, 3, 6), indexing="ij")
    grid = np.stack([x, y, np.sin(x) * np.cos(y) + 0.1 * rng.normal(size=x.shape)], axis=2)
    for du, dv in [(3, 3), (2, 3), (1, 2), (5, 5)]:
        surface = NurbsSurface.from_points(grid, du, dv)
        from torsal.nodes.geometry.nurbs_surface import chord_parameters

        pu, pv = chord_parameters(grid, 0), chord_parameters(grid, 1)
        uu, vv = np.meshgrid(pu, pv, indexing="ij")
        np.testing.assert_allclose(surface.point_at(uu.ravel(), vv.ravel()), grid.reshape(-1, 3), atol=1e-12)
        assert surface.degree_u == min(du, 8) and surface.degree_v == min(dv, 5)


def test_grid_interpolation_with_given_parameters_reproduces_a_cubic_patch_exactly():
    s = np.linspace(0, 1, 6)
    uu, vv = np.meshgrid(s, s, indexing="ij")
    grid = np.stack([uu, vv, uu**3 - 2 * uu * vv**2 + vv**3], axis=2)
    surface = NurbsSurface.from_points(grid, 3, 3, u_params=s, v_params=s)
    rng = np.random.default_rng(1)
    u, v = rng.random(200), rng.random(200)
    np.testing.assert_allclose(
        surface.point_at(u, v), np.column_stack([u, v, u**3 - 2 * u * v**2 + v**3]), atol=1e-13
    )


def test_loft_through_circles_reproduces_the_cylinder():
    circles = [cylinder(1.5, 4.0).isocurve("u", h) for h in (0.0, 0.3, 0.7, 1.0)]
    loft = Loft(circles)
    np.testing.assert_allclose(loft.curve_parameters, [0.0, 0.3, 0.7, 1.0], atol=1e-15)
    rng = np.random.default_rng(2)
    pts = loft.point_at(rng.random(5000), rng.random(5000))
    assert np.abs(np.hypot(pts[:, 0], pts[:, 1]) - 1.5).max() < 1e-7
    t = np.linspace(0, 1, 97)
    np.testing.assert_allclose(loft.isocurve("u", 0.3).point_at(t), circles[1].point_at(t), atol=2e-7)
    assert loft.closed_u and not loft.closed_v


def test_loft_of_two_curves_is_ruled():
    a = cylinder(1.0, 1.0).isocurve("u", 0.0)
    b = cylinder(2.0, 1.0).isocurve("u", 1.0)
    loft = Loft([a, b])
    assert loft.degree_v == 1 and loft.ruling_direction == "v"


def test_nurbs_rejects_bad_definitions():
    grid = np.zeros((3, 3, 3))
    with pytest.raises(ValueError, match="too few"):
        NurbsSurface(grid, 3, 1)
    with pytest.raises(ValueError, match="knots given"):
        NurbsSurface(grid, 2, 2, knots_u=[0, 0, 1, 1])
    with pytest.raises(ValueError, match="positive"):
        NurbsSurface(grid, 2, 2, weights=-np.ones((3, 3)))
    with pytest.raises(ValueError, match="non-decreasing"):
        NurbsSurface(grid, 1, 1, knots_u=[0, 0.5, 0.2, 1, 1])
    with pytest.raises(ValueError, match="order 2"):
        NurbsSurface(np.random.rand(4, 4, 3), 3, 3).derivatives(0.5, 0.5, 3)


# ---------------------------------------------------------------- basis


@pytest.mark.parametrize("degree", [1, 2, 3, 5])
def test_basis_matches_scipy_and_sums_to_one(degree):
    knots = np.array([0.0] * (degree + 1) + [0.2, 0.2, 0.5, 0.7] + [1.0] * (degree + 1))
    count = len(knots) - degree - 1
    x = np.linspace(0, 1, 301)
    spans = find_spans(knots, degree, count, x)
    values = basis_functions(knots, degree, spans, x, 2)
    np.testing.assert_allclose(values[0].sum(axis=1), 1.0, atol=1e-14)
    np.testing.assert_allclose(values[1].sum(axis=1), 0.0, atol=1e-10)
    dense = BSpline.design_matrix(x, knots, degree).toarray()
    rows = np.arange(len(x))[:, None]
    cols = spans[:, None] - degree + np.arange(degree + 1)
    np.testing.assert_allclose(dense[rows, cols], values[0], atol=1e-14)
    first, fast = SpanBasis(knots, degree, count).evaluate(x, 2)
    np.testing.assert_array_equal(first, spans - degree)
    scale = np.maximum(np.abs(values).max(axis=(1, 2)), 1.0)[:, None, None]
    np.testing.assert_allclose(fast / scale, values / scale, atol=1e-11)


# ---------------------------------------------------------------- property tests


@st.composite
def nurbs_surfaces(draw):
    def knot_vector(count, degree):
        inner = sorted(
            draw(st.lists(st.floats(0.05, 0.95), min_size=count - degree - 1, max_size=count - degree - 1))
        )
        lo = draw(st.floats(-5, 5))
        length = draw(st.floats(0.5, 20))
        knots = np.array([0.0] * (degree + 1) + inner + [1.0] * (degree + 1))
        return lo + length * knots

    du, dv = draw(st.integers(1, 4)), draw(st.integers(1, 4))
    nu, nv = du + draw(st.integers(1, 4)), dv + draw(st.integers(1, 4))
    seed = draw(st.integers(0, 2**32 - 1))
    rng = np.random.default_rng(seed)
    x, y = np.meshgrid(np.linspace(0, 3, nu), np.linspace(0, 2, nv), indexing="ij")
    control = np.stack([x, y, np.zeros_like(x)], axis=2) + rng.normal(scale=0.3, size=(nu, nv, 3))
    weights = rng.uniform(0.5, 2.0, size=(nu, nv)) if draw(st.booleans()) else None
    ku, kv = knot_vector(nu, du), knot_vector(nv, dv)
    assume(np.min(np.diff(np.unique((ku - ku[0]) / (ku[-1] - ku[0])))) > 0.02)
    assume(np.min(np.diff(np.unique((kv - kv[0]) / (kv[-1] - kv[0])))) > 0.02)
    return NurbsSurface(control, du, dv, ku, kv, weights), rng


def away_from_knots(knots, x, gap):
    return np.all(np.abs(x[:, None] - knots[None, 1:-1]) > gap, axis=1)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(nurbs_surfaces())
def test_nurbs_derivatives_agree_with_finite_differences(case):
    surface, rng = case
    u, v = rng.uniform(0.02, 0.98, 40), rng.uniform(0.02, 0.98, 40)
    keep = away_from_knots(surface.knots_u, u, 0.005) & away_from_knots(surface.knots_v, v, 0.005)
    u, v = u[keep], v[keep]
    assume(len(u) > 0)
    s, su, sv, suu, suv, svv = surface.derivatives(u, v, 2)
    h = 1e-4

    def p(du, dv):
        return surface.point_at(u + du, v + dv)

    # Fourth-order central differences.
    fd_su = (p(-2 * h, 0) - 8 * p(-h, 0) + 8 * p(h, 0) - p(2 * h, 0)) / (12 * h)
    fd_sv = (p(0, -2 * h) - 8 * p(0, -h) + 8 * p(0, h) - p(0, 2 * h)) / (12 * h)
    g = 1e-3
    fd_suu = (-p(-2 * g, 0) + 16 * p(-g, 0) - 30 * s + 16 * p(g, 0) - p(2 * g, 0)) / (12 * g * g)
    fd_svv = (-p(0, -2 * g) + 16 * p(0, -g) - 30 * s + 16 * p(0, g) - p(0, 2 * g)) / (12 * g * g)

    def corners(k):
        return (p(k, k) - p(k, -k) - p(-k, k) + p(-k, -k)) / (4 * k * k)

    fd_suv = (4 * corners(g) - corners(2 * g)) / 3  # Richardson: O(g⁴)
    scale1 = max(np.abs(su).max(), np.abs(sv).max(), 1.0)
    scale2 = max(np.abs(suu).max(), np.abs(svv).max(), np.abs(suv).max(), 1.0)
    np.testing.assert_allclose(su, fd_su, atol=1e-6 * scale1)
    np.testing.assert_allclose(sv, fd_sv, atol=1e-6 * scale1)
    np.testing.assert_allclose(suu, fd_suu, atol=1e-4 * scale2)
    np.testing.assert_allclose(svv, fd_svv, atol=1e-4 * scale2)
    np.testing.assert_allclose(suv, fd_suv, atol=1e-4 * scale2)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(nurbs_surfaces(), st.floats(-100, 100), st.floats(0.01, 100))
def test_affine_knot_reparameterisation_preserves_geometry(case, shift, scale):
    surface, rng = case
    moved = NurbsSurface(
        surface.control_points,
        surface.degree_u,
        surface.degree_v,
        shift + scale * surface.knots_u,
        surface.knots_v * scale - shift,
        surface.weights,
    )
    u, v = rng.random(50), rng.random(50)
    np.testing.assert_allclose(moved.point_at(u, v), surface.point_at(u, v), atol=1e-11)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(nurbs_surfaces())
def test_reversing_u_maps_the_surface_onto_itself(case):
    surface, rng = case
    reversed_u = NurbsSurface(
        surface.control_points[::-1],
        surface.degree_u,
        surface.degree_v,
        1.0 - surface.knots_u[::-1],
        surface.knots_v,
        surface.weights[::-1],
    )
    u, v = rng.random(50), rng.random(50)
    np.testing.assert_allclose(reversed_u.point_at(1.0 - u, v), surface.point_at(u, v), atol=1e-11)


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(nurbs_surfaces(), st.floats(-10, 10), st.floats(0.1, 30), st.floats(-10, 10), st.floats(0.1, 30))
def test_curvature_is_invariant_under_reparameterisation_to_any_domain(case, a, la, c, lc):
    surface, rng = case
    assume(surface.degree_u >= 3 and surface.degree_v >= 3)  # C² for finite differences

    def through(x, y):  # the same surface, parameterised on [a, a+la] × [c, c+lc]
        return surface.point_at((x - a) / la, (y - c) / lc)

    expression = ParametricSurface(through, (a, a + la), (c, c + lc))
    u, v = rng.uniform(0.05, 0.95, 20), rng.uniform(0.05, 0.95, 20)
    # The difference stencils (reach ≤ 0.006) must not straddle a knot, where S''' jumps.
    keep = away_from_knots(surface.knots_u, u, 0.008) & away_from_knots(surface.knots_v, v, 0.008)
    u, v = u[keep], v[keep]
    assume(len(u) > 0)
    exact = surface.curvature(u, v)
    approx = expression.curvature(u, v)
    scale = np.maximum(np.abs(exact.k1), np.abs(exact.k2)).max() + 1e-3
    np.testing.assert_allclose(approx.k1, exact.k1, atol=1e-6 * scale)
    np.testing.assert_allclose(approx.k2, exact.k2, atol=1e-6 * scale)
    np.testing.assert_allclose(approx.gaussian, exact.gaussian, atol=1e-6 * scale**2)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.filter_too_much])
@given(nurbs_surfaces())
def test_point_fast_path_matches_the_basis_matrix_path(case):
    surface, rng = case
    u = np.concatenate([rng.random(200), [0.0, 1.0, -0.01, 1.01], surface.knots_u])
    v = np.concatenate([rng.random(200), [1.0, 0.0, 1.01, -0.01], rng.random(len(surface.knots_u))])
    fast = surface.point_at(u, v)  # power-form patches
    reference = surface.derivatives(u, v, 1)[0]  # sparse basis matrices
    np.testing.assert_allclose(fast, reference, atol=1e-12 * max(1.0, np.abs(reference).max()))


def test_span_lookup_agrees_with_binary_search_at_and_between_knots():
    knots = np.array([0, 0, 0, 0, 0.1, 0.1, 0.35, 0.36, 0.9, 1, 1, 1, 1], dtype=float)
    basis = SpanBasis(knots, 3, len(knots) - 4)
    x = np.concatenate([np.linspace(-0.1, 1.1, 10007), np.unique(knots), np.nextafter(np.unique(knots), 0)])
    span, _ = basis.locate(x)
    np.testing.assert_array_equal(span, np.searchsorted(basis.breaks[1:-1], x, side="right"))


def test_clamped_knots_are_uniform_and_clamped():
    np.testing.assert_allclose(clamped_knots(5, 2), [0, 0, 0, 1 / 3, 2 / 3, 1, 1, 1])
