"""Closing a strip's ends with one smooth cone instead of a creased pair of triangle fans.

Where the curves' ends admit no torsal ruling (A(0)'s torsal partner would lie before
B(0), say), the strip is closed by triangles from the end of the curves to the first
torsal ruling. Closed one way — a fan through B(0) over A up to the first torsal
*station*, then a fan through that station's point of A over B up to its partner — the
sheet folds along the ruling where the apex changes. But there is a torsal ruling that
passes through B(0) itself: A(s*) → B(0), with s* between the last fan station and the
first torsal one. Closing with the single cone through B(0) over A[0, s*] and joining the
torsal rulings at A(s*) → B(0) leaves no fold: along that ruling the cone's tangent plane
(the ruling and A'(s*)) is the torsal strip's (the ruling, A'(s*) and B'(0)). So the end
is smooth (G1) and exactly developable, and the strip still reaches both curves' ends.

This module finds that ruling (or the one through A(0) over B, whichever the geometry
gives) and rewrites the first run of fan rulings; the last run is done on the reversed
curves. Where the fan run holds a station strictly inside the new torsal stretch (the
solve found no torsal partner for it, so the stretch is not known to be torsal), or no
such ruling exists, the run is left as it was.

Both ends are solved together: the pencils of rulings through the curves' end points
are sampled in one evaluation of the moving curve, every sign change of the coplanarity
function is refined at once by Newton's method inside its bracket (:mod:`..roots`), and
the tail is solved on the curves' own parameters run backwards (1 − x) rather than on
reversed copies of the curves.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from itertools import pairwise
from typing import TYPE_CHECKING

import numpy as np

from torsal.nodes.geometry.array_types import BoolArray, IntArray

from ..curve_base import Curve, FloatArray
from ..vec_ops import cross, dot, flatnonzero, norm
from .brackets import refine_roots
from .candidates import cubic_start, rounding_scale
from .stack import Stack, evaluate_each
from .stations import LengthMap, lengths_at
from .warp import consistently_oriented, sizes

if TYPE_CHECKING:
    from .strip import Strip as Lengths  # (what it reads: a strip's map_a and map_b)

#: Samples of the coplanarity function used to bracket the end ruling's root.
SAMPLES = 33
_STEPS = np.arange(SAMPLES)  # (the samples' steps from the start of their interval)


@dataclass(frozen=True)
class Rulings:
    """The strip's rulings as parameters: per ruling s, t, the station it is (−1 when
    added) and whether it is a fan ruling."""

    s: FloatArray
    t: FloatArray
    source: IntArray
    fan: BoolArray

    def reversed(self) -> Rulings:
        return Rulings(1.0 - self.s[::-1], 1.0 - self.t[::-1], self.source[::-1], self.fan[::-1])


@dataclass(frozen=True)
class _Run:
    """The run of fan rulings before the first torsal ruling ``k`` of the rulings (or of
    the reversed rulings, for the tail: ``reverse``), in those rulings' parameters."""

    k: int
    reverse: bool
    s0: float
    t0: float
    sk: float
    tk: float
    s: FloatArray
    t: FloatArray
    source: IntArray


def smooth_ends(curve_a: Curve, curve_b: Curve, rulings: Rulings) -> Rulings:
    """``rulings`` with each end's run of fans made one cone where that is possible (see
    the module). Not for a closed B, whose partners may run through its seam. Rulings
    away from the ends keep their parameters bit for bit (and ``rulings`` itself comes
    back where neither end changes)."""
    return smooth_all([(curve_a, curve_b, rulings)])[0]


