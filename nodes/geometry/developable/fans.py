"""Fans: the triangles of a strip where its rulings pass through single points, and their share.

Three kinds of fan arise in a strip between curves A and B (steps 6–7 of :mod:`.ruling`):

- *Planar pieces* (:func:`flat_fans`): where the chosen partners lie in a flat run the
  strip is planar and any pairing is developable; it is drawn as two triangles split along
  the shorter diagonal, or, where its edges have corners, cut into fans from the corners
  (:func:`strip_triangulation`).
- *Torsal fans through a point of A* (:func:`a_fans`): where t jumps between two stations
  (B straight and A curved, or a corner of A), rulings from one point A(s*) to a stretch
  of B, each of them torsal.
- *Closing triangles* (:func:`close_gaps`): over a run of stations on A without a torsal
  partner on B, the strip is bounded by the torsal rulings on either side (or by the
  curves' ends) and by the two stretches of A and B in between. That piece is closed by
  a strip of triangles, each with two corners on one curve and one on the other — a
  sequence of fans through single points, as the planar middle of the ZVE roof edge is
  made. Three points are always coplanar, so every triangle is flat and the strip stays
  developable (it unrolls exactly); what it gives up is tangency to the curves, so its
  rulings are flagged, not counted as torsal.

The closing triangles follow the two stretches in step (:func:`zigzag`): the next ruling
advances along the curve whose next vertex is nearer in *fraction of its stretch's
length*, so the triangles are about as wide on both curves and no ruling crosses another.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from nodes.geometry.array_types import BoolArray, IntArray

from ..curve_base import FloatArray
from ..vec_ops import cross, det, flatnonzero, norm, unit
from ..vec_ops import extent as box_extent
from .brackets import refine_roots
from .candidates import FLAT_END, Candidates, rounding_scale
from .strip import SIDE, Strip


def zigzag(length_a: FloatArray, length_b: FloatArray) -> tuple[IntArray, IntArray]:
    """Vertex indices ``(i, j)`` of the rulings of the triangle strip between a chain of
    points on A at arc lengths ``length_a`` (non-decreasing) and one on B at
    ``length_b``: from (0, 0) to (last, last), each step advancing along one chain.

    >>> i, j = zigzag(np.array([0.0, 1.0, 2.0]), np.array([0.0, 3.0, 4.0]))
    >>> i.tolist(), j.tolist()
    ([0, 1, 1, 2, 2], [0, 0, 1, 1, 2])
    """
    fa, fb = _fractions(length_a), _fractions(length_b)
    keys = np.concatenate([fa[1:], fb[1:]])
    along_b = np.concatenate([np.zeros(len(fa) - 1, dtype=bool), np.ones(len(fb) - 1, dtype=bool)])
    # step to whichever next vertex comes first, A's before B's at a tie
    steps = along_b[np.lexsort((along_b, keys))]
    i = np.concatenate([[0], np.cumsum(~steps)])
    j = np.concatenate([[0], np.cumsum(steps)])
    return i.astype(np.int64), j.astype(np.int64)


def _fractions(length: FloatArray) -> FloatArray:
    """Arc lengths as fractions of the chain's length (even steps if it has none)."""
    span = float(length[-1] - length[0])
    if len(length) < 2 or not span > 0:
        return np.linspace(0.0, 1.0, len(length))
    return (length - length[0]) / span


def patch_areas(starts: FloatArray, ends: FloatArray) -> FloatArray:
    """Area of each piece of strip between consecutive rulings ``(starts[k], ends[k])`` and
    ``(starts[k+1], ends[k+1])``: half the cross product of the quad's diagonals, exact
    for a flat quad and for a triangle (two rulings sharing an end)."""
    diagonal = ends[1:] - starts[:-1]
    other = ends[:-1] - starts[1:]
    return 0.5 * norm(cross(diagonal, other))


