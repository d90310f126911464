"""4×4 transforms: builders, application and round trips."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from torsal.nodes.geometry.transforms import (
    apply_to_vectors,
    apply_transform,
    change_of_basis,
    is_affine,
    mirror,
    non_uniform_scaling,
    orient,
    rotation,
    scaling,
    transform_plane,
    translation,
)
from torsal.nodes.geometry.vectors import WORLD_XY, Plane

POINTS = np.random.default_rng(1).normal(size=(50, 3)) * 10
finite = st.floats(-50, 50, allow_nan=False)
vector3 = st.tuples(finite, finite, finite).map(np.array)


def test_translation_moves_every_point_by_the_vector():
    assert np.allclose(apply_transform(translation([1, 2, 3]), POINTS), POINTS + np.array([1, 2, 3]))


def test_rotation_about_axis_through_centre_keeps_centre_and_turns_a_quarter():
    m = rotation([0, 0, 1], math.pi / 2, centre=[1, 1, 0])
    assert np.allclose(apply_transform(m, [1, 1, 5]), [1, 1, 5])
    assert np.allclose(apply_transform(m, [2, 1, 0]), [1, 2, 0])


def test_uniform_scaling_about_centre_scales_distances_from_it():
    m = scaling(3.0, centre=[1, 0, 0])
    image = apply_transform(m, POINTS)
    assert np.allclose(image - [1, 0, 0], 3.0 * (POINTS - [1, 0, 0]))


def test_non_uniform_scaling_along_plane_axes():
    plane = Plane.from_axes([1, 1, 1], [1, 1, 0], [-1, 1, 0])
    m = non_uniform_scaling((2.0, 3.0, 4.0), plane=plane)
    local = plane.to_local(POINTS)
    assert np.allclose(plane.to_local(apply_transform(m, POINTS)), local * [2, 3, 4])


def test_mirror_reverses_signed_distance_and_is_its_own_inverse():
    plane = Plane.from_normal([1, 2, 3], [1, -1, 2])
    m = mirror(plane)
    image = apply_transform(m, POINTS)
    assert np.allclose(plane.signed_distance(image), -plane.signed_distance(POINTS))
    assert np.allclose(plane.project(image), plane.project(POINTS))
    assert np.allclose(m @ m, np.eye(4), atol=1e-14)


def test_orient_maps_source_plane_onto_target_plane():
    source = Plane.from_axes([1, 2, 3], [1, 0, 1], [0, 1, 0])
    target = Plane.from_axes([-4, 0, 2], [0, 1, 1], [1, 0, 0])
    m = orient(source, target)
    local = source.to_local(POINTS)
    assert np.allclose(target.to_local(apply_transform(m, POINTS)), local, atol=1e-12)
    assert transform_plane(m, source).z == pytest.approx(target.z)


def test_change_of_basis_gives_plane_coordinates():
    plane = Plane.from_axes([1, 2, 3], [1, 0, 1], [0, 1, 0])
    assert np.allclose(apply_transform(change_of_basis(plane), POINTS), plane.to_local(POINTS))
    assert np.allclose(change_of_basis(plane) @ orient(WORLD_XY, plane), np.eye(4), atol=1e-15)


@settings(max_examples=60, deadline=None)
@given(vector3, vector3, st.floats(-7, 7), st.floats(0.1, 10), vector3)
def test_composed_transform_round_trips_through_its_inverse(axis, move, angle, factor, centre):
    if np.linalg.norm(axis) < 1e-3:
        axis = np.array([1.0, 0.0, 0.0])
    m = translation(move) @ rotation(axis, angle, centre) @ scaling(factor, centre)
    back = apply_transform(np.linalg.inv(m), apply_transform(m, POINTS))
    assert np.allclose(back, POINTS, atol=1e-9)


def test_vectors_ignore_translation():
    m = translation([5, 5, 5]) @ rotation([0, 0, 1], math.pi)
    assert np.allclose(apply_to_vectors(m, [[1, 0, 0]]), [[-1, 0, 0]])


def test_projective_transform_divides_by_w():
    m = np.eye(4)
    m[3, 2] = 1.0  # w = z + 1
    assert not is_affine(m)
    assert np.allclose(apply_transform(m, [2.0, 4.0, 1.0]), [1.0, 2.0, 0.5])


def test_single_point_in_single_point_out():
    assert apply_transform(translation([1, 0, 0]), [0, 0, 0]).shape == (3,)


def test_wrong_matrix_shape_is_rejected_plainly():
    with pytest.raises(ValueError, match="4×4"):
        apply_transform(np.eye(3), POINTS)
