"""NURBS curves: exact conics, rational evaluation, knots, validation and properties."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from torsal.nodes.geometry.curves import Arc, Circle, NurbsCurve
from torsal.nodes.geometry.transforms import apply_transform, rotation, translation
from torsal.nodes.geometry.vectors import WORLD_XY, Plane

T = np.linspace(0.0, 1.0, 10_000)
TILTED = Plane.from_axes([1.0, -2.0, 0.5], [1, 1, 0], [0, 1, 1])


def random_curve(
    seed: int, rational: bool = True, periodic: bool = False, domain: tuple[float, float] = (0, 1)
) -> NurbsCurve:
    """A random NURBS curve with knot spans of comparable width (no span under 1/5 of another)."""
    rng = np.random.default_rng(seed)
    degree = int(rng.integers(1, 6))
    count = int(rng.integers(degree + 1, degree + 8))
    points = rng.uniform(-10, 10, (count, 3))
    weights = rng.uniform(0.3, 3.0, count) if rational else None
    a, b = domain
    if periodic:
        breaks = np.cumsum(np.concatenate([[0], rng.uniform(0.2, 1.0, count)]))
        knots = a + (b - a) * (breaks / breaks[-1])
    else:
        spans = np.cumsum(np.concatenate([[0], rng.uniform(0.2, 1.0, count - degree)]))
        inner = a + (b - a) * (spans[1:-1] / spans[-1])
        knots = np.concatenate([[a] * (degree + 1), inner, [b] * (degree + 1)])
    return NurbsCurve(points, degree, knots, weights, periodic)


def span_midpoints(curve: NurbsCurve) -> tuple[np.ndarray, np.ndarray]:
    breaks = curve._breakpoints()
    return 0.5 * (breaks[:-1] + breaks[1:]), np.diff(breaks)


# -- circles and arcs -------------------------------------------------------------------


@pytest.mark.parametrize("plane", [WORLD_XY, TILTED])
@pytest.mark.parametrize("radius", [1e-3, 1.0, 2.5, 1e4])
def test_nurbs_circle_radius_error_below_1e_12(plane, radius):
    points = Circle(plane, radius).point_at(T)
    error = np.abs(np.linalg.norm(points - plane.origin, axis=1) - radius) / radius
    assert error.max() < 1e-12
    assert np.abs(plane.signed_distance(points)).max() < 1e-12 * max(radius, 1)


def test_circle_is_closed_and_starts_on_plane_x_axis():
    circle = Circle(TILTED, 2.0)
    assert circle.closed
    assert np.allclose(circle.start, TILTED.origin + 2.0 * TILTED.x, atol=1e-15)
    assert np.allclose(circle.start, circle.end, atol=1e-15)


def test_circle_curvature_is_one_over_radius_within_1e_12():
    kappa = Circle(TILTED, 2.5).curvature_at(T)
    assert np.abs(kappa * 2.5 - 1).max() < 1e-12


def test_circle_tangent_is_perpendicular_to_radius_and_turns_counter_clockwise():
    circle = Circle(WORLD_XY, 3.0)
    p, d = circle.derivatives(T, 1)
    assert np.abs(np.einsum("ij,ij->i", p, d)).max() < 1e-12 * np.abs(d).max()
    assert np.all(np.cross(p, d)[:, 2] > 0)


def test_circle_length_by_quadrature_is_2_pi_r_within_1e_12():
    circle = Circle(TILTED, 2.5)
    assert circle.length == 2 * math.pi * 2.5
    assert abs(circle._length_table.total / (5 * math.pi) - 1) < 1e-12


@pytest.mark.parametrize("sweep", [0.1, math.pi / 2, 2.0, math.pi, 5.0, 2 * math.pi])
def test_arc_ends_at_its_angles_and_stays_on_the_circle(sweep):
    arc = Arc(TILTED, 1.5, start_angle=0.3, end_angle=0.3 + sweep)
    expected_end = TILTED.point_at(1.5 * math.cos(0.3 + sweep), 1.5 * math.sin(0.3 + sweep))
    assert np.allclose(arc.start, TILTED.point_at(1.5 * math.cos(0.3), 1.5 * math.sin(0.3)))
    assert np.allclose(arc.end, expected_end, atol=1e-14)
    radius = np.linalg.norm(arc.point_at(T) - TILTED.origin, axis=1)
    assert np.abs(radius / 1.5 - 1).max() < 1e-12
    assert abs(arc._length_table.total / (1.5 * sweep) - 1) < 1e-12


def test_arc_of_more_than_90_degrees_uses_one_segment_per_quarter():
    assert len(Arc(WORLD_XY, 1.0, 0.0, 3.0).control_points) == 2 * 2 + 1
    assert len(Arc(WORLD_XY, 1.0, 0.0, math.pi / 2).control_points) == 3


def test_arc_through_three_points_passes_through_the_middle_one():
    a, b, c = np.array([3.0, 0, 1]), np.array([0.0, 2, 1]), np.array([-1.0, -1, 1])
    arc = Arc.from_three_points(a, b, c)
    assert np.allclose(arc.start, a, atol=1e-14)
    assert np.allclose(arc.end, c, atol=1e-14)
    assert arc.closest_point(b).distances[0] < 1e-12
    # b comes before c along the arc
    assert arc.closest_point(b).parameters[0] < 1.0


def test_circle_through_three_points_has_the_circumradius():
    # right triangle: circumcentre at the hypotenuse midpoint
    circle = Circle.from_three_points([0, 0, 0], [4, 0, 0], [0, 3, 0])
    assert math.isclose(circle.radius, 2.5, rel_tol=1e-15)
    assert np.allclose(circle.centre, [2, 1.5, 0])


def test_collinear_points_make_no_circle():
    with pytest.raises(ValueError, match="on one line"):
        Circle.from_three_points([0, 0, 0], [1, 1, 1], [2, 2, 2])


@pytest.mark.parametrize("bad", [0.0, -1.0, float("nan")])
def test_circle_radius_must_be_positive(bad):
    with pytest.raises(ValueError, match="positive"):
        Circle(WORLD_XY, bad)


def test_arc_sweep_must_be_positive():
    with pytest.raises(ValueError, match="sweep"):
        Arc(WORLD_XY, 1.0, 1.0, 1.0)


# -- evaluation against closed forms ----------------------------------------------------------


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(1, 7))
def test_rational_bezier_matches_bernstein_formula_within_1e_12(seed, degree):
    rng = np.random.default_rng(seed)
    points = rng.uniform(-5, 5, (degree + 1, 3))
    weights = rng.uniform(0.2, 5.0, degree + 1)
    t = np.linspace(0, 1, 101)
    basis = np.stack([math.comb(degree, i) * t**i * (1 - t) ** (degree - i) for i in range(degree + 1)], 1)
    expected = (basis * weights) @ points / (basis @ weights)[:, None]
    curve = NurbsCurve(points, degree, weights=weights)
    assert np.abs(curve.point_at(t) - expected).max() < 1e-12 * 5


def test_clamped_curve_interpolates_its_end_control_points():
    curve = random_curve(3)
    assert np.allclose(curve.start, curve.control_points[0], atol=1e-13)
    assert np.allclose(curve.end, curve.control_points[-1], atol=1e-13)


def test_derivatives_above_the_degree_of_a_polynomial_curve_are_zero():
    curve = NurbsCurve([[0, 0], [1, 2], [3, 3]], degree=2)
    assert np.all(curve.derivatives(np.array([0.2, 0.7]), 3)[3] == 0)


def test_periodic_square_of_degree_one_visits_its_corners():
    square = NurbsCurve([[0, 0], [1, 0], [1, 1], [0, 1]], degree=1, periodic=True)
    corners = square.point_at(np.array([0, 0.25, 0.5, 0.75, 1.0]))
    assert corners[:, :2].tolist() == [[0, 0], [1, 0], [1, 1], [0, 1], [0, 0]]
    assert square.closed


@pytest.mark.parametrize("seed", range(6))
def test_periodic_curve_is_smooth_across_its_seam_to_order_degree_minus_1(seed):
    curve = random_curve(seed, periodic=True)
    # a non-periodic copy evaluates t = 1 from the left instead of wrapping it to t = 0
    copy = NurbsCurve.from_arrays(curve.control_points, curve.knots, curve.degree, curve.weights)
    start = copy.derivatives(0.0, curve.degree - 1)
    end = copy.derivatives(1.0, curve.degree - 1)
    for k, (a, b) in enumerate(zip(start, end, strict=True)):
        assert np.allclose(a, b, rtol=1e-10, atol=1e-9 * (1 + np.abs(a).max())), k


def test_rhino_knot_convention_gives_the_same_curve():
    full = random_curve(11, rational=True)
    rhino = NurbsCurve(full.control_points, full.degree, full.knots[1:-1], full.weights)
    assert np.array_equal(rhino.point_at(T[::50]), full.point_at(T[::50]))


# -- validation ------------------------------------------------------------------------


def test_too_few_control_points_for_the_degree_is_a_plain_error():
    with pytest.raises(ValueError, match="degree-3 curve needs at least 4 control points; got 3"):
        NurbsCurve([[0, 0], [1, 1], [2, 0]], degree=3)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"degree": 0}, "degree must be a whole number"),
        ({"knots": [0, 0, 1, 1]}, "needs 8 knots; got 4"),
        ({"knots": [0, 0, 0, 1, 0.5, 1, 1, 1]}, "non-decreasing"),
        ({"knots": [0, 0, 0, 0, 0, 0, 0, 0]}, "domain is empty"),
        ({"weights": [1, 0, 1, 1, 1]}, "positive"),
        ({"weights": [1, 1]}, "Expected 5 weights"),
    ],
)
def test_invalid_nurbs_input_is_rejected_with_a_plain_message(kwargs, message):
    points = [[0, 0], [1, 1], [2, 0], [3, 1], [4, 0]]
    kwargs = {"degree": 2, **kwargs}
    with pytest.raises(ValueError, match=message):
        NurbsCurve(points, **kwargs)


def test_interior_knot_repeated_beyond_the_degree_is_rejected():
    with pytest.raises(ValueError, match="repeats more than the degree"):
        NurbsCurve([[0, 0], [1, 1], [2, 0], [3, 1]], 1, knots=[0, 0, 0.5, 0.5, 1, 1])


# -- properties over random curves ---------------------------------------------------------


@settings(max_examples=60, deadline=None)
@given(st.integers(0, 2**32 - 1), st.booleans(), st.booleans())
def test_nurbs_derivatives_agree_with_finite_differences(seed, rational, periodic):
    curve = random_curve(seed, rational, periodic)
    t, width = span_midpoints(curve)
    h = 1e-3 * width
    order = min(3, curve.degree)
    exact = curve.derivatives(t, order)
    for k in range(1, order + 1):
        f = [curve.derivatives(t + j * h, k - 1)[k - 1] for j in (-2, -1, 1, 2)]
        estimate = (f[0] - 8 * f[1] + 8 * f[2] - f[3]) / (12 * h[:, None])
        scale = np.abs(exact[k]).max() + np.abs(exact[k - 1]).max() / width.min() + 1
        assert np.abs(exact[k] - estimate).max() < 1e-7 * scale, k


@settings(max_examples=40, deadline=None)
@given(
    st.integers(0, 2**32 - 1),
    st.floats(-100, 100),
    st.floats(1e-2, 1e3),
    st.booleans(),
)
def test_reparameterising_the_knots_preserves_geometry_and_t_derivatives(seed, shift, length, periodic):
    unit_curve = random_curve(seed, periodic=periodic)
    moved = random_curve(seed, periodic=periodic, domain=(shift, shift + length))
    assert moved.domain == pytest.approx((shift, shift + length))
    t = np.linspace(0, 1, 57)
    for a, b in zip(unit_curve.derivatives(t, 2), moved.derivatives(t, 2), strict=True):
        assert np.allclose(a, b, rtol=1e-9, atol=1e-9 * (1 + np.abs(a).max()))


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.booleans())
def test_reversed_nurbs_traces_the_curve_backwards_exactly(seed, periodic):
    curve = random_curve(seed, periodic=periodic)
    back = curve.reversed()
    t = np.linspace(0, 1, 41)
    assert np.allclose(back.point_at(t), curve.point_at(1 - t), atol=1e-12)
    # derivatives are one-sided at knots (kinks of low degree), so compare inside spans
    t = span_midpoints(curve)[0]
    assert np.allclose(back.derivatives(1 - t)[1], -curve.derivatives(t)[1], atol=1e-9)
    assert back.closed == curve.closed


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(-3, 3))
def test_nurbs_transform_moves_control_points_and_round_trips(seed, angle):
    curve = random_curve(seed)
    m = translation([1, -2, 3]) @ rotation([1, 2, 2], angle)
    moved = curve.transformed(m)
    t = np.linspace(0, 1, 33)
    assert np.allclose(moved.point_at(t), apply_transform(m, curve.point_at(t)), atol=1e-11)
    back = moved.transformed(np.linalg.inv(m))
    assert np.allclose(back.point_at(t), curve.point_at(t), atol=1e-11)


def test_perspective_transform_of_nurbs_is_exact():
    curve = random_curve(5)
    m = np.eye(4)
    m[3, :3] = [0.01, 0.02, 0.005]
    m[3, 3] = 1.0
    m[3, 3] += -min(0, (curve.control_points @ m[3, :3]).min()) + 0.5  # keep w positive
    t = np.linspace(0, 1, 33)
    assert np.allclose(curve.transformed(m).point_at(t), apply_transform(m, curve.point_at(t)), atol=1e-11)


def test_curves_share_a_basis_key_when_their_basis_is_the_same():
    points = np.array([[0.0, 0, 0], [1, 2, 0], [3, 1, 1], [4, 0, 0]])
    cubic = NurbsCurve(points, degree=3)
    assert cubic.basis_key == NurbsCurve(points * 2.0 + 5.0, degree=3).basis_key  # other points
    assert cubic.basis_key != NurbsCurve(points, degree=2).basis_key  # other degree and knots
    assert cubic.basis_key != NurbsCurve(points, degree=3, weights=[1, 2, 1, 1]).basis_key  # rational
