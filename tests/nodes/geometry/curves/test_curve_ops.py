"""Generic curve operations: frames, length, division, closest point, bounds, tessellation."""

from __future__ import annotations

import math
from itertools import pairwise

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from torsal.nodes.geometry.curves import (
    Circle,
    InterpolatedCurve,
    Line,
    NurbsCurve,
    ParametricCurve,
    Polyline,
    ReversedCurve,
    TransformedCurve,
)
from torsal.nodes.geometry.transforms import apply_transform, rotation, scaling, translation
from torsal.nodes.geometry.vectors import Plane

TILTED = Plane.from_axes([1.0, -2.0, 0.5], [1, 1, 0], [0, 1, 1])
T = np.linspace(0, 1, 201)
R, C = 2.0, 0.5
HELIX = ParametricCurve(
    lambda u: np.column_stack([R * np.cos(u), R * np.sin(u), C * u]),
    (0.0, 4 * math.pi),
    derivatives=(
        lambda u: np.column_stack([-R * np.sin(u), R * np.cos(u), np.full_like(u, C)]),
        lambda u: np.column_stack([-R * np.cos(u), -R * np.sin(u), np.zeros_like(u)]),
        lambda u: np.column_stack([R * np.sin(u), -R * np.cos(u), np.zeros_like(u)]),
    ),
)
# A curve whose speed varies a lot along it: arc length is far from proportional to t.
WIGGLE = NurbsCurve(
    [[0, 0, 0], [1, 3, 0], [1.2, 3.1, 1], [4, -1, 0], [6, 0, 2], [6.1, 0.1, 2], [9, 2, 0]],
    degree=3,
    knots=[0, 0, 0, 0, 0.1, 0.15, 0.7, 1, 1, 1, 1],
    weights=[1, 2, 0.5, 1, 3, 1, 1],
)


def test_tangents_are_unit_and_along_the_first_derivative():
    tangents = WIGGLE.tangent_at(T)
    d1 = WIGGLE.derivatives(T)[1]
    assert np.allclose(np.linalg.norm(tangents, axis=1), 1.0, atol=1e-15)
    assert np.allclose(np.cross(tangents, d1), 0, atol=1e-12 * np.abs(d1).max())


def test_tangent_at_a_stationary_end_is_the_limit_direction():
    # repeated first control point: C'(0) = 0, the curve leaves along C''(0)
    curve = NurbsCurve([[0, 0, 0], [0, 0, 0], [1, 0, 0], [1, 1, 0]], degree=2)
    assert np.allclose(curve.tangent_at(0.0), [1, 0, 0])


def test_circle_curvature_vector_points_to_the_centre_with_length_one_over_r():
    circle = Circle(TILTED, 2.5)
    k = circle.curvature_vector_at(T)
    to_centre = TILTED.origin - circle.point_at(T)
    assert np.allclose(k, to_centre / 2.5**2, atol=1e-13)


def test_helix_frenet_frames_are_orthonormal_right_handed_and_normal_points_to_axis():
    frames = HELIX.frames_at(T)
    axes = np.stack([frames.tangents, frames.normals, frames.binormals], axis=1)
    assert np.allclose(axes @ axes.transpose(0, 2, 1), np.eye(3), atol=1e-14)
    assert np.allclose(np.linalg.det(axes), 1.0)
    horizontal = -frames.origins * [1, 1, 0] / R
    assert np.allclose(frames.normals, horizontal, atol=1e-13)


def test_frames_on_a_straight_line_are_valid_not_nan():
    frames = Line([0, 0, 0], [1, 2, 3]).frames_at(T)
    assert np.all(np.isfinite(frames.normals))
    assert np.allclose(np.einsum("ij,ij->i", frames.normals, frames.tangents), 0)
    assert np.allclose(np.linalg.norm(frames.binormals, axis=1), 1)
    assert np.allclose(Line([0, 0, 0], [1, 2, 3]).torsion_at(T), 0)


def test_plane_at_is_the_frenet_frame():
    plane = HELIX.plane_at(0.3)
    frames = HELIX.frames_at(np.array([0.3]))
    assert np.allclose(plane.x, frames.tangents[0]) and np.allclose(plane.z, frames.binormals[0])


def test_length_at_and_parameter_at_length_are_inverse_within_1e_12():
    s = np.linspace(0, WIGGLE.length, 57)
    t = WIGGLE.parameter_at_length(s)
    assert np.abs(WIGGLE.length_at(t) - s).max() < 1e-12 * WIGGLE.length


