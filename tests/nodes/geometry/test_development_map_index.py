"""The development map's point location on finely sampled strips (thousands of sliver
triangles): every point is found in the triangle it was made in, and polylines are split
at exactly the edges shapely finds them crossing (its speed: bench_development_map.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely

from tests.nodes.geometry.test_development_locate import helix_tangent
from torsal.nodes.geometry.unroll import unroll_rulings

RNG = np.random.default_rng(3)


def cone_to_apex(n: int) -> tuple[np.ndarray, np.ndarray]:
    """A right circular cone (radius 1, apex √3 up: slant 2) cut into n − 1 slivers, every
    ruling ending at the apex: half the triangles have no area."""
    phi = np.linspace(0.0, 2.0 * np.pi, n)
    base = np.column_stack([np.cos(phi), np.sin(phi), 0 * phi])
    return base, np.tile([0.0, 0.0, math.sqrt(3.0)], (n, 1))


def frustum(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Half a cone frustum between radius 1 and 0.5: long thin quads."""
    phi = np.linspace(0.0, np.pi, n)
    ring = np.column_stack([np.cos(phi), np.sin(phi), 0 * phi])
    return ring, 0.5 * ring + np.array([0.0, 0.0, 0.5 * math.sqrt(3.0)])


STRIPS = {
    "cone to its apex, 8,701 rulings": lambda: cone_to_apex(8701),
    "frustum, 5,000 rulings": lambda: frustum(5000),
    "tangent developable band, 3,000 rulings": lambda: helix_tangent(2999, 0.9),
}


def points_in(m, count: int) -> tuple[np.ndarray, np.ndarray]:
    """Random points strictly inside random triangles with area, and those triangles."""
    tri = RNG.choice(m.proper, size=count)
    weights = RNG.dirichlet(np.full(3, 2.0), size=count)
    return np.einsum("kj,kjd->kd", weights, m.vertices2d[m.triangles[tri]]), tri


@pytest.mark.parametrize("name", list(STRIPS))
def test_points_are_located_in_the_triangle_they_were_made_in(name):
    m = unroll_rulings(*STRIPS[name]()).map
    assert m._walk is not None and m._walk.coarse is not None  # the coarse-to-fine start
    points, made_in = points_in(m, 20_000)
    found, bary = m.locate(points)
    np.testing.assert_array_equal(found, made_in)
    assert bary.min() >= -1e-9


@pytest.mark.parametrize("name", list(STRIPS))
def test_points_on_the_rulings_are_located_in_a_triangle_beside_them(name):
    m = unroll_rulings(*STRIPS[name]()).map
    i = RNG.integers(1, m.n - 1, 5000)
    t = RNG.uniform(0.01, 0.99, 5000)
    points = m.vertices2d[i] + t[:, None] * (m.vertices2d[m.n + i] - m.vertices2d[i])
    found, bary = m.locate(points)
    assert np.all(np.isin(found, m.proper))
    assert bary.min() >= -1e-9
    # the triangles either side of ruling i belong to quads i − 1 and i
    assert np.all((found // 2 == i - 1) | (found // 2 == i))


@pytest.mark.parametrize("name", list(STRIPS))
def test_segments_are_split_where_shapely_finds_them_crossing_the_edges(name):
    development = unroll_rulings(*STRIPS[name]())
    m = development.map
    start, _ = points_in(m, 12)
    end, _ = points_in(m, 12)
    outline = shapely.Polygon(development.outline)
    inside = shapely.covers(outline, shapely.linestrings(np.stack([start, end], axis=1)))
    start, end = start[inside], end[inside]
    assert len(start) >= 4
    n = m.n
    i = np.arange(n - 1)
    edge_a = np.concatenate([np.arange(n), np.where(m.first_diagonal, i + 1, i)])
    edge_b = np.concatenate([n + np.arange(n), np.where(m.first_diagonal, n + i, n + i + 1)])
    edges = shapely.linestrings(np.stack([m.vertices2d[edge_a], m.vertices2d[edge_b]], axis=1))
    lines = shapely.linestrings(np.stack([start, end], axis=1))
    line_of, edge_of = shapely.STRtree(edges).query(lines, predicate="intersects")
    hits = shapely.intersection(lines[line_of], edges[edge_of])
    size = np.ptp(m.vertices2d, axis=0).max()
    for j, fine in enumerate(m.subdivide_many(list(np.stack([start, end], axis=1)))):
        p, q = start[j], end[j]
        points = shapely.get_coordinates(hits[line_of == j])
        along = (points - p) @ (q - p) / ((q - p) @ (q - p))
        expected = np.unique(np.round(along[(along > 1e-9) & (along < 1 - 1e-9)] * 1e9))  # one per point
        got = (fine[1:-1] - p) @ (q - p) / ((q - p) @ (q - p))
        assert np.array_equal(fine[[0, -1]], [p, q])
        assert len(got) == len(expected)
        assert np.abs(np.sort(got) - expected / 1e9).max() < 1e-8
        d, e = fine - p, q - p  # the 2D cross product: each point's offset from the line p-q
        assert np.abs(d[:, 0] * e[1] - d[:, 1] * e[0]).max() < 1e-12 * size * np.linalg.norm(e)
