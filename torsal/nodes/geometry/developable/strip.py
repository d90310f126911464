"""The state one solve of the strip between two curves shares: stations on A, samples of B.

:class:`Strip` holds the stations on curve A (evenly spaced in arc length or in
parameter, :mod:`.stations`), A and its first two derivatives there and A's corners, and
the samples of curve B (:class:`Grid`) that start the partner search
(:mod:`.candidates`): B on every smooth span, with both one-sided values at its corners,
and its first three derivatives. It also measures lengths along B (for placing a fan's
rulings and the plain loft's partners) and picks the parameters of a fan's rulings on B.
"""

from __future__ import annotations

import struct
from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from math import ceil

import numpy as np
from numpy.typing import ArrayLike

from torsal.nodes.geometry.array_types import BoolArray

from ..closest import sample_parameters
from ..curve_base import Curve, FloatArray
from ..curves import Line, NurbsCurve, Polyline
from ..vec_ops import cross, dot, flatnonzero, norm, unit
from .stack import Stack, evaluate_each
from .stations import LengthMap, Spacing, lengths_at, parameters_at, spaced_parameters

#: A jump of the unit tangent larger than this (rad) at a breakpoint is a corner.
CORNER_ANGLE = 1e-7
#: Parameter offset for one-sided evaluation beside a corner.
SIDE = 1e-11


class Steady(Curve):
    """A curve whose parameter stands still at an end (C'(t) = 0 there: a curve run as t²,
    a NURBS with a doubled end control point), with the tangent there replaced by the
    direction it tends to: C'(t) ≈ (t − end)·C''(end), so C'' at the start and −C'' at
    the end (the curve run forwards as ever). The same points, the geometric tangent. Without it
    det[B − A, A', B'] vanishes at that end for every station, whatever the ruling, and the
    strip took it for a partner of all of them (a fan through B's end)."""

    def __init__(self, curve: Curve, ends: FloatArray) -> None:
        self.curve, self.ends = curve, ends
        self.closed, self.domain = curve.closed, curve.domain

    def _steadied(self, t: FloatArray, values: list[FloatArray], order: int) -> list[FloatArray]:
        # (within 1e-12 of the end: there C' is rounding, its direction anything)
        at = (np.abs(t[:, None] - self.ends[None, :]) <= 1e-12).any(axis=1)
        if order >= 1 and at.any():
            second = self.curve.derivatives(t[at], 2)[2]
            values[1] = values[1].copy()
            values[1][at] = np.where(t[at, None] > 0.5, -second, second)
        return values

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        t = np.atleast_1d(np.asarray(t, dtype=float)).reshape(-1)
        return self._steadied(t, list(self.curve.derivatives(t, order)), order)

    @property
    def anchor(self) -> FloatArray:
        return self.curve.anchor

    def local_derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        t = np.atleast_1d(np.asarray(t, dtype=float)).reshape(-1)
        return self._steadied(t, list(self.curve.local_derivatives(t, order)), order)

    def _breakpoints(self) -> FloatArray:
        return self.curve._breakpoints()


def steady(curve: Curve) -> Curve:
    """``curve``, or :class:`Steady` of it where its parameter stands still at an end (its
    speed there under 1e-9 of its chord, while its second derivative is not)."""
    return steady_all([curve])[0]


def steady_all(curves: Sequence[Curve]) -> list[Curve]:
    """:func:`steady` of every curve of ``curves``, each evaluated at its ends on its own."""
    ends = np.array([0.0, 1.0])
    bounds = 2 * np.arange(len(curves) + 1)
    points, first, second = evaluate_each(curves, np.tile(ends, len(curves)), bounds, 2)
    chord = norm(points[1::2] - points[::2])
    bend = norm(second)
    scale = np.repeat(np.where(chord != 0.0, chord, bend.reshape(-1, 2).max(axis=1)), 2)  # (chord or bend)
    still = ((norm(first) <= 1e-9 * scale) & (bend > 1e-9 * scale)).reshape(-1, 2)
    return [Steady(curve, ends[at]) if at.any() else curve for curve, at in zip(curves, still, strict=True)]


