"""Unrolling ruled strips into the plane: the kernel of IsoMapping.

A strip of n rulings (A_i → B_i) is a chain of n − 1 quads. Each quad is split into
two triangles along its shorter diagonal and the triangles are laid flat one after
another, every triangle congruent to its 3D original and all of them oriented the
same way (the 2D image of the normal (A_{i+1} − A_i) × (B_i − A_i) points to +z).
So every edge — rulings, both rails, diagonals — keeps its 3D length to rounding.
For a developable input the quads are (nearly) planar and the unfolding is an
isometry; for a warped ruled surface (a hyperbolic paraboloid) the rulings and rails
still keep their lengths but the area does not, and :attr:`Development.area_error`
says by how much.

How the recurrence is vectorised. Give ruling i its own 2D frame: A_i at the origin,
B_i at (0, |B_i − A_i|), the strip continuing towards +x. In that frame the next
ruling's end points follow from the quad's own two triangles — local 3D geometry
only, computed for all quads at once. Frame i + 1 then sits in frame i at the
rigid motion z ↦ A'_{i+1} + r_i·z (complex numbers: r_i is the unit rotation taking
+y onto the placed ruling). Composing rigid motions is a cumulative product of the
rotations and a cumulative sum of the rotated offsets — two O(n) numpy scans, no
Python loop. Lengths stay exact because each edge is the image of a local vector
under one unit rotation (renormalised after the product).

Smooth input. Unrolling n chords of a smooth developable is accurate to
O(1/n²): a full cylinder cut into 100 strips unrolls 1.6e-4 narrower than 2πr,
because every strip is as wide as its chord. :func:`unroll_surface` therefore
samples ``subdivisions`` rulings per segment from the smooth surface (error / 64 at
the default 8) and takes the 3D area from the surface itself.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np
import shapely
from numpy.typing import ArrayLike, NDArray
from scipy.spatial import cKDTree

from .area import gauss_legendre_01
from .watch import watch_check, watch_progress

if TYPE_CHECKING:
    from .surface_base import Surface

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: Diagonals within this relative margin count as equally long; the first one
#: (A_{i+1} to B_i) is then taken, so symmetric strips triangulate uniformly.
DIAGONAL_TIE = 1e-12

#: Edges shorter than this share of the strip's size count as collapsed (a cone's apex
#: edge): their length error is measured against the strip's size, not their own length.
EDGE_COLLAPSED = 1e-9

#: Distances within this share of the strip's size count as equal when points are
#: located on the 3D triangles (a point on a shared edge is on both triangles).
TIE = 1e-9

#: Consecutive outline points closer than this share of the development's size are one
#: vertex (a fan's apex, unrolled once per ruling: its images differ by rounding only, and
#: kept apart they would zigzag across each other).
REPEATED = 1e-9

#: Gauss–Legendre points per direction for the area of a bilinear quad.
QUAD_ORDER = 8


def _dot(a: FloatArray, b: FloatArray) -> FloatArray:
    return np.einsum("...i,...i->...", a, b)


def _as_rulings(starts: ArrayLike, ends: ArrayLike) -> tuple[FloatArray, FloatArray]:
    a = np.asarray(starts, dtype=float)
    b = np.asarray(ends, dtype=float)
    if a.ndim != 2 or a.shape[1] != 3 or a.shape != b.shape:
        raise ValueError("starts and ends must be (n, 3) arrays of the same shape")
    if len(a) < 2:
        raise ValueError("a strip needs at least two rulings")
    if not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
        raise ValueError("ruling end points must be finite")
    return a, b


def _rotate_about(points: FloatArray, angle: float, pivot: FloatArray) -> FloatArray:
    c, s = np.cos(angle), np.sin(angle)
    d = points - pivot
    return pivot + np.column_stack([c * d[:, 0] - s * d[:, 1], s * d[:, 0] + c * d[:, 1]])


# --------------------------------------------------------------------------- triangles


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


def bilinear_quad_areas(starts: ArrayLike, ends: ArrayLike, order: int = QUAD_ORDER) -> FloatArray:
    """Area of each ruled quad S(a, b) = lerp(lerp(A_i, A_{i+1}, a), lerp(B_i, B_{i+1}, a), b).

    This is the straight-line loft between consecutive rulings (a piece of a hyperbolic
    paraboloid, or a plane for a planar quad), integrated with an ``order``² Gauss rule:
    exact for planar convex quads (|S_a × S_b| is then bilinear) and ~1e-12 relative
    for warped ones.
    """
    a, b = _as_rulings(starts, ends)
    x, w = gauss_legendre_01(order)
    da, db = np.diff(a, axis=0), np.diff(b, axis=0)  # rail steps
    ra, rb = b[:-1] - a[:-1], b[1:] - a[1:]  # rulings i and i + 1
    # S_a = (1 − b)·dA + b·dB and S_b = (1 − a)·r_i + a·r_{i+1}, so S_a × S_b is bilinear
    # in (a, b) with the four corner values below: evaluate it at the Gauss nodes.
    corners = np.stack([np.cross(da, ra), np.cross(da, rb), np.cross(db, ra), np.cross(db, rb)], 1)
    aa, bb = np.meshgrid(x, x, indexing="ij")
    aa, bb = aa.ravel(), bb.ravel()
    basis = np.column_stack([(1 - bb) * (1 - aa), (1 - bb) * aa, bb * (1 - aa), bb * aa])
    normal = basis @ corners  # (quads, nodes, 3)
    return np.sqrt(np.square(normal).sum(axis=2)) @ np.outer(w, w).ravel()


# --------------------------------------------------------------------------- the map


def _closest_on_triangles(
    p: FloatArray, a: FloatArray, b: FloatArray, c: FloatArray
) -> FloatArray:
    """Barycentric coordinates of the closest point of triangle (a, b, c) to p, row-wise.

    The Voronoi-region case analysis of the triangle (three vertices, three edges,
    the face), evaluated for every row and picked with ``np.select``.
    """
    ab, ac = b - a, c - a
    ap, bp, cp = p - a, p - b, p - c
    d1, d2 = _dot(ab, ap), _dot(ac, ap)
    d3, d4 = _dot(ab, bp), _dot(ac, bp)
    d5, d6 = _dot(ab, cp), _dot(ac, cp)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    one, zero = np.ones_like(d1), np.zeros_like(d1)
    with np.errstate(divide="ignore", invalid="ignore"):
        t_ab = d1 / (d1 - d3)
        t_ac = d2 / (d2 - d6)
        t_bc = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        total = va + vb + vc
        v_in, w_in = vb / total, vc / total
    conditions = [
        (d1 <= 0) & (d2 <= 0),
        (d3 >= 0) & (d4 <= d3),
        (vc <= 0) & (d1 >= 0) & (d3 <= 0),
        (d6 >= 0) & (d5 <= d6),
        (vb <= 0) & (d2 >= 0) & (d6 <= 0),
        (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0),
    ]
    v = np.select(conditions, [zero, one, t_ab, zero, zero, 1.0 - t_bc], v_in)
    w = np.select(conditions, [zero, zero, zero, one, t_ac, t_bc], w_in)
    return np.column_stack([1.0 - v - w, v, w])


class _StripWalk:
    """Which triangle of a (not self-overlapping) development contains each point, by
    walking along the strip — all points at once.

    The triangles form a chain: triangle ``chain[k]`` lies between edges E_k and E_{k+1}
    (the rulings and diagonals in order, each from its A end to its B end), and a point
    to the right of E_{k+1} lies further along. Every point starts at the triangle of
    its nearest sample (seven per triangle, in a k-d tree), steps forward or back —
    always the same way, so at most once along the chain — until it lies between two
    consecutive edges, and that triangle is then checked to contain it.
    """

    #: Samples per triangle (barycentric weights): its centroid, three points near its
    #: corners and its three edge midpoints.
    WEIGHTS = np.array([[2, 2, 2], [4, 1, 1], [1, 4, 1], [1, 1, 4], [3, 3, 0], [0, 3, 3], [3, 0, 3]]) / 6.0

    def __init__(self, vertices2d: FloatArray, first_diagonal: NDArray[np.bool_], proper: IntArray) -> None:
        n = len(vertices2d) // 2
        i = np.arange(n - 1)
        forward = first_diagonal.astype(np.int64)
        # quad i: along A_{i+1}B_i triangle 2i comes first, along A_iB_{i+1} triangle 2i + 1
        self.chain = np.column_stack([2 * i + 1 - forward, 2 * i + forward]).reshape(-1)
        diagonal_a = np.where(first_diagonal, i + 1, i)
        diagonal_b = n + np.where(first_diagonal, i, i + 1)
        edge_a = np.column_stack([i, diagonal_a]).reshape(-1)
        edge_b = np.column_stack([n + i, diagonal_b]).reshape(-1)
        self.edge_start = vertices2d[np.append(edge_a, n - 1)]
        self.edge_vector = vertices2d[np.append(edge_b, 2 * n - 1)] - self.edge_start
        size = float(np.ptp(vertices2d, axis=0).max()) or 1.0
        self.tolerance = 1e-12 * size * size
        position = np.empty(len(self.chain), dtype=np.int64)
        position[self.chain] = np.arange(len(self.chain))
        triangles = strip_triangles(n, first_diagonal)[proper]
        samples = np.einsum("sj,tjd->tsd", self.WEIGHTS, vertices2d[triangles]).reshape(-1, 2)
        self.tree = cKDTree(samples)
        self.sample_position = np.repeat(position[proper], len(self.WEIGHTS))

    def _ahead(self, edge: IntArray, points: FloatArray) -> FloatArray:
        """cross(E, p − E_start): negative ahead of the edge, positive behind it."""
        d = points - self.edge_start[edge]
        e = self.edge_vector[edge]
        return e[:, 0] * d[:, 1] - e[:, 1] * d[:, 0]

    def triangles(self, points: FloatArray) -> IntArray:
        """The triangle (an index into the strip's triangles) each point walks to."""
        k = self.sample_position[self.tree.query(points)[1]]
        last = len(self.chain) - 1
        active = np.arange(len(points))
        while active.size:  # each pass moves every active point one triangle on
            kk, q = k[active], points[active]
            forward = (kk < last) & (self._ahead(kk + 1, q) < -self.tolerance)
            back = ~forward & (kk > 0) & (self._ahead(kk, q) > self.tolerance)
            k[active] = kk + forward - back
            active = active[forward | back]
        return self.chain[k]


class DevelopmentMap:
    """The piecewise-affine map between a development and its 3D strip.

    Both sides are the same triangulation (vertex ``i`` = A_i, ``n + i`` = B_i, see
    :func:`strip_triangles`); within a triangle a point keeps its barycentric
    coordinates. The map is continuous (neighbouring triangles agree on their shared
    edge) and, for a developable strip, an isometry.

    * :meth:`to_3d` — plane → surface, by locating each point in a triangle.
    * :meth:`to_2d` / :meth:`polyline_to_2d` — surface → plane, through the closest
      point on the triangles (on the seam of a closed surface, which the development
      shows twice, a polyline keeps to the side of its neighbouring vertices).
    * :meth:`strip_to_2d` / :meth:`strip_to_3d` — from strip coordinates (i, a, b).
    * :meth:`subdivide` / :meth:`polyline_to_3d` — polylines, split where they cross
      a ruling or diagonal, so their 3D image follows the surface exactly.

    Points outside the development map through the nearest triangle's affine map
    (extrapolation, exact for points that miss by rounding). Where a development
    overlaps itself in the plane (a tangent developable over more than a turn) the
    plane → surface direction is ambiguous; the lowest-numbered triangle wins.
    """

    def __init__(
        self, vertices2d: ArrayLike, vertices3d: ArrayLike, first_diagonal: ArrayLike
    ) -> None:
        self.vertices2d = np.asarray(vertices2d, dtype=float)
        self.vertices3d = np.asarray(vertices3d, dtype=float)
        self.first_diagonal = np.asarray(first_diagonal, dtype=bool)
        self.n = len(self.vertices3d) // 2
        self.triangles = strip_triangles(self.n, self.first_diagonal)
        tri = self.vertices2d[self.triangles]
        e1, e2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
        self._area2 = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]  # twice the signed area
        size = float(np.ptp(self.vertices2d, axis=0).max()) or 1.0
        #: triangles with area: the only ones a point can be located in
        self.proper_area = 1e-13 * size * size
        self.proper = np.flatnonzero(self._area2 > self.proper_area)
        if self.proper.size == 0:
            raise ValueError("the strip has no area: every triangle is degenerate")

    def rotated(self, angle: float, pivot: ArrayLike) -> DevelopmentMap:
        """The same map with the plane side turned by ``angle`` (rad) about ``pivot``."""
        turned = _rotate_about(self.vertices2d, angle, np.asarray(pivot, dtype=float))
        return DevelopmentMap(turned, self.vertices3d, self.first_diagonal)

    # ------------------------------------------------------------- plane → surface

    @cached_property
    def _tree2d(self) -> shapely.STRtree:
        polys = shapely.polygons(self.vertices2d[self.triangles[self.proper]])
        return shapely.STRtree(polys)

    @cached_property
    def _walk(self) -> _StripWalk | None:
        """The fast locator, for developments that do not overlap themselves (there a
        point lies in one triangle only; elsewhere the lowest-numbered must be found)."""
        outline = np.vstack([self.vertices2d[: self.n], self.vertices2d[self.n :][::-1]])
        if not _is_simple(outline):
            return None
        return _StripWalk(self.vertices2d, self.first_diagonal, self.proper)

    def locate(self, points2d: ArrayLike) -> tuple[IntArray, FloatArray]:
        """Triangle index and barycentric coordinates ``(k, 3)`` of each 2D point.

        Each point walks along the strip to its triangle (:class:`_StripWalk`); where
        that fails (a development that overlaps itself, a point outside it) a shapely
        STR-tree finds the triangles that contain it (the lowest-numbered wins, also on
        a shared edge), and points outside every triangle take the nearest one.
        """
        pts = np.asarray(points2d, dtype=float).reshape(-1, 2)
        tri = np.full(len(pts), -1, dtype=np.int64)
        if self._walk is not None and len(pts):
            tri = self._walk.triangles(pts)
            bary = self._barycentric(tri, pts)
            inside = (bary >= -1e-9).all(axis=1) & (self._area2[tri] > self.proper_area)
            tri[~inside] = -1
        lost = np.flatnonzero(tri < 0)
        if lost.size:
            geoms = shapely.points(pts[lost])
            big = np.iinfo(np.int64).max
            found = np.full(lost.size, big, dtype=np.int64)
            hit_point, hit_tree = self._tree2d.query(geoms, predicate="intersects")
            np.minimum.at(found, hit_point, hit_tree)
            missing = np.flatnonzero(found == big)
            if missing.size:
                near_point, near_tree = self._tree2d.query_nearest(geoms[missing])
                np.minimum.at(found, missing[near_point], near_tree)
            tri[lost] = self.proper[found]
        return tri, self._barycentric(tri, pts)

    def _barycentric(self, tri: IntArray, pts: FloatArray) -> FloatArray:
        """Barycentric coordinates of ``pts`` in triangles ``tri`` (any, even outside)."""
        corners = self.vertices2d[self.triangles[tri]]
        e1, e2 = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
        d = pts - corners[:, 0]
        area2 = self._area2[tri]
        with np.errstate(divide="ignore", invalid="ignore"):
            v = (d[:, 0] * e2[:, 1] - d[:, 1] * e2[:, 0]) / area2
            w = (e1[:, 0] * d[:, 1] - e1[:, 1] * d[:, 0]) / area2
        return np.column_stack([1.0 - v - w, v, w])

    def to_3d(self, points2d: ArrayLike) -> FloatArray:
        """Points of the development carried onto the 3D strip, ``(k, 3)``."""
        tri, bary = self.locate(points2d)
        return np.einsum("kj,kjd->kd", bary, self.vertices3d[self.triangles[tri]])

    # ------------------------------------------------------------- surface → plane

    @cached_property
    def _samples3d(self) -> tuple[cKDTree, IntArray]:
        # the centroid and the three edge midpoints of every proper triangle
        corners = self.vertices3d[self.triangles[self.proper]]
        weights = np.array([[1, 1, 1], [2, 2, 0], [0, 2, 2], [2, 0, 2]], dtype=float) / np.array(
            [[3.0], [4.0], [4.0], [4.0]])
        samples = np.einsum("sj,tjd->tsd", weights, corners).reshape(-1, 3)
        owner = np.repeat(np.arange(len(corners)), len(weights))
        return cKDTree(samples), owner

    def _candidates(self, points3d: FloatArray) -> tuple[IntArray, IntArray, FloatArray, FloatArray]:
        """Rows ``(row, triangle, barycentric, distance)``: for every point, each proper
        triangle (index into ``proper``) whose closest point ties for the nearest, to
        ``TIE`` of the strip's size.

        The triangle owning the nearest sample gives an upper bound on the distance;
        only triangles whose bounding box lies within it are measured exactly (in
        memory-bounded blocks of points, each vectorised; between blocks the search
        checks for cancellation and reports progress, see :mod:`.watch`).
        """
        pts = points3d
        tree, owner = self._samples3d
        corners = self.vertices3d[self.triangles[self.proper]]
        guess = owner[tree.query(pts)[1]]
        g = corners[guess]
        bary = _closest_on_triangles(pts, g[:, 0], g[:, 1], g[:, 2])
        bound = np.linalg.norm(np.einsum("kj,kjd->kd", bary, g) - pts, axis=1)
        low, high = self._boxes3d
        tie = TIE * (float(np.linalg.norm(np.ptp(self.vertices3d, axis=0))) or 1.0)
        chunk = max(1, 2_000_000 // len(low))
        check, progress = watch_check(), watch_progress()
        found: list[tuple[IntArray, IntArray, FloatArray, FloatArray]] = []
        for start in range(0, len(pts), chunk):  # memory-bounded chunks, vectorised inside
            if check is not None:
                check()
            q = pts[start:start + chunk]
            gap = np.maximum(low[None] - q[:, None], 0.0) + np.maximum(q[:, None] - high[None], 0.0)
            near = np.linalg.norm(gap, axis=2) <= (bound[start:start + chunk] + tie)[:, None]
            row, col = np.nonzero(near)
            c = corners[col]
            b = _closest_on_triangles(q[row], c[:, 0], c[:, 1], c[:, 2])
            dist = np.linalg.norm(np.einsum("kj,kjd->kd", b, c) - q[row], axis=1)
            best = np.full(len(q), np.inf)
            np.minimum.at(best, row, dist)
            keep = dist <= best[row] + tie
            found.append((start + row[keep], col[keep], b[keep], dist[keep]))
            if progress is not None:
                progress(min(1.0, (start + len(q)) / len(pts)))
        rows, cols, barys, dists = (np.concatenate(parts) for parts in zip(*found, strict=True))
        return rows, cols, barys, dists

    @cached_property
    def _boxes3d(self) -> tuple[FloatArray, FloatArray]:
        corners = self.vertices3d[self.triangles[self.proper]]
        return corners.min(axis=1), corners.max(axis=1)

    def closest(
        self, points3d: ArrayLike, hints2d: ArrayLike | None = None
    ) -> tuple[IntArray, FloatArray, FloatArray]:
        """Closest point on the 3D triangles: triangle index, barycentric coordinates
        ``(k, 3)`` and distance ``(k,)`` for each point.

        Where several triangles are (within rounding) equally close with different
        images in the plane — a point on the seam of a closed surface, which the
        development shows twice — the one whose image is nearest ``hints2d`` wins,
        or, without hints, the lowest-numbered. ``hints2d`` is ``(k, 2)``, or
        ``(k, h, 2)`` for several hints per point (their summed distance counts).
        """
        pts = np.asarray(points3d, dtype=float).reshape(-1, 3)
        rows, cols, barys, dists = self._candidates(pts)
        tri = self.proper[cols]
        if hints2d is None:
            score = dists
        else:
            images = np.einsum("kj,kjd->kd", barys, self.vertices2d[self.triangles[tri]])
            hints = np.asarray(hints2d, dtype=float).reshape(len(pts), -1, 2)
            score = np.linalg.norm(images[:, None] - hints[rows], axis=2).sum(axis=1)
        order = np.lexsort((cols, score, rows))
        first = order[np.r_[True, rows[order][1:] != rows[order][:-1]]]
        return tri[first], barys[first], dists[first]

    def to_2d(self, points3d: ArrayLike, hints2d: ArrayLike | None = None) -> FloatArray:
        """Points on (or near) the 3D strip carried into the development, ``(k, 2)``.

        ``hints2d`` (optional, one per point) settles points the development shows
        twice (the seam of a closed surface): the image nearest the hint is taken.
        """
        tri, bary, _ = self.closest(points3d, hints2d)
        return np.einsum("kj,kjd->kd", bary, self.vertices2d[self.triangles[tri]])

    def polyline_to_2d(self, points3d: ArrayLike) -> FloatArray:
        """A polyline on the 3D strip carried into the development, ``(k, 2)``.

        Like :meth:`to_2d`, but a vertex the development shows twice (on the seam
        of a closed surface) takes the image next to its neighbours': the nearest
        vertices before and after it along the polyline that have only one image
        serve as hints (a closed ring wraps around).
        """
        return self.polylines_to_2d([points3d])[0]

    def polylines_to_2d(self, polylines3d: Sequence[ArrayLike]) -> list[FloatArray]:
        """:meth:`polyline_to_2d` for many polylines at once (one vectorised pass)."""
        polys = [np.asarray(p, dtype=float).reshape(-1, 3) for p in polylines3d]
        if not polys:
            return []
        counts = np.array([len(p) for p in polys])
        pts = np.vstack(polys)
        k = len(pts)
        owner = np.repeat(np.arange(len(polys)), counts)
        rows, cols, barys, dists = self._candidates(pts)
        images = np.einsum("kj,kjd->kd", barys, self.vertices2d[self.triangles[self.proper[cols]]])
        # without hints: the nearest triangle, then the lowest-numbered (a tie within TIE
        # is not a tie in the plane near a cone's apex, where triangles are tiny)
        order = np.lexsort((cols, dists, rows))
        rows, cols, images = rows[order], cols[order], images[order]
        first = np.flatnonzero(np.r_[True, rows[1:] != rows[:-1]])
        plain = images[first]
        # a vertex is ambiguous when its candidate images lie apart (the seam)
        spread = np.maximum.reduceat(np.abs(images - plain[rows]).max(axis=1), first)
        ambiguous = spread > TIE * (float(np.ptp(self.vertices2d, axis=0).max()) or 1.0)
        if ambiguous.any():
            index = np.arange(k)
            starts = np.cumsum(counts) - counts
            clear_at = np.where(ambiguous, -1, index)
            last_clear = np.maximum.reduceat(clear_at, starts)  # per polyline, −1 if none
            first_clear = np.minimum.reduceat(np.where(ambiguous, k, index), starts)
            # nearest clear vertex before / after, within the polyline, wrapping around
            before = np.maximum.accumulate(clear_at)
            before = np.where((before < 0) | (owner[np.maximum(before, 0)] != owner),
                              last_clear[owner], before)
            after = np.minimum.accumulate(np.where(ambiguous, k, index)[::-1])[::-1]
            after = np.where((after >= k) | (owner[np.minimum(after, k - 1)] != owner),
                             first_clear[owner], after)
            usable = ambiguous & (before >= 0)  # a polyline with no clear vertex keeps its guess
            hints = np.stack([plain[np.maximum(before, 0)], plain[np.maximum(after, 0) % k]], axis=1)
            pick = usable[rows]
            score = np.linalg.norm(images[pick][:, None] - hints[rows[pick]], axis=2).sum(axis=1)
            sub = np.lexsort((cols[pick], score, rows[pick]))
            chosen_rows = rows[pick][sub]
            lead = np.r_[True, chosen_rows[1:] != chosen_rows[:-1]]
            plain[chosen_rows[lead]] = images[pick][sub][lead]
        return np.split(plain, np.cumsum(counts)[:-1])

    # ------------------------------------------------------------- strip coordinates

    def _strip_barycentric(
        self, i: ArrayLike, a: ArrayLike, b: ArrayLike
    ) -> tuple[IntArray, FloatArray]:
        """Triangle and barycentric coordinates of strip coordinates (i, a, b)."""
        ii, aa, bb = np.broadcast_arrays(np.asarray(i), np.asarray(a, float), np.asarray(b, float))
        ii, aa, bb = ii.ravel().astype(np.int64), aa.ravel(), bb.ravel()
        if np.any((ii < 0) | (ii > self.n - 2)):
            raise ValueError(f"quad index must be in 0 … {self.n - 2}")
        first = self.first_diagonal[ii]
        # unit-square corners: A_i (0,0), A_{i+1} (1,0), B_i (0,1), B_{i+1} (1,1)
        lower = np.where(first, aa + bb <= 1.0, aa >= bb)
        tri = 2 * ii + (~lower)
        cases = [first & lower, first & ~lower, ~first & lower]
        # (A_i, A_{i+1}, B_i) · (A_{i+1}, B_{i+1}, B_i) · (A_i, A_{i+1}, B_{i+1}) · (A_i, B_{i+1}, B_i)
        l0 = np.select(cases, [1 - aa - bb, 1 - bb, 1 - aa], 1 - bb)
        l1 = np.select(cases, [aa, aa + bb - 1, aa - bb], aa)
        l2 = np.select(cases, [bb, 1 - aa, bb], bb - aa)
        bary = np.column_stack([l0, l1, l2])
        return tri, bary

    def strip_to_2d(self, i: ArrayLike, a: ArrayLike, b: ArrayLike) -> FloatArray:
        """Development points at strip coordinates: quad ``i`` (between rulings i and
        i + 1), ``a`` in [0, 1] across it from ruling i, ``b`` in [0, 1] along the
        rulings from their starts. Within the quad the two triangles are affine images
        of the two halves of the unit square cut along the same diagonal."""
        tri, bary = self._strip_barycentric(i, a, b)
        return np.einsum("kj,kjd->kd", bary, self.vertices2d[self.triangles[tri]])

    def strip_to_3d(self, i: ArrayLike, a: ArrayLike, b: ArrayLike) -> FloatArray:
        """3D points at strip coordinates (see :meth:`strip_to_2d`)."""
        tri, bary = self._strip_barycentric(i, a, b)
        return np.einsum("kj,kjd->kd", bary, self.vertices3d[self.triangles[tri]])

    # ------------------------------------------------------------- polylines

    @cached_property
    def _edge_tree(self) -> tuple[shapely.STRtree, FloatArray, FloatArray]:
        n = self.n
        i = np.arange(n - 1)
        starts = np.concatenate([np.arange(n), np.where(self.first_diagonal, i + 1, i)])
        ends = np.concatenate([n + np.arange(n), np.where(self.first_diagonal, n + i, n + i + 1)])
        p, q = self.vertices2d[starts], self.vertices2d[ends]
        keep = np.linalg.norm(q - p, axis=1) > 0
        p, q = p[keep], q[keep]
        return shapely.STRtree(shapely.linestrings(np.stack([p, q], axis=1))), p, q

    def subdivide(self, polyline2d: ArrayLike, max_length: float | None = None) -> FloatArray:
        """The polyline with a vertex added wherever it crosses a ruling or diagonal.

        Each piece then lies in one triangle, where the map is affine, so the 3D
        image of the subdivided polyline is exactly the image of the straight 2D
        segments (a panel edge follows the surface instead of cutting through it).
        ``max_length`` further splits segments longer than that, evenly (useful when
        the 3D points are afterwards pulled onto a smooth surface).
        """
        return self.subdivide_many([polyline2d], max_length)[0]

    def subdivide_many(
        self, polylines2d: Sequence[ArrayLike], max_length: float | None = None
    ) -> list[FloatArray]:
        """:meth:`subdivide` for many polylines at once (one vectorised pass)."""
        polys = [np.asarray(p, dtype=float).reshape(-1, 2) for p in polylines2d]
        if not polys:
            return []
        counts = np.array([len(p) for p in polys])
        pts = np.vstack(polys)
        owner = np.repeat(np.arange(len(polys)), counts)
        inner = np.flatnonzero(owner[1:] == owner[:-1])  # segment j runs from pts[j] to pts[j + 1]
        p0, d = pts[inner], pts[inner + 1] - pts[inner]
        seg = [np.arange(len(inner))]
        param = [np.zeros(len(inner))]
        if max_length is not None and max_length > 0:
            pieces = np.maximum(1, np.ceil(np.linalg.norm(d, axis=1) / max_length)).astype(np.int64)
            extra = np.repeat(np.arange(len(inner)), pieces - 1)
            rank = np.arange(len(extra)) - np.repeat(np.cumsum(pieces - 1) - (pieces - 1), pieces - 1)
            seg.append(extra)
            param.append((rank + 1) / pieces[extra])
        tree, ep, eq = self._edge_tree
        if len(inner):
            hit_seg, hit_edge = tree.query(shapely.linestrings(np.stack([p0, p0 + d], axis=1)),
                                           predicate="intersects")
            ds, de = d[hit_seg], eq[hit_edge] - ep[hit_edge]
            w = ep[hit_edge] - p0[hit_seg]
            den = ds[:, 0] * de[:, 1] - ds[:, 1] * de[:, 0]
            ok = np.abs(den) > 1e-14 * np.linalg.norm(ds, axis=1) * np.linalg.norm(de, axis=1)
            with np.errstate(divide="ignore", invalid="ignore"):
                t = (w[:, 0] * de[:, 1] - w[:, 1] * de[:, 0]) / den
            ok &= (t > 1e-12) & (t < 1.0 - 1e-12)  # collinear overlaps need no split
            seg.append(hit_seg[ok])
            param.append(t[ok])
        seg_all, par_all = np.concatenate(seg), np.concatenate(param)
        # every polyline's own last vertex closes it: key (its last point's index, 0)
        last = np.cumsum(counts) - 1
        key = np.concatenate([inner[seg_all], last])
        par = np.concatenate([par_all, np.zeros(len(last))])
        order = np.lexsort((par, key))
        key, par = key[order], par[order]
        closing = np.zeros(len(key), dtype=bool)
        closing[len(par_all):] = True
        closing = closing[order]
        nxt = np.minimum(key + 1, len(pts) - 1)
        out = np.where(closing[:, None], pts[key], pts[key] + par[:, None] * (pts[nxt] - pts[key]))
        who = owner[key]
        size = float(np.ptp(pts, axis=0).max()) or 1.0
        step = np.linalg.norm(np.diff(out, axis=0), axis=1)
        twin = np.r_[False, (step <= 1e-12 * size) & (who[1:] == who[:-1])]  # a crossing at a vertex
        # of a twin pair keep the polyline's own end vertex exactly
        move = twin & closing
        twin[np.flatnonzero(move) - 1] = True
        twin[move] = False
        out, who = out[~twin], who[~twin]
        return np.split(out, np.cumsum(np.bincount(who, minlength=len(polys)))[:-1])

    def polyline_to_3d(
        self, polyline2d: ArrayLike, max_length: float | None = None
    ) -> tuple[FloatArray, FloatArray]:
        """Subdivide a development polyline (see :meth:`subdivide`) and carry it onto
        the 3D strip: returns ``(points2d, points3d)`` with one row per vertex."""
        fine = self.subdivide(polyline2d, max_length)
        return fine, self.to_3d(fine)

    def polylines_to_3d(
        self, polylines2d: Sequence[ArrayLike], max_length: float | None = None
    ) -> tuple[list[FloatArray], list[FloatArray]]:
        """:meth:`polyline_to_3d` for many polylines at once."""
        fine = self.subdivide_many(polylines2d, max_length)
        if not fine:
            return [], []
        mapped = self.to_3d(np.vstack(fine))
        return fine, np.split(mapped, np.cumsum([len(f) for f in fine])[:-1])


# --------------------------------------------------------------------------- development


@dataclass(frozen=True)
class Development:
    """A ruled strip unrolled into the XY plane, with its accuracy figures.

    ``starts2d``/``ends2d`` are the images of the rulings. ``area_3d`` is the area of
    the 3D surface (the bilinear loft of the rulings, or the smooth surface's area
    when one was given), ``area_2d`` the area of the development. ``area_error`` is
    (area_2d − area_3d) / area_3d, signed. ``max_edge_length_error`` is the largest
    relative change of any triangle edge (rulings, rails and diagonals; a collapsed
    edge, like those at a cone's apex, relative to the strip's size); it is at
    rounding level by construction. ``hinge_angles`` (rad, one per quad) is the fold
    between each quad's two triangles: zero for a planar quad, so it shows where a
    strip is not developable. ``stride`` marks every stride-th ruling as one the user
    asked for (see :func:`unroll_surface`).
    """

    starts2d: FloatArray
    ends2d: FloatArray
    starts3d: FloatArray
    ends3d: FloatArray
    area_3d: float
    area_2d: float
    area_error: float
    max_edge_length_error: float
    hinge_angles: FloatArray
    map: DevelopmentMap = field(repr=False)
    stride: int = 1

    @property
    def area_difference(self) -> float:
        """area_2d − area_3d, in model units²."""
        return self.area_2d - self.area_3d

    @property
    def rulings2d(self) -> tuple[FloatArray, FloatArray]:
        """Starts and ends of the requested rulings (every ``stride``-th one)."""
        return self.starts2d[:: self.stride], self.ends2d[:: self.stride]

    @property
    def outline(self) -> FloatArray:
        """The boundary polygon ``(m, 2)``: the starts forwards, then the ends backwards
        (m ≤ 2n: a run of points within :data:`REPEATED` of the size of each other, as at
        a fan's apex, is one vertex, so a simple development has a valid outline)."""
        return _merge_repeats(np.vstack([self.starts2d, self.ends2d[::-1]]))

    @property
    def bounds(self) -> FloatArray:
        """Bounding rectangle ``[xmin, ymin, xmax, ymax]`` of the development."""
        pts = np.vstack([self.starts2d, self.ends2d])
        return np.concatenate([pts.min(axis=0), pts.max(axis=0)])

    @property
    def overlaps(self) -> bool:
        """True when the development overlaps itself in the plane (a tangent developable
        of more than a full turn): it cannot be cut from one sheet, and plane → surface
        mapping is ambiguous where it overlaps."""
        return not _is_simple(self.outline)

    @property
    def centroid(self) -> FloatArray:
        """Area centroid of the development ``(2,)``."""
        tri = self.map.vertices2d[self.map.triangles]
        areas = 0.5 * self.map._area2
        return (tri.mean(axis=1) * areas[:, None]).sum(axis=0) / areas.sum()

    def rotated(self, angle_deg: float, pivot: ArrayLike | None = None) -> Development:
        """The development turned counter-clockwise by ``angle_deg`` about ``pivot``
        (default: its area centroid). The 3D side and every figure stay the same."""
        centre = self.centroid if pivot is None else np.asarray(pivot, dtype=float)
        angle = np.deg2rad(angle_deg)
        return replace(
            self,
            starts2d=_rotate_about(self.starts2d, angle, centre),
            ends2d=_rotate_about(self.ends2d, angle, centre),
            map=self.map.rotated(angle, centre),
        )


def _merge_repeats(ring: FloatArray) -> FloatArray:
    """The closed polygon without the points within :data:`REPEATED` of its size of the
    point before them (nor a last point that repeats the first)."""
    size = float(np.ptp(ring, axis=0).max()) or 1.0
    keep = np.r_[True, np.linalg.norm(np.diff(ring, axis=0), axis=1) > REPEATED * size]
    merged = ring[keep]
    if len(merged) > 1 and np.linalg.norm(merged[-1] - merged[0]) <= REPEATED * size:
        merged = merged[:-1]
    return merged


def _is_simple(outline: FloatArray) -> bool:
    """Whether the closed polygon does not cross or touch itself. A point repeated in a
    row, to rounding (a cone's apex, the end of every ruling of its fan), is one vertex."""
    return bool(shapely.LinearRing(_merge_repeats(outline)).is_simple)


def _place(x2: NDArray, y2: NDArray, along: FloatArray, height: FloatArray) -> NDArray:
    """2D points (complex) ``along`` the edge x→y from x and ``height`` to its left."""
    edge = y2 - x2
    return x2 + edge / np.abs(edge) * (along + 1j * height)


def _local(x3: FloatArray, y3: FloatArray, p3: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Coordinates of p over the edge x→y of triangle (x, y, p): the projection along
    the edge and the (unsigned) distance from its line."""
    edge, w = y3 - x3, p3 - x3
    length = np.linalg.norm(edge, axis=1)
    return _dot(w, edge) / length, np.linalg.norm(np.cross(edge, w), axis=1) / length


def unroll_rulings(
    starts: ArrayLike, ends: ArrayLike, area_3d: float | None = None
) -> Development:
    """Unroll the ruled strip through n rulings ``starts[i] → ends[i]`` into the plane.

    Ruling 0 is laid from the origin up the +y axis and the strip continues towards
    +x (the side of ruling 1). Every quad is cut along its shorter diagonal and both
    triangles are laid down congruent to their 3D originals (see the module
    docstring for the vectorised recurrence). ``area_3d`` overrides the 3D area the
    development is compared with (pass the smooth surface's area); by default it is
    the area of the bilinear loft of the rulings (:func:`bilinear_quad_areas`).

    Example:
        >>> import numpy as np
        >>> phi = np.linspace(0, np.pi, 5)   # half a cylinder of radius 1, height 2
        >>> base = np.column_stack([np.cos(phi), np.sin(phi), 0 * phi])
        >>> dev = unroll_rulings(base, base + [0, 0, 2])
        >>> np.round(dev.ends2d[-1], 6).tolist()   # 4 chords of length 2 sin(π/8)
        [3.061467, 2.0]
    """
    a, b = _as_rulings(starts, ends)
    n = len(a)
    ruling = b - a
    length = np.linalg.norm(ruling, axis=1)
    size = float(np.ptp(np.vstack([a, b]), axis=0).max())
    zero = length <= 1e-12 * size
    tip_start, tip_end = bool(zero[0]) and n > 2, bool(zero[-1]) and n > 2
    inner = zero.copy()
    inner[0] &= not tip_start
    inner[-1] &= not tip_end
    if np.any(inner):
        bad = np.flatnonzero(inner)
        raise ValueError(f"ruling {int(bad[0])} has zero length: a strip cannot be unrolled "
                         f"through a point ({len(bad)} such rulings)")
    if tip_start or tip_end:  # the strip tapers to a point: unroll the rest, then its tips
        return _with_tips(a, b, tip_start, tip_end, area_3d)
    starts2d, ends2d, first = _unrolled(a, b, length)
    return _development(a, b, starts2d, ends2d, first, area_3d)


def _with_tips(
    a: FloatArray, b: FloatArray, tip_start: bool, tip_end: bool, area_3d: float | None
) -> Development:
    """Unroll a strip whose first and/or last ruling has zero length (its curves meet
    there): the rulings between are unrolled as usual and each tip is laid down as the
    corner of its triangle with the neighbouring ruling, away from the strip."""
    core = slice(1 if tip_start else 0, len(a) - 1 if tip_end else len(a))
    ca, cb = a[core], b[core]
    starts2d, ends2d, _ = _unrolled(ca, cb, np.linalg.norm(cb - ca, axis=1))
    z_a = starts2d[:, 0] + 1j * starts2d[:, 1]
    z_b = ends2d[:, 0] + 1j * ends2d[:, 1]
    parts_a, parts_b = [z_a], [z_b]
    if tip_start:  # left of the first ruling: the strip runs on to its right
        u, h = _local(a[1:2], b[1:2], a[0:1])
        tip = _place(z_a[:1], z_b[:1], u, h)
        parts_a.insert(0, tip)
        parts_b.insert(0, tip)
    if tip_end:  # right of the last ruling
        u, h = _local(a[-2:-1], b[-2:-1], a[-1:])
        tip = _place(z_a[-1:], z_b[-1:], u, -h)
        parts_a.append(tip)
        parts_b.append(tip)
    za, zb = np.concatenate(parts_a), np.concatenate(parts_b)
    first = np.linalg.norm(a[1:] - b[:-1], axis=1) <= np.linalg.norm(b[1:] - a[:-1], axis=1) * (
        1 + DIAGONAL_TIE
    )
    starts2d = np.column_stack([za.real, za.imag])
    ends2d = np.column_stack([zb.real, zb.imag])
    return _development(a, b, starts2d, ends2d, first, area_3d)


def _unrolled(a: FloatArray, b: FloatArray, length: FloatArray) -> tuple[FloatArray, FloatArray, NDArray]:
    """The 2D ruling ends of a strip with no zero-length ruling, and each quad's diagonal."""
    n = len(a)
    a0, a1, b0, b1 = a[:-1], a[1:], b[:-1], b[1:]
    first = np.linalg.norm(a1 - b0, axis=1) <= np.linalg.norm(b1 - a0, axis=1) * (1 + DIAGONAL_TIE)
    col = first[:, None]

    # Frame i: A_i = 0, B_i = i·|r_i|. The first new vertex sits left of B_i → A_i,
    # the second left of the diagonal (B_i → A_{i+1}, or B_{i+1} → A_i).
    top = 1j * length[:-1]
    origin = np.zeros(n - 1, dtype=complex)
    p1 = np.where(col, a1, b1)
    u1, h1 = _local(b0, a0, p1)
    q1 = _place(top, origin, u1, h1)
    x3, y3, p2 = np.where(col, b0, p1), np.where(col, p1, a0), np.where(col, b1, a1)
    u2, h2 = _local(x3, y3, p2)
    q2 = _place(np.where(first, top, q1), np.where(first, q1, origin), u2, h2)
    next_a, next_b = np.where(first, q1, q2), np.where(first, q2, q1)

    # Compose the frames: R_{i+1} = R_i·r_i, t_{i+1} = t_i + R_i·A'_{i+1}.
    step = (next_b - next_a) / 1j
    rot = np.concatenate([[1.0 + 0j], np.cumprod(step / np.abs(step))])
    rot /= np.abs(rot)
    shift = np.concatenate([[0j], np.cumsum(rot[:-1] * next_a)])
    za, zb = shift, shift + rot * 1j * length
    starts2d = np.column_stack([za.real, za.imag])
    ends2d = np.column_stack([zb.real, zb.imag])
    return starts2d, ends2d, first


def _development(
    a: FloatArray, b: FloatArray, starts2d: FloatArray, ends2d: FloatArray, first: NDArray,
    area_3d: float | None,
) -> Development:
    """The :class:`Development` of the strip ``a → b`` laid down at ``starts2d → ends2d``."""
    n = len(a)
    vertices2d, vertices3d = np.vstack([starts2d, ends2d]), np.vstack([a, b])
    tmap = DevelopmentMap(vertices2d, vertices3d, first)
    t2, t3 = vertices2d[tmap.triangles], vertices3d[tmap.triangles]
    edges2d = np.linalg.norm(t2 - np.roll(t2, -1, axis=1), axis=2)
    edges3d = np.linalg.norm(t3 - np.roll(t3, -1, axis=1), axis=2)
    diameter = float(np.linalg.norm(np.ptp(vertices3d, axis=0)))
    scale = np.where(edges3d > EDGE_COLLAPSED * diameter, edges3d, diameter)
    edge_error = float(np.max(np.abs(edges2d - edges3d) / scale))

    area_2d = float(0.5 * tmap._area2.sum())
    area3 = float(bilinear_quad_areas(a, b).sum()) if area_3d is None else float(area_3d)
    normals = np.cross(t3[:, 1] - t3[:, 0], t3[:, 2] - t3[:, 0]).reshape(n - 1, 2, 3)
    hinge = np.arctan2(np.linalg.norm(np.cross(normals[:, 0], normals[:, 1]), axis=1),
                       _dot(normals[:, 0], normals[:, 1]))
    # a quad with a collapsed edge (in a fan) is one triangle: it does not fold
    hinge = np.where(np.linalg.norm(normals, axis=2).min(axis=1) > EDGE_COLLAPSED * diameter**2, hinge, 0.0)
    return Development(
        starts2d=starts2d, ends2d=ends2d, starts3d=a, ends3d=b,
        area_3d=area3, area_2d=area_2d,
        area_error=(area_2d - area3) / area3 if area3 > 0 else float("nan"),
        max_edge_length_error=edge_error, hinge_angles=hinge, map=tmap,
    )


def _rail_lengths(rulings: FloatArray) -> FloatArray:
    """Lengths ``(2,)`` of the two chord polylines through the rulings' starts and ends."""
    return np.linalg.norm(np.diff(rulings, axis=0), axis=2).sum(axis=0)


def edge_subdivisions(
    surface: Surface, segments: int, subdivisions: int, tolerance: float
) -> tuple[int, FloatArray, float]:
    """About the fewest rulings per segment (at least ``subdivisions``) for which both rails'
    chord polylines are within ``tolerance`` (relative to the strip's size) of the rails'
    arc lengths, the sampled rulings ``(n, 2, 3)`` and that estimated relative error.

    A chord polyline of a smooth rail falls short of its arc length by C/k² at k rulings
    per segment, so the chord sums L(k₁) and L(k₂) of two samplings give the error of the
    finer one as |L(k₂) − L(k₁)| / ((k₂/k₁)² − 1) (Richardson). Starting from
    ``subdivisions`` and twice that, the next k is the one that law asks for (at least
    1.5 times the last). A rail that is not smooth enough for the law (a kink, a cusp at
    an edge of regression) does not settle within :data:`REFINEMENTS` samplings or
    :data:`MAX_RULINGS` rulings: then the first sampling is returned, with its error.
    """
    longest = max(MAX_RULINGS // segments, 2 * subdivisions)
    k1 = first = subdivisions
    coarse = start = surface.rulings(segments * k1 + 1)
    size = float(np.ptp(coarse.reshape(-1, 3), axis=0).max()) or 1.0
    k2 = 2 * k1
    first_error = np.inf
    for _ in range(REFINEMENTS):
        fine = surface.rulings(segments * k2 + 1)
        step = np.abs(_rail_lengths(fine) - _rail_lengths(coarse))
        error = float(step.max() / ((k2 / k1) ** 2 - 1.0) / size)
        if not np.isfinite(error):
            break
        if k1 == first:
            first_error = error * (k2 / k1) ** 2
            if first_error <= tolerance:  # the first sampling was already enough
                return k1, coarse, first_error
        if error <= tolerance:
            return k2, fine, error
        if k2 >= longest:
            break
        wanted = int(np.ceil(k2 * np.sqrt(error / tolerance) * 1.2))
        k1, coarse, k2 = k2, fine, min(max(wanted, int(np.ceil(1.5 * k2))), longest)
    return first, start, first_error


#: Most rulings :func:`edge_subdivisions` samples along a strip.
MAX_RULINGS = 1 << 12
#: Most refined samplings :func:`edge_subdivisions` tries before it gives up.
REFINEMENTS = 4


def unroll_surface(
    surface: Surface, segments: int, subdivisions: int = 8, edge_tolerance: float | None = None
) -> Development:
    """Unroll a smooth ruled surface: IsoMapping's accurate path.

    ``segments + 1`` rulings are the ones the user sees; between each pair
    ``subdivisions − 1`` more are sampled from the surface itself, so the chords the
    strip is made of hug the surface and the O(1/n²) chord error shrinks by
    ``subdivisions²`` (area error of a full cone at 100 segments: 2.9e-4 → 4.5e-6). The 3D area is the
    surface's own (exact cubature). ``Development.rulings2d`` picks the user's rulings.

    With ``edge_tolerance`` (relative to the strip's size) more rulings are sampled, as
    many per segment as :func:`edge_subdivisions` finds, until both flat edges — chord
    polylines congruent to the 3D ones — are as long as the 3D edges to that tolerance:
    then two strips that share a curve have flat edges of the same length (their seam
    closes), whatever stations each strip samples the curve at.

    Raises ValueError("surface has no straight rulings") for a non-ruled surface.
    """
    if segments < 1 or subdivisions < 1:
        raise ValueError("segments and subdivisions must be at least 1")
    if edge_tolerance is None:
        rulings = surface.rulings(segments * subdivisions + 1)
    else:
        subdivisions, rulings, _ = edge_subdivisions(surface, segments, subdivisions, edge_tolerance)
    development = unroll_rulings(rulings[:, 0], rulings[:, 1], area_3d=surface.area())
    return replace(development, stride=subdivisions)
