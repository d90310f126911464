"""Closing triangles: the flat triangles that close a strip where no torsal ruling reaches B.

Over a run of stations on A without a torsal partner on B (:func:`close_gaps`), the strip
is bounded by the torsal rulings on either side (or by the curves' ends) and by the two
stretches of A and B in between. That piece is closed by a strip of triangles, each with
two corners on one curve and one on the other — a sequence of fans through single points,
as the planar middle of the ZVE roof edge is made. Three points are always coplanar, so
every triangle is flat and the strip stays developable (it unrolls exactly); what it gives
up is tangency to the curves, so its rulings are flagged, not counted as torsal.

The closing triangles follow the two stretches in step (:func:`zigzag`): the next triangle
stands on the edge (of either curve) whose middle is nearer in *fraction of its stretch's
length*, so the triangles are about as wide on both curves, no ruling crosses another, and
the strip read from its other end is the same. The other fans of a strip are in
:mod:`.fans`.
"""

from __future__ import annotations

import struct
from collections.abc import Callable, Iterator, Sequence
from functools import partial
from itertools import pairwise

import numpy as np

from torsal.nodes.geometry.array_types import BoolArray, IntArray

from ..curve_base import FloatArray
from ..curves.shared_knots import derivative_each
from ..vec_ops import flatnonzero, norm
from .strip import Strip, gap_lengths_all

#: Fractions of a chain's length this close are one in :func:`zigzag`.
TIE = 1e-9


def zigzag(
    length_a: FloatArray,
    length_b: FloatArray,
    points: Callable[[], tuple[FloatArray, FloatArray]] | None = None,
) -> tuple[IntArray, IntArray]:
    """Vertex indices ``(i, j)`` of the rulings of the triangle strip between a chain of
    points on A at arc lengths ``length_a`` (non-decreasing) and one on B at
    ``length_b``: from (0, 0) to (last, last), each step advancing along one chain.

    Each step is an edge of one chain (a triangle with its apex on the other); the steps
    are taken in the order of their edges' middles, as fractions of each chain's length.
    That order reversed is the order of the chains read from their other ends, so the
    strip is the same whichever way the curves run (stepping to the nearer next *vertex*
    joined each vertex of B to the vertex of A before it, and read backwards, to the one
    after it). An edge of A and one of B with the same middle (chains evenly spaced along
    both curves) are a quad: given the chains' ``points`` it is split
    along its shorter diagonal (``points()`` gives the chains' points, asked for only then),
    else (and where the two are equal) A steps first.

    >>> i, j = zigzag(np.array([0.0, 1.0, 2.0]), np.array([0.0, 3.0, 4.0]))
    >>> i.tolist(), j.tolist()
    ([0, 1, 1, 2, 2], [0, 0, 1, 1, 2])
    """
    chains = None if points is None else lambda _: [points()]
    return zigzag_all([(length_a, length_b)], chains)[0]


def zigzag_all(
    lengths: Sequence[tuple[FloatArray, FloatArray]],
    points: Callable[[list[int]], list[tuple[FloatArray, FloatArray]]] | None = None,
) -> list[tuple[IntArray, IntArray]]:
    """:func:`zigzag` of every pair of chains ``(length_a, length_b)`` (one point or more
    each) of ``lengths``, all steps of all pairs ordered in one sort: each pair gets what it
    gets alone. ``points(pairs)`` gives the chains' points ``(points_a, points_b)`` of the
    pairs ``pairs`` (those with a tie to cut along a diagonal), asked for once."""
    ij, bounds = _zigzag_rows(lengths, points)
    return [(ij[0, low:high], ij[1, low:high]) for low, high in pairwise(bounds.tolist())]


