"""Sections of surfaces and meshes by planes: the level lines of the height above a plane.

A triangle mesh (a mesh, or a surface's (u, v) grid cut into triangles) is cut where the
signed height ``h = (P − origin)·normal − level`` changes sign along an edge. Each cut
triangle gives one segment between two cut edges, so segments are chained through the
edges they share — by index, with no tolerance — into polylines
(:func:`scipy.sparse.csgraph.depth_first_order` walks each chain). A vertex lying exactly
on the plane counts as above it, so every triangle is cut on two edges or none.

On a mesh the crossing on an edge is interpolated linearly (the mesh is flat between its
vertices). On a parametric surface it is found on the surface itself: the height along
the edge's straight (u, v) segment is solved to rounding (scipy's vectorised
``find_root``), so every vertex of a section lies on the surface and on the plane; only
the straight pieces between them stray from the true curve (by the grid's chord error).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy.optimize.elementwise import find_root
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components, depth_first_order

from .array_types import FloatArray

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


class Sectioner:
    """Cuts one triangle mesh (or surface grid) by many planes, sharing its edge table."""

    def __init__(self, points: FloatArray, faces: np.ndarray, uv: FloatArray | None = None,
                 surface: SurfacePoints | None = None) -> None:
        self.points = np.asarray(points, dtype=float)
        self.faces = np.asarray(faces)
        self.edges, self.face_edges = _edges(self.faces)
        self.uv, self.surface = uv, surface

    def section(self, origin: FloatArray, normal: FloatArray) -> list[tuple[FloatArray, bool]]:
        """The section by the plane through ``origin`` with unit ``normal``: a list of
        ``(points (n, 3), closed)`` polylines (a closed one repeats its first point)."""
        height = (self.points - origin) @ normal
        above = height >= 0.0
        a, b = self.edges[:, 0], self.edges[:, 1]
        cut = above[a] != above[b]
        if not cut.any():
            return []
        cut_faces = cut[self.face_edges]
        faces = np.flatnonzero(cut_faces.any(axis=1))
        # each cut face has exactly two cut edges (the sign changes an even number of times)
        which = self.face_edges[faces][cut_faces[faces]].reshape(-1, 2)
        cut_ids = np.flatnonzero(cut)
        node = np.full(len(self.edges), -1)
        node[cut_ids] = np.arange(len(cut_ids))
        crossings = self._crossings(cut_ids, height, origin, normal)
        return _chains(node[which], crossings)

    def _crossings(self, ids: np.ndarray, height: FloatArray, origin: FloatArray,
                   normal: FloatArray) -> FloatArray:
        a, b = self.edges[ids, 0], self.edges[ids, 1]
        ha, hb = height[a], height[b]
        s = ha / (ha - hb)  # the linear estimate, in (0, 1] (ha and hb differ in sign)
        if self.surface is None or self.uv is None:
            return self.points[a] + s[:, None] * (self.points[b] - self.points[a])
        ua, ub = self.uv[a], self.uv[b]
        surface = self.surface

        def along(x: FloatArray, ua: FloatArray, ub: FloatArray) -> FloatArray:
            uv = ua + x[:, None] * (ub - ua)
            return (surface(uv) - origin) @ normal

        def flat(x: FloatArray, ua0: FloatArray, ua1: FloatArray, ub0: FloatArray,
                 ub1: FloatArray) -> FloatArray:
            shape = np.shape(x)
            ua = np.stack([np.ravel(ua0), np.ravel(ua1)], axis=1)
            ub = np.stack([np.ravel(ub0), np.ravel(ub1)], axis=1)
            return along(np.ravel(x), ua, ub).reshape(shape)

        found = find_root(flat, (np.zeros(len(ids)), np.ones(len(ids))),
                          args=(ua[:, 0], ua[:, 1], ub[:, 0], ub[:, 1]))
        x = np.where(found.success, found.x, s)
        uv = ua + x[:, None] * (ub - ua)
        return surface(uv)


def _chains(segments: np.ndarray, points: FloatArray) -> list[tuple[FloatArray, bool]]:
    """Polylines from segments between numbered points (each point on one or two segments)."""
    count = len(points)
    ones = np.ones(len(segments))
    graph = coo_matrix((ones, (segments[:, 0], segments[:, 1])), shape=(count, count)).tocsr()
    graph = graph + graph.T
    parts, labels = connected_components(graph, directed=False)
    degree = np.bincount(segments.ravel(), minlength=count)
    order = np.argsort(labels, kind="stable")
    starts = np.searchsorted(labels[order], np.arange(parts))
    chains: list[tuple[FloatArray, bool]] = []
    for part in range(parts):  # one walk per chain, not per point
        members = order[starts[part]: starts[part + 1] if part + 1 < parts else count]
        ends = members[degree[members] == 1]
        closed = len(ends) == 0
        start = int(ends.min()) if len(ends) else int(members.min())
        walk = depth_first_order(graph, start, directed=False, return_predecessors=False)
        if closed:
            walk = np.append(walk, walk[0])
        if len(walk) >= 2:
            chains.append((points[walk], closed))
    return chains
