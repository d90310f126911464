"""The partner search: every candidate partner on B of every station on A, and the choice.

For each station s on A the torsal partners are the roots t of
f_s(t) = det[B(t) − A(s), A'(s), B'(t)] (see :mod:`.ruling` for the geometry). This
module finds them all at once (steps 2–5 of the algorithm in :mod:`.ruling`):

- :func:`find_all` — brackets from one thin matrix product of f over all
  station–sample pairs (:mod:`.sift`), judged and split by the certified isolation
  (:mod:`.isolation`) until each holds provably no root, one simple root or a double
  root, refined to rounding (:mod:`.brackets`); plus the roots at corners of B and the
  ends of flat runs. Each candidate carries its branch slope dt/ds and whether its
  normals are consistently oriented. Several strips are searched at once: each has its
  own matrix, and the isolation and refinement of all their intervals run together.
- :func:`choose` (:func:`choose_all` for several strips) — one consistently oriented
  candidate per station with t never decreasing (:mod:`.selection`).
- :func:`near_partners` — for stations left without one, a partner whose warp is
  within the tolerance (the plain loft's or the least-warped sample of B), if any.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from torsal.nodes.geometry.array_types import BoolArray, IntArray

from ..curve_base import Curve, FloatArray
from ..vec_ops import cross, dot, flatnonzero, norm
from .brackets import ZERO, refine_roots
from .isolation import Pieces, isolate
from .selection import longest_chain, monotone_path
from .sift import sift_all
from .stack import Stack, evaluate_each, evaluate_rows
from .stations import lengths_at, parameters_at
from .strip import Strip, even_all, with_maps_b
from .warp import _angles, _normals, in_plane_tangent, sizes

#: Most candidates kept per station for the selection.
MAX_CANDIDATES = 8

#: A root is a double root to rounding (:func:`_double_roots`) where rounding alone could
#: move it along B by more than this share of its ruling's length.
LOOSE = 1e-12

#: What a candidate is: a refined root of f, a root at a corner of B, an end of a flat run.
ROOT, CORNER, FLAT_END = 0, 1, 2


#: Offsets of an interval's two ends from its first sample, as a column.
_ENDS = np.array([[0], [1]])


def cubic_start(
    x0: FloatArray, x1: FloatArray, f0: FloatArray, f1: FloatArray, d0: FloatArray, d1: FloatArray
) -> FloatArray:
    """A first guess for each bracket's root, good to O(h⁴): the root of the cubic that
    matches f and f' at both ends of the bracket (two Newton steps on that cubic from
    the secant's root), so that one Newton step on f reaches rounding."""
    h = x1 - x0
    d0, d1 = d0 * h, d1 * h  # slopes in the bracket's unit coordinate
    rise = f1 - f0
    # the cubic f0 + u·(d0 + u·(c2 + u·c3)) and its slope d0 + u·(2·c2 + 3·c3·u)
    c2 = 3.0 * rise - 2.0 * d0 - d1
    c3 = d0 + d1 - 2.0 * rise
    c2_twice, c3_thrice = 2.0 * c2, 3.0 * c3
    with np.errstate(divide="ignore", invalid="ignore"):
        u = np.minimum(np.maximum(-f0 / rise, 0.0), 1.0)  # (np.clip is slow on small arrays)
        for _ in range(2):
            step = (f0 + u * (d0 + u * (c2 + u * c3))) / (d0 + u * (c2_twice + u * c3_thrice))
            u = np.where(np.isfinite(step), np.minimum(np.maximum(u - step, 0.0), 1.0), u)
    return x0 + u * h


def rounding_scale(size_a: FloatArray, b0: FloatArray, speed_a: FloatArray, b1: FloatArray) -> FloatArray:
    """Size of the rounding error of det[B − A, A', B'] from |A|, B, |A'|, B': positions are
    rounded relative to their own magnitude, not to the ruling's length."""
    return (size_a + norm(b0)) * speed_a * norm(b1)


