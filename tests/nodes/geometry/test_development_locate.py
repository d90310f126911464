"""DevelopmentMap.locate (plane → surface for SurfacePatching): the walk along the strip
finds the same surface points as a brute-force search over every triangle (its speed:
tests/benchmarks/bench_unroll.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsal.nodes.geometry.unroll import unroll_rulings


def cylinder(n: int = 60) -> tuple[np.ndarray, np.ndarray]:
    phi = np.linspace(0.0, 2.0 * np.pi, n + 1)
    base = np.column_stack([np.cos(phi), np.sin(phi), 0 * phi])
    base[-1] = base[0]
    return base, base + np.array([0.0, 0.0, 2.0])


def cone_fan(n: int = 40) -> tuple[np.ndarray, np.ndarray]:
    """Rulings from a circle to the apex: every other triangle of the strip is degenerate."""
    phi = np.linspace(0.0, 1.5 * np.pi, n)
    base = np.column_stack([np.cos(phi), np.sin(phi), 0 * phi])
    return base, np.tile([0.0, 0.0, 1.5], (n, 1))


def helix_tangent(n: int, turns: float) -> tuple[np.ndarray, np.ndarray]:
    t = np.linspace(0.0, 2.0 * np.pi * turns, n + 1)
    c = np.column_stack([2.0 * np.cos(t), 2.0 * np.sin(t), 0.5 * t])
    d = np.column_stack([-2.0 * np.sin(t), 2.0 * np.cos(t), np.full_like(t, 0.5)])
    return c, c + 3.0 * d / np.linalg.norm(d, axis=1, keepdims=True)


def brute_force_3d(development, points: np.ndarray) -> np.ndarray:
    """Every point against every triangle: the lowest-numbered one containing it, else the
    nearest by its barycentric coordinates clipped (the reference the walk must match)."""
    m = development.map
    corners = m.vertices2d[m.triangles[m.proper]]  # (t, 3, 2)
    e1, e2 = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
    area2 = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    d = points[:, None, :] - corners[None, :, 0]
    v = (d[..., 0] * e2[None, :, 1] - d[..., 1] * e2[None, :, 0]) / area2
    w = (e1[None, :, 0] * d[..., 1] - e1[None, :, 1] * d[..., 0]) / area2
    bary = np.stack([1 - v - w, v, w], axis=-1)
    inside = (bary >= -1e-12).all(axis=-1)
    assert inside.any(axis=1).all(), "the reference is for points inside the development"
    first = np.argmax(inside, axis=1)
    tri = m.proper[first]
    chosen = bary[np.arange(len(points)), first]
    return np.einsum("kj,kjd->kd", chosen, m.vertices3d[m.triangles[tri]])


def inside_points(development, count: int, seed: int = 0) -> np.ndarray:
    """Random points of the development (random barycentric points of random triangles)."""
    m = development.map
    rng = np.random.default_rng(seed)
    tri = rng.choice(m.proper, size=count)
    weights = rng.dirichlet(np.ones(3), size=count)
    return np.einsum("kj,kjd->kd", weights, m.vertices2d[m.triangles[tri]])


@pytest.mark.parametrize(
    "rulings",
    [cylinder(), cone_fan(), helix_tangent(80, 0.7), helix_tangent(120, 1.3)],
    ids=["cylinder", "cone fan", "helix band", "overlapping helix band"],
)
def test_points_of_the_development_map_to_the_same_surface_points_as_a_brute_force_search(rulings):
    development = unroll_rulings(*rulings)
    points = inside_points(development, 3000)
    m = development.map
    if not development.overlaps:
        # vertices and edge midpoints too: points on the edges shared by two triangles
        # (where a development overlaps itself, which of two triangles an edge point
        # falls in is decided by rounding, and the two differ there)
        corners = m.vertices2d[m.triangles[m.proper]]
        edges = 0.5 * (corners + np.roll(corners, -1, axis=1)).reshape(-1, 2)
        points = np.vstack([points, corners.reshape(-1, 2), edges])
    mapped = m.to_3d(points)
    size = np.ptp(m.vertices3d, axis=0).max()
    np.testing.assert_allclose(mapped, brute_force_3d(development, points), atol=1e-12 * size)


def test_the_walk_is_used_unless_the_development_overlaps_itself():
    assert unroll_rulings(*helix_tangent(80, 0.7)).map._walk is not None
    assert unroll_rulings(*helix_tangent(120, 1.3)).map._walk is None


def test_a_cone_whose_rulings_share_their_end_does_not_overlap_itself():
    development = unroll_rulings(*cone_fan())
    assert not development.overlaps
    assert development.map._walk is not None


def test_points_outside_the_development_take_the_nearest_triangle():
    development = unroll_rulings(*cylinder(24))
    m = development.map
    lo, hi = m.vertices2d.min(axis=0), m.vertices2d.max(axis=0)
    outside = np.array([[lo[0] - 0.01, 0.5 * (lo[1] + hi[1])], [hi[0] + 0.01, hi[1] + 0.01]])
    tri, bary = m.locate(outside)
    assert np.all(np.isin(tri, m.proper))
    # extrapolated by the nearest triangle's affine map: just beyond the first and last ruling
    assert np.all(bary.min(axis=1) < 0)


def test_twenty_thousand_points_are_located_by_the_walk_inside_their_triangles():
    """How fast, against a scipy k-d tree query in the same run: bench_unroll.py."""
    development = unroll_rulings(*helix_tangent(400, 0.9))
    points = inside_points(development, 20_000, seed=1)
    walk = development.map._walk
    assert walk is not None
    tri, bary = development.map.locate(points)
    np.testing.assert_array_equal(tri, walk.triangles(points))  # none left to the slower fallback
    assert bary.min() >= -1e-9  # each point inside the triangle it walked to
    assert math.isfinite(float(development.map.to_3d(points).sum()))
