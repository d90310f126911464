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
reversed copies of the curves. So are the strips of one solve: every end's run of fans
is read from the strips' stacked rulings at once (:class:`_Runs`, as :mod:`.stack`
stacks rows), judged, and rewritten into its cone in one pass for all of them.
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


@dataclass(frozen=True)
class _Runs:
    """The runs of fan rulings before each strip end's first torsal ruling ``k`` (counted
    from the end: for the tail, in the reversed rulings' parameters 1 − s and 1 − t), of
    many strips, stacked: per run its strip (among the strips given), whether it is the
    tail (``reverse``), ``k`` and the ends s0, t0 (the end's ruling) and sk, tk (the first
    torsal one); per run its ``k`` fan rulings (``members``): s, t (the run's parameters),
    source. A strip's head comes before its tail."""

    strip: IntArray
    reverse: BoolArray
    k: IntArray
    s0: FloatArray
    t0: FloatArray
    sk: FloatArray
    tk: FloatArray
    members: Stack
    s: FloatArray
    t: FloatArray
    source: IntArray

    def __len__(self) -> int:
        return len(self.strip)

    def any_of(self, flags: BoolArray) -> BoolArray:
        """Per run, whether any of its members' ``flags`` is set (every run has members)."""
        return np.logical_or.reduceat(flags, self.members.starts)

    def taken(self, chosen: BoolArray) -> _Runs:
        """The runs ``chosen``, with their members."""
        rows = self.members.repeat(chosen)
        return _Runs(
            self.strip[chosen], self.reverse[chosen], self.k[chosen], self.s0[chosen], self.t0[chosen],
            self.sk[chosen], self.tk[chosen], Stack(self.members.counts[chosen]), self.s[rows], self.t[rows],
            self.source[rows],
        )


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
    all of them solved at once, and every end's run read and rewritten in one pass for all
    strips. Given each strip's ``lengths`` (its curves' arc-length maps, as a
    :class:`.strip.Strip` has them), the pencils are sampled evenly along the moving
    curve's length, not its parameter: the roots found then do not depend on its pace."""
    done: list[Rulings] = [rulings for _, _, rulings in strips]
    # the strips whose ends may become cones: B open, with fans and torsal rulings
    mixed = [i for i, (_, curve_b, r) in enumerate(strips)
             if not curve_b.closed and not r.fan.all() and r.fan.any()]
    if not mixed:
        return done
    given = [strips[i][2] for i in mixed]
    stack = Stack.of([r.s for r in given])
    s, t = np.concatenate([r.s for r in given]), np.concatenate([r.t for r in given])
    source, fan = np.concatenate([r.source for r in given]), np.concatenate([r.fan for r in given])
    runs = _runs(stack, s, t, source, fan)
    if not len(runs):
        return done
    pairs = [strips[i][:2] for i in mixed]
    maps_a = maps_b = None
    if lengths is not None:
        maps_a, maps_b = [lengths[i].map_a for i in mixed], [lengths[i].map_b for i in mixed]
    # the torsal ruling through B's end point: A(s*) → B(t0), s* in (s0, sk); all ends at once
    root, has = _roots_of(pairs, runs, True, maps_a)
    stations = runs.source >= 0
    on_b = has & ~runs.any_of(stations & (runs.s > runs.members.repeat(root))
                              & (runs.s < runs.members.repeat(runs.sk)))
    # else the torsal ruling through A's end point: A(s0) → B(t*), t* in (t0, tk), where the
    # cone through A(s0) covers the run's stations
    rest = ~on_b & ~runs.any_of(stations & (runs.s > runs.members.repeat(runs.s0)))
    on_a = np.zeros(len(runs), dtype=bool)
    if rest.any():
        others = runs.taken(rest)
        root_a, on_a[rest] = _roots_of(pairs, others, False, maps_b)
        root[rest] = np.where(on_a[rest], root_a, root[rest])
    coned = on_b | on_a
    if coned.any():
        rewritten = _with_cones(stack, s, t, source, fan, runs.taken(coned), on_a[coned], root[coned])
        for j, rulings in rewritten.items():
            done[mixed[j]] = rulings
    return done