def test_length_of_a_rational_curve_matches_scipy_quad_within_1e_12():
    from scipy.integrate import quad

    def speed(t: float) -> float:
        return float(np.linalg.norm(WIGGLE.derivatives(t)[1]))

    breaks = WIGGLE._breakpoints()
    exact = sum(quad(speed, a, b, epsabs=0, epsrel=1e-13, limit=200)[0] for a, b in pairwise(breaks))
    assert abs(WIGGLE.length / exact - 1) < 1e-12


def test_divide_by_count_gives_pieces_of_equal_arc_length_within_1e_12():
    t = WIGGLE.divide_by_count(13)
    pieces = np.diff(WIGGLE.length_at(t))
    assert len(t) == 14 and t[0] == 0 and t[-1] == 1
    assert np.abs(pieces / (WIGGLE.length / 13) - 1).max() < 1e-12


def test_divide_closed_curve_by_count_does_not_repeat_the_start():
    t = Circle(TILTED, 1.0).divide_by_count(6)
    points = Circle(TILTED, 1.0).point_at(t)
    assert len(t) == 6
    chords = np.linalg.norm(np.roll(points, -1, axis=0) - points, axis=1)
    assert np.allclose(chords, 1.0, atol=1e-12)  # hexagon inscribed in the unit circle


def test_divide_by_length_steps_by_that_arc_length():
    step = 0.7
    t = WIGGLE.divide_by_length(step)
    assert len(t) == math.floor(WIGGLE.length / step) + 1
    assert np.allclose(np.diff(WIGGLE.length_at(t)), step, rtol=1e-12)


def test_divide_helix_by_length_is_exact_on_a_whole_multiple():
    t = HELIX.divide_by_length(HELIX.length / 8)
    assert np.allclose(t, np.linspace(0, 1, 9), atol=1e-12)


def test_closest_point_on_circle_is_the_radial_projection_within_1e_9():
    circle = Circle(TILTED, 2.0)
    rng = np.random.default_rng(4)
    queries = TILTED.point_at(*rng.uniform(-4, 4, (2, 500)), rng.uniform(-1, 1, 500))
    result = circle.closest_point(queries)
    radial = TILTED.project(queries) - TILTED.origin
    expected = TILTED.origin + 2.0 * radial / np.linalg.norm(radial, axis=1)[:, None]
    assert np.abs(result.points - expected).max() < 1e-9
    assert np.allclose(circle.point_at(result.parameters), result.points)


def test_closest_point_near_the_seam_of_a_closed_curve():
    circle = Circle(TILTED, 2.0)
    start = circle.start
    queries = start + 0.5 * TILTED.x + np.outer([-1e-6, 0, 1e-6], TILTED.y)
    result = circle.closest_point(queries)
    radial = TILTED.project(queries) - TILTED.origin
    expected = TILTED.origin + 2.0 * radial / np.linalg.norm(radial, axis=1)[:, None]
    assert np.abs(result.points - expected).max() < 1e-9


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_closest_point_on_helix_converges_to_1e_9(seed):
    rng = np.random.default_rng(seed)
    # points near the helix, within a quarter of a turn's pitch of it
    t0 = rng.uniform(0, 1, 50)
    queries = HELIX.point_at(t0) + rng.normal(scale=0.3, size=(50, 3))
    result = HELIX.closest_point(queries)
    # optimality: the offset is perpendicular to the tangent ...
    offset = queries - result.points
    residual = np.einsum("ij,ij->i", offset, HELIX.tangent_at(result.parameters))
    interior = (result.parameters > 0) & (result.parameters < 1)
    assert np.abs(residual[interior]).max(initial=0) < 1e-9
    # ... and no point of a dense sampling is nearer
    dense = HELIX.point_at(np.linspace(0, 1, 20_001))
    brute = np.min(np.linalg.norm(queries[:, None] - dense[None], axis=2), axis=1)
    assert np.all(result.distances <= brute + 1e-9)