def creased_fans(starts: FloatArray, ends: FloatArray, fan: NDArray[np.bool_]) -> NDArray[np.bool_]:
    """Which pieces between consecutive rulings belong to a fan that creases the sheet.

    A run of fan pieces whose rulings all pass through one point (a cone through a single
    point of A or of B, like the triangle that closes a strip's end where the curves' ends
    admit no torsal ruling) meets the torsal rulings on either side in their own tangent
    planes — both contain the ruling and the moving curve's tangent — so the sheet stays
    smooth (G1) and exactly developable. A run that needs apexes on both curves (a zigzag
    of triangles over a stretch with no torsal ruling) folds at every change of apex:
    those are the pieces that need the designer. Returns one flag per piece.
    """
    in_fan = fan[:-1] | fan[1:]
    creased = np.zeros(len(in_fan), dtype=bool)
    if not in_fan.any():
        return creased
    size = float(box_extent(np.concatenate([starts, ends])).max()) or 1.0
    same_start = norm(starts[1:] - starts[:-1]) <= 1e-12 * size
    same_end = norm(ends[1:] - ends[:-1]) <= 1e-12 * size
    edges = flatnonzero(np.diff(np.concatenate([[0], in_fan.astype(np.int8), [0]])))
    for first, stop in zip(edges[::2], edges[1::2], strict=True):  # runs of fan pieces
        one_apex = same_start[first:stop].all() or same_end[first:stop].all()
        creased[first:stop] = not one_apex
    return creased


def area_share(starts: FloatArray, ends: FloatArray, pieces: NDArray[np.bool_]) -> float:
    """The share of the strip's area in the flagged ``pieces`` (0 to 1)."""
    areas = patch_areas(starts, ends)
    total = float(areas.sum())
    if not total > 0:
        return 0.0 if not pieces.any() else 1.0
    return float(areas[pieces].sum() / total)


def fan_shares(starts: FloatArray, ends: FloatArray, fan: NDArray[np.bool_]) -> tuple[float, float]:
    """:func:`fan_share` and the share of the creased fans (:func:`area_share` of
    :func:`creased_fans`), from one measurement of the pieces' areas."""
    areas = patch_areas(starts, ends)
    total = float(areas.sum())
    creased = creased_fans(starts, ends, fan)
    if not total > 0:
        return (0.0 if not fan.any() else 1.0), (0.0 if not creased.any() else 1.0)
    in_fan = fan[:-1] | fan[1:]
    return float(areas[in_fan].sum() / total), float(areas[creased].sum() / total)


def fan_share(starts: FloatArray, ends: FloatArray, fan: NDArray[np.bool_]) -> float:
    """The share of the strip's area in pieces next to a fan ruling (0 to 1)."""
    areas = patch_areas(starts, ends)
    total = float(areas.sum())
    if not total > 0:
        return 0.0 if not fan.any() else 1.0
    in_fan = fan[:-1] | fan[1:]
    return float(areas[in_fan].sum() / total)


# -- planar pieces ------------------------------------------------------------------------------


