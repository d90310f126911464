"""The developable strip between two space curves: solving for its rulings.

Geometry
--------
A developable surface has one tangent plane along each ruling. If the strip is bounded
by curves A(s) and B(t) and a ruling joins A(s) to B(t), both curves are tangent to the
surface at the ruling's ends, so the ruling R = B(t) − A(s) and the two tangents A'(s),
B'(t) lie in one plane (the ruling is *torsal*)::

    f_s(t) = det[B(t) − A(s), A'(s), B'(t)] = 0.

For each station s on A this is one equation in t. Its roots are the candidate
partners. A root is kept only if its normals are *consistently oriented* (see
:mod:`.warp`: with both curves running the same way and rulings that do not cross, the
sheet's normals N1 = R × A' and N2 = R × B' point to the same side, so the signed warp
is ~0, not ~π), and one root per station is chosen so that t never decreases.

The orientation test is what tells the strip from impostors. Along a branch of roots
with slope dt/ds, the sheet's normal at B is (dt/ds)·(B' × R), so flipped normals mean
either t running backwards (a sheet folded through itself: the rulings cross) or the
edge of regression (the sheet's cusp) lying between the two curves. In particular the
determinant vanishes wherever A'(s) ∥ B'(t), whatever the ruling: when the tangents
point the *same* way that root is a genuine torsal ruling (two curves in parallel
planes are joined exactly there); when they point *opposite* ways the normals are
opposite and the root is rejected (for two coaxial circles, the double cone through
their common centre instead of the frustum between them). Flipped roots on a
decreasing branch are what a curve B running the other way produces, and the message
then says to reverse B.

Algorithm (all stations at once)
--------------------------------
1. Stations: ``Segments + 1`` parameters on A, evenly spaced in arc length
   (:mod:`.stations`).
2. Sampling: B is sampled on every smooth span, with both one-sided values at its
   corners, and the whole ``stations × samples`` matrix of f and of f_t is one thin
   matrix product (see :mod:`.sift`).
3. Certified isolation (:mod:`.isolation`): every sample interval where f changes sign
   or comes within reach of zero is judged with a bound on f_tt from B's derivatives,
   and split until each piece provably holds no root, exactly one simple root (a
   bracket), or a double root to rounding. So no root of f is missed between samples —
   not two roots close together at an inflection of a section, nor where A' and B'
   become parallel, nor at a curve's end (the guarantee and its one assumption are in
   that module). *Flat runs*, where f is zero on consecutive samples (A and B coplanar
   there, e.g. two straight pieces in one plane), contribute their two ends instead; a
   sign change across a corner of B is a root at the corner (the rulings fan through
   it: a cone).
4. Refinement: every bracket is refined to machine precision at once, by Newton's
   method kept inside the brackets (:mod:`.brackets`) with f_t = det[R, A', B''],
   starting from the root of the cubic that matches f and f_t at the bracket's ends —
   usually two evaluations of B in all. A root that rounding alone leaves loose (f
   touches zero there: a double root, where two branches of roots cross) is solved
   instead as the simple root of f_t, found the same way.
5. Selection: the monotone dynamic programme of :mod:`.selection` follows one branch of
   roots, predicting each step from the branch slope dt/ds = −f_s/f_t, with
   f_s = det[R, A'', B'].
6. Planar pieces: where the chosen partners lie in a flat run the strip is planar and
   any pairing is developable; it is drawn as two triangles (a fan of rulings through a
   point of B, then a fan through a point of A), split along the shorter diagonal; a
   piece whose edges have corners is a polygon, cut into such fans from the corners
   along diagonals that stay inside it (:func:`.fans.strip_triangulation`). Fans
   through a point of A also arise where B is straight and A curved (the ZVE roof: a
   triangle leaning on a straight edge) or at a corner of A: there t jumps between two
   neighbouring stations, the fan's apex s* is found by solving f for s, and rulings
   are added through A(s*) at about the station spacing.
7. Stations with no consistently oriented root get the plain loft's partner (in arc
   length between their neighbours' partners) or else the least-warped sample of B
   there, if its warp is within ``warp_tolerance`` (before the planar pieces of step 6
   are drawn, so that a piece's fans end at the next station's partner). The others admit no torsal ruling:
   each run of them is closed by flat triangles between the two stretches of A and B
   (:mod:`.fans`), and so are the ends of B beyond the first and last ruling and any
   stretch of B that t jumps over with no torsal fan to cover it. Their rulings are
   flagged (``fan``), the strip has no holes and stays developable (every triangle is
   flat), and the message gives the share of the strip's area they take.
8. Check: every output ruling's warp is measured from the curves at its (s, t) — end
   points and exact tangents, :func:`.warp.warp_angles`, NaN where no normal is defined
   — and ``valid`` is that warp within the tolerance (never NaN), plus what the rounding
   of the rulings' end points alone can add to it far from the origin (their positions'
   rounding over the ruling's length: nothing at the origin, 3e-6 rad for a 1.3 m ruling
   at 1e9 m; see :func:`.measure.within_tolerance`). A station taken as
   torsal that fails the check joins the fans and the strip is closed again. A fan that
   turns back over itself between two of its rulings (in a plane: over a stretch of a
   curve its apex does not see whole) gets a ruling at the turn, which runs along the
   curve: its warp is undefined and it is not valid (:func:`_fan_folds_all`).
9. A closed B whose seam is away from the strip's start is solved again from A(0)'s
   partner, so that t can run once round B through its seam.

Where the steps live
--------------------
:mod:`.strip` holds what one solve shares (stations on A, samples of B: steps 1–2),
:mod:`.candidates` the partner search (steps 2–5 and the near partners of step 7),
:mod:`.fans` every fan and closing triangle (steps 6–7), :mod:`.end_cones` the smooth
end cones; this module runs the steps, assembles the rulings and checks them (step 8).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from itertools import pairwise

import numpy as np
from numpy.typing import ArrayLike

from torsal.nodes.geometry.array_types import BoolArray, IntArray

from ..counts import segment_count
from ..curve_base import Curve, FloatArray
from ..curves.shared_knots import partitions_kept
from ..vec_ops import cross, flatnonzero, norm, unit
from ..watch import watch_check
from .candidates import Candidates, choose_all, near_partners_all
from .closings import close_gaps_all, outside_gaps
from .end_cones import Rulings, smooth_all
from .fans import a_fans_all, fan_shares_all, flat_fans
from .measure import check_rulings
from .stack import Stack, evaluate_rows
from .stations import Spacing, lengths_at
from .strip import SIDE, Strip, fans_all, set_up
from .warp import PARALLEL

#: Most rounds of checking the torsal rulings and closing the stations that fail.
MAX_CHECKS = 3


@dataclass(frozen=True)
class RulingResult:
    """The rulings of a developable strip between curves A and B, in order along the strip.

    Rulings run from ``A(s)`` to ``B(t)``. There is one per station on A (``Segments + 1``
    of them, marked in ``stations``) plus the rulings of any fan through a single point of
    A (a planar triangle), which repeat that point's s, and of the flat triangles that
    close the strip where no torsal ruling exists (marked in ``fan``, with the stations
    there); so ``len(s) >= Segments + 1``.
    Neither ``s`` nor ``t`` ever decreases, so rulings do not cross — except that on a
    closed curve B, t increases *cyclically*: from the strip's start it runs up to 1,
    wraps through B's seam to 0 and rises again.
    """

    s: FloatArray  #: parameters on curve A, in [0, 1]
    t: FloatArray  #: partner parameters on curve B, in [0, 1]
    starts: FloatArray  #: (n, 3) points A(s)
    ends: FloatArray  #: (n, 3) points B(t)
    #: warp angle per ruling, rad, in [0, π]: the angle between the end normals R × A'
    #: and R × B', recomputed from the output (NaN where a normal is not defined)
    warp: FloatArray
    signed_warp: FloatArray  #: angle from N1 to N2 about the ruling, rad, in (−π, π] (or NaN)
    valid: BoolArray  #: the recomputed warp is within the tolerance (never where it is NaN)
    message: str | None  #: how much of the strip is closed by flat triangles, or None
    stations: BoolArray  #: True for the Segments + 1 station rulings, False for added fan rulings
    #: True for the rulings of the flat triangles that close the strip where no torsal
    #: ruling exists (gap stations and the rulings added there), False for torsal ones
    fan: BoolArray
    fan_share: float  #: share of the strip's area in those triangles, 0 to 1
    #: share of the area in fans that crease the sheet (apexes on both curves, see
    #: :func:`.fans.creased_fans`); a single cone closing a strip's end is smooth and not counted
    creased_share: float = 0.0
    #: stations closed by fans that do have a torsal ruling, but one that would cross the
    #: strip's other rulings: its partner lies behind the neighbours' on B
    out_of_order: int = 0
    #: stations closed by fans whose torsal rulings run backwards along B (their normals
    #: flip: B runs against A there), and whether any station of the strip has one
    backward: int = 0
    any_backward: bool = False

    @property
    def max_warp(self) -> float:
        """Largest warp angle, rad."""
        return float(self.warp.max(initial=0.0))

class _Rotated(Curve):
    """A closed curve started from parameter ``shift`` instead of its seam: C((t + shift) mod 1)."""

    closed = True

    def __init__(self, curve: Curve, shift: float) -> None:
        self.curve, self.shift = curve, float(shift)

    def original(self, t: FloatArray) -> FloatArray:
        """The wrapped curve's parameter for parameters ``t`` of this one."""
        u = np.asarray(t, dtype=float) + self.shift
        return np.where(u >= 1.0, u - 1.0, u)

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        return self.curve.derivatives(self.original(np.atleast_1d(np.asarray(t, dtype=float))), order)

    def _breakpoints(self) -> FloatArray:
        moved = self.curve._breakpoints() - self.shift
        return np.unique(np.concatenate([[0.0, 1.0], np.where(moved < 0, moved + 1.0, moved)]))