def _zigzag_rows(
    lengths: Sequence[tuple[FloatArray, FloatArray]],
    points: Callable[[list[int]], list[tuple[FloatArray, FloatArray]]] | None,
) -> tuple[IntArray, IntArray]:
    """:func:`zigzag_all` as one ``(2, rows)`` array of every pair's ``(i, j)``, pair after
    pair, and where each pair's rows start (and the last one ends)."""
    count = len(lengths)
    fa, bounds_a = _fractions_all([a for a, _ in lengths])
    fb, bounds_b = _fractions_all([b for _, b in lengths])
    # the edges' middles, all of A's (pair after pair) then all of B's
    left_a, left_b = _lefts(bounds_a), _lefts(bounds_b)
    middles = 0.5 * np.concatenate([fa[left_a + 1] + fa[left_a], fb[left_b + 1] + fb[left_b]])
    # middles equal to TIE count as a tie: chains evenly spaced along both curves meet at
    # equal fractions that rounding alone would otherwise order, so that the triangles of a
    # model moved far from the origin flipped diagonals
    keys = np.round(middles / TIE)
    edges_a, edges_b = np.diff(bounds_a) - 1, np.diff(bounds_b) - 1
    pair = np.concatenate([np.repeat(np.arange(count), edges_a), np.repeat(np.arange(count), edges_b)])
    along_b = np.arange(len(keys)) >= len(left_a)
    # step along whichever edge's middle comes first, A's before B's at a tie (then in
    # their order along the chain: the sort is stable), pair after pair
    order = np.lexsort((along_b, keys, pair))
    steps = along_b[order]
    # each pair's steps, then its (i, j) with one more row: both start at 0
    sizes = edges_a + edges_b
    first = np.zeros(count + 1, dtype=np.int64)
    np.cumsum(sizes, out=first[1:])
    row = np.arange(len(steps)) + np.repeat(np.arange(count), sizes) + 1  # (each step's row after it)
    ij = np.zeros((2, len(steps) + count), dtype=np.int64)
    for k, moves in enumerate((~steps, steps)):
        total = np.zeros(len(moves) + 1, dtype=np.int64)
        np.cumsum(moves, out=total[1:])
        ij[k, row] = total[1:] - np.repeat(total[first[:-1]], sizes)
    if points is not None:
        # a tie of an edge of A (taken first) and one of B of the same pair: the quad A_i
        # A_i+1 B_j+1 B_j, cut along A_i+1 B_j so far; along A_i B_j+1 where that is shorter
        sorted_keys, owner = keys[order], pair[order]
        tie = flatnonzero((sorted_keys[1:] == sorted_keys[:-1]) & ~steps[:-1] & steps[1:]
                          & (owner[1:] == owner[:-1]))
        if len(tie):
            _cut_ties(ij, row[tie] - 1, owner[tie], points)
    return ij, first + np.arange(count + 1)


def _cut_ties(
    ij: IntArray, at: IntArray, owner: IntArray,
    points: Callable[[list[int]], list[tuple[FloatArray, FloatArray]]],
) -> None:
    """Cuts the quads of the ties at rows ``at`` of ``ij`` (of pairs ``owner``, in
    increasing order) along their shorter diagonal, as :func:`zigzag_all` tells."""
    pairs, which = np.unique(owner, return_inverse=True)
    chains = points(pairs.tolist())
    offsets_a = np.cumsum([0] + [len(a) for a, _ in chains])[which]
    offsets_b = np.cumsum([0] + [len(b) for _, b in chains])[which]
    points_a = np.concatenate([a for a, _ in chains])
    points_b = np.concatenate([b for _, b in chains])
    i, j = ij[0, at] + offsets_a, ij[1, at] + offsets_b
    taken = norm(points_a[i + 1] - points_b[j])
    other = norm(points_a[i] - points_b[j + 1])
    swap = at[other < taken * (1.0 - 1e-9)]
    if len(swap):  # B steps first: the ruling between the two steps is A_i B_j+1
        ij[0, swap + 1] -= 1
        ij[1, swap + 1] += 1