def smooth_all(
    strips: Sequence[tuple[Curve, Curve, Rulings]], lengths: Sequence[Lengths] | None = None
) -> list[Rulings]:
    """:func:`smooth_ends` of every strip ``(curve_a, curve_b, rulings)``, the end rulings of
    all of them solved at once. Given each strip's ``lengths`` (its curves' arc-length maps,
    as a :class:`.strip.Strip` has them), the pencils are sampled evenly along the moving
    curve's length, not its parameter: the roots found then do not depend on its pace."""
    done: list[Rulings] = [rulings for _, _, rulings in strips]
    # per strip its runs: those of the strips whose ends may become cones
    jobs: list[tuple[int, list[_Run]]] = []
    for index, (_, curve_b, rulings) in enumerate(strips):
        if curve_b.closed or rulings.fan.all() or not rulings.fan.any():
            continue
        runs = [run for run in (_run(rulings, False), _run(rulings, True)) if run is not None]
        if runs:
            jobs.append((index, runs))
    if not jobs:
        return done
    # the torsal ruling through B's end point: A(s*) → B(t0), s* in (s0, sk); all ends at once
    through_b = _roots([(strips[i][0], strips[i][1], runs) for i, runs in jobs], True,
                       None if lengths is None else [lengths[i].map_a for i, _ in jobs])
    cones: list[dict[bool, tuple[bool, float]]] = []
    others: list[tuple[int, list[_Run]]] = []
    for (_, runs), roots in zip(jobs, through_b, strict=True):
        found: dict[bool, tuple[bool, float]] = {}
        rest = []
        for run, root in zip(runs, roots, strict=True):
            stations = run.source >= 0
            if root is not None and not (stations & (run.s > root) & (run.s < run.sk)).any():
                found[run.reverse] = (False, root)
            elif not (stations & (run.s > run.s0)).any():
                rest.append(run)  # else the cone through A(s0) could not cover the run's stations
        cones.append(found)
        if rest:
            others.append((len(cones) - 1, rest))
    if others:  # the torsal ruling through A's end point: A(s0) → B(t*), t* in (t0, tk)
        through_a = _roots([(*strips[jobs[j][0]][:2], rest) for j, rest in others], False,
                           None if lengths is None else [lengths[jobs[j][0]].map_b for j, _ in others])
        for (j, rest), roots in zip(others, through_a, strict=True):
            for run, root in zip(rest, roots, strict=True):
                if root is not None:
                    cones[j][run.reverse] = (True, root)
    for (index, runs), found in zip(jobs, cones, strict=True):
        if found:
            done[index] = _with_cones(strips[index][2], runs, found)
    return done


def _with_cones(rulings: Rulings, runs: list[_Run], cones: dict[bool, tuple[bool, float]]) -> Rulings:
    """The rulings with the end runs that have a cone (``cones``, by ``reverse``: whether
    it is through A and the end ruling's root) made that cone."""
    # the rulings between the ends' runs stay; the first (last) of them is the torsal
    # ruling the head's (tail's) cone joins, and may become that cone's station
    n = len(rulings.s)
    head = next((run for run in runs if not run.reverse and False in cones), None)
    tail = next((run for run in runs if run.reverse and True in cones), None)
    first, stop = (head.k if head else 0), (n - tail.k if tail else n)
    source = rulings.source[first:stop].copy()
    pieces = [Rulings(rulings.s[first:stop], rulings.t[first:stop], source, rulings.fan[first:stop])]
    if head is not None:
        cone, source[0] = _cone(head, *cones[False], int(source[0]))
        pieces.insert(0, cone)
    if tail is not None:
        # (the head's cone leaves the tail's run as it was, but may have given the first
        # torsal ruling, if it is also the last, a station)
        cone, source[-1] = _cone(tail, *cones[True], int(source[-1]))
        pieces.append(cone.reversed())
    columns = zip(*((piece.s, piece.t, piece.source, piece.fan) for piece in pieces), strict=True)
    return Rulings(*(np.concatenate(column) for column in columns))


def _run(r: Rulings, reverse: bool) -> _Run | None:
    """The run of fans before the first torsal ruling (from the strip's end, in the reversed
    rulings' parameters 1 − s and 1 − t, when ``reverse``), or None where there is none or
    it is one cone already."""
    k = int(r.fan[::-1].argmin() if reverse else r.fan.argmin())  # the first torsal ruling
    if k == 0:
        return None
    if reverse:  # the first k + 1 of the reversed rulings
        s, t, source = 1.0 - r.s[-1 - k :][::-1], 1.0 - r.t[-1 - k :][::-1], r.source[-k:][::-1]
    else:
        s, t, source = r.s[: k + 1], r.t[: k + 1], r.source[:k]
    s0, t0 = s[0], t[0]
    if (s == s0).all() or (t == t0).all():
        return None  # already one cone
    return _Run(k, reverse, float(s0), float(t0), float(s[k]), float(t[k]), s[:k], t[:k], source)