def ruling_developable(
    curve_a: Curve,
    curve_b: Curve,
    segments: int,
    warp_tolerance: float = 0.01,
    *,
    spacing: Spacing = "length",
    samples: int = 128,
) -> RulingResult:
    """The developable strip between two curves, as rulings from A to B.

    Args:
        curve_a: the base curve; ``segments + 1`` stations are placed along it.
        curve_b: the partner curve. Both should run the same way (from the same end of
            the strip); otherwise almost no ruling is torsal and the strip is mostly flat
            triangles (:func:`.alternatives.better_pairing` says whether reversing B helps).
        segments: number of rulings minus one (at least 1).
        warp_tolerance: largest warp angle (rad) a ruling may have and count as valid,
            e.g. 0.01; for a sheet allowed a warp factor of k rad/m over rulings about
            L long, k·L.
        spacing: ``"length"`` (default) spaces the stations evenly in arc length along A,
            ``"parameter"`` evenly in its parameter.
        samples: how many samples of B start the root isolation (at least this many and
            two per smooth span of B); roots closer together are separated by subdivision,
            so more samples only trade matrix work for fewer subdivisions.

    Returns:
        A :class:`RulingResult`. On curves cut from a developable the rulings are the true
        ones to rounding (partner error ~1e-14, warp ~1e-14 rad).

    See the module docstring for the geometry and the algorithm. Two coplanar segments
    bound a planar quad, drawn as two triangles: a fan through B(0) from the three
    stations, then a fan through A(1) whose rulings are about as far apart on B (B is
    √10 long, the stations 1 apart; a fan gets at most one ruling per station, so three
    steps of B/3):

    >>> from torsal.nodes.geometry.curves import Line
    >>> r = ruling_developable(Line([0, 0, 0], [2, 0, 0]), Line([0, 1, 0], [3, 2, 0]), 2)
    >>> r.s.tolist(), r.t.round(3).tolist(), r.message
    ([0.0, 0.5, 1.0, 1.0, 1.0, 1.0], [0.0, 0.0, 0.0, 0.333, 0.667, 1.0], None)
    """
    job = (curve_a, curve_b, segments, warp_tolerance)
    result = ruling_developables([job], spacing=spacing, samples=samples)[0]
    if isinstance(result, ValueError):
        raise result
    return result