def _lefts(bounds: IntArray) -> IntArray:
    """The first point of every edge of chains ``bounds[k]:bounds[k + 1]`` (one point or
    more each) of a flat array, chain after chain."""
    sizes = np.diff(bounds) - 1
    return np.arange(sizes.sum()) + np.repeat(np.arange(len(sizes)), sizes)


def _fractions_all(lengths: Sequence[FloatArray]) -> tuple[FloatArray, IntArray]:
    """Each chain's arc lengths ``lengths`` (one or more) as fractions of its length (even
    steps if it has none), chain after chain in one array, and where each chain's lie."""
    counts = np.array([len(length) for length in lengths], dtype=np.int64)
    bounds = np.zeros(len(counts) + 1, dtype=np.int64)
    np.cumsum(counts, out=bounds[1:])
    flat = np.concatenate([np.asarray(length, dtype=float) for length in lengths])
    start = flat[bounds[:-1]]
    span = flat[bounds[1:] - 1] - start
    even = (counts < 2) | ~(span > 0)
    with np.errstate(invalid="ignore", divide="ignore"):  # (the even ones are replaced)
        fractions = (flat - np.repeat(start, counts)) / np.repeat(span, counts)
    for k in flatnonzero(even).tolist():
        fractions[bounds[k] : bounds[k + 1]] = np.linspace(0.0, 1.0, int(counts[k]))
    return fractions, bounds


# -- closing the stretches without a torsal ruling ------------------------------------------------


def close_gaps(strip: Strip, t: FloatArray, fans: list | None = None) -> list[tuple[FloatArray, FloatArray]]:
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
    return close_gaps_all([(strip, t, fans)])[0]


def close_gaps_all(
    jobs: Sequence[tuple[Strip, FloatArray, list | None]],
) -> list[list[tuple[FloatArray, FloatArray]]]:
    """:func:`close_gaps` of every ``(strip, t, fans)`` of ``jobs``: the stretches of B that
    the strips' holes and gaps span measured together first, then those beyond the first and
    last rulings (:func:`.strip.gap_lengths_all`); each strip gets what it gets alone."""
    stretches = []
    pending = []  # the gaps to close, as the strips' t say before any is closed
    for strip, t, fans in jobs:
        gap = np.isnan(t)
        stretches += [
            (strip, float(t[i]), float(t[i + 1])) for i in strip.holes if not (gap[i] or gap[i + 1])
        ]
        # (a closed B's last gap may end at the first station, which the first gap's closing
        # sets: that stretch is found, and that gap closed, when it is reached)
        for i0, i1, t_lo, t_hi, key in _gap_runs(strip, t, fans):
            if key not in strip.closings:
                seam = t_hi < t_lo  # (through the seam of a closed B: two stretches)
                stretches += [(strip, t_lo, 1.0), (strip, 0.0, t_hi)] if seam else [(strip, t_lo, t_hi)]
                if t_lo == t_lo and t_hi == t_hi:  # (not NaN)
                    pending.append((strip, i0, i1, t_lo, t_hi, key))
    gap_lengths_all(stretches)
    for (strip, *_, key), closing in zip(pending, _closings_all([gap[:5] for gap in pending]), strict=True):
        strip.closings[key] = closing
    added = [_close_inner(strip, t, fans) for strip, t, fans in jobs]
    ends = []
    for strip, t, _ in jobs:
        if not strip.curve_b.closed:
            ends += [(strip, 0.0, float(t[0]))] if t[0] > 0.0 else []
            ends += [(strip, float(t[-1]), 1.0)] if t[-1] < 1.0 else []
    gap_lengths_all(ends)
    for (strip, t, _), more in zip(jobs, added, strict=True):
        if not strip.curve_b.closed:
            if t[0] > 0.0:
                tb = strip.gap_lengths(0.0, float(t[0]))[0][:-1]
                more.append((np.zeros(len(tb)), tb))
            if t[-1] < 1.0:
                tb = strip.gap_lengths(float(t[-1]), 1.0)[0][1:]
                more.append((np.ones(len(tb)), tb))
    return added