def _runs(stack: Stack, s: FloatArray, t: FloatArray, source: IntArray, fan: BoolArray) -> _Runs:
    """The runs of fans at both ends of the stacked rulings of strips that have fans and
    torsal rulings (``stack`` says where each strip's are), but for an end with no run
    (its ruling is torsal) or whose run is one cone already."""
    n, starts = stack.counts, stack.starts
    local = np.arange(stack.rows) - stack.repeat(starts)
    # per strip (head, tail): the first torsal ruling from that end
    k = np.empty((len(stack), 2), dtype=np.int64)
    k[:, 0] = np.minimum.reduceat(np.where(fan, stack.rows, local), starts)
    k[:, 1] = n - 1 - np.maximum.reduceat(np.where(fan, -1, local), starts)
    candidate = k.reshape(-1) > 0
    strip = np.repeat(np.arange(len(stack)), 2)[candidate]
    reverse = np.tile([False, True], len(stack))[candidate]
    k = k.reshape(-1)[candidate]
    # each run's k + 1 rulings from its end, in its parameters (1 − u on the tail)
    ends = Stack(k + 1)
    run = ends.owner()
    step = np.arange(ends.rows) - ends.repeat(ends.starts)
    backwards = reverse[run]
    rows = starts[strip][run] + np.where(backwards, n[strip][run] - 1 - step, step)
    run_s = np.where(backwards, 1.0 - s[rows], s[rows])
    run_t = np.where(backwards, 1.0 - t[rows], t[rows])
    first, last = ends.starts, ends.offsets[1:] - 1
    one_cone = (np.logical_and.reduceat(run_s == ends.repeat(run_s[first]), first)
                | np.logical_and.reduceat(run_t == ends.repeat(run_t[first]), first))
    member = step < ends.repeat(k)  # (the k fan rulings, not the torsal one)
    runs = _Runs(strip, reverse, k, run_s[first], run_t[first], run_s[last], run_t[last], Stack(k),
                 run_s[member], run_t[member], source[rows[member]])
    return runs.taken(~one_cone)


def _roots_of(
    pairs: Sequence[tuple[Curve, Curve]], runs: _Runs, moving_a: bool, maps: Sequence[LengthMap] | None
) -> tuple[FloatArray, BoolArray]:
    """:func:`_roots` of ``runs`` (of the strips whose curves are ``pairs``): per run the root
    and whether there is one."""
    strips, per_strip = np.unique(runs.strip, return_counts=True)
    fixed, low, high = (runs.t0, runs.s0, runs.sk) if moving_a else (runs.s0, runs.t0, runs.tk)
    listed = strips.tolist()
    return _roots([pairs[j] for j in listed], Stack(per_strip), runs.reverse, fixed, low, high, moving_a,
                  None if maps is None else [maps[j] for j in listed])