def ruling_developables(
    jobs: Sequence[tuple[Curve, Curve, int, float]],
    *,
    spacing: Spacing = "length",
    samples: int = 128,
) -> list[RulingResult | ValueError]:
    """:func:`ruling_developable` of every ``(curve_a, curve_b, segments, warp_tolerance)``
    of ``jobs``, solved side by side: each step of the solve runs once for all the strips
    (their stations and rulings one after another in the same arrays), so a node with many
    strips pays each step's fixed cost once rather than once per strip. Each strip's result
    is the one it gets alone, bit for bit; a job the solve refuses gets its ValueError in
    its place."""
    with partitions_kept():  # (the curves' partitions by basis made once a solve)
        return _ruling_developables(jobs, spacing, samples)


def _ruling_developables(
    jobs: Sequence[tuple[Curve, Curve, int, float]], spacing: Spacing, samples: int
) -> list[RulingResult | ValueError]:
    samples = max(int(samples), 8)
    made = _strips(jobs, spacing, samples)
    solved = iter(_solve_all([strip for strip in made if isinstance(strip, Strip)]))
    results = [next(solved) if isinstance(strip, Strip) else strip for strip in made]
    # a closed B whose seam sits away from where the strip starts: restart B at A(0)'s
    # partner (or, when A is closed too, at the partner of its end, the same point)
    again: list[tuple[int, _Rotated]] = []
    for index, (result, (curve_a, curve_b, _, _)) in enumerate(zip(results, jobs, strict=True)):
        if isinstance(result, ValueError) or not (curve_b.closed and result.fan.any()):
            continue
        station = result.t[result.stations]
        torsal = (result.valid & ~result.fan)[result.stations]
        shift = station[0] if torsal[0] else station[-1] if curve_a.closed and torsal[-1] else None
        if shift is not None and 1e-9 < shift < 1.0 - 1e-9:
            again.append((index, _Rotated(curve_b, shift)))
    if again:
        rotated_jobs = [(jobs[index][0], rotated, *jobs[index][2:]) for index, rotated in again]
        made = _strips(rotated_jobs, spacing, samples)
        again = [pair for pair, strip in zip(again, made, strict=True) if isinstance(strip, Strip)]
        rotated_strips = [strip for strip in made if isinstance(strip, Strip)]
        for (index, rotated), other in zip(again, _solve_all(rotated_strips), strict=True):
            if other.fan_share < results[index].fan_share:  # type: ignore[union-attr]
                results[index] = replace(other, t=rotated.original(other.t))
    return results


