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

import numpy as np

from torsal.nodes.geometry.array_types import BoolArray, IntArray

from ..curve_base import FloatArray
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
    fa, fb = _fractions(length_a), _fractions(length_b)
    middles = 0.5 * np.concatenate([fa[1:] + fa[:-1], fb[1:] + fb[:-1]])
    # middles equal to TIE count as a tie: chains evenly spaced along both curves meet at
    # equal fractions that rounding alone would otherwise order, so that the triangles of a
    # model moved far from the origin flipped diagonals
    keys = np.round(middles / TIE)
    along_b = np.arange(len(keys)) >= len(fa) - 1
    # step along whichever edge's middle comes first, A's before B's at a tie
    order = np.lexsort((along_b, keys))
    steps = along_b[order]
    ij = np.zeros((2, len(keys) + 1), dtype=np.int64)  # both start at 0
    np.cumsum(~steps, dtype=np.int64, out=ij[0, 1:])
    np.cumsum(steps, dtype=np.int64, out=ij[1, 1:])
    if points is None or len(keys) < 2:
        return ij[0], ij[1]
    # a tie of an edge of A (taken first) and one of B: the quad A_i A_i+1 B_j+1 B_j, cut
    # along A_i+1 B_j so far; along A_i B_j+1 where that is shorter
    sorted_keys = keys[order]
    tie = flatnonzero((sorted_keys[1:] == sorted_keys[:-1]) & ~steps[:-1] & steps[1:])
    if len(tie):
        points_a, points_b = points()
        i, j = ij[0, tie], ij[1, tie]
        taken = norm(points_a[i + 1] - points_b[j])
        other = norm(points_a[i] - points_b[j + 1])
        swap = tie[other < taken * (1.0 - 1e-9)]
        if len(swap):  # B steps first: the ruling between the two steps is A_i B_j+1
            ij[0, swap + 1] -= 1
            ij[1, swap + 1] += 1
    return ij[0], ij[1]


def _fractions(length: FloatArray) -> FloatArray:
    """Arc lengths as fractions of the chain's length (even steps if it has none)."""
    span = float(length[-1] - length[0])
    if len(length) < 2 or not span > 0:
        return np.linspace(0.0, 1.0, len(length))
    return (length - length[0]) / span


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
    for strip, t, fans in jobs:
        gap = np.isnan(t)
        stretches += [
            (strip, float(t[i]), float(t[i + 1])) for i in strip.holes if not (gap[i] or gap[i + 1])
        ]
        # (a closed B's last gap may end at the first station, which the first gap's closing
        # sets: that stretch is found when it is closed)
        for _, _, t_lo, t_hi, key in _gap_runs(strip, t, fans):
            if key not in strip.closings:
                seam = t_hi < t_lo  # (through the seam of a closed B: two stretches)
                stretches += [(strip, t_lo, 1.0), (strip, 0.0, t_hi)] if seam else [(strip, t_lo, t_hi)]
    gap_lengths_all(stretches)
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
    n = len(strip.s)
    k0, k1 = max(i0 - 1, 0), min(i1 + 1, n - 1)
    if t_hi < t_lo:  # through the seam of a closed B
        (before, lb_before), (after, lb_after) = strip.gap_lengths(t_lo, 1.0), strip.gap_lengths(0.0, t_hi)
        tb = np.concatenate([before, after[1:]])
        lb = np.concatenate([lb_before, lb_after[1:] + strip.map_b.total])
    else:
        tb, lb = strip.gap_lengths(t_lo, t_hi)
    i, j = zigzag(strip.station_lengths[k0 : k1 + 1], lb, partial(_chains, strip, k0, k1 + 1, tb))
    # the first ruling from each gap station is its station ruling (i runs through every
    # station from k0 to k1 in order, so those are stations i0..i1 in order); the rest are added
    own = np.empty(len(i), dtype=bool)
    own[0] = True
    own[1:] = i[1:] != i[:-1]
    own &= (i >= i0 - k0) & (i <= i1 - k0)
    partners = tb[j[own]]
    extra = ~own
    if i0 > 0:
        extra[0] = False  # the torsal ruling before the gap
    if i1 < n - 1:
        extra[-1] = False  # and after it
    added = None
    if extra.any():
        added = (strip.s[k0 + i[extra]], tb[j[extra]])
        for array in added:
            array.setflags(write=False)
    return partners, added


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
