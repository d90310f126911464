"""Which triangle of a strip's development holds each point: a walk along the strip,
started from a coarser copy of the same strip.

A development's triangles form a chain: chain position ``k`` is the triangle between edges
E_k and E_{k+1} (the rulings and diagonals in order, each from its A end to its B end), and
a point to the right of E_{k+1} lies further along. A point that starts next to its
triangle walks to it in a few steps, all points at once (each pass moves every point still
walking one triangle on, always the same way).

The start. A k-d tree of sample points per triangle, nearest sample first, is cheap on
triangles of about equal sides, but the triangles of a finely sampled strip are slivers
(a cone at 8,700 rulings: 2,000 times longer than wide), and the nearest sample is then
searched among thousands of equally near ones. So the strip is thinned: every
:data:`STRIDE`-th ruling (and the last) makes a coarser strip, whose triangles are that
many times wider, again until at most :data:`TOP` rulings are left. Only that coarsest
strip starts from the k-d tree. Each finer one starts a point in the middle of the coarse
quad it was found in (the coarse rulings are among its own), walks at most 2·STRIDE steps
and checks the triangle it reaches; a point it does not hold (a walk can go astray where
the lines of edges a few steps apart cross inside the strip, as on a tangent developable
near its edge of regression) is looked up among the triangles of that coarse quad and of
its two neighbours. Cost per point: a few steps per level, log₈ of the rulings levels.
The caller checks the final triangle and looks elsewhere (a slower search) for any point
it does not hold (one outside the development).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from scipy.spatial import cKDTree

from torsal.nodes.geometry.array_types import FloatArray, IntArray
from torsal.nodes.geometry.vec_ops import cross2, linalg_norm

#: Every STRIDE-th ruling makes the next coarser strip.
STRIDE = 8
#: A strip of at most this many rulings starts its points from a k-d tree of samples.
TOP = 256
#: Twice a triangle's area below this share of the strip's size² makes it no start.
PROPER_AREA = 1e-13
#: Points closer to an edge's line than this share of the size² (as a cross product)
#: count as on it: the walk does not step over it.
ON_EDGE = 1e-12
#: A point whose barycentric coordinates in a triangle are all above −HELD lies in it.
HELD = 1e-9


def strip_triangles(n: int, first_diagonal: NDArray[np.bool_]) -> IntArray:
    """Vertex indices of the 2(n − 1) triangles of an n-ruling strip, counter-clockwise.

    Vertex ``i`` is A_i (a start), vertex ``n + i`` is B_i (an end). Quad i gives
    triangles 2i and 2i + 1: along diagonal A_{i+1}B_i (``first_diagonal[i]``) they are
    (A_i, A_{i+1}, B_i) and (A_{i+1}, B_{i+1}, B_i), along A_iB_{i+1} they are
    (A_i, A_{i+1}, B_{i+1}) and (A_i, B_{i+1}, B_i).
    """
    i = np.arange(n - 1)
    a0, a1, b0, b1 = i, i + 1, n + i, n + i + 1
    first = np.where(first_diagonal[:, None], np.column_stack([a0, a1, b0]),
                     np.column_stack([a0, a1, b1]))
    second = np.where(first_diagonal[:, None], np.column_stack([a1, b1, b0]),
                      np.column_stack([a0, b1, b0]))
    return np.stack([first, second], axis=1).reshape(-1, 3).astype(np.int64)


class StripWalk:
    """Locates points of a (not self-overlapping) development along its chain of
    triangles; ``vertices2d`` is ``(2n, 2)``: the n starts A_i, then the n ends B_i."""

    #: Samples per triangle of the coarsest strip (barycentric weights): its centroid,
    #: three points near its corners and its three edge midpoints.
    WEIGHTS = np.array([[2, 2, 2], [4, 1, 1], [1, 4, 1], [1, 1, 4], [3, 3, 0], [0, 3, 3], [3, 0, 3]]) / 6.0

    def __init__(self, vertices2d: FloatArray, first_diagonal: NDArray[np.bool_]) -> None:
        n = len(vertices2d) // 2
        self.n = n
        i = np.arange(n - 1)
        forward = first_diagonal.astype(np.int64)
        #: chain position → triangle (quad i: along A_{i+1}B_i triangle 2i comes first,
        #: along A_iB_{i+1} triangle 2i + 1)
        self.chain = np.column_stack([2 * i + 1 - forward, 2 * i + forward]).reshape(-1)
        diagonal_a = np.where(first_diagonal, i + 1, i)
        diagonal_b = n + np.where(first_diagonal, i, i + 1)
        edge_a = np.column_stack([i, diagonal_a]).reshape(-1)
        edge_b = np.column_stack([n + i, diagonal_b]).reshape(-1)
        #: edge k (k = 0 … 2n − 2) from its A end, and its vector to its B end
        self.edge_start = vertices2d[np.append(edge_a, n - 1)]
        self.edge_vector = vertices2d[np.append(edge_b, 2 * n - 1)] - self.edge_start
        size = float(np.ptp(vertices2d, axis=0).max()) or 1.0
        self.tolerance = ON_EDGE * size * size
        corners = vertices2d[strip_triangles(n, first_diagonal)]
        e1, e2 = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
        proper = cross2(e1, e2) > PROPER_AREA * size * size
        #: whether the triangle at each chain position has area (a point can be in it)
        self.proper = proper[self.chain]
        self.coarse: StripWalk | None = None
        if n > TOP:
            keep = np.unique(np.append(np.arange(0, n, STRIDE), n - 1))
            a, b = vertices2d[:n][keep], vertices2d[n:][keep]
            diagonal = linalg_norm(a[1:] - b[:-1]) <= linalg_norm(b[1:] - a[:-1])
            self.coarse = StripWalk(np.vstack([a, b]), diagonal)
            #: per coarse quad, the chain positions of its triangles here: from, how many
            self.coarse_first, self.coarse_count = 2 * keep[:-1], 2 * np.diff(keep)
            # per chain position: the first corner and the inverse of the triangle's edge
            # matrix [e1 e2], which give a point's barycentric coordinates (v, w)
            at = corners[self.chain]
            e1, e2 = at[:, 1] - at[:, 0], at[:, 2] - at[:, 0]
            det = cross2(e1, e2)
            det = np.where(self.proper, det, 1.0)
            self.origin = at[:, 0]
            self.inverse = np.stack([np.column_stack([e2[:, 1], -e2[:, 0]]),
                                     np.column_stack([-e1[:, 1], e1[:, 0]])], axis=1) / det[:, None, None]
        else:
            position = np.empty(len(self.chain), dtype=np.int64)
            position[self.chain] = np.arange(len(self.chain))
            starts = np.flatnonzero(proper)
            if starts.size == 0:  # no triangle has area: start everywhere from the first
                starts = np.arange(1)
            samples = np.einsum("sj,tjd->tsd", self.WEIGHTS, corners[starts]).reshape(-1, 2)
            self.tree = cKDTree(samples)
            self.sample_position = np.repeat(position[starts], len(self.WEIGHTS))

    def _ahead(self, edge: IntArray, points: FloatArray) -> FloatArray:
        """cross(E, p − E_start): negative ahead of the edge, positive behind it."""
        d = points - self.edge_start[edge]
        e = self.edge_vector[edge]
        return cross2(e, d)

    def positions(self, points: FloatArray) -> IntArray:
        """The chain position of the triangle each point lies in (between edges k and
        k + 1): exact where the point is inside the development, a nearby one elsewhere."""
        if self.coarse is None:
            return self._walk(self.sample_position[self.tree.query(points)[1]], points)
        quad = self.coarse.positions(points) // 2
        k = self._walk(self.coarse_first[quad] + self.coarse_count[quad] // 2, points, 2 * STRIDE)
        lost = np.flatnonzero(self._inside_score(k[:, None], points)[:, 0] < -HELD)
        if lost.size:  # walked astray (lines of far edges can cross the strip): search
            k[lost] = self._within(quad[lost], points[lost])
        return k

    def _walk(self, k: IntArray, points: FloatArray, steps: int | None = None) -> IntArray:
        """Chain positions reached from ``k`` stepping over every edge the point lies
        ahead of (or behind), at most ``steps`` steps."""
        last = len(self.chain) - 1
        active = np.arange(len(points))
        taken = 0
        while active.size and (steps is None or taken < steps):  # a pass: every active point one step
            kk, q = k[active], points[active]
            forward = (kk < last) & (self._ahead(kk + 1, q) < -self.tolerance)
            back = ~forward & (kk > 0) & (self._ahead(kk, q) > self.tolerance)
            k[active] = kk + forward - back
            active = active[forward | back]
            taken += 1
        # a point on the edge of a triangle without area (beside a fan's apex, where two
        # edges are one line) belongs to the neighbour across that edge
        for _ in range(2):
            flat = np.flatnonzero(~self.proper[k])
            if flat.size == 0:
                break
            ahead = np.minimum(k[flat] + 1, last)
            k[flat] = np.where(self.proper[ahead], ahead, np.maximum(k[flat] - 1, 0))
        return k

    def _within(self, quad: IntArray, points: FloatArray) -> IntArray:
        """Chain positions of the points, given the coarse quad each lies in (or near):
        the first of that quad's triangles that holds the point, else of the quads beside
        it, else the one it is least outside of (by its barycentric coordinates)."""
        found = np.full(len(points), -1, dtype=np.int64)
        best = np.full(len(points), -np.inf)
        best_at = np.zeros(len(points), dtype=np.int64)
        todo = np.arange(len(points))
        span = 2 * STRIDE
        for shift in (0, -1, 1):
            if todo.size == 0:
                break
            q = np.clip(quad[todo] + shift, 0, len(self.coarse_first) - 1)
            first, count = self.coarse_first[q], self.coarse_count[q]
            k = first[:, None] + np.arange(span)[None, :]
            valid = np.arange(span)[None, :] < count[:, None]
            k = np.where(valid, k, first[:, None])
            score = self._inside_score(k, points[todo])
            score[~valid] = -np.inf
            held = score >= -HELD
            hit = held.any(axis=1)
            found[todo[hit]] = k[hit, np.argmax(held[hit], axis=1)]
            top = np.argmax(score, axis=1)
            value = score[np.arange(len(todo)), top]
            better = value > best[todo]
            best[todo[better]], best_at[todo[better]] = value[better], k[better, top[better]]
            todo = todo[~hit]
        found[todo] = best_at[todo]
        return found

    def _inside_score(self, k: IntArray, points: FloatArray) -> FloatArray:
        """The smallest barycentric coordinate of each point (rows) in the triangles at
        chain positions ``k`` (columns): ≥ 0 inside; −inf for a triangle without area."""
        d = points[:, None, :] - self.origin[k]
        inverse = self.inverse[k]
        v = inverse[..., 0, 0] * d[..., 0] + inverse[..., 0, 1] * d[..., 1]
        w = inverse[..., 1, 0] * d[..., 0] + inverse[..., 1, 1] * d[..., 1]
        score = np.minimum(np.minimum(v, w), 1.0 - v - w)
        return np.where(self.proper[k], score, -np.inf)

    def triangles(self, points: FloatArray) -> IntArray:
        """The triangle (an index into the strip's triangles) each point walks to."""
        return self.chain[self.positions(points)]