def _oriented(
    rr: FloatArray, aa: FloatArray, bb: FloatArray, ra: FloatArray, rb: FloatArray, ab: FloatArray
) -> BoolArray:
    """Whether N1 = R × A' and N2 = R × B' point to the same side (or one vanishes), from
    |R|², |A'|², |B'|², R·A', R·B' and A'·B'.

    N1·N2 = |R|²(A'·B') − (R·A')(R·B') and |N|² = |R|²|T|² − (R·T)² (Lagrange's identity).
    """
    n1n1 = np.maximum(rr * aa - ra * ra, 0.0)
    n2n2 = np.maximum(rr * bb - rb * rb, 0.0)
    return rr * ab - ra * rb >= -1e-9 * np.sqrt(n1n1 * n2n2)


@dataclass
class Candidates:
    """Candidate partners, one entry each, sorted by station then t."""

    row: IntArray
    t: FloatArray
    kind: IntArray
    slope: FloatArray  #: dt/ds of the branch (0 at corners and flat ends)
    low: FloatArray  #: flat run extent (NaN for roots and corners)
    high: FloatArray
    points: FloatArray  #: (k, 3) B(t)
    tangents: FloatArray  #: (k, 3) tangent of B there (the in-plane one at a corner)
    oriented: BoolArray  #: normals point to the same side (signed warp ~0, not ~π)

    def subset(self, keep: BoolArray | IntArray) -> Candidates:
        """The candidates ``keep`` (a mask or indices), in that order."""
        index = flatnonzero(keep) if keep.dtype == bool else keep
        return Candidates(*(getattr(self, name).take(index, axis=0) for name in _FIELDS))


_FIELDS = tuple(Candidates.__dataclass_fields__)


