"""Circle and Arc closest points in closed form, against the generic curve search and the
projection onto the plane and then radially onto the circle."""

from __future__ import annotations

import math

import numpy as np

from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curves import Arc, Circle
from torsal.nodes.geometry.vectors import Plane

PLANE = Plane.from_normal([3.0, -2.0, 1.5], [1.0, 2.0, 2.0])
QUERIES = np.random.default_rng(7).uniform(-6, 6, (2000, 3)) + PLANE.origin


def radial_projection(plane: Plane, radius: float, points: np.ndarray) -> np.ndarray:
    """The closed form, written out: drop each point onto the plane, scale it to the radius."""
    flat = points - plane.origin
    flat = flat - np.outer(flat @ plane.z, plane.z)
    return plane.origin + radius * flat / np.linalg.norm(flat, axis=1, keepdims=True)


def test_circle_closest_points_are_the_radial_projection():
    found = Circle(PLANE, 2.5).closest_point(QUERIES)
    # measured 1.2e-14
    np.testing.assert_allclose(found.points, radial_projection(PLANE, 2.5, QUERIES), rtol=0, atol=1e-13)


def test_circle_closest_point_parameters_give_the_closest_points():
    circle = Circle(PLANE, 2.5)
    found = circle.closest_point(QUERIES)
    # measured 1.8e-15
    np.testing.assert_allclose(circle.point_at(found.parameters), found.points, rtol=0, atol=2e-14)


def test_circle_closest_points_agree_with_the_generic_search():
    circle = Circle(PLANE, 2.5)
    closed = circle.closest_point(QUERIES)
    generic = Curve.closest_point(circle, QUERIES)
    # measured 1.8e-15 (the distances) and 6.7e-16 (the parameters)
    np.testing.assert_allclose(closed.distances, generic.distances, rtol=0, atol=2e-14)
    np.testing.assert_allclose(closed.parameters, generic.parameters, rtol=0, atol=1e-14)


def test_arc_closest_points_agree_with_the_generic_search():
    arc = Arc(PLANE, 2.5, 0.4, 0.4 + 3.9)
    closed = arc.closest_point(QUERIES)
    generic = Curve.closest_point(arc, QUERIES)
    # measured 1.8e-15 (the distances) and 6.7e-16 (the parameters)
    np.testing.assert_allclose(closed.distances, generic.distances, rtol=0, atol=2e-14)
    np.testing.assert_allclose(closed.parameters, generic.parameters, rtol=0, atol=1e-14)


def test_arc_closest_points_beyond_its_ends_are_the_nearer_end():
    start, end = 0.4, 0.4 + 3.9
    arc = Arc(PLANE, 2.5, start, end)
    local = PLANE.to_local(QUERIES)
    beyond = np.mod(np.arctan2(local[:, 1], local[:, 0]) - start, 2 * math.pi) > end - start
    ends = PLANE.point_at(2.5 * np.cos([start, end]), 2.5 * np.sin([start, end]))
    to_ends = np.linalg.norm(QUERIES[beyond, None, :] - ends[None], axis=2)
    found = arc.closest_point(QUERIES[beyond])
    assert beyond.sum() > 200
    np.testing.assert_array_equal(found.parameters, np.where(to_ends[:, 1] < to_ends[:, 0], 1.0, 0.0))
    np.testing.assert_allclose(found.distances, to_ends.min(axis=1), rtol=0, atol=1e-13)


def test_arc_closest_points_within_its_sweep_are_the_radial_projection():
    start, end = 0.4, 0.4 + 3.9
    local = PLANE.to_local(QUERIES)
    within = np.mod(np.arctan2(local[:, 1], local[:, 0]) - start, 2 * math.pi) <= end - start
    found = Arc(PLANE, 2.5, start, end).closest_point(QUERIES[within])
    expected = radial_projection(PLANE, 2.5, QUERIES[within])
    np.testing.assert_allclose(found.points, expected, rtol=0, atol=1e-13)  # measured 6.2e-15


def test_a_query_on_the_circle_axis_gets_the_start_at_the_radius_and_height():
    circle = Circle(PLANE, 2.5)
    found = circle.closest_point(PLANE.origin + 4.0 * PLANE.z)
    assert found.parameters.tolist() == [0.0]
    assert abs(found.distances[0] - math.hypot(2.5, 4.0)) < 1e-13


def test_circle_closest_points_at_site_coordinates_keep_their_digits():
    far = Plane.from_normal([2.0e6, 1.0e6, 30.0], [0.0, 0.3, 1.0])
    queries = np.random.default_rng(8).uniform(-6, 6, (200, 3)) + far.origin
    found = Circle(far, 2.5).closest_point(queries)
    # measured 1.4e-14 (the coordinates themselves are 2e6)
    np.testing.assert_allclose(found.points, radial_projection(far, 2.5, queries), rtol=0, atol=1e-13)