def _gap_runs(
    strip: Strip, t: FloatArray, fans: list | None
) -> Iterator[tuple[int, int, float, float, tuple]]:
    """Each run ``i0..i1`` of stations without a partner in ``t``, with the stretch of B
    ``t_lo``, ``t_hi`` its closing spans (:func:`close_gaps`) and its key among the strip's
    closings. (The runs are found at the first step; each stretch is read from ``t`` as it
    is when its run is reached.)"""
    n = len(t)
    # the runs of gap stations: where the gaps padded with False on both sides change
    padded = np.zeros(n + 2, dtype=bool)
    padded[1:-1] = np.isnan(t)
    edges = flatnonzero(padded[1:] != padded[:-1]).tolist()
    closed = strip.curve_b.closed
    for i0, stop in zip(edges[::2], edges[1::2], strict=True):  # one pass per gap (few)
        i1 = stop - 1
        t_lo = float(t[i0 - 1]) if i0 > 0 else 0.0
        t_hi = float(t[i1 + 1]) if i1 < n - 1 else (float(t[0]) if closed and i0 > 0 else 1.0)
        for fan in fans or ():  # a torsal fan through the station before (after) the gap
            if i0 > 0 and fan[0] == strip.s[i0 - 1] and t_lo < fan[2] <= t_hi:
                t_lo = fan[2]
            if i1 < n - 1 and fan[0] == strip.s[i1 + 1] and t_lo <= fan[1] < t_hi:
                t_hi = fan[1]
        if t_hi < t_lo and not closed:
            t_hi = t_lo
        yield i0, i1, t_lo, t_hi, (i0, i1, struct.pack("2d", t_lo, t_hi))


def _close_inner(strip: Strip, t: FloatArray, fans: list | None) -> list[tuple[FloatArray, FloatArray]]:
    """:func:`close_gaps` within the rulings: the holes, then the gaps one by one (:func:`_gap_runs`)."""
    gap = np.isnan(t)
    added: list[tuple[FloatArray, FloatArray]] = []
    for i in strip.holes:  # one pass per stretch of B that t jumps over (rare)
        if gap[i] or gap[i + 1]:
            continue  # closed with the gap around it
        tb, lb = strip.gap_lengths(float(t[i]), float(t[i + 1]))
        a, b = zigzag(strip.station_lengths[i : i + 2], lb, partial(_chains, strip, i, i + 2, tb))
        inner = slice(1, len(a) - 1)  # the two stations' own rulings are there already
        added.append((strip.s[i + a[inner]], tb[b[inner]]))
    for i0, i1, t_lo, t_hi, key in _gap_runs(strip, t, fans):
        closing = strip.closings.get(key)
        if closing is None:
            closing = strip.closings[key] = _closing(strip, i0, i1, t_lo, t_hi)
        t[i0 : i1 + 1], extra = closing
        if extra is not None:
            added.append(extra)
    return added


def _closing(
    strip: Strip, i0: int, i1: int, t_lo: float, t_hi: float
) -> tuple[FloatArray, tuple[FloatArray, FloatArray] | None]:
    """The flat triangles closing the gap stations ``i0..i1`` between B(t_lo) and B(t_hi)
    (:func:`close_gaps`): the gap stations' partners, and the added rulings ``(s, t)``
    (None if there are none), read-only."""
    return _closings_all([(strip, i0, i1, t_lo, t_hi)])[0]