def find_all(strips: Sequence[Strip]) -> list[Candidates]:
    """All candidate partners of all stations of every strip: refined roots (every root of
    f, isolated with the guarantee of :mod:`.isolation`), corner roots, flat-run ends. Each
    strip's matrix of f is its own; the isolation and refinement of every strip's
    intervals run at once (the stations stacked, each strip's B evaluated on its rows)."""
    sifted = sift_all(strips)
    stations = Stack([len(strip.s) for strip in strips])
    strip_of = stations.owner()
    shift = stations.starts
    a0 = np.concatenate([strip.a0 for strip in strips])
    a1 = np.concatenate([strip.a1 for strip in strips])
    a2 = np.concatenate([strip.a2 for strip in strips])
    units = sifted.units
    curves = [strip.curve_b for strip in strips]

    def ends(pieces: Pieces, index: IntArray) -> Pieces:
        return replace(pieces.take(index), **sifted.piece_ends(index))

    def evaluate_b(x: FloatArray, rows: IntArray) -> list[FloatArray]:
        return evaluate_rows(curves, x, strip_of[rows], 2)

    isolated = isolate(sifted.first, sifted.curvature, evaluate_b, a0, units, ends, strip_of)
    rows = isolated.rows
    # single zero samples (runs of no extent) are roots
    single = [(run_rows[~flat] + shift[i], strip.grid.t[first[~flat]])
              for i, (strip, (run_rows, first, _, flat)) in enumerate(zip(strips, sifted.runs, strict=True))]
    run_rows = np.concatenate([rows_i for rows_i, _ in single])
    run_t = np.concatenate([t_i for _, t_i in single])
    if len(run_rows) or len(isolated.double_rows):  # single zero samples, double roots
        point_rows = np.concatenate([run_rows, isolated.double_rows])
        point_t = np.concatenate([run_t, isolated.double_t])
    else:
        point_rows, point_t = isolated.double_rows, isolated.double_t

    # refine every bracket at once: Newton with f_t = det[R, A', B''], bisection fallback;
    # each bracket's last evaluation (at its root, to rounding) is kept for what follows
    root_rows = np.concatenate([rows, point_rows]) if len(point_rows) else rows
    k = len(rows)
    root_t = np.concatenate([np.empty(k), point_t]) if len(point_rows) else np.empty(k)
    b0, b1 = np.empty((2, len(root_rows), 3))
    f, f_t = np.empty((2, len(root_rows)))
    # the stations of the roots, gathered once for every evaluation and what follows
    a0_root, a1_root = a0.take(root_rows, axis=0), a1.take(root_rows, axis=0)
    speed_a, size_a = norm(a1_root), norm(a0_root)
    strip_of_root = strip_of[root_rows]

    def evaluate(x: FloatArray, index: IntArray | slice) -> tuple[FloatArray, FloatArray, FloatArray]:
        c0, c1, c2 = evaluate_rows(curves, x, strip_of_root[index], 2)
        plane = cross(c0 - a0_root[index], a1_root[index])  # det[R, A', X] = X · (R × A')
        value, slope = dot(plane, c1), dot(plane, c2)
        root_t[index], b0[index], b1[index], f[index], f_t[index] = x, c0, c1, value, slope
        return value, slope, rounding_scale(size_a[index], c0, speed_a[index], c1)

    def coplanarity(x: FloatArray, index: IntArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        # all of them (the first step): a slice reads and writes without gathering
        return evaluate(x, slice(0, k) if len(index) == k else index)

    if k:
        i = isolated
        start = cubic_start(i.low, i.high, i.f_low, i.f_high, i.d_low, i.d_high)
        refine_roots(coplanarity, i.low, i.high, i.f_low, start)
    if len(point_rows):
        evaluate(root_t[k:], slice(k, None))
    a2_root = a2.take(root_rows, axis=0)
    double, mean_slope = _double_roots(
        curves, strip_of_root, (a0_root, a1_root, a2_root, size_a, speed_a), (root_t, b0, b1, f, f_t))

    # the slope dt/ds = −f_s/f_t of each smooth root's branch, f_s = det[R, A'', B'] =
    # R · (A'' × B') with R = B − A
    r = b0 - a0_root
    rr, bb, ra, rb, ab = dot(r, r), dot(b1, b1), dot(r, a1_root), dot(r, b1), dot(a1_root, b1)
    f_s = dot(r, cross(a2_root, b1))
    aa = speed_a**2
    with np.errstate(over="ignore"):  # (a still end of B: f_t ~ 0 there, the slope is clipped)
        slope = np.minimum(np.maximum(-f_s / np.where(f_t == 0, 1e-300, f_t), -1e6), 1e6)
    slope[double] = mean_slope
    # converged onto a jump of B' that is not a flagged corner: f is far from zero there
    jumped = np.abs(f) > 1e-7 * np.sqrt(rr * aa * bb)
    kind = np.where(jumped, CORNER, ROOT)
    slope[jumped] = 0.0
    oriented = _oriented(rr, aa, bb, ra, rb, ab)
    # each strip's roots (its brackets', then its points'), in the order it finds them alone
    by_strip = np.argsort(strip_of_root, kind="stable")
    per_strip = Stack(np.bincount(strip_of_root, minlength=len(strips)))
    fields = (root_rows - shift[strip_of_root], root_t, kind, slope, b0, b1, oriented)
    split = [per_strip.split(values[by_strip]) for values in fields]
    results = []
    for i, strip in enumerate(strips):
        rows_i, t_i, kind_i, slope_i, b0_i, b1_i, oriented_i = (part[i] for part in split)
        nan = np.full(len(rows_i), np.nan)
        candidates = Candidates(rows_i, t_i, kind_i, slope_i, nan, nan, b0_i, b1_i, oriented_i)
        results.append(_with_extras(strip, candidates, sifted.corners[i], sifted.runs[i]))
    return results


def _double_roots(
    curves: Sequence[Curve], strip_of: IntArray, stations: tuple[FloatArray, ...],
    roots: tuple[FloatArray, ...],
) -> tuple[IntArray, FloatArray]:
    """Roots of f that are double roots to rounding, moved onto the double root itself:
    in place in ``roots`` = (t, B, B', f, f_t), with ``stations`` = (A, A', A'', |A|, |A'|)
    at every root. Returns which roots moved and their branches' mean slope dt/ds.

    Where f touches zero (a cylinder's generator at an inflection of its section, where
    two branches of roots cross), f is zero to rounding over a stretch of B as wide as the
    square root of its rounding, and a root found inside it is only that good (1.4e-9 of
    the length on that cylinder). Such a root is told by its conditioning: rounding alone
    could move it by ZERO·scale/|f_t|, more than :data:`LOOSE` of its ruling's length
    along B. There the double root is the simple root of f_t = det[R, A', B''] (whose
    derivative is f_tt = det[B', A', B''] + det[R, A', B''']), refined in a bracket twice
    as wide as that stretch, and taken where f is zero to rounding too (else the root
    stays: two roots that rounding tells apart). Its branch slope −f_s/f_t is 0/0 there
    (both branches pass through it): it takes their mean, −f_st/f_tt with f_st =
    det[R, A'', B''], which favours neither."""
    t, b0, b1, f, f_t = roots
    a0, a1, a2, size_a, speed_a = stations
    noise = ZERO * rounding_scale(size_a, b0, speed_a, b1)
    with np.errstate(invalid="ignore"):
        loose = (noise * norm(b1) > LOOSE * np.abs(f_t) * norm(b0 - a0)) & (np.abs(f) <= 4.0 * noise)
    index = flatnonzero(loose)
    if len(index) == 0:  # (the usual case: every root is simple)
        return index, np.empty(0)
    rows, a0_i, a1_i, noise_i = strip_of[index], a0[index], a1[index], noise[index]
    size_i, speed_i = size_a[index], speed_a[index]

    def f_t_of(x: FloatArray, at: IntArray | slice) -> tuple[FloatArray, ...]:
        """f_t, f_tt and f_t's rounding scale at ``x`` for the roots ``at``, and B, B', B''."""
        c0, c1, c2, c3 = evaluate_rows(curves, x, rows[at], 3)
        plane = cross(c0 - a0_i[at], a1_i[at])
        slope_t = dot(cross(c1, a1_i[at]), c2) + dot(plane, c3)
        return dot(plane, c2), slope_t, rounding_scale(size_i[at], c0, speed_i[at], c2), c0, c1, c2

    x = t[index]
    g, dg = f_t_of(x, slice(None))[:2]
    with np.errstate(divide="ignore", invalid="ignore"):
        step = g / dg
        width = 2.0 * np.maximum(np.abs(step), np.sqrt(2.0 * noise_i / np.abs(dg)))
    width = np.where(np.isfinite(width), width, 0.0)
    low, high = np.maximum(x - width, 0.0), np.minimum(x + width, 1.0)
    n = len(x)
    both = f_t_of(np.concatenate([low, high]), np.concatenate([np.arange(n), np.arange(n)]))[0]
    g_low, g_high = both[:n], both[n:]
    keep = flatnonzero((width > 0) & (np.signbit(g_low) != np.signbit(g_high)))
    if len(keep) == 0:
        return keep, np.empty(0)
    index, rows, a0_i, a1_i = index[keep], rows[keep], a0_i[keep], a1_i[keep]
    size_i, speed_i, x, low, high = size_i[keep], speed_i[keep], x[keep], low[keep], high[keep]
    start = np.minimum(np.maximum(x - step[keep], low), high)
    found = refine_roots(lambda y, at: f_t_of(y, at)[:3], low, high, g_low[keep], start)
    g, dg, _, c0, c1, c2 = f_t_of(found, slice(None))
    value = dot(cross(c0 - a0_i, a1_i), c1)
    zero = flatnonzero(np.abs(value) <= 2.0 * ZERO * rounding_scale(size_i, c0, speed_i, c1))
    index = index[zero]
    t[index], b0[index], b1[index] = found[zero], c0[zero], c1[zero]
    f[index], f_t[index] = value[zero], g[zero]
    f_st = dot(c0[zero] - a0_i[zero], cross(a2[index], c2[zero]))
    with np.errstate(divide="ignore", invalid="ignore"):
        mean = -f_st / dg[zero]
    return index, np.where(np.isfinite(mean), np.minimum(np.maximum(mean, -1e6), 1e6), 0.0)


def _with_extras(
    strip: Strip, candidates: Candidates, corners: tuple[IntArray, IntArray],
    runs: tuple[IntArray, IntArray, IntArray, BoolArray],
) -> Candidates:
    """One strip's refined roots with its roots at corners of B (the intervals ``corners``
    that straddle one: their stations and first samples) and the ends of its flat runs
    (of its ``runs`` of zero samples: stations, first and last samples, flat or not)."""
    (corner_rows, corner_cols), (run_rows, run_first, run_last, flat) = corners, runs
    if len(corner_rows) == 0 and not flat.any():
        return _in_order(candidates)
    grid, a0, a1 = strip.grid, strip.a0, strip.a1
    # roots at corners of B: the tangent plane turns about the corner (a cone through it)
    corner_points = grid.points[corner_cols + 1]
    corner_tangents = in_plane_tangent(
        corner_points - a0[corner_rows],
        a1[corner_rows],
        grid.tangents[corner_cols],
        grid.tangents[corner_cols + 1],
    )
    # the two ends of every flat run
    flat_rows = np.repeat(run_rows[flat], 2)
    flat_cols = np.column_stack([run_first[flat], run_last[flat]]).reshape(-1)
    extra_rows = np.concatenate([corner_rows, flat_rows])
    extra_points = np.concatenate([corner_points, grid.points[flat_cols]])
    extra_tangents = np.concatenate([corner_tangents, grid.tangents[flat_cols]])
    r, ta, tb = extra_points - a0[extra_rows], a1[extra_rows], extra_tangents
    corner_nan = np.full(len(corner_rows), np.nan)
    extra = Candidates(
        extra_rows,
        np.concatenate([grid.t[corner_cols], grid.t[flat_cols]]),
        np.concatenate([np.full(len(corner_rows), CORNER), np.full(len(flat_rows), FLAT_END)]),
        np.zeros(len(extra_rows)),
        np.concatenate([corner_nan, np.repeat(grid.t[run_first[flat]], 2)]),
        np.concatenate([corner_nan, np.repeat(grid.t[run_last[flat]], 2)]),
        extra_points,
        extra_tangents,
        _oriented(*dot(np.array([r, ta, tb, r, r, ta]), np.array([r, ta, tb, ta, tb, tb]))),
    )
    both = Candidates(
        *(np.concatenate([getattr(candidates, name), getattr(extra, name)]) for name in _FIELDS)
    )
    return _in_order(both)


def _in_order(c: Candidates) -> Candidates:
    """The candidates sorted by station, then t (stably); as they are when already so (the
    refined roots usually are: their brackets come in that order)."""
    step = c.row[1:] - c.row[:-1]
    if ((step > 0) | ((step == 0) & (c.t[1:] >= c.t[:-1]))).all():
        return c
    return c.subset(np.lexsort((c.t, c.row)))


def _pad(c: Candidates, n: int) -> tuple[FloatArray, FloatArray, IntArray]:
    """Candidates as ``(n, K)`` arrays (NaN padded) and the index of each cell's candidate."""
    # drop duplicates (a flat end that is also a root) and keep at most MAX_CANDIDATES
    first = np.ones(len(c.row), dtype=bool)
    first[1:] = (c.row[1:] != c.row[:-1]) | (c.t[1:] - c.t[:-1] > 1e-13)
    keep = flatnonzero(first)
    rows = c.row[keep]
    column = np.arange(len(rows)) - np.searchsorted(rows, rows, side="left")
    fits = column < MAX_CANDIDATES
    keep, rows, column = keep[fits], rows[fits], column[fits]
    k = max(int(column.max(initial=-1)) + 1, 1)
    t = np.full((n, k), np.nan)
    slope = np.full((n, k), np.nan)
    index = np.full((n, k), -1, dtype=np.int64)
    t[rows, column] = c.t[keep]
    slope[rows, column] = c.slope[keep]
    index[rows, column] = keep
    return t, slope, index


def choose(strip: Strip) -> tuple[IntArray, Candidates]:
    """The chosen candidate per station (−1 where none) and the consistently oriented
    candidates."""
    return choose_all([strip])[0]


def choose_all(strips: Sequence[Strip]) -> list[tuple[IntArray, Candidates]]:
    """:func:`choose` of every strip, their candidates found at once (:func:`find_all`)."""
    return [_choose(strip, found) for strip, found in zip(strips, find_all(strips), strict=True)]


def _choose(strip: Strip, found: Candidates) -> tuple[IntArray, Candidates]:
    """One strip's choice among its candidates ``found``."""
    n = len(strip.s)
    good = found if found.oriented.all() else found.subset(found.oriented)
    if len(good.row) < len(found.row):  # (roots whose partner runs backwards along B)
        strip.flipped[found.row[~found.oriented & (found.kind == ROOT)]] = True
    chosen = np.full(n, -1, dtype=np.int64)
    if len(good.row) and (good.row[1:] > good.row[:-1]).all() and (good.t[1:] >= good.t[:-1]).all():
        # at most one candidate per station, in order along B: nothing to choose
        chosen[good.row] = np.arange(len(good.row))
        return chosen, good
    t_pad, slope_pad, index_pad = _pad(good, n)
    rows = flatnonzero(~np.isnan(t_pad).all(axis=1))
    if len(rows):
        x, y, rate = _along(strip, good, rows, t_pad[rows], slope_pad[rows], index_pad[rows])
        pick = monotone_path(y, rate, x[1:] - x[:-1])
        chosen[rows] = index_pad[rows, pick]
        t = good.t[chosen[rows]]
        if (t[1:] - t[:-1] < -1e-12).any():  # the selection had to step back: the longest chain
            pick = longest_chain(y, rate, x)
            chosen[rows] = np.where(pick >= 0, index_pad[rows, np.maximum(pick, 0)], -1)
    return chosen, good


def _along(
    strip: Strip, good: Candidates, rows: IntArray, t: FloatArray, slope: FloatArray, index: IntArray
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The stations ``rows`` and their candidates as the choice reads them: where they are
    along each curve as shares of its length (x on A, y on B; t and y rise together) and
    each branch's slope dy/dx = (dt/ds)·|B'|/|A'| — so that which branch the strip follows
    does not depend on how either curve is parameterised, only on the curves."""
    x = strip.station_lengths[rows] / strip.map_a.total
    total_b = strip.map_b.total
    y = strip.length_b(t) / total_b
    speed_b = norm(good.tangents[np.maximum(index, 0)])
    speed_a = norm(strip.a1[rows])
    with np.errstate(divide="ignore", invalid="ignore"):
        rate = slope * speed_b * (strip.map_a.total / total_b) / speed_a[:, None]
    rate = np.where(np.isnan(slope), np.nan, np.minimum(np.maximum(np.nan_to_num(rate), -1e6), 1e6))
    if strip.still_a[rows].any():
        _still_rates(strip.still_a[rows], y, rate)
    return x, y, rate


def _still_rates(still: BoolArray, y: FloatArray, rate: FloatArray) -> None:
    """Where A stands still at a station (A' = 0 at its end: a curve run as t²) dt/ds and
    |A'| are both 0 and their quotient is not at hand: each candidate there takes the
    slope of the nearest candidate (along B) of the next station, in place."""
    for row in flatnonzero(still).tolist():  # (a curve's two ends at most)
        other = row + 1 if row + 1 < len(y) else row - 1
        if other < 0 or still[other]:
            continue
        gaps = np.abs(y[row][:, None] - y[other][None, :])
        gaps = np.where(np.isnan(gaps), np.inf, gaps)
        nearest = np.argmin(gaps, axis=1)
        known = np.isfinite(gaps.min(axis=1, initial=np.inf)) & ~np.isnan(rate[row])
        rate[row] = np.where(known, rate[other][nearest], rate[row])

def near_partners(strip: Strip, t: FloatArray) -> None:
    """Give every station without a partner one whose warp is within the tolerance
    (the strip is torsal to within it there), if it has one between its neighbours'
    partners: the plain loft's (in arc length between those neighbours) if that is
    within it, else the least-warped sample of B. The others stay NaN, to be closed
    by fans."""
    near_partners_all([strip], [t])


def near_partners_all(strips: Sequence[Strip], ts: Sequence[FloatArray]) -> None:
    """:func:`near_partners` of every strip (its partners ``ts[i]``, filled in in place),
    the plain lofts' partners found and their warps measured for all of them at once, and
    the samples of B where a loft's is not within the tolerance."""
    at = [i for i, t in enumerate(ts) if np.isnan(t).any()]
    if not at:
        return
    with_maps_b([strips[i] for i in at])
    windows = _windows([strips[i] for i in at], [ts[i] for i in at])
    # the lofts' partners: along B's length as the stations are along A's, within the window
    found = parameters_at([strips[i].map_b for i in at], [window[-1] for window in windows])
    lofts = [np.minimum(np.maximum(t, lo), hi) for t, (_, lo, hi, *_) in zip(found, windows, strict=True)]
    stack = Stack.of(lofts)
    points, tangents = evaluate_each([strips[i].curve_b for i in at], np.concatenate(lofts), stack.offsets, 1)
    missing = [window[0] for window in windows]
    a0 = np.concatenate([strips[i].a0.take(rows, axis=0) for i, rows in zip(at, missing, strict=True)])
    a1 = np.concatenate([strips[i].a1.take(rows, axis=0) for i, rows in zip(at, missing, strict=True)])
    # the lofts' warps, every strip's at once (each with its own size)
    warps = stack.split(_angles(*_normals(a0, points, a1, tangents, None, None, stack.repeat(
        sizes(stack, a0, points))), False))
    with np.errstate(invalid="ignore"):
        loft_ok = [warp <= strips[i].tolerance for i, warp in zip(at, warps, strict=True)]
    # else the least angle between the end normals among B's samples in the window (evenly
    # spaced along B: :meth:`.strip.Strip.even_b`), made only where the loft's is not within it
    worse = [k for k, ok in enumerate(loft_ok) if not ok.all()]
    samples = dict(zip(worse, even_all(
        [strips[at[k]] for k in worse], [windows[k][3][~loft_ok[k]] for k in worse],
        [windows[k][4][~loft_ok[k]] for k in worse]), strict=True))
    a0s, a1s = stack.split(a0), stack.split(a1)
    near = list(lofts)
    if worse:
        picked, rows = _least_warped(
            [strips[at[k]].tolerance for k in worse], [a0s[k] for k in worse], [a1s[k] for k in worse],
            [~loft_ok[k] for k in worse], [windows[k][1:3] for k in worse], [samples[k] for k in worse])
        for k, own_rows, own in zip(worse, rows, picked, strict=True):
            near[k] = lofts[k].copy()
            near[k][own_rows] = own
    for k, i in enumerate(at):
        t = ts[i]
        t[missing[k]] = near[k]
        # consecutive stations in one window may have picked samples out of order
        known = ~np.isnan(t)
        t[known] = np.maximum.accumulate(t[known])


def _windows(strips: Sequence[Strip], ts: Sequence[FloatArray]) -> list[tuple[FloatArray, ...]]:
    """For each strip's stations without a partner (some): where they are, their neighbours'
    partners ``lo`` and ``hi``, the lengths along B there and the plain loft's partners'
    lengths along B (between them, as the stations lie between theirs along A); the lengths
    along B of all strips measured at once (:func:`.stations.lengths_at`)."""
    found = []
    for strip, t in zip(strips, ts, strict=True):
        gap = np.isnan(t)
        missing = flatnonzero(gap)
        # where each station without a partner falls among those with one: the partners of
        # its two neighbours (padded with B's ends where there is none before or after it)
        # and their arc lengths along A (padded with A's ends), one row for each neighbour
        partnered = flatnonzero(~gap)
        neighbours = np.searchsorted(partnered, missing) + _ENDS
        t_window = np.concatenate([[0.0], t.take(partnered), [1.0]]).take(neighbours)
        length_a = strip.station_lengths
        a_lo, a_hi = np.concatenate([[0.0], length_a.take(partnered), [strip.map_a.total]]).take(neighbours)
        span = a_hi - a_lo
        spans = span > 0
        fraction = np.where(spans, (length_a.take(missing) - a_lo) / np.where(spans, span, 1.0), 0.0)
        found.append((missing, t_window, fraction))
    lengths = lengths_at([strip.map_b for strip in strips], [t_window.ravel() for _, t_window, _ in found])
    windows = []
    for (missing, (lo, hi), fraction), length in zip(found, lengths, strict=True):
        b_lo, b_hi = length.reshape(2, -1)
        windows.append((missing, lo, hi, b_lo, b_hi, b_lo + fraction * (b_hi - b_lo)))
    return windows


def _least_warped(
    tolerances: Sequence[float], a0s: Sequence[FloatArray], a1s: Sequence[FloatArray],
    wanted: Sequence[BoolArray], windows: Sequence[tuple[FloatArray, FloatArray]],
    samples: Sequence[tuple[FloatArray, FloatArray, FloatArray]],
) -> tuple[list[FloatArray], list[IntArray]]:
    """For the stations ``wanted`` of each strip (of its stations without a partner, at
    ``a0s`` with tangents ``a1s``): the least-warped of B's ``samples`` (parameters,
    points, tangents: :meth:`.strip.Strip.even_b`) between the window's ``lo`` and ``hi``
    (``windows``), where that warp is within the strip's tolerance, else NaN; and those
    stations' indices. Every strip's stations and samples at once, each station's row of
    angles padded with +inf beyond its strip's samples.

    The angle between N1 = R × A'_i and N2 = R × B'_j (R = B_j − A_i) is read from the dot
    products |R|², R·A', R·B' and A'·B': N1·N2 = |R|²(A'·B') − (R·A')(R·B') (Lagrange's
    identity), and |N1 × N2| = |R|·|det[R, A', B']| with det[R, A', B'] = A'·(B' × B) −
    (A × A')·B'. Coordinates are taken about each strip's centre (its middle station
    without a partner and its middle sample, as in :mod:`.sift`).
    """
    rows = [flatnonzero(own) for own in wanted]
    stations, per_sample = Stack.of(rows), Stack.of([tb for tb, _, _ in samples])
    width = int(per_sample.counts.max(initial=0))
    if width == 0:
        return [np.full(len(own), np.nan) for own in rows], rows
    owner = stations.owner()
    centre = np.array([0.5 * (a0[len(a0) // 2] + points[len(points) // 2]) if len(points) else np.zeros(3)
                       for a0, (_, points, _) in zip(a0s, samples, strict=True)])
    a = np.concatenate([a0[own] for a0, own in zip(a0s, rows, strict=True)]) - stations.repeat(centre)
    ta = np.concatenate([a1[own] for a1, own in zip(a1s, rows, strict=True)])
    t_b, b, tb = (np.concatenate(parts) for parts in zip(*samples, strict=True))
    b = b - per_sample.repeat(centre)
    # each station's row of samples (its strip's, then any sample as padding, never chosen)
    column = np.arange(width)
    real = column < per_sample.counts[owner][:, None]
    index = np.minimum(per_sample.starts[owner][:, None] + column, len(t_b) - 1)
    b_at, tb_at = b[index], tb[index]
    a_row, ta_row = a[:, None], ta[:, None]
    rr = np.maximum(np.einsum("ij,ij->i", b, b)[index] - 2.0 * dot(a_row, b_at)
                    + np.einsum("ij,ij->i", a, a)[:, None], 0.0)
    ra = dot(ta_row, b_at) - np.einsum("ij,ij->i", a, ta)[:, None]
    rb = np.einsum("ij,ij->i", b, tb)[index] - dot(a_row, tb_at)
    triple = dot(ta_row, cross(tb, b)[index]) - dot(cross(a, ta)[:, None], tb_at)
    angle = np.arctan2(np.sqrt(rr) * np.abs(triple), rr * dot(ta_row, tb_at) - ra * rb)
    t_at = t_b[index]
    lo = np.concatenate([window[0][own] for window, own in zip(windows, rows, strict=True)])
    hi = np.concatenate([window[1][own] for window, own in zip(windows, rows, strict=True)])
    inside = real & (t_at >= lo[:, None]) & (t_at <= hi[:, None]) & ~np.isnan(angle)
    angle = np.where(inside, angle, np.inf)
    best = np.argmin(angle, axis=1)
    ok = angle.min(axis=1, initial=np.inf) <= stations.repeat(np.array(tolerances))  # (the angle at best)
    return stations.split(np.where(ok, t_at[np.arange(len(best)), best], np.nan)), rows