def flat_fans(strip: Strip, t: FloatArray, chosen: IntArray, good: Candidates) -> tuple[list, BoolArray]:
    """Two triangles for every run of stations inside one planar piece.

    Rewrites ``t`` there and returns the fans ``(s*, t_low, t_high)`` through a point
    of A, and a mask of the stations of planar pieces.
    """
    n = len(t)
    has = chosen >= 0
    is_flat = np.zeros(n, dtype=bool)
    is_flat[has] = good.kind[chosen[has]] == FLAT_END
    fans: list[tuple[float, float, float]] = []
    if not is_flat.any():
        return fans, is_flat
    low = np.where(is_flat, good.low[chosen], np.nan)
    high = np.where(is_flat, good.high[chosen], np.nan)
    # consecutive flat stations whose flat intervals overlap form one planar piece
    joins = is_flat[1:] & is_flat[:-1] & (low[1:] <= high[:-1]) & (low[:-1] <= high[1:])
    begins = flatnonzero(is_flat & ~np.concatenate([[False], joins]))
    finishes = flatnonzero(is_flat & ~np.concatenate([joins, [False]]))
    for i0, i1 in zip(begins, finishes, strict=True):  # one pass per planar piece (few)
        t_in = low[i0] if i0 == 0 or np.isnan(t[i0 - 1]) else max(low[i0], t[i0 - 1])
        t_out = high[i1] if i1 == n - 1 or np.isnan(t[i1 + 1]) else min(high[i1], t[i1 + 1])
        t_out = max(t_out, t_in)
        corners_a = strip.kinks_a[(strip.kinks_a > strip.s[i0]) & (strip.kinks_a < strip.s[i1])]
        corners_b = strip.kinks_b[(strip.kinks_b > t_in) & (strip.kinks_b < t_out)]
        if len(corners_a) or len(corners_b):  # a polygon, not a quad
            fans += _polygon_fans(strip, t, i0, i1, corners_a, t_in, corners_b, t_out)
            continue
        b_in, b_out = strip.curve_b.point_at(np.array([t_in, t_out]))
        # the shorter diagonal: a fan through B(t_in) then one through A(s_i1), or a fan
        # through A(s_i0) then one through B(t_out)
        if norm(strip.a0[i1] - b_in) <= norm(strip.a0[i0] - b_out):
            t[i0 : i1 + 1] = t_in
            fans.append((float(strip.s[i1]), float(t_in), float(t_out)))
        else:
            t[i0 : i1 + 1] = t_out
            fans.append((float(strip.s[i0]), float(t_in), float(t_out)))
    return fans, is_flat

def _polygon_fans(
    strip: Strip,
    t: FloatArray,
    i0: int,
    i1: int,
    corners_a: FloatArray,
    t_in: float,
    corners_b: FloatArray,
    t_out: float,
) -> list[tuple[float, float, float]]:
    """Fans for a planar piece whose edges have corners: a polygon, cut into triangles
    that each join an edge of one curve (between corners) to a corner of the other.

    Rewrites ``t`` for stations ``i0..i1`` (each takes the corner of B its triangle
    leans on) and returns the fans through corners of A; see :func:`strip_triangulation`.
    """
    sa = np.concatenate([[strip.s[i0]], corners_a, [strip.s[i1]]])
    tb = np.concatenate([[t_in], corners_b, [t_out]])
    stations = strip.s[i0 : i1 + 1]
    piece = t[i0 : i1 + 1]
    fans = []
    i = j = 0
    for along_a in strip_triangulation(strip.curve_a.point_at(sa), strip.curve_b.point_at(tb)):
        if along_a:  # triangle A_i A_i+1 B_j: the stations between lean on B_j
            piece[(stations >= sa[i]) & (stations <= sa[i + 1])] = tb[j]
            i += 1
        else:  # triangle A_i B_j B_j+1: a fan through A_i
            fans.append((float(sa[i]), float(tb[j]), float(tb[j + 1])))
            j += 1
    return fans