def _jumps(left: FloatArray, right: FloatArray) -> BoolArray:
    """Whether the unit tangent turns by more than CORNER_ANGLE from ``left`` to ``right``."""
    left, right = unit(left), unit(right)
    return np.arctan2(norm(cross(left, right)), dot(left, right)) > CORNER_ANGLE


def _is_linear(curve: Curve) -> bool:
    return isinstance(curve, Line | Polyline) or (
        isinstance(curve, NurbsCurve) and curve.degree == 1 and not curve.is_rational
    )


@dataclass
class Grid:
    """Samples of curve B: nominal parameters, where they are evaluated (a corner's first
    copy just before it), and B and its first three derivatives there."""

    t: FloatArray
    at: FloatArray
    pair: BoolArray  #: (m−1,) samples j and j+1 are the two sides of one corner
    points: FloatArray
    tangents: FloatArray
    second: FloatArray  #: B'' there
    third: FloatArray  #: B''' there
    left_second: FloatArray  #: B'' and B''' as seen from the left (they differ at knots)
    left_third: FloatArray


def sample_grids(curves: Sequence[Curve], minimum: int) -> list[tuple[Grid, FloatArray]]:
    """The samples of each curve B of ``curves`` (a straight span needs only its ends: f is
    linear in t there) and its corners, found and sampled on both sides in the same
    evaluation; the curves evaluated together (:func:`.stack.evaluate_each`: each gets what
    it gets alone)."""
    found = []
    for curve in curves:
        t = sample_parameters(curve, per_span=1 if _is_linear(curve) else 2, minimum=minimum)
        breaks = curve._breakpoints()[1:-1]
        found.append((t, breaks, np.concatenate([t, breaks - SIDE]) if len(breaks) else t))
    at = [x for _, _, x in found]
    rows = Stack.of(at)
    values = [rows.split(v) for v in evaluate_each(curves, np.concatenate(at), rows.offsets, 3)]
    return [_grid(t, breaks, *own) for (t, breaks, _), *own in zip(found, *values, strict=True)]


def _grid(
    t: FloatArray, breaks: FloatArray, points: FloatArray, tangents: FloatArray, second: FloatArray,
    third: FloatArray,
) -> tuple[Grid, FloatArray]:
    """:func:`sample_grids` of one curve from B and its derivatives at its samples ``t``
    and just before its inner breakpoints ``breaks``."""
    m = len(t)
    if not len(breaks):  # one smooth span
        smooth = Grid(t, t, np.zeros(m - 1, dtype=bool), points, tangents, second, third, second, third)
        return smooth, breaks
    # samples include every breakpoint; compare each with its left neighbour's tangent
    at_break = np.searchsorted(t, breaks)
    kink = _jumps(tangents[m:], tangents[at_break])
    kinks = breaks[kink]
    # from the left, a smooth breakpoint shows its left-hand derivatives
    left = np.arange(m)
    left[at_break[~kink]] = m + flatnonzero(~kink)
    if not len(kinks):  # the samples themselves, on the right (views: no copies)
        on_right = points[:m], tangents[:m], second[:m], third[:m]
        return Grid(t, t, np.zeros(m - 1, dtype=bool), *on_right, second[left], third[left]), kinks
    # a corner gets two samples: its left copy just before its right copy
    index = at_break[kink]
    right = np.insert(np.arange(m), index, m + flatnonzero(kink))
    left = np.insert(left, index, m + flatnonzero(kink))
    t_all = np.insert(t, index, kinks)
    at = np.insert(t, index, kinks - SIDE)
    pair = np.diff(t_all) == 0
    on_right = points[right], tangents[right], second[right], third[right]
    grid = Grid(t_all, at, pair, *on_right, second[left], third[left])
    return grid, kinks


