"""The map between a strip's development and its 3D triangles (:class:`DevelopmentMap`).

An n-ruling strip is triangulated the same way in the plane and in space
(:func:`strip_triangles`: vertex ``i`` = A_i, ``n + i`` = B_i, two triangles per quad
along one diagonal); within a triangle a point keeps its barycentric coordinates.
:mod:`.unroll` lays the triangles flat and builds the map; here it is used: plane →
surface (point location), surface → plane (closest point on the 3D triangles), strip
coordinates, and polylines split where they cross a ruling or a diagonal.

shapely is imported where an STR-tree or a ring test is first needed: a strip that does
not overlap itself is located by its walk alone, and ``torsal gui`` on such a graph (the
flagship) reaches its first frame without importing shapely (~36 modules).
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.spatial import cKDTree

from torsal.nodes.geometry.array_types import FloatArray, IntArray
from torsal.nodes.geometry.vec_ops import cross2, extent, linalg_norm
from torsal.nodes.geometry.vec_ops import dot as _dot

from .strip_walk import StripWalk, strip_triangles
from .watch import watch_check, watch_progress

if TYPE_CHECKING:
    import shapely

#: Distances within this share of the strip's size count as equal when points are
#: located on the 3D triangles (a point on a shared edge is on both triangles).
TIE = 1e-9

#: Points carried onto the strip between two looks at the cancel token (≈ 2 ms a block).
MAP_BLOCK = 1024

#: Segments tested for crossings between two looks at the cancel token (≈ 5 ms a block:
#: the walk that places their ends costs ten times the point location above).
CROSSING_BLOCK = 256

#: Consecutive outline points closer than this share of the development's size are one
#: vertex (a fan's apex, unrolled once per ruling: its images differ by rounding only, and
#: kept apart they would zigzag across each other).
REPEATED = 1e-9


def rotate_about(points: FloatArray, angle: float, pivot: FloatArray) -> FloatArray:
    """2D points ``(k, 2)`` turned counter-clockwise by ``angle`` (rad) about ``pivot``."""
    c, s = np.cos(angle), np.sin(angle)
    d = points - pivot
    return pivot + np.column_stack([c * d[:, 0] - s * d[:, 1], s * d[:, 0] + c * d[:, 1]])


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
        self._area2 = cross2(e1, e2)  # twice the signed area
        size = float(extent(self.vertices2d).max()) or 1.0
        #: triangles with area: the only ones a point can be located in
        self.proper_area = 1e-13 * size * size
        self.proper = np.flatnonzero(self._area2 > self.proper_area)
        if self.proper.size == 0:
            raise ValueError("the strip has no area: every triangle is degenerate")

    def moved(self, offset: ArrayLike) -> DevelopmentMap:
        """The same map with the 3D side moved by ``offset``."""
        return DevelopmentMap(self.vertices2d, self.vertices3d + np.asarray(offset, dtype=float).reshape(3),
                              self.first_diagonal)

    def rotated(self, angle: float, pivot: ArrayLike) -> DevelopmentMap:
        """The same map with the plane side turned by ``angle`` (rad) about ``pivot``."""
        turned = rotate_about(self.vertices2d, angle, np.asarray(pivot, dtype=float))
        return DevelopmentMap(turned, self.vertices3d, self.first_diagonal)

    # ------------------------------------------------------------- plane → surface

    @cached_property
    def _tree2d(self) -> shapely.STRtree:
        import shapely

        polys = shapely.polygons(self.vertices2d[self.triangles[self.proper]])
        return shapely.STRtree(polys)

    @cached_property
    def _walk(self) -> StripWalk | None:
        """The fast locator, for developments that do not overlap themselves (there a
        point lies in one triangle only; elsewhere the lowest-numbered must be found)."""
        outline = np.vstack([self.vertices2d[: self.n], self.vertices2d[self.n :][::-1]])
        if not is_simple(outline):
            return None
        return StripWalk(self.vertices2d, self.first_diagonal)

    def locate(self, points2d: ArrayLike) -> tuple[IntArray, FloatArray]:
        """Triangle index and barycentric coordinates ``(k, 3)`` of each 2D point.

        Each point walks along the strip to its triangle (:class:`.strip_walk.StripWalk`); where
        that fails (a development that overlaps itself, a point outside it) a shapely
        STR-tree finds the triangles that contain it (the lowest-numbered wins, also on
        a shared edge), and points outside every triangle take the nearest one.
        """
        pts = np.asarray(points2d, dtype=float).reshape(-1, 2)
        tri = np.full(len(pts), -1, dtype=np.int64)
        if self._walk is not None and len(pts):
            tri = self._walk.triangles(pts)
            tri[~self._holds(tri, pts)] = -1
        lost = np.flatnonzero(tri < 0)
        if lost.size:
            import shapely

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

    def _holds(self, tri: IntArray, pts: FloatArray) -> NDArray[np.bool_]:
        """Whether each triangle has area and holds its point (to rounding)."""
        with np.errstate(invalid="ignore"):
            inside = (self._barycentric(tri, pts) >= -1e-9).all(axis=1)
        return inside & (self._area2[tri] > self.proper_area)

    def _barycentric(self, tri: IntArray, pts: FloatArray) -> FloatArray:
        """Barycentric coordinates of ``pts`` in triangles ``tri`` (any, even outside)."""
        corners = self.vertices2d[self.triangles[tri]]
        e1, e2 = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
        d = pts - corners[:, 0]
        area2 = self._area2[tri]
        with np.errstate(divide="ignore", invalid="ignore"):
            v = cross2(d, e2) / area2
            w = cross2(e1, d) / area2
        return np.column_stack([1.0 - v - w, v, w])

    def to_3d(self, points2d: ArrayLike) -> FloatArray:
        """Points of the development carried onto the 3D strip, ``(k, 3)`` (in blocks of
        :data:`MAP_BLOCK` points, with a look at the cancel token before each, see :mod:`.watch`)."""
        pts = np.asarray(points2d, dtype=float).reshape(-1, 2)
        check = watch_check()
        blocks = [np.empty((0, 3))]
        for start in range(0, len(pts), MAP_BLOCK):
            if check:
                check()
            tri, bary = self.locate(pts[start:start + MAP_BLOCK])
            blocks.append(np.einsum("kj,kjd->kd", bary, self.vertices3d[self.triangles[tri]]))
        return np.vstack(blocks)

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
        bound = linalg_norm(np.einsum("kj,kjd->kd", bary, g) - pts)
        low, high = self._boxes3d
        tie = TIE * (float(np.linalg.norm(extent(self.vertices3d))) or 1.0)
        chunk = max(1, 2_000_000 // len(low))
        check, progress = watch_check(), watch_progress()
        found: list[tuple[IntArray, IntArray, FloatArray, FloatArray]] = []
        for start in range(0, len(pts), chunk):  # memory-bounded chunks, vectorised inside
            if check is not None:
                check()
            q = pts[start:start + chunk]
            gap = np.maximum(low[None] - q[:, None], 0.0) + np.maximum(q[:, None] - high[None], 0.0)
            near = linalg_norm(gap) <= (bound[start:start + chunk] + tie)[:, None]
            row, col = np.nonzero(near)
            c = corners[col]
            b = _closest_on_triangles(q[row], c[:, 0], c[:, 1], c[:, 2])
            dist = linalg_norm(np.einsum("kj,kjd->kd", b, c) - q[row])
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
            score = linalg_norm(images[:, None] - hints[rows]).sum(axis=1)
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
        ambiguous = spread > TIE * (float(extent(self.vertices2d).max()) or 1.0)
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
            score = linalg_norm(images[pick][:, None] - hints[rows[pick]]).sum(axis=1)
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
        import shapely

        n = self.n
        i = np.arange(n - 1)
        starts = np.concatenate([np.arange(n), np.where(self.first_diagonal, i + 1, i)])
        ends = np.concatenate([n + np.arange(n), np.where(self.first_diagonal, n + i, n + i + 1)])
        p, q = self.vertices2d[starts], self.vertices2d[ends]
        keep = linalg_norm(q - p) > 0
        p, q = p[keep], q[keep]
        return shapely.STRtree(shapely.linestrings(np.stack([p, q], axis=1))), p, q

    @cached_property
    def _outline_tree(self) -> shapely.STRtree:
        """The development's outline, edge by edge (short edges: a tight tree)."""
        import shapely

        ring = merge_repeats(np.vstack([self.vertices2d[: self.n], self.vertices2d[self.n :][::-1]]))
        return shapely.STRtree(shapely.linestrings(np.stack([ring, np.roll(ring, -1, axis=0)], axis=1)))

    def _crossings(self, p0: FloatArray, d: FloatArray) -> tuple[IntArray, FloatArray]:
        """Where segments ``p0 → p0 + d`` cross a ruling or diagonal: pairs (segment,
        parameter along it), ends excluded; in blocks of :data:`CROSSING_BLOCK` segments,
        with a look at the cancel token before each (see :mod:`.watch`)."""
        check = watch_check()
        seg_parts: list[IntArray] = [np.empty(0, dtype=np.int64)]
        par_parts: list[FloatArray] = [np.empty(0)]
        for start in range(0, len(p0), CROSSING_BLOCK):
            if check:
                check()
            stop = start + CROSSING_BLOCK
            seg, par = self._block_crossings(p0[start:stop], d[start:stop])
            seg_parts.append(seg + start)
            par_parts.append(par)
        return np.concatenate(seg_parts), np.concatenate(par_parts)

    def _block_crossings(self, p0: FloatArray, d: FloatArray) -> tuple[IntArray, FloatArray]:
        """:meth:`_crossings` for one block of segments.

        A segment that lies in a development which does not overlap itself crosses exactly
        the edges between the chain positions of its two ends, each once (two straight
        segments meet at most once, and an edge between them separates the ends); those
        are measured directly (its ends located by the walk, the outline not crossed). The
        other segments (an overlapping development, a segment that leaves the outline) are
        tested against every edge through a shapely STR-tree.
        """
        import shapely

        walk = self._walk
        rest = np.arange(len(p0))
        seg_parts: list[IntArray] = []
        par_parts: list[FloatArray] = []
        if walk is not None:
            lines = shapely.linestrings(np.stack([p0, p0 + d], axis=1))
            inside = np.ones(len(p0), dtype=bool)
            inside[self._outline_tree.query(lines, predicate="crosses")[0]] = False
            k0, k1 = walk.positions(p0), walk.positions(p0 + d)
            inside &= self._holds(walk.chain[k0], p0) & self._holds(walk.chain[k1], p0 + d)
            rest, seg = np.flatnonzero(~inside), np.flatnonzero(inside)
            k0, k1 = k0[seg], k1[seg]
            low, count = np.minimum(k0, k1), np.abs(k1 - k0)
            pair_seg = np.repeat(seg, count)
            edge = np.repeat(low + 1 - np.cumsum(count) + count, count) + np.arange(int(count.sum()))
            seg_parts.append(pair_seg)
            par_parts.append(self._cross_parameters(p0[pair_seg], d[pair_seg], walk.edge_start[edge],
                                                    walk.edge_vector[edge]))
        if rest.size:
            tree, ep, eq = self._edge_tree
            hit, hit_edge = tree.query(shapely.linestrings(np.stack([p0[rest], p0[rest] + d[rest]], axis=1)),
                                       predicate="intersects")
            seg_parts.append(rest[hit])
            par_parts.append(self._cross_parameters(p0[rest[hit]], d[rest[hit]], ep[hit_edge],
                                                    eq[hit_edge] - ep[hit_edge]))
        seg_all, par_all = np.concatenate(seg_parts), np.concatenate(par_parts)
        ok = np.isfinite(par_all)
        return seg_all[ok], par_all[ok]

    @staticmethod
    def _cross_parameters(p0: FloatArray, ds: FloatArray, ep: FloatArray, de: FloatArray) -> FloatArray:
        """Parameter along each segment ``p0 → p0 + ds`` where it meets the line of its edge
        ``ep → ep + de``; NaN where they are parallel or meet at (or beyond) the segment's
        ends (collinear overlaps need no split)."""
        w = ep - p0
        den = cross2(ds, de)
        ok = np.abs(den) > 1e-14 * linalg_norm(ds) * linalg_norm(de)
        with np.errstate(divide="ignore", invalid="ignore"):
            t = cross2(w, de) / den
        ok &= (t > 1e-12) & (t < 1.0 - 1e-12)
        return np.where(ok, t, np.nan)

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
            pieces = np.maximum(1, np.ceil(linalg_norm(d) / max_length)).astype(np.int64)
            extra = np.repeat(np.arange(len(inner)), pieces - 1)
            rank = np.arange(len(extra)) - np.repeat(np.cumsum(pieces - 1) - (pieces - 1), pieces - 1)
            seg.append(extra)
            param.append((rank + 1) / pieces[extra])
        if len(inner):
            hit_seg, t = self._crossings(p0, d)
            seg.append(hit_seg)
            param.append(t)
        # the sort and the new points each cost about a block of crossings (≈ 10 ms for
        # 70,000 points): a look at the cancel token before each (see :mod:`.watch`)
        check = watch_check()
        if check:
            check()
        seg_all, par_all = np.concatenate(seg), np.concatenate(param)
        # every polyline's own last vertex closes it: key (its last point's index, 0)
        last = np.cumsum(counts) - 1
        key = np.concatenate([inner[seg_all], last])
        par = np.concatenate([par_all, np.zeros(len(last))])
        order = np.lexsort((par, key))
        if check:
            check()
        key, par = key[order], par[order]
        closing = np.zeros(len(key), dtype=bool)
        closing[len(par_all):] = True
        closing = closing[order]
        nxt = np.minimum(key + 1, len(pts) - 1)
        out = np.where(closing[:, None], pts[key], pts[key] + par[:, None] * (pts[nxt] - pts[key]))
        who = owner[key]
        size = float(extent(pts).max()) or 1.0
        step = linalg_norm(np.diff(out, axis=0))
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



def merge_repeats(ring: FloatArray) -> FloatArray:
    """The closed polygon without the points within :data:`REPEATED` of its size of the
    point before them (nor a last point that repeats the first)."""
    size = float(extent(ring).max()) or 1.0
    keep = np.r_[True, linalg_norm(np.diff(ring, axis=0)) > REPEATED * size]
    merged = ring[keep]
    if len(merged) > 1 and np.linalg.norm(merged[-1] - merged[0]) <= REPEATED * size:
        merged = merged[:-1]
    return merged


def is_simple(outline: FloatArray) -> bool:
    """Whether the closed polygon does not cross or touch itself. A point repeated in a
    row, to rounding (a cone's apex, the end of every ruling of its fan), is one vertex."""
    import shapely

    return bool(shapely.LinearRing(merge_repeats(outline)).is_simple)
