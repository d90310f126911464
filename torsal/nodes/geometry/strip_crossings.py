"""Where a strip of rulings passes through itself: pairs of its triangles that cross.

The strip between consecutive rulings ``starts[i] → ends[i]`` is drawn as triangles: a
piece whose rulings share an end is one triangle (a fan through that point), any other
is a quad cut along its shorter diagonal. Two triangles *cross* when an edge of one
passes through the inside of the other. Triangles that share a corner (neighbours along
the strip, the triangles of one fan) touch there by construction, so only their edges
away from the shared corners are tested: two triangles meeting at one corner that cross
beyond it do so along a segment from that corner whose far end lies on such an edge.
Triangles sharing an edge fold about it; that is a crease (:mod:`.developable.kinds`),
not a crossing.

Candidate pairs are those whose bounding boxes overlap (a k-d tree of the boxes'
centres, searched in blocks so a long strip never holds all pairs at once); each is
then tested with the Möller–Trumbore segment–triangle test, all pairs at once. Touching
within ``1e-9`` of the strip's size does not count as crossing.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from .array_types import FloatArray, IntArray
from .vec_ops import cross, dot, norm

#: Touching within this share of the strip's size is not crossing.
TOUCH = 1e-9
#: Triangles whose neighbours are looked up at once (bounds the candidate pairs held).
_BLOCK = 256


@dataclass(frozen=True)
class Crossings:
    """Pairs of a strip's triangles that cross each other."""

    first: IntArray  #: the piece (between rulings i and i + 1) of one triangle of each pair
    second: IntArray  #: the piece of the other
    points: FloatArray  #: ``(k, 3)``: a point where each pair crosses

    def __len__(self) -> int:
        return len(self.first)


def strip_triangles(starts: FloatArray, ends: FloatArray) -> tuple[FloatArray, IntArray, IntArray]:
    """The strip's triangles: corners ``(m, 3, 3)``, the corners' vertex numbers ``(m, 3)``
    (one number per distinct point: a fan's apex is one vertex) and each triangle's piece."""
    a = np.asarray(starts, dtype=float).reshape(-1, 3)
    b = np.asarray(ends, dtype=float).reshape(-1, 3)
    n = len(a)
    points = np.concatenate([a, b])
    size = float(norm(points.max(axis=0) - points.min(axis=0))) if n else 0.0
    grid = np.round((points - points.min(axis=0)) / (size * 1e-12 or 1.0))
    _, vertex = np.unique(grid, axis=0, return_inverse=True)
    vertex = vertex.reshape(-1)
    va, vb = vertex[:n], vertex[n:]
    i = np.arange(n - 1)
    p0, p1, q0, q1 = va[:-1], va[1:], vb[:-1], vb[1:]
    fan_a = p0 == p1  # apex on A: the triangle A_i, B_i, B_i+1
    fan_b = (q0 == q1) & ~fan_a
    quad = ~fan_a & ~fan_b
    # a quad is cut along its shorter diagonal
    short = norm(b[1:] - a[:-1]) <= norm(a[1:] - b[:-1])
    rows = []
    rows.append((i[fan_a], np.stack([p0, q0, q1], axis=1)[fan_a]))
    rows.append((i[fan_b], np.stack([p0, q0, p1], axis=1)[fan_b]))
    qs = quad & short  # diagonal A_i → B_i+1
    rows.append((i[qs], np.stack([p0, q0, q1], axis=1)[qs]))
    rows.append((i[qs], np.stack([p0, q1, p1], axis=1)[qs]))
    ql = quad & ~short  # diagonal B_i → A_i+1
    rows.append((i[ql], np.stack([p0, q0, p1], axis=1)[ql]))
    rows.append((i[ql], np.stack([p1, q0, q1], axis=1)[ql]))
    piece = np.concatenate([r[0] for r in rows]).astype(np.int64)
    ids = np.concatenate([r[1] for r in rows]).astype(np.int64).reshape(-1, 3)
    unique_points = np.empty((int(vertex.max(initial=-1)) + 1, 3))
    unique_points[vertex] = points
    return unique_points[ids], ids, piece


