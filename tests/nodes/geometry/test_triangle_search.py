"""Closest points on triangles through TriangleIndex (MeshSurface.closest_point and the
development map's 3D search) equal brute force: every point against every triangle with
trimesh's point–triangle projection. The strips mix long thin triangles with one big one,
the case where searching by the largest triangle's reach was slow.

How fast: tests/benchmarks/bench_kernels.py.
"""

from __future__ import annotations

import numpy as np
import trimesh

from tests.nodes.geometry.test_development_locate import helix_tangent
from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.triangle_search import TriangleIndex
from torsal.nodes.geometry.unroll import unroll_rulings


def thin_strip(n: int = 400, width: float = 0.02, offset: float = 0.0) -> trimesh.Trimesh:
    """A long band of ``width`` following a sine wave, and one big triangle past its end."""
    t = np.linspace(0, 20, n)
    a = np.column_stack([t, np.sin(t), 0 * t])
    lift = np.array([0.0, 0.0, width])
    vertices = np.vstack([a, a + lift, [[20, 0, 0], [30, 0, 0], [25, 8, 0]]]) + offset
    faces = [[i, i + 1, n + i] for i in range(n - 1)] + [[i + 1, n + i + 1, n + i] for i in range(n - 1)]
    return trimesh.Trimesh(vertices, np.array([*faces, [2 * n, 2 * n + 1, 2 * n + 2]]), process=False)


def brute_distances(triangles: np.ndarray, points: np.ndarray) -> np.ndarray:
    rows = np.repeat(np.arange(len(points)), len(triangles))
    cols = np.tile(np.arange(len(triangles)), len(points))
    found = trimesh.triangles.closest_point(triangles[cols], points[rows])
    return np.linalg.norm(found - points[rows], axis=1).reshape(len(points), -1).min(axis=1)


def queries(mesh: trimesh.Trimesh, count: int, spread: float, seed: int = 0) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return mesh.vertices[rng.integers(0, len(mesh.vertices), count)] + rng.normal(0, spread, (count, 3))


def test_mesh_closest_point_distances_equal_brute_force_on_a_thin_strip():
    mesh = thin_strip()
    points = queries(mesh, 300, 0.3)
    result = MeshSurface(mesh).closest_point(points)
    # measured 0 (the same projection of the same winning triangle)
    np.testing.assert_allclose(result.distances, brute_distances(mesh.triangles, points), rtol=0, atol=1e-12)


def test_mesh_closest_point_equals_brute_force_at_site_coordinates():
    mesh = thin_strip(offset=2.5e6)
    points = queries(mesh, 200, 0.3)
    result = MeshSurface(mesh).closest_point(points)
    # positions round to ~5e-10 at 2.5e6 m
    np.testing.assert_allclose(result.distances, brute_distances(mesh.triangles, points), rtol=0, atol=2e-9)


def test_candidates_hold_every_triangle_within_the_bound():
    mesh = thin_strip(100)
    triangles = np.asarray(mesh.triangles)
    points = queries(mesh, 100, 1.0)
    bound = np.full(len(points), 0.5)
    rows, cols = TriangleIndex(triangles).candidates(points, bound)
    near = np.linalg.norm(
        trimesh.triangles.closest_point(triangles[np.tile(np.arange(len(triangles)), 100)],
                                        np.repeat(points, len(triangles), axis=0)) -
        np.repeat(points, len(triangles), axis=0), axis=1).reshape(100, -1) <= 0.5
    found = np.zeros_like(near)
    found[rows, cols] = True
    assert not (near & ~found).any()


def test_development_map_closest_distances_equal_brute_force():
    starts, ends = helix_tangent(200, 2)
    m = unroll_rulings(starts, ends).map
    triangles = m.vertices3d[m.triangles[m.proper]]
    rng = np.random.default_rng(2)
    points = triangles.mean(axis=1)[rng.integers(0, len(triangles), 300)] + rng.normal(0, 0.05, (300, 3))
    _, _, distances = m.closest(points)
    np.testing.assert_allclose(distances, brute_distances(triangles, points), rtol=0, atol=1e-12)