def strip_triangulation(a: FloatArray, b: FloatArray) -> list[bool]:
    """Triangles for the planar polygon a[0] … a[-1], b[-1] … b[0] whose every diagonal
    joins a vertex of chain ``a`` to one of chain ``b``: the moves, True to advance along
    ``a`` (triangle a_i a_i+1 b_j), False along ``b`` (triangle a_i b_j b_j+1).

    Each step takes the shorter new diagonal among the moves whose triangle turns the way
    the polygon does and whose diagonal crosses no edge of the polygon (so a chain that
    bends towards the other, as a V, is fanned from its corner instead of being cut off).
    """
    polygon = np.concatenate([a, b[::-1]])
    # the polygon's normal (Newell) and two axes of its plane, for signed areas and crossings
    normal = cross(polygon, np.roll(polygon, -1, axis=0)).sum(axis=0)
    normal = normal / max(float(norm(normal)), 1e-300)
    x_axis = unit(polygon[np.argmax(norm(polygon - polygon[0]))] - polygon[0])
    flat = np.column_stack([polygon @ x_axis, polygon @ cross(normal, x_axis)])
    fa, fb = flat[: len(a)], flat[len(a) :][::-1]
    size = float(np.ptp(flat, axis=0).max()) or 1.0
    edges = np.stack([flat, np.roll(flat, -1, axis=0)], axis=1)

    def area(p: FloatArray, q: FloatArray, r: FloatArray) -> float:
        return float((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]))

    def crosses(p: FloatArray, q: FloatArray) -> bool:
        """Whether segment pq properly crosses an edge of the polygon (shared ends do not count)."""
        e0, e1 = edges[:, 0], edges[:, 1]
        d = q - p
        side0 = d[0] * (e0[:, 1] - p[1]) - d[1] * (e0[:, 0] - p[0])
        side1 = d[0] * (e1[:, 1] - p[1]) - d[1] * (e1[:, 0] - p[0])
        e = e1 - e0
        side_p = e[:, 0] * (p[1] - e0[:, 1]) - e[:, 1] * (p[0] - e0[:, 0])
        side_q = e[:, 0] * (q[1] - e0[:, 1]) - e[:, 1] * (q[0] - e0[:, 0])
        tiny = 1e-12 * size * size
        return bool(np.any((side0 * side1 < -tiny * tiny) & (side_p * side_q < -tiny * tiny)))

    moves: list[bool] = []
    i = j = 0
    while i < len(a) - 1 or j < len(b) - 1:
        options = []  # (invalid, diagonal length, move)
        if i < len(a) - 1:
            diagonal = (fa[i + 1], fb[j])
            bad = area(fa[i], fa[i + 1], fb[j]) <= 1e-12 * size * size or crosses(*diagonal)
            options.append((bad, float(np.hypot(*(diagonal[1] - diagonal[0]))), True))
        if j < len(b) - 1:
            diagonal = (fa[i], fb[j + 1])
            bad = area(fa[i], fb[j + 1], fb[j]) <= 1e-12 * size * size or crosses(*diagonal)
            options.append((bad, float(np.hypot(*(diagonal[1] - diagonal[0]))), False))
        move = min(options)[2]
        moves.append(move)
        i, j = (i + 1, j) if move else (i, j + 1)
    return moves


# -- fans through a point of A -------------------------------------------------------------------


def a_fans(
    strip: Strip, t: FloatArray, slope: FloatArray, regular: BoolArray
) -> list[tuple[float, float, float]]:
    """Fans through single points of A, found where t jumps between two stations.

    Along one branch t steps by about Δs·(mean slope); a much larger step means the
    strip's path in the (s, t) square runs vertically in between: a fan of rulings
    from one point A(s*) to a stretch of B (a triangle on a straight piece of B, or a
    cone at a corner of A). s* solves f(s, t_mid) = 0 for s, or is the corner of A.
    """
    s = strip.s
    dt = t[1:] - t[:-1]
    predicted = 0.5 * (s[1:] - s[:-1]) * (slope[:-1] + slope[1:])
    jump = regular[:-1] & regular[1:] & (dt > 1e-10) & (np.abs(dt - predicted) > 0.25 * dt)
    pairs = flatnonzero(jump)
    if len(pairs) == 0:
        return []
    # a hole, if no torsal fan covers it, only where the step is over twice both neighbouring
    # ones (the slope is a poor guide where f_t vanishes, as at an inflection)
    before = np.concatenate([[np.nan], dt[:-1]])
    after = np.concatenate([dt[1:], [np.nan]])
    neighbours = np.fmax(before, after)
    with np.errstate(invalid="ignore"):
        dwarfs = dt > 2.0 * neighbours  # (never with no neighbour to compare)
    t_mid = 0.5 * (t[pairs] + t[pairs + 1])
    bm0, bm1 = strip.curve_b.derivatives(t_mid, 1)
    f_left = det(bm0 - strip.a0[pairs], strip.a1[pairs], bm1)
    f_right = det(bm0 - strip.a0[pairs + 1], strip.a1[pairs + 1], bm1)
    apex = np.full(len(pairs), np.nan)
    which = flatnonzero(f_left * f_right < 0)
    if len(which):

        def coplanarity(x: FloatArray, index: IntArray) -> tuple[FloatArray, FloatArray, FloatArray]:
            c0, c1, c2 = strip.curve_a.derivatives(x, 2)
            k = which[index]
            r = bm0[k] - c0
            # f and f_s = det[R, A'', B'] (the term det[−A', A', B'] vanishes)
            return (
                det(r, c1, bm1[k]),
                det(r, c2, bm1[k]),
                rounding_scale(norm(c0), bm0[k], norm(c1), bm1[k]),
            )

        low, high = s[pairs[which]], s[pairs[which] + 1]
        apex[which] = refine_roots(coplanarity, low, high, f_left[which])
        # a root that converged onto a corner of A (a jump of f) or onto a station is that point
        for exact in (strip.kinks_a, s):
            if len(exact):
                nearest = exact[np.argmin(np.abs(apex[:, None] - exact[None, :]), axis=1)]
                apex = np.where(np.abs(apex - nearest) <= 1e-12, nearest, apex)
    fans = []
    for k, i in enumerate(pairs):  # one pass per possible fan (rare)
        s_star = float(apex[k])
        if np.isnan(s_star):
            inside = strip.kinks_a[(strip.kinks_a >= s[i]) & (strip.kinks_a <= s[i + 1])]
            if len(inside) == 0:
                if dwarfs[i]:
                    strip.holes.append(int(i))
                continue
            s_star = float(inside[0])
        extent = _fan_extent(strip, s_star, float(t[i]), float(t[i + 1]))
        if extent is not None:
            fans.append((s_star, *extent))
        elif dwarfs[i]:
            strip.holes.append(int(i))
    return fans

