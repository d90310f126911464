"""Line–line closest points, line–plane, plane–plane and curve–plane intersections."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from torsal.nodes.geometry.curves import Circle, Line, ParametricCurve
from torsal.nodes.geometry.intersections import (
    curve_plane_intersections,
    line_line_closest_points,
    line_plane_intersection,
    plane_plane_intersection,
)
from torsal.nodes.geometry.vectors import WORLD_XY, WORLD_YZ, Plane

TILTED = Plane.from_axes([1.0, -2.0, 0.5], [1, 1, 0], [0, 1, 1])


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1))
def test_line_line_closest_points_match_closed_form_and_brute_force(seed):
    rng = np.random.default_rng(seed)
    a0, a1, b0, b1 = rng.uniform(-10, 10, (4, 200, 3))
    result = line_line_closest_points(a0, a1, b0, b1)
    u, v = a1 - a0, b1 - b0
    normal = np.cross(u, v)
    # distance between skew lines: |(a0 − b0)·(u × v)| / |u × v|
    expected = np.abs(np.einsum("ij,ij->i", a0 - b0, normal)) / np.linalg.norm(normal, axis=1)
    assert np.allclose(result.distances, expected, rtol=1e-9, atol=1e-12)
    assert np.allclose(result.points_a, a0 + result.parameters_a[:, None] * u)
    assert np.allclose(result.points_b, b0 + result.parameters_b[:, None] * v)
    # brute force: no pair of parameters on a grid around the answer is closer
    offsets = np.linspace(-0.5, 0.5, 41)
    s = result.parameters_a[:, None, None] + offsets[None, :, None]
    t = result.parameters_b[:, None, None] + offsets[None, None, :]
    pa = a0[:, None, None] + s[..., None] * u[:, None, None]
    pb = b0[:, None, None] + t[..., None] * v[:, None, None]
    brute = np.linalg.norm(pa - pb, axis=-1).min(axis=(1, 2))
    assert np.all(result.distances <= brute + 1e-12)
    assert not result.parallel.any()


def test_crossing_lines_meet_at_their_intersection():
    result = line_line_closest_points([0, 0, 0], [2, 2, 0], [0, 2, 0], [2, 0, 0])
    assert np.allclose(result.points_a, [[1, 1, 0]]) and np.allclose(result.points_b, [[1, 1, 0]])
    assert result.parameters_a.tolist() == [0.5] and result.distances[0] == 0


def test_parallel_lines_are_flagged_and_give_their_separation():
    result = line_line_closest_points([0, 0, 0], [1, 0, 0], [[5, 3, 4], [5, 3, 4]], [[7, 3, 4], [3, 3, 4]])
    assert result.parallel.tolist() == [True, True]
    assert np.allclose(result.distances, 5.0)
    assert np.allclose(result.points_a, 0)


def test_zero_length_line_reduces_to_its_point():
    result = line_line_closest_points([0, 0, 0], [2, 0, 0], [1, 5, 5], [1, 5, 5])
    assert result.parallel[0]
    assert np.allclose(result.points_a, [[1, 0, 0]]) and np.allclose(result.points_b, [[1, 5, 5]])


def test_lines_broadcast_one_against_many():
    lift = np.array([0.0, 0.0, 2.0])
    result = line_line_closest_points([0, 0, 0], [0, 0, 1], np.eye(3) + lift, 2 * np.eye(3) + lift)
    assert result.points_a.shape == (3, 3)


def test_line_plane_intersection_lies_on_the_plane():
    rng = np.random.default_rng(2)
    start, end = rng.normal(size=(2, 100, 3))
    points, t, parallel = line_plane_intersection(start, end, TILTED)
    assert not parallel.any()
    assert np.abs(TILTED.signed_distance(points)).max() < 1e-10
    assert np.allclose(points, start + t[:, None] * (end - start))


def test_line_parallel_to_plane_is_flagged_with_nan():
    points, t, parallel = line_plane_intersection([0, 0, 1], [1, 1, 1], WORLD_XY)
    assert parallel.tolist() == [True] and math.isnan(t[0]) and np.isnan(points).all()


def test_plane_plane_intersection_lies_on_both_planes_nearest_the_first_origin():
    a = Plane.from_normal([1, 2, 3], [1, 0, 1])
    b = TILTED
    point, direction = plane_plane_intersection(a, b)
    for p in (point, point + 3 * direction):
        assert abs(a.signed_distance(p)) < 1e-12 and abs(b.signed_distance(p)) < 1e-12
    assert abs(direction @ a.z) < 1e-15 and abs(direction @ b.z) < 1e-15
    assert abs((point - a.origin) @ direction) < 1e-12


def test_world_xy_meets_world_yz_along_the_y_axis():
    point, direction = plane_plane_intersection(WORLD_XY, WORLD_YZ)
    assert np.allclose(point, 0) and np.allclose(np.abs(direction), [0, 1, 0])


def test_parallel_planes_do_not_intersect():
    assert plane_plane_intersection(WORLD_XY, Plane.from_normal([0, 0, 5], [0, 0, -1])) is None


def test_circle_crosses_a_plane_through_its_centre_twice_at_the_closed_form_points():
    circle = Circle(TILTED, 2.0)
    cut = Plane.from_normal(TILTED.origin, TILTED.x + 0.3 * TILTED.z)
    hits = curve_plane_intersections(circle, cut)
    assert len(hits.parameters) == 2
    # the chord through the centre: ±r along the line where the planes meet
    _, direction = plane_plane_intersection(TILTED, cut)
    expected = TILTED.origin + 2.0 * np.array([direction, -direction])
    distances = np.linalg.norm(hits.points[:, None] - expected[None], axis=2).min(axis=1)
    assert distances.max() < 1e-12


def test_plane_tangent_to_a_circle_touches_it_once():
    circle = Circle(WORLD_XY, 2.0)
    hits = curve_plane_intersections(circle, Plane.from_normal([0, 2, 0], [0, 1, 0]))
    assert len(hits.parameters) == 1
    assert np.allclose(hits.points, [[0, 2, 0]], atol=1e-7)  # a double root: √ε accuracy


def test_helix_meets_each_horizontal_plane_once_at_its_height():
    r, c, turns = 1.0, 0.2, 5
    helix = ParametricCurve(
        lambda u: np.column_stack([r * np.cos(u), r * np.sin(u), c * u]), (0, 2 * math.pi * turns)
    )
    for height in (0.1, 1.0, 3.3, 6.2):
        hits = curve_plane_intersections(helix, Plane.from_normal([0, 0, height], [0, 0, 1]))
        u = height / c
        assert hits.parameters == pytest.approx([u / (2 * math.pi * turns)], abs=1e-13)


def test_sine_wave_crosses_the_axis_at_every_multiple_of_pi():
    wave = ParametricCurve(lambda u: np.column_stack([u, np.sin(u), 0 * u]), (0.5, 20.0))
    hits = curve_plane_intersections(wave, Plane.from_normal([0, 0, 0], [0, 1, 0]))
    assert np.allclose(hits.points[:, 0], np.pi * np.arange(1, 7), atol=1e-12)


def test_line_lying_in_the_plane_reports_points_along_it():
    hits = curve_plane_intersections(Line([0, 0, 0], [1, 0, 0]), WORLD_XY)
    assert hits.parameters[0] == 0 and hits.parameters[-1] == 1


def test_curve_missing_the_plane_has_no_intersections():
    hits = curve_plane_intersections(Circle(WORLD_XY, 1.0), Plane.from_normal([0, 0, 1], [0, 0, 1]))
    assert hits.parameters.shape == (0,) and hits.points.shape == (0, 3)


def test_crossing_at_the_seam_of_a_closed_curve_is_reported_once():
    hits = curve_plane_intersections(Circle(WORLD_XY, 2.0), Plane.from_normal([0, 0, 0], [0, 1, 0]))
    assert hits.parameters == pytest.approx([0.0, 0.5], abs=1e-14)