def _cone(run: _Run, through_a: bool, root: float, source_k: int) -> tuple[Rulings, int]:
    """The rulings that replace the run (a cone's rulings and the torsal ruling through the
    curve's end point ``root``), and the station index the first torsal ruling carries
    from then on (``source_k`` now)."""
    stations = run.source >= 0
    if not through_a:  # the stations the cone through B(t0) covers, then A(root) → B(t0)
        keep = flatnonzero((run.s < root) & stations)
        torsal = root, run.t0
    else:  # the cone through A(s0) over B[t0, t*], then A(s0) → B(root)
        keep = flatnonzero((run.t < root) & (run.s == run.s0))
        torsal = run.s0, root
    m = len(keep)
    head = np.empty((2, m + 1))
    head[0, :m] = run.s[keep]
    head[1, :m] = run.t[keep] if through_a else run.t0
    head[:, m] = torsal
    head_source = np.empty(m + 1, dtype=np.int64)
    head_source[:m] = kept = run.source[keep]
    head_source[m] = -1
    dropped = set(run.source[stations].tolist()) - set(kept.tolist())
    if dropped and source_k < 0:  # a fan ruling of the station at the first torsal ruling's s
        source_k = min(dropped)
    head_fan = np.ones(m + 1, dtype=bool)
    head_fan[m] = False
    return Rulings(head[0], head[1], head_source, head_fan), source_k


def _even_in_length(
    x: FloatArray, maps: Sequence[LengthMap], per_strip: Stack, reverse: BoolArray, low: FloatArray,
    high: FloatArray,
) -> None:
    """Rewrites the samples ``x`` of every run (from ``low`` to ``high`` in its parameters,
    1 − u for a run read backwards) to be evenly spaced in its strip's arc length
    (``maps``, one per strip), in place."""
    bounds = per_strip.offsets.tolist()
    u0, u1 = np.where(reverse, 1.0 - low, low), np.where(reverse, 1.0 - high, high)
    # (the runs' ends measured along every strip's curve at once)
    measured = lengths_at(maps, [np.concatenate([u0[first:stop], u1[first:stop]])
                                 for first, stop in pairwise(bounds)])
    for lengths, first, stop, found in zip(maps, bounds[:-1], bounds[1:], measured, strict=True):
        ends = found.reshape(2, -1)
        at = ends[0][:, None] + (ends[1] - ends[0])[:, None] * (_STEPS / (SAMPLES - 1))
        u = lengths.parameter_near(at)  # (samples: their roots are refined)
        x[first:stop] = np.where(reverse[first:stop, None], 1.0 - u, u)
    x[:, 0] = low


