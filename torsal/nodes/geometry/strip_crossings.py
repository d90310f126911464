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

from collections.abc import Iterator, Sequence
from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from .array_types import FloatArray, IntArray
from .vec_ops import cross, dot, flatnonzero, norm

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
    corners, ids, piece, _ = _triangles([(starts, ends)])
    return corners, ids, piece


def _triangles(
    strips: Sequence[tuple[FloatArray, FloatArray]],
) -> tuple[FloatArray, IntArray, IntArray, IntArray]:
    """:func:`strip_triangles` of every strip at once, strip after strip (each strip's in the
    order it has alone; vertex numbers distinct across strips), and each triangle's strip."""
    a_all = [np.asarray(starts, dtype=float).reshape(-1, 3) for starts, _ in strips]
    b_all = [np.asarray(ends, dtype=float).reshape(-1, 3) for _, ends in strips]
    n = np.array([len(a) for a in a_all], dtype=np.int64)
    a, b = np.concatenate(a_all), np.concatenate(b_all)
    # each strip's points: its starts then its ends (as the strip alone lists them)
    points = np.concatenate([np.concatenate([x, y]) for x, y in zip(a_all, b_all, strict=True)])
    rows = 2 * n
    has = rows > 0
    first = (np.cumsum(rows) - rows)[has]
    low = np.zeros((len(strips), 3))
    size = np.zeros(len(strips))
    if len(first):
        low[has] = np.minimum.reduceat(points, first, axis=0)
        size[has] = norm(np.maximum.reduceat(points, first, axis=0) - low[has])
    step = np.where(size * 1e-12 != 0, size * 1e-12, 1.0)  # (size·1e-12 or 1)
    strip_of_point = np.repeat(np.arange(len(strips)), rows)
    grid = np.round((points - low[strip_of_point]) / step[strip_of_point, None])
    # one vertex number per distinct point of a strip, numbered in the order of (strip, x, y,
    # z) as np.unique(axis=0) numbers them (a sort by the columns: several times faster)
    order = np.lexsort((grid[:, 2], grid[:, 1], grid[:, 0], strip_of_point))
    ranked, owner = grid[order], strip_of_point[order]
    new = np.ones(len(order), dtype=bool)
    new[1:] = (owner[1:] != owner[:-1]) | (ranked[1:] != ranked[:-1]).any(axis=1)
    vertex = np.empty(len(order), dtype=np.int64)
    vertex[order] = np.cumsum(new) - 1
    start_of = np.cumsum(rows) - rows  # (each strip's first point)
    ruling = np.arange(len(a))
    strip_of_ruling = np.repeat(np.arange(len(strips)), n)
    point_a = start_of[strip_of_ruling] + (ruling - (np.cumsum(n) - n)[strip_of_ruling])
    va, vb = vertex[point_a], vertex[point_a + n[strip_of_ruling]]
    # the pieces between consecutive rulings of one strip
    inner = flatnonzero(strip_of_ruling[1:] == strip_of_ruling[:-1])
    i = inner - (np.cumsum(n) - n)[strip_of_ruling[inner]]  # (each piece's number in its strip)
    p0, p1, q0, q1 = va[inner], va[inner + 1], vb[inner], vb[inner + 1]
    fan_a = p0 == p1  # apex on A: the triangle A_i, B_i, B_i+1
    fan_b = (q0 == q1) & ~fan_a
    quad = ~fan_a & ~fan_b
    # a quad is cut along its shorter diagonal
    short = norm(b[inner + 1] - a[inner]) <= norm(a[inner + 1] - b[inner])
    own = strip_of_ruling[inner]
    parts = []
    parts.append((i[fan_a], np.stack([p0, q0, q1], axis=1)[fan_a], own[fan_a]))
    parts.append((i[fan_b], np.stack([p0, q0, p1], axis=1)[fan_b], own[fan_b]))
    qs = quad & short  # diagonal A_i → B_i+1
    parts.append((i[qs], np.stack([p0, q0, q1], axis=1)[qs], own[qs]))
    parts.append((i[qs], np.stack([p0, q1, p1], axis=1)[qs], own[qs]))
    ql = quad & ~short  # diagonal B_i → A_i+1
    parts.append((i[ql], np.stack([p0, q0, p1], axis=1)[ql], own[ql]))
    parts.append((i[ql], np.stack([p1, q0, q1], axis=1)[ql], own[ql]))
    piece = np.concatenate([part[0] for part in parts]).astype(np.int64)
    ids = np.concatenate([part[1] for part in parts]).astype(np.int64).reshape(-1, 3)
    strip_of = np.concatenate([part[2] for part in parts]).astype(np.int64)
    order = np.argsort(strip_of, kind="stable")  # strip after strip, each in its own order
    unique_points = np.empty((int(vertex.max(initial=-1)) + 1, 3))
    unique_points[vertex] = points
    ids = ids[order]
    return unique_points[ids], ids, piece[order], strip_of[order]


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