def _strips(
    jobs: Sequence[tuple[Curve, Curve, int, float]], spacing: Spacing, samples: int
) -> list[Strip | ValueError]:
    """The checked arguments of every job, as the :class:`Strip` its solve starts from, or
    the ValueError that refuses it (the strips set up together: :func:`.strip.set_up`)."""
    checked: list[tuple[Curve, Curve, int, float]] = []
    made: list[Strip | ValueError | None] = []
    for curve_a, curve_b, segments, warp_tolerance in jobs:
        try:
            segments = segment_count(segments)
            tolerance = float(warp_tolerance)
            if not (np.isfinite(tolerance) and tolerance >= 0):
                raise ValueError(f"The warp tolerance must be a number >= 0 (rad); got {warp_tolerance}.")
            checked.append((curve_a, curve_b, int(segments), tolerance))
            made.append(None)
        except ValueError as exc:
            made.append(exc)
    try:
        strips = iter(set_up(checked, spacing, samples))
    except ValueError:  # a curve that refuses its evaluation: each strip alone, with its own error
        strips = iter([_alone(job, spacing, samples) for job in checked])
    return [next(strips) if strip is None else strip for strip in made]


def _alone(job: tuple[Curve, Curve, int, float], spacing: Spacing, samples: int) -> Strip | ValueError:
    """One job's strip set up alone, or the ValueError its curves raise."""
    try:
        return set_up([job], spacing, samples)[0]
    except ValueError as exc:
        return exc


@dataclass
class _Solve:
    """One strip's state between the steps of :func:`_solve_all`."""

    strip: Strip
    chosen: IntArray  #: the chosen candidate per station (−1 where none)
    good: Candidates  #: the consistently oriented candidates
    t: FloatArray  #: the partner per station (NaN where none)
    fans: list  #: the torsal fans ``(s*, t_low, t_high)``
    #: the rulings s, t, source, fan (:func:`_merge_all`) and their check (:func:`_checked`)
    rulings: tuple[FloatArray, FloatArray, IntArray, BoolArray] | None = None
    checked: tuple[FloatArray, FloatArray, FloatArray, FloatArray, BoolArray] | None = None