def _closings_all(
    gaps: Sequence[tuple[Strip, int, int, float, float]],
) -> list[tuple[FloatArray, tuple[FloatArray, FloatArray] | None]]:
    """:func:`_closing` of every gap ``(strip, i0, i1, t_lo, t_hi)`` of ``gaps``: their
    triangles stepped in one pass (:func:`zigzag_all`, B's points at the ties evaluated
    together) and sorted out at once; each gap's are the ones it gets alone."""
    if not gaps:
        return []
    chains = []  # per gap: the first and last station k0, k1 of its chain on A, B's parameters tb
    lengths = []
    for strip, i0, i1, t_lo, t_hi in gaps:
        k0, k1 = max(i0 - 1, 0), min(i1 + 1, len(strip.s) - 1)
        if t_hi < t_lo:  # through the seam of a closed B
            before, lb_before = strip.gap_lengths(t_lo, 1.0)
            after, lb_after = strip.gap_lengths(0.0, t_hi)
            tb = np.concatenate([before, after[1:]])
            lb = np.concatenate([lb_before, lb_after[1:] + strip.map_b.total])
        else:
            tb, lb = strip.gap_lengths(t_lo, t_hi)
        chains.append((k0, k1, tb))
        lengths.append((strip.station_lengths[k0 : k1 + 1], lb))

    def points(which: list[int]) -> list[tuple[FloatArray, FloatArray]]:
        on_b = derivative_each([gaps[g][0].curve_b for g in which], [chains[g][2] for g in which], 0)
        return [(gaps[g][0].a0[chains[g][0] : chains[g][1] + 1], b) for g, b in zip(which, on_b, strict=True)]

    ij, bounds = _zigzag_rows(lengths, points)
    i, j = ij
    sizes = np.diff(bounds)
    firsts, lasts = bounds[:-1], bounds[1:] - 1
    # each gap's rows against its own chains: station k0 + i of its strip, B at tb[j]
    k0 = np.array([k for k, _, _ in chains])
    i0 = np.array([gap[1] for gap in gaps])
    i1 = np.array([gap[2] for gap in gaps])
    n = np.array([len(gap[0].s) for gap in gaps])
    s_chains = np.concatenate([gap[0].s[k : k1 + 1] for gap, (k, k1, _) in zip(gaps, chains, strict=True)])
    s_first = np.cumsum([0, *(k1 - k + 1 for k, k1, _ in chains)])[:-1]
    tbs = np.concatenate([tb for _, _, tb in chains])
    tb_first = np.cumsum([0, *(len(tb) for _, _, tb in chains)])[:-1]
    at_s = s_chains[i + np.repeat(s_first, sizes)]
    at_t = tbs[j + np.repeat(tb_first, sizes)]
    # the first ruling from each gap station is its station ruling (i runs through every
    # station from k0 to k1 in order, so those are stations i0..i1 in order); the rest are added
    own = np.empty(len(i), dtype=bool)
    own[1:] = i[1:] != i[:-1]
    own[firsts] = True
    own &= (i >= np.repeat(i0 - k0, sizes)) & (i <= np.repeat(i1 - k0, sizes))
    extra = ~own
    extra[firsts[i0 > 0]] = False  # the torsal ruling before the gap
    extra[lasts[i1 < n - 1]] = False  # and after it
    partners = np.split(at_t[own], np.cumsum(np.add.reduceat(own, firsts))[:-1])
    cuts = np.cumsum(np.add.reduceat(extra, firsts))[:-1]
    added_s, added_t = np.split(at_s[extra], cuts), np.split(at_t[extra], cuts)
    closings: list[tuple[FloatArray, tuple[FloatArray, FloatArray] | None]] = []
    for partner, s_add, t_add in zip(partners, added_s, added_t, strict=True):
        added = None
        if len(s_add):
            added = (s_add, t_add)
            for array in added:
                array.setflags(write=False)
        closings.append((partner, added))
    return closings


def _chains(strip: Strip, first: int, stop: int, tb: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The points of a closing's two chains: stations ``first`` to ``stop`` − 1 on A, B at ``tb``."""
    return strip.a0[first:stop], strip.curve_b.point_at(tb)


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
