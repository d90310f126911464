"""Sections of surfaces and meshes by planes: the level lines of the height above a plane.

A triangle mesh (a mesh, or a surface's (u, v) grid cut into triangles) is cut where the
signed height ``h = (P − origin)·normal − level`` changes sign along an edge. Each cut
triangle gives one segment between two cut edges, so segments are chained through the
edges they share — by index, with no tolerance — into polylines
(every chain walked at once, a step of all of them per round). A vertex lying exactly
on the plane counts as above it, so every triangle is cut on two edges or none.

On a mesh the crossing on an edge is interpolated linearly (the mesh is flat between its
vertices). On a parametric surface it is found on the surface itself: the height along
the edge's straight (u, v) segment is solved to rounding (scipy's vectorised
``find_root``), so every vertex of a section lies on the surface and on the plane; only
the straight pieces between them stray from the true curve (by the grid's chord error).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np
from scipy.optimize.elementwise import find_root
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from .array_types import FloatArray

#: Level × edge cells cut in one block (booleans; a few tens of MB at most).
_BLOCK = 4_000_000

#: A function from (m, 2) (u, v) to (m, 3) points of a surface.
SurfacePoints = Callable[[FloatArray], FloatArray]


def grid_triangles(nu: int, nv: int) -> np.ndarray:
    """The triangles of an ``nu × nv`` grid of vertices numbered ``i * nv + j``."""
    i, j = np.meshgrid(np.arange(nu - 1), np.arange(nv - 1), indexing="ij")
    a = (i * nv + j).ravel()
    b, c, d = a + nv, a + nv + 1, a + 1
    return np.concatenate([np.stack([a, b, c], axis=1), np.stack([a, c, d], axis=1)])


def _edges(faces: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The unique edges ``(k, 2)`` (low vertex first) and, per face, its three edges' ids."""
    pairs = np.sort(faces[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    edges, inverse = np.unique(pairs, axis=0, return_inverse=True)
    return edges, inverse.reshape(-1, 3)


class Chain(NamedTuple):
    """One section polyline: its points (a closed one repeats its first), and on a
    parametric surface their (u, v)."""

    points: FloatArray
    closed: bool
    uv: FloatArray | None


class Sectioner:
    """Cuts one triangle mesh (or surface grid) by many planes, sharing its edge table."""

    def __init__(self, points: FloatArray, faces: np.ndarray, uv: FloatArray | None = None,
                 surface: SurfacePoints | None = None) -> None:
        self.points = np.asarray(points, dtype=float)
        self.faces = np.asarray(faces)
        self.edges, self.face_edges = _edges(self.faces)
        self.uv, self.surface = uv, surface

    def section(self, origin: FloatArray, normal: FloatArray) -> list[Chain]:
        """The section by the plane through ``origin`` with unit ``normal``: a list of
        ``(points (n, 3), closed)`` polylines (a closed one repeats its first point)."""
        return self.sections(origin, normal, np.zeros(1))[0]

    def sections(self, origin: FloatArray, normal: FloatArray, levels: FloatArray
                 ) -> list[list[Chain]]:
        """The sections by the planes ``level`` along unit ``normal`` from ``origin``, one
        list of polylines per level. The levels are cut together in blocks (one pass over
        the mesh per block, one root search for every crossing of the block)."""
        height = (self.points - origin) @ normal
        block = max(1, _BLOCK // max(len(self.edges), 1))
        out: list[list[Chain]] = []
        for first in range(0, len(levels), block):
            out += self._block(height, origin, normal, np.asarray(levels[first:first + block], dtype=float))
        return out

    def _block(self, height: FloatArray, origin: FloatArray, normal: FloatArray, levels: FloatArray
               ) -> list[list[Chain]]:
        above = height[None, :] >= levels[:, None]  # (levels, points)
        a, b = self.edges[:, 0], self.edges[:, 1]
        cut = above[:, a] != above[:, b]  # (levels, edges)
        cut_ids = np.flatnonzero(cut)  # level-major: each level's crossings are one run
        edge_count = len(self.edges)
        level_of, edge_of = np.divmod(cut_ids, edge_count)
        node = np.full(cut.size, -1)
        node[cut_ids] = np.arange(len(cut_ids))
        cut_faces = cut[:, self.face_edges]  # (levels, faces, 3)
        level_face = np.flatnonzero(cut_faces.any(axis=2))
        face_level, face = np.divmod(level_face, len(self.faces))
        # each cut face has exactly two cut edges (the sign changes an even number of times)
        pairs = self.face_edges[face][cut_faces[face_level, face]].reshape(-1, 2)
        segments = node[face_level[:, None] * edge_count + pairs]
        crossings, uv = self._crossings(edge_of, height, levels[level_of], origin, normal)
        out: list[list[Chain]] = [[] for _ in levels]
        for walk, closed in _walks(segments, len(cut_ids)):  # one chain of one level each
            out[level_of[walk[0]]].append(Chain(crossings[walk], closed, None if uv is None else uv[walk]))
        return out

    def _crossings(self, ids: np.ndarray, height: FloatArray, level: FloatArray, origin: FloatArray,
                   normal: FloatArray) -> tuple[FloatArray, FloatArray | None]:
        """Where each edge ``ids[i]`` crosses the plane at ``level[i]``, and its (u, v) on a surface."""
        a, b = self.edges[ids, 0], self.edges[ids, 1]
        ha, hb = height[a] - level, height[b] - level
        s = ha / (ha - hb)  # the linear estimate, in (0, 1] (ha and hb differ in sign)
        if self.surface is None or self.uv is None:
            return self.points[a] + s[:, None] * (self.points[b] - self.points[a]), None
        ua, ub = self.uv[a], self.uv[b]
        surface = self.surface

        def flat(x: FloatArray, ua0: FloatArray, ua1: FloatArray, ub0: FloatArray,
                 ub1: FloatArray, lv: FloatArray) -> FloatArray:
            shape = np.shape(x)
            ua = np.stack([np.ravel(ua0), np.ravel(ua1)], axis=1)
            ub = np.stack([np.ravel(ub0), np.ravel(ub1)], axis=1)
            uv = ua + np.ravel(x)[:, None] * (ub - ua)
            return ((surface(uv) - origin) @ normal - np.ravel(lv)).reshape(shape)

        if not len(ids):
            return np.empty((0, 3)), np.empty((0, 2))
        found = find_root(flat, (np.zeros(len(ids)), np.ones(len(ids))),
                          args=(ua[:, 0], ua[:, 1], ub[:, 0], ub[:, 1], level))
        x = np.where(found.success, found.x, s)
        uv = ua + x[:, None] * (ub - ua)
        return surface(uv), uv


def _walks(segments: np.ndarray, count: int) -> list[tuple[np.ndarray, bool]]:
    """Each chain of the graph on ``count`` nodes joined by ``segments`` (a node on one or
    two segments), as its nodes in order and whether it closes. Every chain is walked at
    once, a step of all of them per round (rounds: the longest chain's length)."""
    if not len(segments):
        return []
    ends, other = segments.ravel(), segments[:, ::-1].ravel()
    order = np.argsort(ends, kind="stable")
    first = np.searchsorted(ends[order], np.arange(count))
    slot = np.arange(len(order)) - first[ends[order]]
    keep = slot < 2  # a node on three or more segments (a non-manifold mesh) breaks its chain there
    neighbours = np.full((count, 2), -1)
    neighbours[ends[order][keep], slot[keep]] = other[order][keep]
    degree = (neighbours >= 0).sum(axis=1)
    graph = coo_matrix((np.ones(len(segments)), (segments[:, 0], segments[:, 1])), shape=(count, count))
    parts, labels = connected_components(graph, directed=False)
    key = np.where(degree == 1, np.arange(count), np.arange(count) + count)  # an open chain starts at an end
    best = np.full(parts, 2 * count)
    np.minimum.at(best, labels, key)
    closed = best >= count
    start = np.where(closed, best - count, best)
    current, previous = start.copy(), np.full(parts, -1)
    steps = [current]
    active = np.ones(parts, dtype=bool)
    while active.any():
        n0, n1 = neighbours[current, 0], neighbours[current, 1]
        following = np.where(n0 != previous, n0, n1)
        back = closed & (following == start)
        going = active & (following >= 0) & ~back
        steps.append(np.where(going | (active & back), following, -1))
        previous, current = current, np.where(going, following, current)
        active = going
    walks = np.stack(steps, axis=1)  # (chains, rounds), -1 past each chain's end
    lengths = (walks >= 0).sum(axis=1)
    return [(walks[i, :lengths[i]], bool(closed[i])) for i in range(parts) if lengths[i] >= 2]