def _solve_all(strips: list[Strip]) -> list[RulingResult]:
    """One solve of :func:`ruling_developable` as the module docstring describes it, for
    every strip of ``strips`` step by step. Between its steps it calls the enclosing
    :func:`~..watch.watched` block's check, if any (a 2,000-station solve takes tens of
    milliseconds: Esc is seen within one step)."""
    check = watch_check() or _unwatched
    check()
    if not strips:
        return []
    solves = []
    choices = choose_all(strips)
    check()
    partners = _partners(choices)
    # stations without a partner get one first, so that a planar piece's fans end where
    # the next station's partner is (two curves in one plane: otherwise a fan over all of
    # B, then a partner running back)
    near_partners_all(strips, [t for t, _, _, _ in partners])
    flat, jumps = [], []
    for strip, (chosen, good), (t, slope, has, speed) in zip(strips, choices, partners, strict=True):
        fans, planar = flat_fans(strip, t, chosen, good)
        flat.append(fans)
        jumps.append((strip, t, slope, has & ~planar, speed))  # (the stations on a regular branch)
    for strip, (chosen, good), (t, _, _, _), fans, more in zip(
        strips, choices, partners, flat, a_fans_all(jumps), strict=True
    ):
        solves.append(_Solve(strip, chosen, good, t, fans + more))
    check()

    # the check (step 8), round by round for the strips some of whose stations failed it
    open_ = solves
    for _ in range(MAX_CHECKS):
        jobs = [(solve.strip, solve.t.copy(), outside_gaps(solve.fans, solve.strip.s, np.isnan(solve.t)))
                for solve in open_]
        closed = zip(open_, jobs, close_gaps_all(jobs), strict=True)
        merged = _merge_all([(strip, t, np.isnan(solve.t), kept, added)
                             for solve, (strip, t, kept), added in closed])
        for solve, rulings in zip(open_, merged, strict=True):
            solve.rulings = rulings
        _check_all(open_)
        check()
        still = []
        for solve in open_:
            source, fan = solve.rulings[2], solve.rulings[3]
            # a station ruling taken as torsal that fails the check is a gap after all
            failed = source[(source >= 0) & ~fan & ~solve.checked[4]]
            if len(failed):
                solve.t[failed] = np.nan
                still.append(solve)
        if not still:
            break
        open_ = still
    # each end's fans as one smooth cone, joining the torsal rulings at the ruling through
    # the curve's end point, where that ruling exists (see .end_cones)
    given = [Rulings(*solve.rulings) for solve in solves]
    smoothed = []
    curves = [(solve.strip.steady_a, solve.strip.curve_b) for solve in solves]
    # (the pencils sampled along each curve's length, as the strip measures it)
    strips = [solve.strip for solve in solves]
    ends = smooth_all([(*pair, r) for pair, r in zip(curves, given, strict=True)], strips)
    for solve, rulings, smooth in zip(solves, given, ends, strict=True):
        s_out = rulings.s
        if smooth is not rulings and (len(smooth.s) != len(s_out) or not np.array_equal(smooth.s, s_out)):
            smoothed.append((solve, smooth))
    check()
    if smoothed:
        again = [replace(solve, rulings=(r.s, r.t, r.source, r.fan)) for solve, r in smoothed]
        _check_all(again)
        for (solve, smooth), other in zip(smoothed, again, strict=True):
            valid, fan, valid2 = solve.checked[4], solve.rulings[3], other.checked[4]
            torsal = ~smooth.fan
            kept_torsal = np.count_nonzero(valid2 & torsal) >= np.count_nonzero(valid & ~fan)
            if kept_torsal and valid2[torsal & (smooth.source < 0)].all():
                solve.rulings, solve.checked = other.rulings, other.checked
    folded = []
    for solve, folds in zip(solves, _fan_folds_all(solves), strict=True):
        if len(folds[0]):
            solve.rulings = _with_folds(*solve.rulings, *folds)
            folded.append(solve)
    if folded:
        _check_all(folded)
    # the share of each strip's area in fans (of the strips that have some), all measured at once
    fanned = [solve for solve in solves if solve.rulings[3].any()]
    measured = [(solve.checked[0], solve.checked[1], solve.rulings[3]) for solve in fanned]
    shares = iter(fan_shares_all(measured) if fanned else [])
    return _results(solves, [next(shares) if solve.rulings[3].any() else (0.0, 0.0) for solve in solves])


def _partners(choices: list[tuple[IntArray, Candidates]]) -> list[tuple[FloatArray, ...]]:
    """Each strip's chosen partners ``(t, slope, has, speed)`` from its ``choices`` (the
    chosen candidate per station, −1 where none, among its consistently oriented ones):
    t, the branch slope dt/ds and |B'| per station (NaN, 0 and NaN where none), and which
    stations have one; every strip's stations at once."""
    stations = Stack.of([chosen for chosen, _ in choices])
    found = Stack.of([good.t for _, good in choices])
    chosen = np.concatenate([chosen for chosen, _ in choices])
    has = chosen >= 0
    # (each strip's candidates after those of the strips before it)
    partner = (chosen + stations.repeat(found.starts))[has]
    t, slope, speed = np.full(len(chosen), np.nan), np.zeros(len(chosen)), np.full(len(chosen), np.nan)
    t[has] = np.concatenate([good.t for _, good in choices])[partner]
    slope[has] = np.concatenate([good.slope for _, good in choices])[partner]
    speed[has] = norm(np.concatenate([good.tangents for _, good in choices])[partner])
    return list(zip(*(stations.split(x) for x in (t, slope, has, speed)), strict=True))


def _check_all(solves: list[_Solve]) -> None:
    """The check of every strip's rulings, all at once (:func:`.measure.check_rulings`)."""
    rulings = [(solve.strip, *solve.rulings[:3], solve.chosen, solve.good) for solve in solves]
    for solve, checked in zip(solves, check_rulings(rulings), strict=True):
        solve.checked = checked


