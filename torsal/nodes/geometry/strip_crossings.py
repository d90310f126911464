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


def strip_triangles(
    starts: FloatArray, ends: FloatArray, owner: IntArray | None = None
) -> tuple[FloatArray, IntArray, IntArray]:
    """The strip's triangles: corners ``(m, 3, 3)``, the corners' vertex numbers ``(m, 3)``
    (one number per point of each edge, a run of rulings sharing an end — a fan's apex —
    sharing its number) and each triangle's piece (its first ruling's row). ``owner``
    numbers the strip of each row, for rulings of several strips one after the other:
    no piece joins two strips."""
    a = np.asarray(starts, dtype=float).reshape(-1, 3)
    b = np.asarray(ends, dtype=float).reshape(-1, 3)
    n = len(a)
    if owner is None:
        owner = np.zeros(n, dtype=np.int64)
    joined = owner[1:] == owner[:-1]
    # each strip's size (the ends' box), for what counts as the same point
    size = np.zeros(int(owner.max(initial=-1)) + 1)
    if n:
        low = np.full((len(size), 3), np.inf)
        high = np.full((len(size), 3), -np.inf)
        np.minimum.at(low, owner, np.minimum(a, b))
        np.maximum.at(high, owner, np.maximum(a, b))
        size = norm(high - low)
    tol = 1e-12 * size[owner[:-1]] if n else np.empty(0)
    same_a = (norm(a[1:] - a[:-1]) <= tol) & joined
    same_b = (norm(b[1:] - b[:-1]) <= tol) & joined
    va = np.concatenate([[0], np.cumsum(~same_a)])
    vb = np.concatenate([[0], np.cumsum(~same_b)]) + int(va[-1]) + 1
    i = np.arange(n - 1)
    p0, p1, q0, q1 = va[:-1], va[1:], vb[:-1], vb[1:]
    fan_a = same_a  # apex on A: the triangle A_i, B_i, B_i+1
    fan_b = same_b & ~fan_a
    quad = ~fan_a & ~fan_b & joined
    short = norm(b[1:] - a[:-1]) <= norm(a[1:] - b[:-1])  # a quad is cut along its shorter diagonal
    qs, ql = quad & short, quad & ~short
    corners_of = (  # (rows, its three corners) of each triangle, by sort of piece
        (fan_a, (p0, q0, q1)), (fan_b, (p0, q0, p1)), (qs, (p0, q0, q1)), (qs, (p0, q1, p1)),
        (ql, (p0, q0, p1)), (ql, (p1, q0, q1)),
    )
    piece = np.concatenate([i[rows] for rows, _ in corners_of]).astype(np.int64)
    ids = np.concatenate([np.stack(v, axis=1)[rows] for rows, v in corners_of]).astype(np.int64)
    ids = ids.reshape(-1, 3)
    vertices = np.empty((int(vb[-1]) + 1, 3))
    vertices[va], vertices[vb] = a, b
    return vertices[ids], ids, piece


_NONE = Crossings(np.empty(0, np.int64), np.empty(0, np.int64), np.empty((0, 3)))

#: Below this many triangles every pair is looked at; above, only those a k-d tree finds near.
_ALL_PAIRS = 400


def crossings(starts: FloatArray, ends: FloatArray) -> Crossings:
    """Pairs of the strip's triangles (:func:`strip_triangles`) that cross each other."""
    return crossings_of([(starts, ends)])[0]


