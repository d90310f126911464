"""Closest point on surfaces converges to 1e-9 of the exact answer."""

from __future__ import annotations

import numpy as np
import trimesh

from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.nurbs_surface import NurbsSurface
from torsal.nodes.geometry.parametric_surface import ParametricSurface, cylinder, sphere, torus
from torsal.nodes.geometry.ruled import RuledSurface

TOL = 1e-9


def random_points(count, scale=3.0, seed=7):
    return np.random.default_rng(seed).normal(size=(count, 3)) * scale


def test_closest_point_on_sphere_is_radial_projection():
    radius, centre = 2.0, np.array([0.5, -1.0, 2.0])
    points = centre + random_points(300)
    result = sphere(radius, centre).closest_point(points)
    exact = centre + radius * (points - centre) / np.linalg.norm(points - centre, axis=1)[:, None]
    np.testing.assert_allclose(result.points, exact, atol=TOL)
    np.testing.assert_allclose(
        result.distances, np.abs(np.linalg.norm(points - centre, axis=1) - radius), atol=TOL
    )
    np.testing.assert_allclose(sphere(radius, centre).point_at(*result.parameters.T), result.points)


def test_closest_point_on_expression_torus_is_tube_projection():
    big, small = 2.0, 0.6
    surface = ParametricSurface(
        lambda u, v: (
            (big + small * np.cos(v)) * np.cos(u),
            (big + small * np.cos(v)) * np.sin(u),
            small * np.sin(v),
        ),
        (-3.7, -3.7 + 2 * np.pi),
        (1.0, 1.0 + 2 * np.pi),  # shifted, still closed
    )
    points = random_points(300, 2.0, seed=3)
    points = points[np.hypot(points[:, 0], points[:, 1]) > 0.1]
    rho = np.hypot(points[:, 0], points[:, 1])
    core = np.column_stack([big * points[:, 0] / rho, big * points[:, 1] / rho, 0 * rho])
    offset = points - core
    exact = core + small * offset / np.linalg.norm(offset, axis=1)[:, None]
    result = surface.closest_point(points)
    np.testing.assert_allclose(result.points, exact, atol=TOL)


def test_closest_point_beyond_a_patch_edge_lands_on_the_edge():
    # Plane patch [0, 2] × [0, 1] at z = 0: the answer is the clamped projection.
    grid = np.array([[[0, 0, 0], [0, 1, 0]], [[2, 0, 0], [2, 1, 0]]], dtype=float)
    patch = NurbsSurface(grid, 1, 1)
    points = random_points(400, 2.0, seed=11) + np.array([1.0, 0.5, 0.0])
    exact = np.column_stack([np.clip(points[:, 0], 0, 2), np.clip(points[:, 1], 0, 1), 0 * points[:, 0]])
    result = patch.closest_point(points)
    np.testing.assert_allclose(result.points, exact, atol=TOL)
    np.testing.assert_allclose(result.parameters, exact[:, :2] / [2.0, 1.0], atol=TOL)


def test_closest_point_on_cylinder_wraps_across_the_seam():
    surface = cylinder(radius=1.0, height=3.0)
    angles = np.array([-1e-3, -1e-9, 0.0, 1e-9, 2e-3])  # straddling u = 0 ≡ 1
    points = np.column_stack([2 * np.cos(angles), 2 * np.sin(angles), np.full(5, 1.5)])
    result = surface.closest_point(points)
    exact = np.column_stack([np.cos(angles), np.sin(angles), np.full(5, 1.5)])
    np.testing.assert_allclose(result.points, exact, atol=TOL)


def test_closest_point_on_curved_nurbs_agrees_with_dense_brute_force_refined():
    rng = np.random.default_rng(5)
    control = np.zeros((5, 4, 3))
    control[..., 0], control[..., 1] = np.meshgrid(np.linspace(0, 4, 5), np.linspace(0, 3, 4), indexing="ij")
    control[..., 2] = rng.normal(scale=0.5, size=(5, 4))
    surface = NurbsSurface(control, 3, 3, weights=rng.uniform(0.7, 1.5, size=(5, 4)))
    points = rng.uniform([0, 0, -1], [4, 3, 1], size=(100, 3))
    result = surface.closest_point(points)
    # First-order optimality: the offset is normal to the surface (or the point is
    # on the boundary), and no dense sample is closer.
    _, su, sv = surface.derivatives(*result.parameters.T, 1)
    offset = points - result.points
    interior = np.all((result.parameters > 1e-9) & (result.parameters < 1 - 1e-9), axis=1)
    tangency = np.abs(np.column_stack([np.einsum("ij,ij->i", offset, su), np.einsum("ij,ij->i", offset, sv)]))
    assert np.all(tangency[interior] <= 1e-9 * np.linalg.norm(su[interior], axis=1)[:, None])
    gu, gv = np.meshgrid(np.linspace(0, 1, 301), np.linspace(0, 1, 301), indexing="ij")
    samples = surface.point_at(gu.ravel(), gv.ravel())
    brute = np.min(np.linalg.norm(points[:, None] - samples[None], axis=2), axis=1)
    assert np.all(result.distances <= brute + 1e-12)


def test_closest_point_on_ruled_surface_from_rulings_is_on_the_ruling_for_points_on_it():
    rulings = np.array(
        [[[0, 0, 0], [0, 0, 1]], [[1, 0, 0], [1, 0.3, 1]], [[2, 0.5, 0], [2, 1, 1]], [[3, 0, 0], [3, 0, 1]]],
        dtype=float,
    )
    surface = RuledSurface.from_rulings(rulings)
    t = np.linspace(0, 1, 7)[:, None]
    on_ruling = rulings[2, 0] + t * (rulings[2, 1] - rulings[2, 0])
    result = surface.closest_point(on_ruling)
    np.testing.assert_allclose(result.distances, 0.0, atol=TOL)
    np.testing.assert_allclose(result.parameters[:, 0], 2 / 3, atol=TOL)


def test_closest_point_on_mesh_matches_brute_force_over_all_triangles():
    mesh = torus(2.0, 0.5).to_mesh(24, 16)
    surface = MeshSurface(mesh)
    points = random_points(60, 2.0, seed=2)
    result = surface.closest_point(points)
    tri = np.asarray(mesh.triangles)
    all_pairs = trimesh.triangles.closest_point(
        np.repeat(tri, len(points), axis=0), np.tile(points, (len(tri), 1))
    )
    dist = np.linalg.norm(all_pairs - np.tile(points, (len(tri), 1)), axis=1).reshape(len(tri), -1)
    np.testing.assert_allclose(result.distances, dist.min(axis=0), atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(result.points - points, axis=1), result.distances)