def _fan_extent(strip: Strip, s_star: float, t0: float, t1: float) -> tuple[float, float] | None:
    """The stretch of B inside [t0, t1] over which rulings from A(s*) are torsal."""
    c0 = strip.curve_a.point_at(s_star)
    sides = strip.curve_a.derivatives(np.clip([s_star - SIDE, s_star + SIDE], 0.0, 1.0), 1)[1]
    window = (strip.grid.t >= t0) & (strip.grid.t <= t1)
    ts = np.unique(np.concatenate([[t0, t1], strip.grid.t[window]]))
    # at a corner of B the stretch may end with the tangent from either side
    at_kink = np.isin(ts, strip.kinks_b)
    b0, b1 = strip.curve_b.derivatives(np.concatenate([ts, ts[at_kink] - SIDE]), 1)
    r = b0 - c0
    r = np.concatenate([r[: len(ts)], r[: len(ts)][at_kink]])
    scale = norm(r) * norm(b1)
    scale = np.where(scale > 0, scale, 1.0)
    g_left = det(r, unit(sides[0]), b1) / scale
    g_right = det(r, unit(sides[1]), b1) / scale
    # torsal: flat (B straight there), or between the two one-sided tangents of a corner
    torsal_all = (np.abs(g_left) <= 1e-9) | (np.abs(g_right) <= 1e-9) | (g_left * g_right < 0)
    torsal = torsal_all[: len(ts)]
    torsal[at_kink] |= torsal_all[len(ts) :]
    if torsal.sum() < 2:
        return None
    first = int(np.argmax(torsal))
    last = len(ts) - 1 - int(np.argmax(torsal[::-1]))
    if not torsal[first : last + 1].all() or ts[last] <= ts[first]:
        return None
    return float(ts[first]), float(ts[last])


# -- closing the stretches without a torsal ruling ------------------------------------------------