def crossings(starts: FloatArray, ends: FloatArray) -> Crossings:
    """Pairs of the strip's triangles (:func:`strip_triangles`) that cross each other."""
    corners, ids, piece = strip_triangles(starts, ends)
    empty = Crossings(np.empty(0, np.int64), np.empty(0, np.int64), np.empty((0, 3)))
    if len(corners) < 2:
        return empty
    low, high = corners.min(axis=1), corners.max(axis=1)
    size = float(norm(high.max(axis=0) - low.min(axis=0)))
    eps = TOUCH * size
    centre, half = 0.5 * (low + high), 0.5 * (high - low)
    tree = cKDTree(centre)
    reach = 2.0 * float(half.max())
    found: list[tuple[IntArray, IntArray, FloatArray]] = []
    for start in range(0, len(corners), _BLOCK):
        rows = np.arange(start, min(start + _BLOCK, len(corners)))
        near = tree.query_ball_point(centre[rows], reach, p=np.inf)
        counts = np.fromiter((len(x) for x in near), dtype=np.int64, count=len(rows))
        if not counts.sum():
            continue
        i = np.repeat(rows, counts)
        j = np.concatenate([np.asarray(x, dtype=np.int64) for x in near if len(x)])
        keep = j > i
        i, j = i[keep], j[keep]
        overlap = (np.abs(centre[i] - centre[j]) <= half[i] + half[j] + eps).all(axis=1)
        i, j = i[overlap], j[overlap]
        if len(i):
            hit, point = _pairs_cross(corners, ids, i, j, eps)
            found.append((i[hit], j[hit], point[hit]))
    if not found:
        return empty
    i, j, points = (np.concatenate(parts) for parts in zip(*found, strict=True))
    return Crossings(piece[i], piece[j], points)


def _pairs_cross(
    corners: FloatArray, ids: IntArray, i: IntArray, j: IntArray, eps: float
) -> tuple[np.ndarray, FloatArray]:
    """Whether each pair (triangle i, triangle j) crosses, and a point where it does."""
    hit = np.zeros(len(i), dtype=bool)
    point = np.full((len(i), 3), np.nan)
    for one, other in ((i, j), (j, i)):
        for k in range(3):
            m = (k + 1) % 3
            # an edge touching the other triangle at a shared corner is not tested
            shared = (ids[one, k, None] == ids[other]) | (ids[one, m, None] == ids[other])
            free = ~shared.any(axis=1)
            h, x = _segment_through(corners[one, k], corners[one, m], corners[other], eps)
            new = free & h & ~hit
            point[new] = x[new]
            hit |= free & h
    return hit, point


def _segment_through(
    p: FloatArray, q: FloatArray, tri: FloatArray, eps: float
) -> tuple[np.ndarray, FloatArray]:
    """Whether segments ``p → q`` pass through the inside of triangles ``tri`` (``(k, 3, 3)``)
    more than ``eps`` from their edges and the segments' ends, and where."""
    d = q - p
    e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    h = cross(d, e2)
    det = dot(e1, h)
    normal = cross(e1, e2)
    area2 = norm(normal)
    length = norm(d)
    # the segment crosses the plane (not along it) by more than rounding
    ok = np.abs(det) > 1e-12 * np.maximum(length * area2, 1e-300)
    f = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
    sv = p - tri[:, 0]
    u = f * dot(sv, h)
    qv = cross(sv, e1)
    v = f * dot(d, qv)
    w = f * dot(e2, qv)
    # margins in parameter units: eps over the triangle's heights and the segment's length
    e3 = tri[:, 2] - tri[:, 1]
    longest = np.maximum(np.maximum(norm(e1), norm(e2)), norm(e3))
    height = area2 / np.maximum(longest, 1e-300)
    mu = eps / np.maximum(height, 1e-300)
    mw = eps / np.maximum(length, 1e-300)
    inside = ok & (u > mu) & (v > mu) & (u + v < 1.0 - mu) & (w > mw) & (w < 1.0 - mw)
    return inside, p + w[:, None] * d