def _results(solves: list[_Solve], shares: list[tuple[float, float]]) -> list[RulingResult]:
    """Each strip's result from its checked rulings and the ``shares`` of its area in fans
    and in creased ones (0 without fans: no piece counts), and the message; the stations
    closed by fans of every strip judged at once (whether a torsal ruling exists there
    out of the strip's order: a consistently oriented candidate of that station; whether
    its torsal partner runs backwards along B)."""
    stations = Stack([len(solve.strip.s) for solve in solves])
    closed = [solve.rulings[2][(solve.rulings[2] >= 0) & solve.rulings[3]] for solve in solves]
    per_strip = Stack.of(closed)
    owner = per_strip.owner()
    # (each strip's stations numbered after the strips' before it: one search for all of them)
    at = np.concatenate(closed) + per_strip.repeat(stations.starts)
    good = np.concatenate([s.good.row + first for s, first in zip(solves, stations.starts, strict=True)])
    out_of_order = np.bincount(owner[np.isin(at, good)], minlength=len(solves)).tolist()
    flipped = np.concatenate([solve.strip.flipped for solve in solves])
    backward = np.bincount(owner[flipped[at]], minlength=len(solves)).tolist()
    any_backward = np.logical_or.reduceat(flipped, stations.starts).tolist() if len(flipped) else []
    results = []
    for k, (solve, (share, creased)) in enumerate(zip(solves, shares, strict=True)):
        s_out, t_out, source, fan = solve.rulings
        starts, ends, signed, warp, valid = solve.checked
        strip = solve.strip
        counts = (out_of_order[k], backward[k], any_backward[k])
        message = _message(len(closed[k]), len(strip.s), strip.tolerance, share, creased, *counts)
        station = source >= 0
        results.append(RulingResult(
            s_out, t_out, starts, ends, warp, signed, valid, message, station, fan, share, creased, *counts
        ))
    return results


def _unwatched() -> None:
    """The check outside a :func:`~..watch.watched` block: nothing to look at."""


def _merge_all(
    jobs: list[tuple[Strip, FloatArray, BoolArray, list, list[tuple[FloatArray, FloatArray]]]],
) -> list[tuple[FloatArray, FloatArray, IntArray, BoolArray]]:
    """All rulings of each strip ordered along it, for every ``(strip, t, gap, fans, added)``
    of ``jobs``: the stations, every torsal fan's rulings ``(s*, t_low, t_high)`` and the
    rulings ``added`` to close gaps. The fans' parameters of all strips are found together,
    and so are the lengths along B that tell equal rulings apart.

    Returns per strip s, t, per ruling the station it is (−1 for an added ruling) and
    whether it closes a gap (the gap stations ``gap`` and the ``added`` rulings).
    """
    fan_ts = iter(fans_all([(strip, t_low, t_high) for strip, _, _, fans, _ in jobs
                            for _, t_low, t_high in fans]))
    merged: list = [None] * len(jobs)
    more = []  # (index in merged, strip, its rulings s, t and gap, stations first)
    for index, (strip, t, gap, fans, added) in enumerate(jobs):
        if not fans and not added:
            merged[index] = (strip.s, t, np.arange(len(strip.s)), gap.copy())
            continue
        s_parts, t_parts, gap_parts = [strip.s], [t], [gap]
        for s_star, _, _ in fans:
            ts = next(fan_ts)[0]
            s_parts.append(np.full(len(ts), s_star))
            t_parts.append(ts)
            gap_parts.append(np.zeros(len(ts), dtype=bool))
        for s_add, t_add in added:
            s_parts.append(s_add)
            t_parts.append(t_add)
            gap_parts.append(np.ones(len(s_add), dtype=bool))
        more.append((index, strip, *(np.concatenate(x) for x in (s_parts, t_parts, gap_parts))))
    if more:
        for (index, *_), rulings in zip(more, _unrepeated([job[1:] for job in more]), strict=True):
            merged[index] = rulings
    return merged