def close_gaps(
    strip: Strip, t: FloatArray, fans: list | None = None
) -> list[tuple[FloatArray, FloatArray]]:
    """Close every run of stations still without a partner (NaN in ``t``) with flat
    triangles (:mod:`.fans`), and the stretches of B beyond the first and the last
    ruling with fans through A's ends.

    A stretch of B between two torsal stations that no torsal fan covers (t jumps
    there: :func:`a_fans` lists it in ``holes``) is closed the same way. A gap starts
    where the torsal rulings before it end on B: at the station before it, or at the far
    end of a torsal fan ``(s*, t_low, t_high)`` through that station (``fans``, those
    :func:`outside_gaps` keeps), and likewise it ends where those after it begin, so
    the closing rulings never run back over B (they would cross the fan's).

    Sets ``t`` at the gap stations and returns the added rulings as ``(s, t)`` arrays.
    """
    n = len(t)
    gap = np.isnan(t)
    added: list[tuple[FloatArray, FloatArray]] = []
    for i in strip.holes:  # one pass per stretch of B that t jumps over (rare)
        if gap[i] or gap[i + 1]:
            continue  # closed with the gap around it
        tb = strip.gap_parameters(float(t[i]), float(t[i + 1]))
        a, b = zigzag(strip.station_lengths[i : i + 2], strip.length_b(tb))
        inner = slice(1, len(a) - 1)  # the two stations' own rulings are there already
        added.append((strip.s[i + a[inner]], tb[b[inner]]))
    begins = flatnonzero(gap & ~np.concatenate([[False], gap[:-1]]))
    finishes = flatnonzero(gap & ~np.concatenate([gap[1:], [False]]))
    closed = strip.curve_b.closed
    for i0, i1 in zip(begins, finishes, strict=True):  # one pass per gap (few)
        k0, k1 = max(i0 - 1, 0), min(i1 + 1, n - 1)
        t_lo = float(t[i0 - 1]) if i0 > 0 else 0.0
        t_hi = float(t[i1 + 1]) if i1 < n - 1 else (float(t[0]) if closed and i0 > 0 else 1.0)
        for fan in fans or ():  # a torsal fan through the station before (after) the gap
            if i0 > 0 and fan[0] == strip.s[i0 - 1] and t_lo < fan[2] <= t_hi:
                t_lo = fan[2]
            if i1 < n - 1 and fan[0] == strip.s[i1 + 1] and t_lo <= fan[1] < t_hi:
                t_hi = fan[1]
        if t_hi < t_lo and not closed:
            t_hi = t_lo
        if t_hi < t_lo:  # through the seam of a closed B
            before, after = strip.gap_parameters(t_lo, 1.0), strip.gap_parameters(0.0, t_hi)[1:]
            tb = np.concatenate([before, after])
            lb = np.concatenate([strip.length_b(before), strip.length_b(after) + strip.chords_b[-1]])
        else:
            tb = strip.gap_parameters(t_lo, t_hi)
            lb = strip.length_b(tb)
        i, j = zigzag(strip.station_lengths[k0 : k1 + 1], lb)
        station = k0 + i
        # the first ruling from each gap station is its station ruling; the rest are added
        first = np.ones(len(i), dtype=bool)
        first[1:] = i[1:] != i[:-1]
        is_gap = (station >= i0) & (station <= i1)
        t[station[first & is_gap]] = tb[j[first & is_gap]]
        extra = ~(first & is_gap)
        if i0 > 0:
            extra[0] = False  # the torsal ruling before the gap
        if i1 < n - 1:
            extra[-1] = False  # and after it
        if extra.any():
            added.append((strip.s[station[extra]], tb[j[extra]]))
    if not closed:
        if t[0] > 0.0:
            tb = strip.gap_parameters(0.0, float(t[0]))[:-1]
            added.append((np.zeros(len(tb)), tb))
        if t[-1] < 1.0:
            tb = strip.gap_parameters(float(t[-1]), 1.0)[1:]
            added.append((np.ones(len(tb)), tb))
    return added

def outside_gaps(fans: list, s: FloatArray, gap: BoolArray) -> list:
    """The torsal fans ``(s*, t_low, t_high)`` whose apex is neither inside a gap's stretch
    of A (from the torsal station before the gap to the one after it) nor a gap station."""
    if not fans or not gap.any():
        return fans
    n = len(s)
    begins = flatnonzero(gap & ~np.concatenate([[False], gap[:-1]]))
    finishes = flatnonzero(gap & ~np.concatenate([gap[1:], [False]]))
    low, high = s[np.maximum(begins - 1, 0)], s[np.minimum(finishes + 1, n - 1)]
    through_gap = s[gap]
    return [
        fan for fan in fans if not (np.any((low < fan[0]) & (fan[0] < high)) or np.any(through_gap == fan[0]))
    ]
