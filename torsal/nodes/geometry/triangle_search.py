"""Which triangles may hold the closest point to each query: a spatial index of triangles.

Each triangle is bounded by the ball about its centroid through its farthest corner.
A triangle can be within ``d`` of a point only if its ball is, so the candidates of a
query with bound ``d`` are the triangles whose centroid lies within ``d + r`` (``r`` the
ball's radius). One k-d tree for all triangles would have to use the largest ``r``:
on a strip of long thin triangles beside short ones that is most of the strip. The
triangles are therefore put in classes of radius (each within a factor of two), each
with its own tree, searched with its own largest radius.
"""

from __future__ import annotations

import itertools
from functools import cached_property

import numpy as np
from scipy.spatial import cKDTree

from torsal.nodes.geometry.array_types import FloatArray, IntArray

#: Most (point, triangle) pairs a block of :meth:`TriangleIndex.candidates` holds.
_PAIRS = 2_000_000
#: A point whose bound exceeds this share of a class's extent takes the whole class.
WIDE = 0.25


class TriangleIndex:
    """Candidate triangles near query points; ``corners`` is ``(t, 3, 3)``."""

    def __init__(self, corners: FloatArray) -> None:
        corners = np.asarray(corners, dtype=float)
        self.centres = corners.mean(axis=1)
        self.radii = np.linalg.norm(corners - self.centres[:, None], axis=2).max(axis=1)
        self.low, self.high = corners.min(axis=1), corners.max(axis=1)
        normal = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
        length = np.linalg.norm(normal, axis=1)
        # a degenerate triangle has no plane: its offset is 0, so the plane never excludes it
        self.normals = np.divide(
            normal, length[:, None], out=np.zeros_like(normal), where=length[:, None] > 0
        )
        self.offsets = np.einsum("ij,ij->i", self.normals, self.centres)

    @cached_property
    def _classes(self) -> list[tuple[IntArray, cKDTree, float, float]]:
        """(triangle numbers, tree of their centroids, largest radius, extent of the
        centroids) per radius class."""
        r = self.radii
        positive = r[r > 0]
        smallest = float(positive.min()) if positive.size else 1.0
        level = np.floor(np.log2(np.maximum(r, smallest) / smallest)).astype(np.int64)
        classes = []
        for k in np.unique(level):
            members = np.flatnonzero(level == k)
            centres = self.centres[members]
            extent = float(np.linalg.norm(np.ptp(centres, axis=0)))
            classes.append((members, cKDTree(centres), float(r[members].max()), extent))
        return classes

    def nearest_centre(self, points: FloatArray) -> IntArray:
        """The triangle whose centroid is nearest each point (a first guess)."""
        best = np.full(len(points), np.inf)
        owner = np.zeros(len(points), dtype=np.int64)
        for members, tree, _, _ in self._classes:
            d, i = tree.query(points)
            closer = d < best
            best[closer], owner[closer] = d[closer], members[i[closer]]
        return owner

    def candidates(self, points: FloatArray, bound: FloatArray) -> tuple[IntArray, IntArray]:
        """Pairs ``(point row, triangle)`` of every triangle that may be within ``bound``
        of its point (``bound`` per point): a superset, to be measured exactly. The balls
        found by the trees are thinned by two more lower bounds of the distance: to the
        triangle's bounding box and to its plane. A point whose bound reaches across
        most of a class (a point far from the mesh) takes the whole class, without the
        tree; points go in blocks, so that at most ~2·10⁶ pairs are held at once."""
        block = max(1, _PAIRS // max(1, len(self.radii)))
        parts = [self._block(points[i:i + block], bound[i:i + block]) for i in range(0, len(points), block)]
        if not parts:
            return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
        offsets = range(0, len(points), block)
        return (np.concatenate([rows + i for (rows, _), i in zip(parts, offsets, strict=True)]),
                np.concatenate([cols for _, cols in parts]))

    def _block(self, points: FloatArray, bound: FloatArray) -> tuple[IntArray, IntArray]:
        rows_all, cols_all = [], []
        for members, tree, radius, extent in self._classes:
            reach = bound + radius
            wide = bound > WIDE * extent
            narrow = np.flatnonzero(~wide)
            hits = tree.query_ball_point(points[narrow], reach[narrow], return_sorted=False)
            counts = np.fromiter(map(len, hits), dtype=np.int64, count=len(narrow))
            cols = np.fromiter(itertools.chain.from_iterable(hits), dtype=np.int64, count=int(counts.sum()))
            rows = np.repeat(narrow, counts)
            far = np.flatnonzero(wide)
            rows = np.concatenate([rows, np.repeat(far, len(members))])
            cols = members[np.concatenate([cols, np.tile(np.arange(len(members)), len(far))])]
            if len(rows) == 0:
                continue
            q, within = points[rows], bound[rows]
            gap = np.maximum(self.low[cols] - q, 0.0) + np.maximum(q - self.high[cols], 0.0)
            keep = np.einsum("ij,ij->i", gap, gap) <= within * within
            keep &= np.abs(np.einsum("ij,ij->i", self.normals[cols], q) - self.offsets[cols]) <= within
            rows_all.append(rows[keep])
            cols_all.append(cols[keep])
        if not rows_all:
            return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
        return np.concatenate(rows_all), np.concatenate(cols_all)