def _unrepeated(
    strips: list[tuple[Strip, FloatArray, FloatArray, BoolArray]],
) -> list[tuple[FloatArray, FloatArray, IntArray, BoolArray]]:
    """:func:`_merge_all` of the strips ``(strip, s, t, gap)`` whose rulings (its stations
    first) need ordering: each strip's ordered by s, then t, and of equal rulings the
    best-ranked one; every strip's rulings one strip after another, ordered and told apart
    at once (the strip is the first key: each strip's rulings in the order they have alone)."""
    rulings = Stack.of([s for _, s, _, _ in strips])
    owner = rulings.owner()
    s_all, t_all, gap_all = (np.concatenate([strip[k] for strip in strips]) for k in (1, 2, 3))
    stations = np.array([len(strip.s) for strip, *_ in strips])
    local = np.arange(rulings.rows) - rulings.repeat(rulings.starts)
    # of equal rulings keep the station, else a torsal fan's, else an added one (rank 0, 1, 2)
    rank = np.where(local < rulings.repeat(stations), 0, np.where(gap_all, 2, 1))
    order = np.lexsort((rank, t_all, s_all, owner))
    s_sorted, t_sorted = s_all[order], t_all[order]
    lengths = np.concatenate(lengths_at([strip.map_b for strip, *_ in strips], rulings.split(t_sorted)))
    # equal: the same point of A, and points of B within 1e-12 of its length (one point
    # reached by two ways of counting along B: rounding, in t, depends on its pace)
    near = rulings.repeat(np.array([1e-12 * strip.map_b.total for strip, *_ in strips]))
    repeat = np.zeros(len(order), dtype=bool)
    repeat[1:] = (s_sorted[1:] - s_sorted[:-1] <= 1e-14) & (
        (t_sorted[1:] - t_sorted[:-1] <= 1e-14) | (lengths[1:] - lengths[:-1] <= near[1:])
    )
    repeat[rulings.starts] = False  # (a strip's first ruling repeats none of the strip before)
    if repeat.any():  # (equal to rounding: the better-ranked one may sort after the other)
        group = np.cumsum(~repeat) - 1
        best = np.lexsort((rank[order], group))
        first = np.ones(len(best), dtype=bool)
        first[1:] = group[best[1:]] != group[best[:-1]]
        order = order[best[first]]
    whose = owner[order]
    at = order - rulings.starts[whose]
    kept = Stack(np.bincount(whose, minlength=len(strips)))
    columns = s_all[order], t_all[order], np.where(at < stations[whose], at, -1), gap_all[order]
    return list(zip(*(kept.split(x) for x in columns), strict=True))


def _fan_folds_all(solves: list[_Solve]) -> list[tuple[IntArray, FloatArray, FloatArray]]:
    """Where a fan folds back on itself between two of its rulings, in every strip of
    ``solves`` at once (their checked rulings one strip after another): per strip the
    pieces, and the parameters (s, t) of the ruling at each fold.

    In a fan through a point P (consecutive rulings sharing an end) the sheet's normal
    is N(x) = (C(x) − P) × C'(x), C the curve the rulings move along. It turns smoothly
    while the rulings sweep on; where a ruling runs along C's tangent N passes through
    zero and the sheet turns back over itself (in a plane: a fan over a stretch of C that
    P does not see whole). Neither ruling of the piece shows it, each measures its own
    plane; so where N at the piece's two ends points to opposite sides, the ruling where
    N·N(start) = 0 is found by bisection and, if N vanishes there (within
    :data:`.warp.PARALLEL`: a true fold, not a fast turn of a curved cone), returned, to
    be added: its warp is undefined (NaN) and it is not valid.
    """
    rulings = Stack([len(solve.rulings[0]) for solve in solves])
    s, t = (np.concatenate([solve.rulings[k] for solve in solves]) for k in (0, 1))
    starts, ends = (np.concatenate([solve.checked[k] for solve in solves]) for k in (0, 1))
    undefined = np.isnan(np.concatenate([solve.checked[3] for solve in solves]))
    apex_a = s[1:] == s[:-1]
    apex_b = (t[1:] == t[:-1]) & ~apex_a
    # pieces between two rulings of one strip (not from a strip's last to the next one's first);
    # (a piece next to a ruling with no warp, of no length or along the curve, has no
    # normal there to compare: that ruling is not valid itself)
    inside_strip = np.ones(len(s) - 1, dtype=bool) if len(s) else np.ones(0, dtype=bool)
    inside_strip[rulings.offsets[1:-1] - 1] = False
    pieces = flatnonzero((apex_a | apex_b) & ~undefined[:-1] & ~undefined[1:] & inside_strip)
    if len(pieces) == 0:
        return [_NO_FOLDS] * len(solves)
    strip_of = np.searchsorted(rulings.offsets, pieces, side="right") - 1
    on_b = apex_a[pieces]  # the rulings move along B; else along A
    low = np.where(on_b, t[pieces], s[pieces])
    high = np.where(on_b, t[pieces + 1], s[pieces + 1])
    apex = np.where(on_b[:, None], starts[pieces], ends[pieces])
    # each strip's A and B, curve 2·i and 2·i + 1
    curves = [curve for solve in solves for curve in (solve.strip.curve_a, solve.strip.curve_b)]

    def normal(x: FloatArray, curve: IntArray, apex: FloatArray) -> tuple[FloatArray, FloatArray]:
        point, tangent = evaluate_rows(curves, x, curve, 1)
        ruling = point - apex
        return cross(ruling, unit(tangent)), ruling

    inside = np.minimum(SIDE, 0.5 * (high - low))  # one-sided: beside a corner, its piece's side
    k = len(pieces)
    curve = 2 * strip_of + on_b
    ends_x = np.concatenate([low + inside, high - inside])  # both ends of every piece at once
    both, both_rulings = normal(ends_x, np.concatenate([curve, curve]), np.concatenate([apex, apex]))
    has = norm(both) > PARALLEL * norm(both_rulings)
    first, last = both[:k], both[k:]
    flips = flatnonzero(has[:k] & has[k:] & (np.einsum("ij,ij->i", first, last) < 0.0))
    if len(flips) == 0:
        return [_NO_FOLDS] * len(solves)
    pieces, on_b, apex, first, curve = pieces[flips], on_b[flips], apex[flips], first[flips], curve[flips]
    lo, hi = low[flips] + inside[flips], high[flips] - inside[flips]
    for _ in range(60):  # bisection on N(x)·N(start): halves the bracket to rounding
        mid = 0.5 * (lo + hi)
        n, _ = normal(mid, curve, apex)
        same = np.einsum("ij,ij->i", n, first) > 0.0
        lo, hi = np.where(same, mid, lo), np.where(same, hi, mid)
    x = 0.5 * (lo + hi)
    n, ruling = normal(x, curve, apex)
    fold = norm(n) <= PARALLEL * norm(ruling)
    pieces, x, on_b = pieces[fold], x[fold], on_b[fold]
    s_add, t_add = np.where(on_b, s[pieces], x), np.where(on_b, x, t[pieces])
    bounds = rulings.groups(pieces).tolist()  # (each strip's folds, as indices into its rulings)
    return [
        (pieces[start:stop] - rulings.offsets[i], s_add[start:stop], t_add[start:stop])
        for i, (start, stop) in enumerate(pairwise(bounds))
    ]