def _roots(
    strips: Sequence[tuple[Curve, Curve, list[_Run]]], moving_a: bool, maps: Sequence[LengthMap] | None = None
) -> list[list[float | None]]:
    """For each run of each strip ``(curve_a, curve_b, runs)``, the parameter nearest the
    first torsal ruling of the moving end of a torsal ruling with consistently oriented
    normals (signed warp near 0, not near π) through the fixed end point — B(t0) when
    ``moving_a`` (the root in (s0, sk)), else A(s0) (the root in (t0, tk)) — or None.

    Each run's pencil is bracketed on :data:`SAMPLES` samples (evenly spaced along the
    moving curve's length given its ``maps``, else in its parameter); all runs' samples are one
    evaluation of each strip's moving curve, which also tells the orientation
    (:func:`.warp.consistently_oriented`, with each strip's own size). Every sign change
    of every strip is then refined at once, by Newton's method inside its bracket on
    g = det[B − A, A', B'] (the coplanarity with the curves' own tangents: the same
    roots), with g' = det[R, A'', B'] (or det[R, A', B''] when B moves).
    """
    moving = [(a, b) if moving_a else (b, a) for a, b, _ in strips]
    runs = [run for _, _, of_strip in strips for run in of_strip]
    per_strip = Stack([len(of_strip) for _, _, of_strip in strips])
    strip_of = per_strip.owner()  # (of every run)
    found: list[float | None] = [None] * len(runs)

    def by_strip(flat: list[float | None]) -> list[list[float | None]]:
        bounds = per_strip.offsets.tolist()
        return [flat[low:high] for low, high in pairwise(bounds)]

    reverse = np.array([run.reverse for run in runs])
    # per run, the fixed end's parameter and the moving end's interval
    fixed, low, high = np.array(
        [(run.t0, run.s0, run.sk) if moving_a else (run.s0, run.t0, run.tk) for run in runs]
    ).T
    wide = high > low
    if not wide.any():
        return by_strip(found)
    offset = per_strip.repeat(np.array([b.anchor - a.anchor for a, b, _ in strips]))
    q, dq = evaluate_each(
        [m[1] for m in moving], np.where(reverse, 1.0 - fixed, fixed), per_strip.offsets, 1, local=True
    )
    # (runs, SAMPLES), in each run's parameters, as np.linspace places them
    x = low[:, None] + ((high - low) / (SAMPLES - 1))[:, None] * _STEPS
    if maps is not None:
        _even_in_length(x, maps, per_strip, reverse, low, high)
    x[:, -1] = high
    flip = np.repeat(reverse, SAMPLES)
    u = x.reshape(-1)
    p, dp, ddp = evaluate_each(
        [m[0] for m in moving], np.where(flip, 1.0 - u, u), per_strip.offsets * SAMPLES, 2, local=True
    )
    rows = np.repeat(np.arange(len(runs)), SAMPLES)

    def pencil(rows: IntArray, p: FloatArray, dp: FloatArray) -> tuple[FloatArray, ...]:
        """The rulings of the pencils ``rows`` to the moving points ``p`` (tangents ``dp``)
        as ``(a, da, b, db)``, B's points measured in A's local coordinates."""
        if moving_a:
            return p, dp, q[rows] + offset[rows], dq[rows]
        return q[rows], dq[rows], p + offset[rows], dp

    def coplanarity(
        rows: IntArray, p: FloatArray, dp: FloatArray, ddp: FloatArray, flip: BoolArray, scaled: bool = True
    ):
        """g, its slope in the run's parameter, its rounding scale (None unless ``scaled``)
        and the rulings."""
        a, da, b, db = pencil(rows, p, dp)
        r = b - a
        if moving_a:  # g' = det[R, A'', B'] (det[−A', A', B'] vanishes)
            plane = cross(r, db)
            g, slope = -dot(plane, da), -dot(plane, ddp)
        else:  # g' = det[R, A', B''] (det[B', A', B''] vanishes)
            plane = cross(r, da)
            g, slope = dot(plane, db), dot(plane, ddp)
        slope = np.where(flip, -slope, slope)  # d/dx = −d/du on a run read backwards
        scale = rounding_scale(norm(a), b, norm(da), db) if scaled else None
        return g, slope, scale, (a, da, b, db)

    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        g, slope, _, (a, da, b, db) = coplanarity(rows, p, dp, ddp, flip, scaled=False)
        samples = Stack(per_strip.counts * SAMPLES)
        size = samples.repeat(sizes(samples, a, b))
        oriented = consistently_oriented(a, b, da, db, size).reshape(x.shape)
    g, slope = g.reshape(x.shape), slope.reshape(x.shape)
    usable = wide & np.isfinite(g).all(axis=1)
    change = (np.sign(g[:, :-1]) * np.sign(g[:, 1:]) < 0) & (oriented[:, :-1] | oriented[:, 1:])
    change &= usable[:, None]
    run_of, j = np.nonzero(change)
    if len(run_of) == 0:
        return by_strip(found)
    # the samples before and after each sign change, as flat indices of the (runs, SAMPLES) arrays
    before = run_of * SAMPLES + j
    after = before + 1
    xs, gs, slopes = x.reshape(-1), g.reshape(-1), slope.reshape(-1)
    x0, x1 = xs[before], xs[after]
    g0, g1 = gs[before], gs[after]
    start = cubic_start(x0, x1, g0, g1, slopes[before], slopes[after])
    roots = np.empty(len(run_of))
    at_root = np.empty((4, len(run_of), 3))
    strip_of_root = strip_of[run_of]
    curves = [m[0] for m in moving]

    def refined(xs: FloatArray, index: IntArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        back = reverse[run_of[index]]
        bounds = np.searchsorted(strip_of_root[index], np.arange(len(strips) + 1))
        c = evaluate_each(curves, np.where(back, 1.0 - xs, xs), bounds, 2, local=True)
        value, value_slope, scale, ends = coplanarity(run_of[index], *c, back)
        roots[index] = xs  # the last evaluated point of each bracket, and its ruling
        at_root[:, index] = ends
        return value, value_slope, scale

    refine_roots(refined, x0, x1, g0, start)
    with np.errstate(invalid="ignore", over="ignore"):
        a, da, b, db = at_root
        strip_roots = Stack(np.bincount(strip_of_root, minlength=len(strips)))
        good = consistently_oriented(a, b, da, db, strip_roots.repeat(sizes(strip_roots, a, b)))
    # per run, the root of the last (nearest the torsal ruling) sign change whose root is oriented
    for i in set(run_of[good].tolist()):
        found[int(i)] = float(roots[good & (run_of == i)][-1])
    return by_strip(found)
