"""MeshSurface: the discrete curvature estimator and mesh queries."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from torsal.nodes.geometry.curvature import vertex_areas
from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.parametric_surface import torus


def welded_torus(big, small, nu, nv):
    """A closed torus grid mesh (seams welded), vertex (i, j) at u_i = i/nu, v_j = j/nv."""
    u, v = np.meshgrid(np.arange(nu) / nu, np.arange(nv) / nv, indexing="ij")
    points = torus(big, small).point_at(u.ravel(), v.ravel())
    i, j = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    a = (i * nv + j).ravel()
    b = (((i + 1) % nu) * nv + j).ravel()
    c = (((i + 1) % nu) * nv + (j + 1) % nv).ravel()
    d = (i * nv + (j + 1) % nv).ravel()
    faces = np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    return trimesh.Trimesh(points, faces, process=False), v.ravel()


def test_quadric_fit_on_icosphere_recovers_sphere_curvature():
    radius = 2.0
    surface = MeshSurface(trimesh.creation.icosphere(subdivisions=4, radius=radius))
    curv = surface.curvature()
    np.testing.assert_allclose(curv.gaussian, 1 / radius**2, rtol=2e-2)
    np.testing.assert_allclose(curv.mean, -1 / radius, rtol=2e-2)  # outward vertex normals


def test_quadric_fit_on_torus_grid_is_second_order_accurate():
    big, small = 2.0, 0.7
    errors = []
    for n in (50, 100):
        mesh, v = welded_torus(big, small, 2 * n, n)
        curv = MeshSurface(mesh).curvature()
        exact = np.cos(2 * np.pi * v) / (small * (big + small * np.cos(2 * np.pi * v)))
        errors.append(np.abs(curv.gaussian - exact).max() * small**2)
    assert errors[1] < 1e-2
    assert errors[0] / errors[1] > 3.0  # halving the spacing cuts the error ~4×


def test_angle_defect_over_vertex_area_matches_trimesh_measure():
    mesh = trimesh.creation.icosphere(subdivisions=3, radius=1.5)
    curv = MeshSurface(mesh).curvature(method="angle_defect")
    np.testing.assert_allclose(curv.gaussian, mesh.vertex_defects / vertex_areas(mesh))
    assert np.median(np.abs(curv.gaussian * 1.5**2 - 1)) < 0.01  # valence-5 vertices are off
    with pytest.raises(ValueError):
        MeshSurface(mesh).curvature(method="bogus")


def test_vertex_areas_sum_to_the_mesh_area():
    mesh = trimesh.creation.icosphere(subdivisions=2)
    assert vertex_areas(mesh).sum() == pytest.approx(mesh.area, rel=1e-14)


def test_mesh_surface_exposes_points_normals_and_bounds():
    mesh = trimesh.creation.box(extents=(2.0, 4.0, 6.0))
    surface = MeshSurface(mesh)
    assert surface.points.shape == (8, 3) and surface.normals.shape == (8, 3)
    np.testing.assert_allclose(surface.bounding_box(), [[-1, -2, -3], [1, 2, 3]])
    assert not surface.is_ruled
    assert surface.to_mesh() is not mesh
    with pytest.raises(TypeError):
        MeshSurface("not a mesh")


def test_closest_point_on_a_box_face_is_the_orthogonal_projection():
    surface = MeshSurface(trimesh.creation.box(extents=(2.0, 2.0, 2.0)))
    result = surface.closest_point([[0.3, -0.2, 5.0], [4.0, 0.5, 0.25], [0.1, 0.2, 0.3]])
    np.testing.assert_allclose(
        result.points, [[0.3, -0.2, 1.0], [1.0, 0.5, 0.25], [0.1, 0.2, 1.0]], atol=1e-15
    )
    np.testing.assert_allclose(result.distances, [4.0, 3.0, 0.7], atol=1e-15)