#: :func:`_fan_folds_all` of a strip where no fan folds (empty, never written to).
_NO_FOLDS: tuple[IntArray, FloatArray, FloatArray] = (np.empty(0, dtype=np.int64), np.empty(0), np.empty(0))


def _with_folds(
    s: FloatArray, t: FloatArray, source: IntArray, fan: BoolArray, pieces: IntArray, s_add: FloatArray,
    t_add: FloatArray,
) -> tuple[FloatArray, FloatArray, IntArray, BoolArray]:
    """The rulings with one added inside each piece in ``pieces`` at (s_add, t_add)."""
    at = pieces + 1
    return (
        np.insert(s, at, s_add),
        np.insert(t, at, t_add),
        np.insert(source, at, -1),
        np.insert(fan, at, fan[pieces] | fan[pieces + 1]),
    )


def _message(
    fan_stations: int, n: int, tolerance: float, share: float, creased: float = 0.0, out_of_order: int = 0,
    backward: int = 0, any_backward: bool = False,
) -> str | None:
    """How much of the strip had to be closed by flat triangles; None when none.

    It says only what the solve checked: that no torsal ruling keeps the strip's order
    there (the certified partner search found none between the neighbours' partners),
    and, where one exists out of that order, that it would cross the other rulings or
    runs backwards along B."""
    if fan_stations == 0 and share == 0.0:
        return None
    area = f"{100 * share:.3g} % of the strip's area"
    why = []
    if out_of_order:
        why.append(f"at {out_of_order} of them a torsal ruling exists but would cross its neighbours")
    if backward:
        why.append(f"at {backward} of them the torsal ruling runs backwards along curve B")
    elif any_backward and not fan_stations:
        why.append("torsal rulings from other stations run backwards along curve B")
    if creased == 0.0:
        where = f"at {fan_stations} of {n} stations" if fan_stations else "beyond the last torsal ruling"
        text = (
            f"closed by smooth cones through single points of the curves {where}, where no ruling "
            f"tangent to both curves keeps the rulings' order ({area}; the sheet stays smooth and "
            "developable)"
        )
    elif fan_stations == 0:
        if creased < share:
            area = f"{area}, {100 * creased:.3g} % in creased fans"
        text = (
            f"no torsal ruling in the strip's order reaches part of curve B: it is closed by flat triangles "
            f"({area})"
        )
    else:
        if creased < share:
            area = f"{area}, {100 * creased:.3g} % in creased fans"
        text = (
            f"no torsal ruling within {tolerance:g} rad keeps the rulings' order at {fan_stations} of {n} "
            f"stations: closed by flat triangles ({area})"
        )
    return f"{text}; {'; '.join(why)}" if why else text