def _with_cones(
    stack: Stack, s: FloatArray, t: FloatArray, source: IntArray, fan: BoolArray, runs: _Runs,
    through_a: BoolArray, root: FloatArray,
) -> dict[int, Rulings]:
    """The rulings of each strip with a cone at one end or both (by its place in ``stack``),
    the ``runs`` that have one made that cone (:func:`_cones`); the rulings between the
    ends' runs stay, and the first (last) of them, the torsal ruling the head's (tail's)
    cone joins, may become that cone's station."""
    cone_s, cone_t, cone_source, cone_fan, blocks, first_station = _cones(runs, through_a, root)
    strips = np.unique(runs.strip)
    # per strip the head's and the tail's run (−1: none), and the rulings kept between them
    head, tail = np.full(len(stack), -1), np.full(len(stack), -1)
    head[runs.strip[~runs.reverse]] = np.flatnonzero(~runs.reverse)
    tail[runs.strip[runs.reverse]] = np.flatnonzero(runs.reverse)
    head, tail = head[strips], tail[strips]
    low = stack.starts[strips] + np.where(head >= 0, runs.k[head], 0)
    high = stack.offsets[1:][strips] - np.where(tail >= 0, runs.k[tail], 0)
    # the new rulings: per strip its head's cone, its rulings low:high, its tail's cone,
    # gathered from the rulings followed by the cones
    rows = stack.rows
    begin = np.column_stack([rows + blocks.starts[head], low, rows + blocks.starts[tail]])
    count = np.column_stack([np.where(head >= 0, blocks.counts[head], 0), high - low,
                             np.where(tail >= 0, blocks.counts[tail], 0)])
    pieces = Stack(count.reshape(-1))
    at = np.arange(pieces.rows) - pieces.repeat(pieces.starts) + pieces.repeat(begin.reshape(-1))
    out_s = np.concatenate([s, cone_s])[at]
    out_t = np.concatenate([t, cone_t])[at]
    out_source = np.concatenate([source, cone_source])[at]
    out_fan = np.concatenate([fan, cone_fan])[at]
    # the first torsal ruling may take the station of a fan ruling its cone dropped (the
    # head's first, then the tail's, on what the head left where it is also the last one)
    kept = pieces.starts[1::3]
    for runs_at, place in ((head, kept), (tail, kept + count[:, 1] - 1)):
        given = runs_at >= 0
        station = first_station[runs_at]
        takes = given & (station >= 0) & (out_source[place] < 0)
        out_source[place[takes]] = station[takes]
    per_strip = Stack(count.sum(axis=1))
    columns = [per_strip.split(a) for a in (out_s, out_t, out_source, out_fan)]
    return {int(j): Rulings(*row) for j, *row in zip(strips.tolist(), *columns, strict=True)}


