"""Fans: the triangles of a strip where its rulings pass through single points, and their share.

Three kinds of fan arise in a strip between curves A and B (steps 6–7 of :mod:`.ruling`):

- *Planar pieces* (:func:`flat_fans`): where the chosen partners lie in a flat run the
  strip is planar and any pairing is developable; it is drawn as two triangles split along
  the shorter diagonal, or, where its edges have corners, cut into fans from the corners
  (:func:`strip_triangulation`).
- *Torsal fans through a point of A* (:func:`a_fans`): where t jumps between two stations
  (B straight and A curved, or a corner of A), rulings from one point A(s*) to a stretch
  of B, each of them torsal.
- *Closing triangles* (:mod:`.closings`): over a run of stations on A without a torsal
  partner on B, flat triangles between the two stretches of A and B (fans through single
  points, flagged rather than counted as torsal).
"""

from __future__ import annotations

from collections.abc import Sequence
from itertools import pairwise
from math import isnan

import numpy as np
from numpy.typing import NDArray

from torsal.nodes.geometry.array_types import BoolArray, IntArray

from ..curve_base import FloatArray
from ..vec_ops import cross, det, flatnonzero, norm, unit
from .brackets import refine_roots
from .candidates import FLAT_END, Candidates, rounding_scale
from .stack import Stack, evaluate_each, evaluate_rows
from .stations import lengths_at, parameters_at
from .strip import SIDE, Steady, Strip


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
    return _creased(starts, ends, fan[:-1] | fan[1:])


def _creased(starts: FloatArray, ends: FloatArray, in_fan: BoolArray) -> BoolArray:
    """:func:`creased_fans` for the pieces ``in_fan`` next to a fan ruling."""
    return _creased_all(starts, ends, in_fan, Stack([len(starts)]))


def _creased_all(starts: FloatArray, ends: FloatArray, in_fan: BoolArray, rulings: Stack) -> BoolArray:
    """:func:`_creased` of several strips whose rulings are stacked (``rulings``), the pieces
    between consecutive rulings with ``in_fan`` False between two strips' rulings."""
    creased = np.zeros(len(in_fan), dtype=bool)
    if not in_fan.any():
        return creased
    # each strip's size: the largest extent of its rulings' ends (1 where they are one point)
    low = np.minimum(np.minimum.reduceat(starts, rulings.starts), np.minimum.reduceat(ends, rulings.starts))
    high = np.maximum(np.maximum.reduceat(starts, rulings.starts), np.maximum.reduceat(ends, rulings.starts))
    size = (high - low).max(axis=1)
    close = rulings.repeat(1e-12 * np.where(size != 0.0, size, 1.0))  # (size or 1)
    same_start = norm(starts[1:] - starts[:-1]) <= close[:-1]
    same_end = norm(ends[1:] - ends[:-1]) <= close[:-1]
    # a piece next to a "ruling" of no length (the point a strip trimmed by the design's
    # edge tapers to, :mod:`.outline_cut`) is one triangle: flat, it creases nothing
    point = norm(ends - starts) <= close
    triangle = point[:-1] | point[1:]
    # the runs of fan pieces: where ``in_fan`` padded with False on both sides changes
    padded = np.zeros(len(in_fan) + 2, dtype=bool)
    padded[1:-1] = in_fan
    edges = flatnonzero(padded[1:] != padded[:-1]).tolist()
    for first, stop in zip(edges[::2], edges[1::2], strict=True):  # runs of fan pieces
        one_apex = np.count_nonzero(same_start[first:stop]) == stop - first or (
            np.count_nonzero(same_end[first:stop]) == stop - first
        )
        creased[first:stop] = not (one_apex or np.all(triangle[first:stop]))
    return creased