def crossings_all(strips: Sequence[tuple[FloatArray, FloatArray]]) -> list[Crossings]:
    """:func:`crossings` of every strip ``(starts, ends)``: each strip's triangles its own
    (:func:`strip_triangles`), their candidate pairs found in one k-d tree of all strips'
    boxes (pairs within a strip only, each strip's reach and touching margin its own) and
    tested at once. Each strip's pairs come in the order :func:`crossings` gives them."""
    empty = Crossings(np.empty(0, np.int64), np.empty(0, np.int64), np.empty((0, 3)))
    results = [empty] * len(strips)
    if not strips:
        return results
    corners, ids, piece, strip_of = _triangles(strips)
    counts = np.bincount(strip_of, minlength=len(strips))
    tested = flatnonzero(counts >= 2)  # (a strip of fewer than two triangles cannot cross)
    if len(tested) == 0:
        return results
    if len(tested) < len(strips):
        keep = np.isin(strip_of, tested)
        corners, ids, piece = corners[keep], ids[keep], piece[keep]
    strip_of = np.repeat(np.arange(len(tested)), counts[tested])
    offsets = np.concatenate([[0], np.cumsum(counts[tested])])
    low, high = corners.min(axis=1), corners.max(axis=1)
    first = offsets[:-1]
    size = norm(np.maximum.reduceat(high, first, axis=0) - np.minimum.reduceat(low, first, axis=0))
    eps = TOUCH * size
    centre, half = 0.5 * (low + high), 0.5 * (high - low)
    reach = 2.0 * np.maximum.reduceat(half, first, axis=0).max(axis=1)
    # one tree of every strip's boxes, the strips set apart along a fourth axis further than
    # any reach, so that a search finds the boxes of the searching triangle's strip alone
    apart_by = 2.0 * float(reach.max()) + 1.0
    tree = cKDTree(np.column_stack([centre, strip_of * apart_by]))
    found: list[tuple[IntArray, IntArray, FloatArray]] = []
    # (there are no pairs across strips: at most each strip's pairs of triangles)
    most = int(np.sum(counts[tested] * (counts[tested] - 1) // 2))
    for i, j in _near_pairs(tree, float(reach.max()), most):
        own = strip_of[i]
        # pairs within that strip's reach whose boxes overlap
        apart = np.abs(centre[i] - centre[j])
        keep = (apart.max(axis=1) <= reach[own]) & (apart <= half[i] + half[j] + eps[own, None]).all(axis=1)
        i, j, own = i[keep], j[keep], own[keep]
        if len(i):
            hit, point = _pairs_cross(corners, ids, i, j, eps[own])
            found.append((i[hit], j[hit], point[hit]))
    if not found:
        return results
    i, j, points = (np.concatenate(parts) for parts in zip(*found, strict=True))
    own = strip_of[i]
    order = np.argsort(own, kind="stable")  # (each strip's pairs in the order of its own search)
    bounds = np.searchsorted(own[order], np.arange(len(tested) + 1)).tolist()
    spans = zip(tested.tolist(), bounds[:-1], bounds[1:], offsets[:-1].tolist(), strict=True)
    for k, low_row, high_row, _ in spans:
        if high_row > low_row:
            rows = order[low_row:high_row]
            results[k] = Crossings(piece[i[rows]], piece[j[rows]], points[rows])
    return results


#: Most candidate pairs searched at once (else in blocks of :data:`_BLOCK` triangles).
_MOST_PAIRS = 1 << 20


def _near_pairs(tree: cKDTree, reach: float, most: int) -> Iterator[tuple[IntArray, IntArray]]:
    """The pairs ``i < j`` of the tree's points within ``reach`` of each other (the greatest
    coordinate difference), ordered by i then j: all at once when there can be few (at most
    ``most``), else the pairs of :data:`_BLOCK` points at a time (so a long strip never
    holds all of them)."""
    if most <= _MOST_PAIRS:
        pairs = tree.query_pairs(reach, p=np.inf, output_type="ndarray")
        order = np.lexsort((pairs[:, 1], pairs[:, 0]))
        yield pairs[order, 0].astype(np.int64), pairs[order, 1].astype(np.int64)
        return
    for start in range(0, tree.n, _BLOCK):
        rows = np.arange(start, min(start + _BLOCK, tree.n))
        near = tree.query_ball_point(tree.data[rows], reach, p=np.inf)  # (each sorted)
        counts = np.fromiter((len(x) for x in near), dtype=np.int64, count=len(rows))
        i = np.repeat(rows, counts)
        j = np.concatenate([np.asarray(x, dtype=np.int64) for x in near if len(x)])
        keep = j > i
        yield i[keep], j[keep]


def _pairs_cross(
    corners: FloatArray, ids: IntArray, i: IntArray, j: IntArray, eps: float | FloatArray
) -> tuple[np.ndarray, FloatArray]:
    """Whether each pair (triangle i, triangle j) crosses, and a point where it does: the
    first of the edges of i, then of j, that passes through the other triangle. An edge
    touching the other triangle at a shared corner is not tested: of two triangles sharing
    an edge (neighbours along the strip, most of the pairs) none is, of two sharing a
    corner one each way."""
    n = len(i)
    one, other = np.concatenate([i, j]), np.concatenate([j, i])  # (both ways, one after the other)
    ids_one = ids[one]
    shared = (ids_one[:, :, None] == ids[other][:, None, :]).any(axis=2)  # corner k of one is the other's
    row, edge = np.nonzero(~(shared | shared[:, _NEXT]))  # edge k, from corner k to corner k + 1
    margin = np.concatenate([eps, eps])[row] if np.ndim(eps) else eps
    ends = corners[one[row]]
    h, x = _segment_through(ends[np.arange(len(row)), edge], ends[np.arange(len(row)), _NEXT[edge]],
                            corners[other[row]], margin)
    # per pair: the edges of i (k = 0, 1, 2), then of j; the first that crosses gives the point
    order, pair = 3 * (row // n) + edge, row % n
    hits = np.zeros((6, n), dtype=bool)
    hits[order[h], pair[h]] = True
    points = np.full((6, n, 3), np.nan)
    points[order[h], pair[h]] = x[h]
    first = hits.argmax(axis=0)
    return hits.any(axis=0), points[first, np.arange(n)]


#: Each corner's next (the other end of the edge from it).
_NEXT = np.array([1, 2, 0])


def _segment_through(
    p: FloatArray, q: FloatArray, tri: FloatArray, eps: float | FloatArray
) -> tuple[np.ndarray, FloatArray]:
    """Whether segments ``p → q`` pass through the inside of triangles ``tri`` (``(k, 3, 3)``;
    the segments ``(k, 3)``, or ``(e, k, 3)`` for ``e`` segments against each triangle) more
    than ``eps`` from their edges and the segments' ends, and where."""
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
    return inside, p + w[..., None] * d