def crossings_of(strips: list[tuple[FloatArray, FloatArray]]) -> list[Crossings]:
    """:func:`crossings` of each strip ``(starts, ends)``, all tested at once (each strip's
    triangles only against its own: the fixed costs of the tests are paid once)."""
    rows_per = np.array([len(np.asarray(a).reshape(-1, 3)) for a, _ in strips], dtype=np.int64)
    if not len(strips) or not rows_per.sum():
        return [_NONE for _ in strips]
    owner_rows = np.repeat(np.arange(len(strips)), rows_per)
    corners, ids, piece_all = strip_triangles(
        np.concatenate([np.asarray(a, dtype=float).reshape(-1, 3) for a, _ in strips]),
        np.concatenate([np.asarray(b, dtype=float).reshape(-1, 3) for _, b in strips]),
        owner_rows,
    )
    order = np.argsort(owner_rows[piece_all], kind="stable")  # triangles strip by strip
    corners, ids, piece_all = corners[order], ids[order], piece_all[order]
    strip_of = owner_rows[piece_all]
    piece = piece_all - np.concatenate([[0], np.cumsum(rows_per)])[strip_of]  # row within its strip
    counts = np.bincount(strip_of, minlength=len(strips)).astype(np.int64)
    first = np.concatenate([[0], np.cumsum(counts)])
    parts = range(len(strips))
    low, high = corners.min(axis=1), corners.max(axis=1)
    box_low = np.full((len(strips), 3), np.inf)
    box_high = np.full((len(strips), 3), -np.inf)
    np.minimum.at(box_low, strip_of, low)
    np.maximum.at(box_high, strip_of, high)
    eps = TOUCH * np.where(counts > 0, norm(np.where(counts[:, None] > 0, box_high - box_low, 0.0)), 0.0)
    centre, half = 0.5 * (low + high), 0.5 * (high - low)
    pairs: list[tuple[IntArray, IntArray]] = []
    for k in range(len(parts)):
        m = int(counts[k])
        if m < 2:
            continue
        if m <= _ALL_PAIRS:
            i, j = np.triu_indices(m, 1)
            pairs.append((i + first[k], j + first[k]))
            continue
        rows_k = slice(first[k], first[k + 1])
        tree = cKDTree(centre[rows_k])
        reach = 2.0 * float(half[rows_k].max())
        for start in range(0, m, _BLOCK):
            rows = np.arange(start, min(start + _BLOCK, m))
            near = tree.query_ball_point(centre[rows_k][rows], reach, p=np.inf)
            lengths = np.fromiter((len(x) for x in near), dtype=np.int64, count=len(rows))
            if not lengths.sum():
                continue
            i = np.repeat(rows, lengths)
            j = np.concatenate([np.asarray(x, dtype=np.int64) for x in near if len(x)])
            later = j > i
            pairs.append((i[later] + first[k], j[later] + first[k]))
    found_i, found_j, found_x = [], [], []
    if pairs:  # (all strips' pairs tested at once)
        pairs = [(np.concatenate([i for i, _ in pairs]), np.concatenate([j for _, j in pairs]))]
    for i, j in pairs:
        i, j = np.asarray(i, dtype=np.int64), np.asarray(j, dtype=np.int64)
        e = eps[strip_of[i]]
        keep = (np.abs(centre[i] - centre[j]) <= half[i] + half[j] + e[:, None]).all(axis=1)
        i, j = i[keep], j[keep]
        # neighbours along the strip share an edge (two corners): no edge of either is free
        shared = (ids[i, :, None] == ids[j, None, :]).any(axis=2).sum(axis=1)
        i, j = i[shared < 2], j[shared < 2]
        if len(i):
            hit, point = _pairs_cross(corners, ids, i, j, eps[strip_of[i]])
            found_i.append(i[hit])
            found_j.append(j[hit])
            found_x.append(point[hit])
    if found_i:
        i, j, x = np.concatenate(found_i), np.concatenate(found_j), np.concatenate(found_x)
    else:
        i = j = np.empty(0, np.int64)
        x = np.empty((0, 3))
    owner = strip_of[i]
    return [Crossings(piece[i[owner == k]], piece[j[owner == k]], x[owner == k]) for k in parts]


def _pairs_cross(
    corners: FloatArray, ids: IntArray, i: IntArray, j: IntArray, eps: FloatArray
) -> tuple[np.ndarray, FloatArray]:
    """Whether each pair (triangle i, triangle j) crosses, and a point where it does: the
    three edges of each against the other, all six at once."""
    k = len(i)
    one = np.concatenate([i, j])  # the triangle whose edges are tested, against the other's inside
    other = np.concatenate([j, i])
    start = np.array([0, 1, 2])
    stop = np.array([1, 2, 0])
    # (edge e of triangle ``one``): rows ordered edge-major, (3, 2k)
    p = corners[one][:, start].transpose(1, 0, 2).reshape(-1, 3)
    q = corners[one][:, stop].transpose(1, 0, 2).reshape(-1, 3)
    tri = np.tile(corners[other], (3, 1, 1))
    ends_ids = np.stack([ids[one][:, start].T.reshape(-1), ids[one][:, stop].T.reshape(-1)], axis=1)
    others = np.tile(ids[other], (3, 1))
    # an edge touching the other triangle at a shared corner is not tested
    free = ~(ends_ids[:, :, None] == others[:, None, :]).any(axis=(1, 2))
    h, x = _segment_through(p, q, tri, np.tile(eps, 6))
    h &= free
    h = h.reshape(6, k)  # (edge of i or j, pair)
    x = x.reshape(6, k, 3)
    hit = h.any(axis=0)
    first = np.argmax(h, axis=0)
    return hit, x[first, np.arange(k)]


def _segment_through(
    p: FloatArray, q: FloatArray, tri: FloatArray, eps: FloatArray
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