def creased_runs(in_fan: BoolArray, folded: BoolArray) -> BoolArray:
    """Which pieces between consecutive rulings belong to a run of pieces next to a fan
    ruling (``in_fan``, one per piece) with a ruling across which the sheet folds
    (``folded``, one per ruling: :meth:`.kinds.SheetFolds.creases`) among the run's rulings.
    A run with no fold is smooth (cones through one point, or a fan ruling inside a smooth
    stretch of the sheet, as on a cut strip's ramp, :mod:`.cut_pace`), however many apexes
    its rulings have."""
    first = in_fan & ~np.concatenate([[False], in_fan[:-1]])
    run = np.cumsum(first) * in_fan  # 0 outside the runs, 1, 2, … in them
    hit = np.zeros(int(run.max(initial=0)) + 1, dtype=bool)
    at = flatnonzero(folded)
    for pieces in (at - 1, at):  # ruling i is the end of piece i − 1 and the start of piece i
        pieces = pieces[(pieces >= 0) & (pieces < len(in_fan))]
        hit[run[pieces]] = True
    hit[0] = False
    return hit[run]


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
    return fan_shares_all([(starts, ends, fan)])[0]


def fan_shares_all(strips: Sequence[tuple[FloatArray, FloatArray, BoolArray]]) -> list[tuple[float, float]]:
    """:func:`fan_shares` of every strip ``(starts, ends, fan)`` (of one ruling or more), their
    pieces measured at once; each strip's areas are summed on their own (a sum's rounding depends on what
    else it adds), so each gets the shares it gets alone, bit for bit."""
    rulings = Stack.of([starts for starts, _, _ in strips])
    starts, ends, fan = (np.concatenate(parts) for parts in zip(*strips, strict=True))
    areas = patch_areas(starts, ends)  # (and one across each pair of strips, never read)
    in_fan = fan[:-1] | fan[1:]
    in_fan[rulings.offsets[1:-1] - 1] = False
    creased = _creased_all(starts, ends, in_fan, rulings)
    shares = []
    for low, high in zip(rulings.starts.tolist(), (rulings.offsets[1:] - 1).tolist(), strict=True):
        own = areas[low:high]
        total = float(own.sum())
        pieces, folded = in_fan[low:high], creased[low:high]
        if not total > 0:
            none = 0.0 if not fan[low : high + 1].any() else 1.0
            shares.append((none, 0.0 if not folded.any() else 1.0))
        else:
            shares.append((float(own[pieces].sum() / total), float(own[folded].sum() / total)))
    return shares


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
    is_flat = np.zeros(n, dtype=bool)
    fans: list[tuple[float, float, float]] = []
    if not (good.kind == FLAT_END).any():  # (no flat run among the candidates at all)
        return fans, is_flat
    has = chosen >= 0
    is_flat[has] = good.kind[chosen[has]] == FLAT_END
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

    Along one branch B's length steps by about Δs·(mean dL/ds); a much larger step means
    the strip's path in the (s, t) square runs vertically in between: a fan of rulings
    from one point A(s*) to a stretch of B (a triangle on a straight piece of B, or a
    cone at a corner of A). s* solves f(s, t_mid) = 0 for s (t_mid halfway along B's
    length), or is the corner of A.
    """
    speed = np.full(len(t), np.nan)
    speed[regular] = norm(strip.curve_b.derivatives(t[regular], 1)[1])
    return a_fans_all([(strip, t, slope, regular, speed)])[0]


def a_fans_all(
    strips: Sequence[tuple[Strip, FloatArray, FloatArray, BoolArray, FloatArray]],
) -> list[list[tuple[float, float, float]]]:
    """:func:`a_fans` of every strip ``(strip, t, slope, regular, speed)`` (``speed``: |B'|
    at the stations on a regular branch, as the partner search found it), the apexes of all
    their fans solved at once (each strip's curves evaluated on its own rows)."""
    if not strips:
        return []
    jumps = [(np.empty(0, dtype=np.int64), np.empty(0))] * len(strips)
    # every strip's stations one strip after another (the steps from one strip's last to
    # the next one's first are no steps)
    stations = Stack([len(job[1]) for job in strips])
    t, slope, regular, speed = (np.concatenate([job[k] for job in strips]) for k in (1, 2, 3, 4))
    rate, speed = _rates([job[0] for job in strips], stations, t, slope, speed)
    along_a = np.concatenate([job[0].station_lengths for job in strips])
    dt = t[1:] - t[:-1]
    # the steps along B's length by the trapezoid rule, against those the slopes predict
    # (a looser bar than :func:`_jumps_along_b_all`'s, which measures the steps themselves)
    step = 0.5 * dt * (speed[:-1] + speed[1:])
    predicted = 0.5 * (along_a[1:] - along_a[:-1]) * (rate[:-1] + rate[1:])
    with np.errstate(invalid="ignore"):
        jump = regular[:-1] & regular[1:] & (dt > 1e-10) & (np.abs(step - predicted) > 0.2 * step)
    jump[stations.offsets[1:-1] - 1] = False
    steps = flatnonzero(jump)
    bounds = stations.groups(steps).tolist()
    rates = stations.split(rate)
    possible = [  # (strip's index, its stations' rates, the steps that may be jumps: rare)
        (index, rates[index], steps[low:high] - stations.offsets[index])
        for index, (low, high) in enumerate(pairwise(bounds)) if high > low
    ]
    found_jumps = _jumps_along_b_all([(strips[index][0], strips[index][1], rate, pairs)
                                      for index, rate, pairs in possible])
    for (index, _, _), found_k in zip(possible, found_jumps, strict=True):
        jumps[index] = found_k
    found: list[list[tuple[float, float, float]]] = [[] for _ in strips]
    with_pairs = [i for i, (pairs, _) in enumerate(jumps) if len(pairs)]
    if not with_pairs:
        return found
    stack = Stack([len(jumps[i][0]) for i in with_pairs])
    owner = stack.owner()
    stations = np.cumsum([0] + [len(strips[i][0].s) for i in with_pairs])[:-1]
    pairs = np.concatenate([jumps[i][0] for i in with_pairs])
    s_all = np.concatenate([strips[i][0].s for i in with_pairs])
    at = pairs + stations[owner]  # (the pairs' first stations among all strips' stations)
    t_mid = np.concatenate([jumps[i][1] for i in with_pairs])
    bm0, bm1 = evaluate_each([strips[i][0].curve_b for i in with_pairs], t_mid, stack.offsets, 1)
    # f at both stations of every pair at once: rows (i, i + 1)
    a0 = np.concatenate([strips[i][0].a0 for i in with_pairs])
    a1 = np.concatenate([strips[i][0].a1 for i in with_pairs])
    both = at + _NEXT
    f_left, f_right = det(bm0 - a0[both], a1[both], bm1)
    apex = np.full(len(pairs), np.nan)
    which = flatnonzero(f_left * f_right < 0)
    if len(which):
        # B and B' at each bracket's t_mid, gathered once: the same on every iteration
        b0, b1 = bm0[which], bm1[which]
        curves_a = [strips[i][0].curve_a for i in with_pairs]
        strip_of = owner[which]

        def coplanarity(x: FloatArray, index: IntArray) -> tuple[FloatArray, FloatArray, FloatArray]:
            c0, c1, c2 = evaluate_rows(curves_a, x, strip_of[index], 2)
            r0, r1 = (b0, b1) if len(index) == len(which) else (b0[index], b1[index])
            r = r0 - c0
            # f and f_s = det[R, A'', B'] (the term det[−A', A', B'] vanishes), in one det
            f, f_s = det(r, np.array([c1, c2]), r1)
            return f, f_s, rounding_scale(norm(c0), r0, norm(c1), r1)

        low, high = s_all[at[which]], s_all[at[which] + 1]
        apex[which] = refine_roots(coplanarity, low, high, f_left[which])
    # (a hole is told by the steps along B's length, not its parameter: those of every strip
    # with pairs measured at once)
    known = [~np.isnan(strips[index][1]) for index in with_pairs]
    measured = lengths_at([strips[index][0].map_b for index in with_pairs],
                          [strips[index][1][at] for index, at in zip(with_pairs, known, strict=True)])
    for k, index in enumerate(with_pairs):
        strip, t = strips[index][:2]
        pairs_k = jumps[index][0]
        lengths = np.full(len(t), np.nan)
        lengths[known[k]] = measured[k]
        apex_k = apex[stack.offsets[k]:stack.offsets[k + 1]]
        if not np.isnan(apex_k).all():
            # a root that converged onto a corner of A (a jump of f) or onto a station is that point
            for exact in (strip.kinks_a, strip.s):
                if len(exact):
                    nearest = exact[np.argmin(np.abs(apex_k[:, None] - exact[None, :]), axis=1)]
                    apex_k = np.where(np.abs(apex_k - nearest) <= 1e-12, nearest, apex_k)
        found[index] = _a_fans_of(strip, t, pairs_k, apex_k, lengths)
    return found


def _rates(
    strips: Sequence[Strip], stations: Stack, t: FloatArray, slope: FloatArray, speed: FloatArray
) -> tuple[FloatArray, FloatArray]:
    """dL/dℓ = (dt/ds)·|B'|/|A'| at every station of every strip (``stations`` says whose
    rows ``t``, ``slope`` and ``speed`` are), L and ℓ the lengths along B and A (what
    either curve's pace does to t and s cancels), and |B'| itself.

    Where B's parameter stands still (|B'| = 0 at an end, a curve run as t²: the partner
    search sees the limit of its direction there, :class:`.strip.Steady`) dt/ds is
    infinite and |B'| zero, and where A's does |A'| is zero: that station takes the next
    one's dL/dℓ (the one before's at the curve's end): near B(0) a curve run as t² takes
    steps of t like √s, a jump by their slope alone, not by their length.
    """
    still = np.concatenate([strip.still_a for strip in strips])
    speed = speed.copy()
    for strip, low, high in zip(strips, stations.starts.tolist(), stations.offsets[1:].tolist(), strict=True):
        if isinstance(strip.curve_b, Steady):  # (rare)
            at_end = (np.abs(t[low:high, None] - strip.curve_b.ends[None, :]) <= 1e-12).any(axis=1)
            speed[low:high][at_end] = 0.0
            still[low:high] |= at_end
    with np.errstate(invalid="ignore", divide="ignore"):
        rate = np.where(still, np.nan, slope * speed / norm(np.concatenate([strip.a1 for strip in strips])))
    if still.any():
        row = np.arange(len(t))
        first, last = stations.repeat(stations.starts), stations.repeat(stations.offsets[1:] - 1)
        neighbour = np.minimum(np.maximum(np.where(t > 0.5, row - 1, row + 1), first), last)
        rate = np.where(still, rate[neighbour], rate)
    return rate, speed


def _jumps_along_b_all(
    jobs: Sequence[tuple[Strip, FloatArray, FloatArray, IntArray]],
) -> list[tuple[IntArray, FloatArray]]:
    """For each ``(strip, t, rate, pairs)``: of the steps ``pairs`` (i, i + 1), each a jump
    of t, those that jump along B's length too, and B's parameter halfway along its length
    between their two ends; the lengths along B of all strips, then the halfway parameters,
    each measured in one pass (:func:`.stations.lengths_at`, :func:`.stations.parameters_at`).

    The step is measured along B's length (:attr:`.strip.Strip.map_b`) and predicted from
    the stations' ``rate``, dL/ds (:func:`_rates`): what B's parameterisation does to t
    cancels.
    """
    maps = [strip.map_b for strip, _, _, _ in jobs]
    ends = lengths_at(maps, [np.concatenate([t[pairs], t[pairs + 1]]) for _, t, _, pairs in jobs])
    jumps, halfway = [], []
    for (strip, _, rate, pairs), found in zip(jobs, ends, strict=True):
        lengths = found.reshape(2, -1)
        step = lengths[1] - lengths[0]
        along_a = strip.station_lengths
        predicted = 0.5 * (along_a[pairs + 1] - along_a[pairs]) * (rate[pairs] + rate[pairs + 1])
        jump = ~(np.abs(step - predicted) <= 0.25 * step)
        jumps.append(pairs[jump])
        halfway.append(0.5 * (lengths[0] + lengths[1])[jump])
    return list(zip(jumps, parameters_at(maps, halfway), strict=True))


def _a_fans_of(
    strip: Strip, t: FloatArray, pairs: IntArray, apex: FloatArray, lengths: FloatArray
) -> list[tuple[float, float, float]]:
    """One strip's fans through points of A at the jumps ``pairs`` with the apexes found
    (NaN where f had no root between the two stations); ``lengths`` along B at ``t``."""
    s = strip.s
    fans = []
    dt = lengths[1:] - lengths[:-1]  # (a hole is told by the steps along B's length, not its parameter)
    for i, s_star in zip(pairs.tolist(), apex.tolist(), strict=True):  # one pass per possible fan (rare)
        if isnan(s_star):
            inside = strip.kinks_a[(strip.kinks_a >= s[i]) & (strip.kinks_a <= s[i + 1])]
            if len(inside) == 0:
                if _dwarfs(dt, i):
                    strip.holes.append(i)
                continue
            s_star = float(inside[0])
        extent = _fan_extent(strip, s_star, float(t[i]), float(t[i + 1]))
        if extent is not None:
            fans.append((s_star, *extent))
        elif _dwarfs(dt, i):
            strip.holes.append(i)
    return fans


#: Offsets of the two stations of a pair (i, i + 1), as rows.
_NEXT = np.array([[0], [1]])


def _dwarfs(dt: FloatArray, i: int) -> bool:
    """Whether the step ``dt[i]`` (along B's length) is over twice both its neighbours (the
    larger of them, where there are two; never with none to compare): only then is a jump of t that no
    torsal fan covers a hole (the slope is a poor guide where f_t vanishes, as at an
    inflection). NaN neighbours (next to a station without a partner) do not count."""
    neighbours = [float(dt[k]) for k in (i - 1, i + 1) if 0 <= k < len(dt) and not isnan(dt[k])]
    return bool(neighbours) and bool(dt[i] > 2.0 * max(neighbours))

def _fan_extent(strip: Strip, s_star: float, t0: float, t1: float) -> tuple[float, float] | None:
    """The stretch of B inside [t0, t1] over which rulings from A(s*) are torsal."""
    # A(s*) and A's tangents on either side of it, in one evaluation
    around = [s_star, min(max(s_star - SIDE, 0.0), 1.0), min(max(s_star + SIDE, 0.0), 1.0)]
    a0, a1 = strip.curve_a.derivatives(np.array(around), 1)
    c0, sides = a0[0], a1[1:]
    window = (strip.grid.t >= t0) & (strip.grid.t <= t1)
    ts = np.unique(np.concatenate([[t0, t1], strip.grid.t[window]]))
    # at a corner of B the stretch may end with the tangent from either side
    at_kink = np.isin(ts, strip.kinks_b) if len(strip.kinks_b) else None
    if at_kink is None:  # (B has no corners)
        b0, b1 = strip.curve_b.derivatives(ts, 1)
        r = b0 - c0
    else:
        b0, b1 = strip.curve_b.derivatives(np.concatenate([ts, ts[at_kink] - SIDE]), 1)
        r = b0 - c0
        r = np.concatenate([r[: len(ts)], r[: len(ts)][at_kink]])
    scale = norm(r) * norm(b1)
    scale = np.where(scale > 0, scale, 1.0)
    g = det(r, unit(sides)[:, None], b1) / scale  # rows: with A's tangent from the left, from the right
    # torsal: flat (B straight there), or between the two one-sided tangents of a corner
    flat = np.abs(g) <= 1e-9
    torsal_all = flat[0] | flat[1] | (g[0] * g[1] < 0)
    torsal = torsal_all[: len(ts)]
    if at_kink is not None:
        torsal[at_kink] |= torsal_all[len(ts) :]
    if np.count_nonzero(torsal) < 2:
        return None
    first = int(np.argmax(torsal))
    last = len(ts) - 1 - int(np.argmax(torsal[::-1]))
    if not torsal[first : last + 1].all() or ts[last] <= ts[first]:
        return None
    return float(ts[first]), float(ts[last])