def _cones(
    runs: _Runs, through_a: BoolArray, root: FloatArray
) -> tuple[FloatArray, FloatArray, IntArray, BoolArray, Stack, IntArray]:
    """The rulings that replace each run (a cone's rulings and the torsal ruling through the
    curve's end point ``root``: through A(s0) where ``through_a``, else through B(t0)), in
    the strip's parameters and order (a tail's read back), one block per run (the
    returned stack); and per run the station a dropped fan ruling leaves for the first
    torsal ruling to carry (the least, −1 for none)."""
    m = runs.members
    owner = m.owner()
    stations = runs.source >= 0
    by_a = m.repeat(through_a)
    bound = m.repeat(root)
    # through B(t0): the stations the cone covers; through A(s0): its fans over B up to t*
    keep = np.where(by_a, (runs.t < bound) & (runs.s == m.repeat(runs.s0)), (runs.s < bound) & stations)
    kept = np.add.reduceat(keep.astype(np.int64), m.starts)
    blocks = Stack(kept + 1)
    # each kept ruling's place in its block, then the torsal ruling's (the last; the first
    # of a tail's block, read backwards)
    rank = np.cumsum(keep) - keep - m.repeat(np.cumsum(kept) - kept)
    rank = rank[keep]
    back = runs.reverse[owner[keep]]
    place = blocks.starts[owner[keep]] + np.where(back, kept[owner[keep]] - rank, rank)
    torsal = blocks.starts + np.where(runs.reverse, 0, kept)
    cone_s, cone_t = np.empty(blocks.rows), np.empty(blocks.rows)
    cone_s[place] = runs.s[keep]
    cone_t[place] = np.where(by_a[keep], runs.t[keep], runs.t0[owner[keep]])
    cone_s[torsal] = np.where(through_a, runs.s0, root)
    cone_t[torsal] = np.where(through_a, root, runs.t0)
    back_rows = blocks.repeat(runs.reverse)
    cone_s = np.where(back_rows, 1.0 - cone_s, cone_s)
    cone_t = np.where(back_rows, 1.0 - cone_t, cone_t)
    cone_source = np.full(blocks.rows, -1, dtype=np.int64)
    cone_source[place] = runs.source[keep]
    cone_fan = np.ones(blocks.rows, dtype=bool)
    cone_fan[torsal] = False
    # the stations of fan rulings no kept ruling carries any more (by run: run · span + source)
    span = int(runs.source.max()) + 2
    key = owner * span + runs.source + 1
    dropped = stations & ~np.isin(key, key[keep])
    least = np.minimum.reduceat(np.where(dropped, runs.source, np.iinfo(np.int64).max), m.starts)
    first_station = np.where(runs.any_of(dropped), least, -1)
    return cone_s, cone_t, cone_source, cone_fan, blocks, first_station


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
    pairs: Sequence[tuple[Curve, Curve]], per_strip: Stack, reverse: BoolArray, fixed: FloatArray,
    low: FloatArray, high: FloatArray, moving_a: bool, maps: Sequence[LengthMap] | None = None,
) -> tuple[FloatArray, BoolArray]:
    """For each run (``per_strip`` of them on each strip of curves ``pairs``, read backwards
    where ``reverse``), the parameter nearest the first torsal ruling of the moving end of
    a torsal ruling with consistently oriented normals (signed warp near 0, not near π)
    through the fixed end point — B(``fixed``) when ``moving_a`` (the root in (s0, sk):
    ``low``, ``high``), else A(``fixed``) (the root in (t0, tk)) — and whether there is one
    (the root is NaN where not).

    Each run's pencil is bracketed on :data:`SAMPLES` samples (evenly spaced along the
    moving curve's length given its ``maps``, else in its parameter); all runs' samples are one
    evaluation of each strip's moving curve, which also tells the orientation
    (:func:`.warp.consistently_oriented`, with each strip's own size). Every sign change
    of every strip is then refined at once, by Newton's method inside its bracket on
    g = det[B − A, A', B'] (the coplanarity with the curves' own tangents: the same
    roots), with g' = det[R, A'', B'] (or det[R, A', B''] when B moves).
    """
    moving = [(a, b) if moving_a else (b, a) for a, b in pairs]
    strip_of = per_strip.owner()  # (of every run)
    found, has = np.full(len(reverse), np.nan), np.zeros(len(reverse), dtype=bool)
    wide = high > low
    if not wide.any():
        return found, has
    offset = per_strip.repeat(np.array([b.anchor - a.anchor for a, b in pairs]))
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
    rows = np.repeat(np.arange(len(reverse)), SAMPLES)

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
        return found, has
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
        bounds = np.searchsorted(strip_of_root[index], np.arange(len(pairs) + 1))
        c = evaluate_each(curves, np.where(back, 1.0 - xs, xs), bounds, 2, local=True)
        value, value_slope, scale, ends = coplanarity(run_of[index], *c, back)
        roots[index] = xs  # the last evaluated point of each bracket, and its ruling
        at_root[:, index] = ends
        return value, value_slope, scale

    refine_roots(refined, x0, x1, g0, start)
    with np.errstate(invalid="ignore", over="ignore"):
        a, da, b, db = at_root
        strip_roots = Stack(np.bincount(strip_of_root, minlength=len(pairs)))
        good = consistently_oriented(a, b, da, db, strip_roots.repeat(sizes(strip_roots, a, b)))
    # per run, the root of the last (nearest the torsal ruling) sign change whose root is
    # oriented (the sign changes come run by run, in order along each)
    oriented_at = flatnonzero(good)
    if oriented_at.size == 0:  # no run has an oriented root
        return found, has
    of_run = run_of[oriented_at]
    last = oriented_at[np.append(of_run[1:] != of_run[:-1], True)]
    found[run_of[last]], has[run_of[last]] = roots[last], True
    return found, has
