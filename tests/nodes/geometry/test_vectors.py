"""Vectors and frames: unit vectors, angles, rotations and planes."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from torsal.nodes.geometry.vectors import (
    WORLD_XY,
    WORLD_YZ,
    WORLD_ZX,
    Plane,
    angle_between,
    as_points,
    normalise,
    perpendicular,
    rotate,
    rotate_2d,
    rotation_matrix,
    signed_angle,
    unit,
)

finite = st.floats(-100, 100, allow_nan=False)
vector3 = st.tuples(finite, finite, finite).map(np.array)


def test_unit_vectors_have_length_one():
    v = np.array([[3.0, 4.0, 0.0], [1e-100, 0.0, 0.0], [-2.0, 2.0, 1.0]])
    assert np.allclose(np.linalg.norm(unit(v), axis=1), 1.0, atol=1e-15)


def test_unit_of_zero_vector_is_zero_not_nan():
    assert unit(np.zeros((2, 3))).tolist() == [[0.0, 0.0, 0.0]] * 2


def test_normalise_zero_vector_raises_naming_it():
    with pytest.raises(ValueError, match="rotation axis has zero length"):
        normalise([0, 0, 0], "rotation axis")


def test_as_points_pads_2d_points_with_zero_z():
    assert as_points([[1, 2], [3, 4]]).tolist() == [[1, 2, 0], [3, 4, 0]]


def test_angle_between_orthogonal_parallel_and_opposite():
    a = np.array([[1.0, 0, 0]] * 3)
    b = np.array([[0, 5.0, 0], [2.0, 0, 0], [-1.0, 0, 0]])
    assert np.allclose(angle_between(a, b), [math.pi / 2, 0.0, math.pi], atol=1e-15)


def test_angle_between_nearly_parallel_vectors_is_accurate_to_1e_20():
    # arccos of the dot product would give 0 (or 2e-8) here; the true angle is 1e-12
    a = np.array([1.0, 0.0, 0.0])
    b = np.array([1.0, 1e-12, 0.0])
    assert abs(angle_between(a, b) - 1e-12) < 1e-20


def test_angle_with_zero_vector_is_zero_not_nan():
    assert angle_between([0, 0, 0], [1, 0, 0]) == 0.0


def test_signed_angle_is_positive_counter_clockwise_about_normal():
    assert math.isclose(signed_angle([1, 0, 0], [0, 1, 0], [0, 0, 1]), math.pi / 2)
    assert math.isclose(signed_angle([1, 0, 0], [0, 1, 0], [0, 0, -1]), -math.pi / 2)


def test_quarter_turn_about_z_takes_x_to_y():
    assert np.allclose(rotate([1.0, 0, 0], [0, 0, 1], math.pi / 2), [0, 1, 0], atol=1e-16)


def test_rotation_matrix_of_120_degrees_about_diagonal_cycles_the_axes():
    r = rotation_matrix([1, 1, 1], 2 * math.pi / 3)
    assert np.allclose(r @ [1, 0, 0], [0, 1, 0], atol=1e-15)
    assert np.allclose(r @ [0, 1, 0], [0, 0, 1], atol=1e-15)


@settings(max_examples=50, deadline=None)
@given(vector3, vector3, st.floats(-10, 10))
def test_rodrigues_rotation_matches_matrix_and_preserves_length(v, axis, angle):
    if np.linalg.norm(axis) < 1e-3:
        axis = np.array([0.0, 0.0, 1.0])
    rotated = rotate(v, axis, angle)
    assert np.allclose(rotated, rotation_matrix(axis, angle) @ v, atol=1e-12)
    assert math.isclose(np.linalg.norm(rotated), np.linalg.norm(v), rel_tol=1e-13, abs_tol=1e-13)
    r = rotation_matrix(axis, angle)
    assert np.allclose(r @ r.T, np.eye(3), atol=1e-14)
    assert math.isclose(np.linalg.det(r), 1.0, rel_tol=1e-13)


def test_rotate_takes_one_angle_per_vector():
    v = np.array([[1.0, 0, 0], [1.0, 0, 0]])
    out = rotate(v, [0, 0, 1], np.array([math.pi / 2, math.pi]))
    assert np.allclose(out, [[0, 1, 0], [-1, 0, 0]], atol=1e-15)


def test_rotate_2d_quarter_turn():
    assert np.allclose(rotate_2d([[1.0, 0.0], [0.0, 2.0]], math.pi / 2), [[0, 1], [-2, 0]])


def test_perpendicular_is_unit_and_orthogonal():
    v = np.array([[1.0, 0, 0], [0, 0, 3.0], [1.0, 2.0, 3.0], [1e-8, 1.0, 0]])
    p = perpendicular(v)
    assert np.allclose(np.einsum("ij,ij->i", p, v), 0, atol=1e-15)
    assert np.allclose(np.linalg.norm(p, axis=1), 1.0)


def test_world_planes_are_right_handed():
    for plane in (WORLD_XY, WORLD_YZ, WORLD_ZX):
        assert np.allclose(np.cross(plane.x, plane.y), plane.z)


def test_plane_from_normal_of_world_z_is_world_xy():
    assert Plane.from_normal([0, 0, 0], [0, 0, 5]) == WORLD_XY


def test_plane_from_normal_is_orthonormal_for_any_normal():
    for n in ([1, 0, 0], [0, -1, 0], [1, 2, 3], [-1e-3, 1, 0]):
        p = Plane.from_normal([1, 2, 3], n)
        assert np.allclose(p.axes @ p.axes.T, np.eye(3), atol=1e-15)
        assert np.allclose(p.z, unit(n))


def test_plane_from_points_puts_third_point_on_positive_y_side():
    p = Plane.from_points([0, 0, 0], [2, 0, 0], [5, 3, 0])
    assert p == WORLD_XY
    assert p.to_local([5, 3, 0])[1] == 3.0


def test_plane_rejects_axes_that_are_not_orthonormal():
    with pytest.raises(ValueError, match="orthonormal"):
        Plane([0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 0, 1])


def test_plane_rejects_parallel_axes():
    with pytest.raises(ValueError, match="parallel"):
        Plane.from_axes([0, 0, 0], [1, 0, 0], [2, 0, 0])


def test_plane_local_coordinates_round_trip():
    p = Plane.from_axes([1, -2, 3], [1, 1, 0], [0, 1, 1])
    pts = np.random.default_rng(0).normal(size=(20, 3))
    local = p.to_local(pts)
    assert np.allclose(p.point_at(local[:, 0], local[:, 1], local[:, 2]), pts, atol=1e-14)
    assert np.allclose(p.signed_distance(p.project(pts)), 0, atol=1e-14)


def test_flipped_plane_has_opposite_normal_and_stays_right_handed():
    p = Plane.from_normal([0, 0, 1], [1, 2, 3]).flipped()
    assert np.allclose(p.z, -unit([1, 2, 3]))
    assert np.allclose(np.cross(p.x, p.y), p.z)


def test_plane_is_immutable():
    with pytest.raises(ValueError):
        WORLD_XY.origin[0] = 1.0