class Strip:
    """One solve of :func:`.ruling.ruling_developable`: the state its steps share (made by
    :func:`set_up`)."""

    def __init__(
        self, curve_a: Curve, curve_b: Curve, segments: int, tolerance: float, spacing: Spacing,
        map_a: LengthMap, s: FloatArray, a: tuple[FloatArray, FloatArray, FloatArray], still_a: BoolArray,
        kinks_a: FloatArray, grid: Grid, kinks_b: FloatArray, chords_b: FloatArray,
    ) -> None:
        self.curve_a, self.curve_b = curve_a, curve_b
        self.segments, self.tolerance, self.spacing = segments, tolerance, spacing
        self.map_a, self.s = map_a, s
        self.a0, self.a1, self.a2 = a  #: A and its first two derivatives at the stations
        #: per station, whether A's parameter stands still there (A' is then along ±A'')
        self.still_a: BoolArray = still_a
        #: A, as a :class:`Steady` curve where it stands still at an end (for the end cones'
        #: pencils through its end points)
        ends = np.array([0.0, 1.0])[[bool(still_a[0]), bool(still_a[-1])]]
        self.steady_a: Curve = Steady(curve_a, ends) if len(ends) else curve_a
        self.kinks_a, self.grid, self.kinks_b = kinks_a, grid, kinks_b
        #: Arc length along the polyline through B's samples to each sample (for the check
        #: that B has a length, before anything is measured along it).
        self.chords_b = chords_b
        #: pairs of stations (i, i + 1) between which t jumps over a stretch of B that no
        #: torsal fan covers (set by :func:`.fans.a_fans`)
        self.holes: list[int] = []
        #: per station, whether it has a torsal partner whose normals are flipped: one that
        #: runs backwards along B (set by the partner choice, :func:`.candidates.choose`)
        self.flipped: BoolArray = np.zeros(len(s), dtype=bool)
        #: :meth:`gap_lengths` found so far, by the bits of their ends
        self._gaps: dict[bytes, tuple[FloatArray, FloatArray]] = {}
        #: the closing triangles of each gap found so far (:func:`.closings.close_gaps`), by
        #: its stations and the bits of its ends on B
        self.closings: dict[tuple[int, int, bytes], tuple[FloatArray, tuple | None]] = {}

    def length_b(self, t: FloatArray) -> FloatArray:
        """Arc length along B to each ``t`` (:attr:`map_b`): fans' rulings and the plain
        loft's partners are placed by it, so they lie where they do whatever B's pace."""
        return self.map_b.length_at(t)

    def parameter_b(self, length: FloatArray) -> FloatArray:
        """The inverse of :meth:`length_b`."""
        return self.map_b.parameter_at(length)

    @cached_property
    def map_b(self) -> LengthMap:
        """Arc length along B (the curve itself: a :class:`Steady` B's tangent at its still
        end is not its speed), made when a solve first needs it (:func:`with_maps_b` makes
        those of many strips together)."""
        return LengthMap(self.measured_b)

    @property
    def measured_b(self) -> Curve:
        """The curve :attr:`map_b` measures: B itself (not its :class:`Steady` stand-in)."""
        return self.curve_b.curve if isinstance(self.curve_b, Steady) else self.curve_b

    def even_b(self, low: FloatArray, high: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """B's samples evenly spaced along its length (as many over all of B as :attr:`grid`
        has) that lie within any of the stretches from ``low`` to ``high`` of its length,
        and its corners: their parameters, B and B' there (where a station without a torsal
        partner looks for its least-warped one: the same points whatever B's pace)."""
        return even_all([self], [low], [high])[0]

    @cached_property
    def station_lengths(self) -> FloatArray:
        """Arc length along A to each station."""
        if self.spacing == "length":
            return np.arange(len(self.s)) * (self.map_a.total / (len(self.s) - 1))
        return self.map_a.length_at(self.s)

    def gap_parameters(self, t_low: float, t_high: float) -> FloatArray:
        """Parameters on B from ``t_low`` to ``t_high`` at about the station spacing, with
        every corner of B between them (read-only: :meth:`gap_lengths`)."""
        return self.gap_lengths(t_low, t_high)[0]

    def gap_lengths(self, t_low: float, t_high: float) -> tuple[FloatArray, FloatArray]:
        """:meth:`gap_parameters` and their :meth:`length_b`, read-only, found once per stretch
        of B: each round of the solve's check closes the same gaps again (and
        :func:`gap_lengths_all` finds many strips' stretches together)."""
        key = struct.pack("2d", t_low, t_high)  # (the bits: 0.0 and -0.0 give different rulings)
        found = self._gaps.get(key)
        if found is None:
            gap_lengths_all([(self, t_low, t_high)])
            found = self._gaps[key]
        return found

    def fan_parameters(self, t_low: float, t_high: float) -> FloatArray:
        """Parameters on B for a fan's rulings, at about the station spacing along A
        (:func:`fans_all` finds many fans' together)."""
        return fans_all([(self, t_low, t_high)])[0][0]


def with_maps_b(strips: Sequence[Strip]) -> None:
    """Makes :attr:`Strip.map_b` of every strip of ``strips`` that has none yet, all of them
    together (:meth:`.stations.LengthMap.many`: each the map it gets alone, bit for bit).
    A B that is another of the strips' A (the edge between two strips of a roof) takes
    that strip's :attr:`Strip.map_a`: the same curve's map (a map is not changed once made)."""
    missing = [strip for strip in strips if "map_b" not in vars(strip)]
    if not missing:
        return
    known = {id(strip.curve_a): strip.map_a for strip in strips}
    made = []
    for strip in missing:
        same = known.get(id(strip.measured_b))
        if same is not None and same.curve is strip.measured_b:
            vars(strip)["map_b"] = same  # (where the cached property keeps it)
        else:
            made.append(strip)
    for strip, length_map in zip(made, LengthMap.many([s.measured_b for s in made]), strict=True):
        vars(strip)["map_b"] = length_map


def fans_all(stretches: Sequence[tuple[Strip, float, float]]) -> list[tuple[FloatArray, FloatArray | None]]:
    """:meth:`Strip.fan_parameters` of every ``(strip, t_low, t_high)`` of ``stretches``, and
    their lengths along B when they are the fan's two ends alone (measured already to count
    the rulings; None otherwise), all together: B's lengths at the ends in one pass, the
    inner parameters in another (:func:`.stations.lengths_at`, :func:`.stations.parameters_at`),
    each what it is alone, bit for bit."""
    if not stretches:
        return []
    strips = [strip for strip, _, _ in stretches]
    with_maps_b(strips)
    ends = [np.array([t_low, t_high]) for _, t_low, t_high in stretches]
    found: list[tuple[FloatArray, FloatArray | None]] = []
    inner: list[tuple[int, FloatArray]] = []
    for index, ((strip, t_low, t_high), lb) in enumerate(
        zip(stretches, lengths_at([strip.map_b for strip in strips], ends), strict=True)
    ):
        # at most one fan ruling per station (B far longer than A — a stray vertex at 1e12 —
        # must not ask for billions); and at least the fan's two bounding rulings
        spacing = strip.map_a.total / strip.segments
        wanted = (lb[1] - lb[0]) / spacing if spacing > 0 else 1.0
        count = max(2, ceil(min(wanted, strip.segments + 1) - 1e-9) + 1)
        # (where t_high < t_low, or is NaN, the second is t_low: its length is not lb[1])
        found.append((np.maximum.accumulate(ends[index]), lb if t_high >= t_low else None))
        if count > 2:
            inner.append((index, np.linspace(lb[0], lb[1], count)))
    if inner:
        ts = parameters_at([strips[index].map_b for index, _ in inner], [lengths for _, lengths in inner])
        for (index, _), t in zip(inner, ts, strict=True):
            t[0], t[-1] = stretches[index][1], stretches[index][2]
            found[index] = (np.maximum.accumulate(t), None)
    return found


def gap_lengths_all(stretches: Sequence[tuple[Strip, float, float]]) -> None:
    """Finds :meth:`Strip.gap_lengths` of every ``(strip, t_low, t_high)`` of ``stretches``
    not found yet, all together (:func:`fans_all`, with B's corners between the ends, then
    the lengths of those that have none in one pass), each what it is alone, bit for bit."""
    wanted: dict[tuple[int, bytes], tuple[Strip, float, float]] = {}
    for strip, t_low, t_high in stretches:
        key = struct.pack("2d", t_low, t_high)
        if key not in strip._gaps:
            wanted.setdefault((id(strip), key), (strip, t_low, t_high))
    if not wanted:
        return
    jobs = list(wanted.values())
    strips = [strip for strip, _, _ in jobs]
    found = fans_all(jobs)
    # B's corners between the ends join the parameters
    for index, (strip, t_low, t_high) in enumerate(jobs):
        if len(strip.kinks_b):
            corners = strip.kinks_b[(strip.kinks_b > t_low) & (strip.kinks_b < t_high)]
            if len(corners):
                found[index] = (np.unique(np.concatenate([found[index][0], corners])), None)
    unmeasured = [index for index, (_, lb) in enumerate(found) if lb is None]
    measured = lengths_at([strips[index].map_b for index in unmeasured],
                          [found[index][0] for index in unmeasured])
    for index, lb in zip(unmeasured, measured, strict=True):
        found[index] = (found[index][0], lb)
    for (strip, t_low, t_high), (tb, lb) in zip(jobs, found, strict=True):
        tb.setflags(write=False)
        lb.setflags(write=False)
        strip._gaps[struct.pack("2d", t_low, t_high)] = (tb, lb)


def even_all(
    strips: Sequence[Strip], lows: Sequence[FloatArray], highs: Sequence[FloatArray]
) -> list[tuple[FloatArray, FloatArray, FloatArray]]:
    """:meth:`Strip.even_b` of every strip (``lows[i]`` to ``highs[i]`` along its B), their
    lengths inverted together and each B evaluated once (:func:`.stack.evaluate_each`)."""
    if not strips:
        return []
    with_maps_b(strips)
    found = parameters_at([strip.map_b for strip in strips], _even_lengths(strips, lows, highs))
    ts = [np.unique(np.concatenate([t, strip.kinks_b])) for strip, t in zip(strips, found, strict=True)]
    rows = Stack.of(ts)
    points, tangents = evaluate_each([strip.curve_b for strip in strips], np.concatenate(ts), rows.offsets, 1)
    return list(zip(ts, rows.split(points), rows.split(tangents), strict=True))


def _even_lengths(
    strips: Sequence[Strip], lows: Sequence[FloatArray], highs: Sequence[FloatArray]
) -> list[FloatArray]:
    """The lengths along B of :meth:`Strip.even_b`'s samples (without its corners) of every
    strip: B's samples evenly spaced along its length, as many as :attr:`Strip.grid` has,
    within any of the stretches ``lows[i]`` to ``highs[i]``; those of all strips numbered
    one strip after another, so that one ``np.unique`` sorts them all."""
    stretches = Stack.of(lows)
    count = np.array([len(strip.grid.t) for strip in strips])
    step = np.array([strip.map_b.total for strip in strips]) / (count - 1)
    low, high = np.concatenate(lows), np.concatenate(highs)
    each_step = stretches.repeat(step)
    first = np.maximum(np.ceil(low / each_step - 1e-9), 0).astype(np.int64)
    last = np.minimum(np.floor(high / each_step + 1e-9), stretches.repeat(count) - 1).astype(np.int64)
    sizes = np.maximum(last - first + 1, 0)
    k = np.repeat(first - np.cumsum(sizes) + sizes, sizes) + np.arange(sizes.sum())
    before = np.cumsum(count) - count  # (each strip's samples after those of the strips before it)
    numbered = np.unique(k + np.repeat(stretches.repeat(before), sizes))
    strip_of = np.searchsorted(before, numbered, side="right") - 1
    lengths = (numbered - before[strip_of]) * step[strip_of]
    return Stack(np.bincount(strip_of, minlength=len(strips))).split(lengths)


def set_up(
    jobs: Sequence[tuple[Curve, Curve, int, float]], spacing: Spacing, samples: int
) -> list[Strip | ValueError]:
    """The :class:`Strip` of every ``(curve_a, curve_b, segments, tolerance)`` of ``jobs``
    (checked: ``segments`` at least 1), set up together: each curve is evaluated on its own
    and the arithmetic runs once for all of them, so each strip is the one it is alone, bit
    for bit. A strip one of whose curves has zero length is a ValueError in its place.

    Its stations on A (evenly spaced in arc length or in parameter, :mod:`.stations`), A
    and its first two derivatives there and A's corners, and the samples of B
    (:func:`sample_grids`) with the lengths along them."""
    curves_a = [job[0] for job in jobs]
    curves_b = steady_all([job[1] for job in jobs])
    maps = LengthMap.many(curves_a)
    made: list[Strip | ValueError | None] = [None] * len(jobs)
    kept = []
    for i, length_map in enumerate(maps):
        if not length_map.total > 0:
            made[i] = ValueError("Curve A has zero length: there is nothing to place rulings along.")
        elif spacing not in ("length", "parameter"):
            made[i] = ValueError(f"Station spacing must be 'length' or 'parameter'; got {spacing!r}.")
        else:
            kept.append(i)
    if not kept:
        return made  # type: ignore[return-value]  (every job has its error)
    counts = [jobs[i][2] + 1 for i in kept]
    if spacing == "length":
        stations = spaced_parameters([maps[i] for i in kept], counts)
    else:
        stations = [np.linspace(0.0, 1.0, count) for count in counts]
    # A at the stations and just beside its breakpoints (both sides), each curve on its own
    breaks = [curves_a[i]._breakpoints()[1:-1] for i in kept]
    x = [np.concatenate([s, b - SIDE, b + SIDE]) if len(b) else s
         for s, b in zip(stations, breaks, strict=True)]
    rows = Stack.of(x)
    at = np.concatenate(x) if x else np.empty(0)
    a0, a1, a2 = evaluate_each([curves_a[i] for i in kept], at, rows.offsets, 2)
    # A's corners: where its unit tangent turns at a breakpoint
    sides = [len(b) for b in breaks]
    beside = [np.arange(start + count, start + count + side)  # (the rows just before each breakpoint)
              for start, count, side in zip(rows.starts.tolist(), counts, sides, strict=True)]
    left = np.concatenate(beside) if beside else np.empty(0, dtype=np.int64)
    turns = Stack(sides).split(_jumps(a1[left], a1[left + np.repeat(sides, sides)]))
    # where A's parameter stands still (A'(s) = 0: a curve run as t²), its tangent is the
    # limit of A'/|A'|, the direction of A'' there: the strip does not depend on the pace
    still_rows = norm(a1) <= 1e-9 * rows.repeat(np.array([maps[i].total for i in kept]))
    still = flatnonzero(still_rows)
    # (A' ≈ (s − s0)·A'': −A'' where A stands still at its end; beside a breakpoint too:
    # those rows only find the corners)
    a1[still] = np.where(at[still, None] > 0.5, -a2[still], a2[still])
    # B's samples and the lengths along them
    grids = sample_grids([curves_b[i] for i in kept], samples)
    points = np.concatenate([grid.points for grid, _ in grids]) if grids else np.empty((0, 3))
    chords = norm(points[1:] - points[:-1])
    first_sample = Stack([len(grid.t) for grid, _ in grids]).starts.tolist()
    for i, first, (grid, kinks_b), s, corner, b, start in zip(
        kept, first_sample, grids, stations, turns, breaks, rows.starts.tolist(), strict=True
    ):
        lengths = np.empty(len(grid.t))
        lengths[0] = 0.0
        np.cumsum(chords[first : first + len(grid.t) - 1], out=lengths[1:])
        if not lengths[-1] > 0:
            made[i] = ValueError("Curve B has zero length: there is nothing to place rulings along.")
            continue
        n = len(s)
        a = a0[start : start + n], a1[start : start + n], a2[start : start + n]
        curve_a, _, segments, tolerance = jobs[i]
        made[i] = Strip(curve_a, curves_b[i], segments, tolerance, spacing, maps[i], s, a,
                        still_rows[start : start + n], b[corner], grid, kinks_b, lengths)
    return made  # type: ignore[return-value]  (every job has its strip or its error)