def test_closest_point_on_a_helix_of_fifty_turns_finds_the_right_turn():
    r, c = 1.0, 0.05  # turns 0.31 apart: the nearest turn is easy to miss
    long_helix = ParametricCurve(
        lambda u: np.column_stack([r * np.cos(u), r * np.sin(u), c * u]), (0.0, 100 * math.pi)
    )
    u = np.linspace(0.3, 100 * math.pi - 0.3, 200)
    # points 0.5 outside the helix, radially: the closest point is the radial foot
    queries = np.column_stack([1.5 * np.cos(u), 1.5 * np.sin(u), c * u])
    result = long_helix.closest_point(queries)
    expected = np.column_stack([np.cos(u), np.sin(u), c * u])
    assert np.abs(result.points - expected).max() < 1e-9


def test_closest_point_beyond_the_end_of_an_open_curve_is_the_end():
    result = WIGGLE.closest_point([[-5.0, -5.0, 0.0], [20.0, 3.0, 0.0]])
    assert result.parameters.tolist() == [0.0, 1.0]


def test_reversed_generic_curve_negates_odd_derivatives():
    back = HELIX.reversed()
    assert isinstance(back, ReversedCurve)
    ours, theirs = back.derivatives(T, 3), HELIX.derivatives(1 - T, 3)
    for k in range(4):
        assert np.allclose(ours[k], (-1) ** k * theirs[k], atol=1e-12)
    assert back.reversed() is HELIX
    assert back.length == pytest.approx(HELIX.length, rel=1e-13)


def test_transformed_generic_curve_round_trips():
    m = translation([3, 0, -1]) @ rotation([1, 1, 0], 0.9) @ scaling(2.0)
    moved = HELIX.transformed(m)
    assert isinstance(moved, TransformedCurve)
    assert np.allclose(moved.point_at(T), apply_transform(m, HELIX.point_at(T)), atol=1e-12)
    back = moved.transformed(np.linalg.inv(m))
    assert np.allclose(back.point_at(T), HELIX.point_at(T), atol=1e-12)
    assert moved.length == pytest.approx(2 * HELIX.length, rel=1e-12)
    assert np.allclose(moved.curvature_at(T), HELIX.curvature_at(T) / 2, rtol=1e-12)


def test_generic_transform_rejects_perspective():
    m = np.eye(4)
    m[3, 0] = 1.0
    with pytest.raises(ValueError, match="only to NURBS"):
        HELIX.transformed(m)


def test_bounding_box_of_a_tilted_circle_is_exact():
    # half-extent along world axis i of a circle of radius r with unit normal n: r√(1 − nᵢ²)
    circle = Circle(TILTED, 2.0)
    half = 2.0 * np.sqrt(1 - TILTED.z**2)
    box = circle.bounding_box()
    assert np.allclose(box, [TILTED.origin - half, TILTED.origin + half], atol=1e-12)


def test_bounding_box_of_a_helix_spans_its_radius_and_height():
    box = HELIX.bounding_box()
    assert np.allclose(box, [[-R, -R, 0], [R, R, C * 4 * math.pi]], atol=1e-12)


@pytest.mark.parametrize("tolerance", [1e-1, 1e-3, 1e-5])
def test_polyline_stays_within_tolerance_of_the_curve(tolerance):
    polyline = Polyline.from_curve(WIGGLE, tolerance)
    dense = WIGGLE.point_at(np.linspace(0, 1, 5_001))
    assert polyline.closest_point(dense).distances.max() <= tolerance * 1.01
    assert np.allclose(polyline.points[[0, -1]], [WIGGLE.start, WIGGLE.end])


def test_circle_tessellation_needs_about_pi_over_sqrt_of_2_tol_over_r_segments():
    # a chord of angle θ deviates r(1 − cos θ/2) ≈ rθ²/8 from the arc, so the coarsest
    # polygon within tol has 2π / √(8 tol / r) segments; halving can at most double that
    r, tol = 1.0, 1e-4
    count = len(Circle(radius=r).tessellate(tol)) - 1
    ideal = 2 * math.pi / math.sqrt(8 * tol / r)
    assert ideal <= count <= 2.1 * ideal


def test_start_and_end_are_the_points_at_zero_and_one():
    assert np.array_equal(WIGGLE.start, WIGGLE.point_at(0.0))
    assert np.allclose(WIGGLE.end, [9, 2, 0])


def test_polyline_and_interpolation_are_curves_with_the_same_operations():
    points = np.random.default_rng(0).normal(size=(6, 3))
    for curve in (Polyline(points), InterpolatedCurve(points)):
        assert curve.bounding_box().shape == (2, 3)
        assert curve.divide_by_count(3).shape == (4,)
