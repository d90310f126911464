"""The partner search's first pass, for every strip of a solve at once: the intervals
between samples of B where f may vanish, and the samples where it does.

For station s_i on A and sample t_j of B, f = det[B_j − A_i, Â'_i, B'_j] (see
:mod:`.ruling`). By the cyclic symmetry of the triple product
``det[B − A, Â', B'] = Â'·(B' × B) − (A × Â')·B'``, so a strip's whole matrix of f is one
(n×6)(6×m) product. Coordinates are taken about a centre of each strip's two curves, to
keep the terms small. The product is formed in blocks of at most 16,000 samples: a
block that small keeps OpenBLAS on one thread (threads cost more than they save on a
product this thin, and stall when the machine is busy).

Every strip's matrix is its own product; what follows runs once for all the strips of
a solve (:func:`sift_all`), their matrices side by side in one array whose rows are the
stations of every strip, each padded with NaN beyond its strip's own samples, as many
blocks as fit in :data:`CELLS`. An interval passes a first sift with the reach of
:mod:`.isolation` bounded from the diameter of both curves, then a second with the reach
from its own two rulings (the longer of |B_j − A_i| and |B_j+1 − A_i| in place of the
diameter); a sign change always passes. Each strip gets what it gets alone, bit for bit,
in the order it finds it alone.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from itertools import pairwise

import numpy as np

from ..array_types import BoolArray, FloatArray, IntArray
from ..vec_ops import cross, dot, flatnonzero, norm, position_roundings, unit
from .isolation import Pieces, interval_bounds, third_bound
from .stack import Stack
from .strip import Strip

#: A sample is zero (flat) where |det[R, Â', B̂']| <= FLAT·|R|: coplanar to 1e-10 rad.
FLAT = 1e-10
#: Samples in one block of a strip's rows of f (each block is one matrix product).
BLOCK = 16_000
#: Most cells of f (padded) sifted at once: 1 MiB an array.
CELLS = 1 << 17

#: Offsets of an interval's two ends from its first sample, as a column.
_ENDS = np.array([[0], [1]])


@dataclass
class Sifted:
    """What the sift of every strip found, stacked strip after strip.

    The first pieces to judge (station rows of the stacked strips), the bounds of f''
    on them and, to fill in the pieces judged again (:meth:`piece_ends`), their
    intervals (as the index of their first sample among all strips') and the rulings'
    lengths at both ends; per strip, the intervals that straddle a corner of B and the
    runs of samples where f is zero."""

    units: FloatArray  #: (N, 3) A's unit tangents at every station
    first: Pieces
    curvature: FloatArray
    cols: IntArray
    lengths: FloatArray  #: (2, k)
    samples: _Samples
    corners: list[tuple[IntArray, IntArray]]  #: per strip, station rows and columns (its own)
    #: per strip: station rows, first and last column of each run of zero samples, and
    #: whether it is flat (of positive extent)
    runs: list[tuple[IntArray, IntArray, IntArray, BoolArray]]

    def piece_ends(self, index: IntArray) -> dict[str, FloatArray]:
        """The B-data of the first pieces ``index`` (see :func:`.isolation.isolate`)."""
        s, c = self.samples, self.cols[index]
        c_next = c + 1
        return {
            "speed0": s.speeds[c],
            "speed1": s.speeds[c_next],
            "second0": s.second_lengths[c],
            "second1": s.left_second_lengths[c_next],
            "bound3": s.third[c],
            "r0": self.lengths[0, index],
            "r1": self.lengths[1, index],
        }


@dataclass
class _Samples:
    """Every strip's samples of B one strip after another, and the bounds of f on the
    intervals between them (interval j between samples j and j + 1 of the stack; the one
    from a strip's last sample to the next strip's first is never looked at)."""

    stack: Stack
    t: FloatArray
    at: FloatArray
    points: FloatArray
    tangents: FloatArray
    second: FloatArray
    left_second: FloatArray
    speeds: FloatArray
    second_lengths: FloatArray
    left_second_lengths: FloatArray
    pair: BoolArray  #: intervals between the two sides of a corner
    reach: FloatArray  #: per interval (−1 between a corner's sides and across strips)
    slope: FloatArray
    chord: FloatArray
    curvature: FloatArray
    third: FloatArray


def _samples(
    strips: Sequence[Strip], stations: Stack, a0: FloatArray
) -> tuple[_Samples, FloatArray, FloatArray]:
    """The stacked samples of every strip's B and the bounds of :mod:`.isolation` on their
    intervals, from the diameter of the strip's two curves' points (the zero-width
    intervals between the two sides of a corner get reach −1: never looked at, a sign
    change there is a corner root); and each strip's diameter and rounding of its
    positions (as :func:`.vec_ops.position_rounding` gives it)."""
    grids = [strip.grid for strip in strips]
    stack = Stack([len(grid.t) for grid in grids])

    def joined(name: str) -> FloatArray:
        return np.concatenate([getattr(grid, name) for grid in grids])

    t, at, points, tangents = joined("t"), joined("at"), joined("points"), joined("tangents")
    low = np.minimum(np.minimum.reduceat(a0, stations.starts), np.minimum.reduceat(points, stack.starts))
    high = np.maximum(np.maximum.reduceat(a0, stations.starts), np.maximum.reduceat(points, stack.starts))
    diameter = norm(high - low)
    largest = np.maximum(np.abs(low), np.abs(high)).max(axis=1)
    rounding = position_roundings(largest)
    second, left_second, third, left_third = (joined(name) for name in ("second", "left_second", "third",
                                                                          "left_third"))
    speeds, second_lengths, left_second_lengths = norm(tangents), norm(second), norm(left_second)
    # (a curve without a third derivative gets β3 = 0 from its zero vectors, as it gets alone)
    b3 = third_bound(third[:-1], left_third[1:])
    length = stack.repeat(diameter)[:-1]
    ends = (speeds[:-1], speeds[1:]), (second_lengths[:-1], left_second_lengths[1:])
    bounds = interval_bounds(at[1:] - at[:-1], *ends, b3, length)
    pair = np.zeros(len(t) - 1 if len(t) else 0, dtype=bool)
    for grid, low in zip(grids, stack.starts.tolist(), strict=True):
        pair[low : low + len(grid.pair)] = grid.pair
    bounds.reach[pair] = -1.0
    samples = _Samples(stack, t, at, points, tangents, second, left_second, speeds, second_lengths,
                       left_second_lengths, pair, bounds.reach, bounds.slope, bounds.chord, bounds.curvature,
                       bounds.third)
    return samples, diameter, rounding


def sift_all(strips: Sequence[Strip]) -> Sifted:
    """The sift of the module docstring over every strip of ``strips``, and what it hands
    the isolation: the first pieces, corner intervals and runs of zero samples."""
    stations = Stack([len(strip.s) for strip in strips])
    row_strip = stations.owner()
    a0 = np.concatenate([strip.a0 for strip in strips])
    units = unit(np.concatenate([strip.a1 for strip in strips]))
    samples, diameter, rounding = _samples(strips, stations, a0)
    b0, b1 = samples.points, samples.tangents
    first_sample = samples.stack.starts
    # f = left · right: rows [Â', Â' × (A − c)] of every station, columns [B' × (B − c); B']
    centre = 0.5 * (a0[stations.starts + stations.counts // 2] + b0[first_sample + samples.stack.counts // 2])
    tangent = unit(units)
    left = np.concatenate([tangent, cross(tangent, a0 - stations.repeat(centre))], axis=1)
    right = np.concatenate([cross(b1, b0 - samples.stack.repeat(centre)).T, b1.T])
    # a flat run is coplanar to FLAT, or to the rounding of the positions themselves far
    # from the origin (site coordinates: the input points carry ~1e-7 m at 1e9 m)
    floor = FLAT * diameter + rounding
    flat_scale = samples.stack.repeat(floor) * samples.speeds
    found: list[tuple[IntArray, ...]] = []
    zeros: list[tuple[IntArray, IntArray]] = []
    for rows, pieces in _batches(stations, samples.stack):
        width = int(samples.stack.counts[row_strip[rows]].max())
        f = np.full((len(rows), width), np.nan)
        for strip, low_row, high_row in pieces:  # each strip's product, as alone
            m, column = int(samples.stack.counts[strip]), int(first_sample[strip])
            np.matmul(left[low_row:high_row], right[:, column : column + m],
                      out=f[low_row - rows[0] : high_row - rows[0], :m])
        owner = row_strip[rows]
        # each strip's samples along a row (padded with its last), their reach and flat
        # scale gathered once per strip and repeated onto its stations' rows
        first_strip = int(owner[0])
        own = owner - first_strip  # (the strip of each row among the batch's)
        sample = np.minimum(first_sample[first_strip : int(owner[-1]) + 1, None] + np.arange(width),
                            len(samples.t) - 1)
        repeats = np.bincount(own)
        interval = np.minimum(sample[:, :-1], len(samples.reach) - 1)  # (padding: any interval)
        reach_rows = np.repeat(samples.reach.take(interval), repeats, axis=0)
        negative = np.signbit(f)
        size_f = np.abs(f)
        lower = np.minimum(size_f[:, :-1], size_f[:, 1:])
        change = negative[:, :-1] != negative[:, 1:]
        inside = np.arange(width - 1) < (samples.stack.counts[owner] - 1)[:, None]
        look = (change | (lower <= reach_rows)) & inside
        flat_rows = np.repeat(flat_scale.take(sample), repeats, axis=0)
        maybe = flatnonzero(size_f <= flat_rows)  # (NaN padding never)
        if len(maybe):  # rare: test the candidates against their own ruling length
            r, c = np.divmod(maybe, width)
            j, at_row = sample[own[r], c], rows[r]
            exact = (FLAT * norm(b0[j] - a0[at_row]) + rounding[row_strip[at_row]]) * samples.speeds[j]
            exact = size_f.flat[maybe] <= exact
            if exact.any():
                zero = np.zeros(f.shape, dtype=bool)
                zero.flat[maybe[exact]] = True
                look &= ~(zero[:, :-1] | zero[:, 1:])
                zeros.append((at_row[exact], c[exact]))
        index = flatnonzero(look)  # (flat indices gather faster than pairs of indices)
        r, c = np.divmod(index, width - 1)
        j, at_row = sample[own[r], c], rows[r]
        # sift again with the rulings' own lengths in place of the diameter; the rulings to
        # both ends at once, (2, k, 3), as their lengths and f there (take gathers rows
        # several times faster than indexing does)
        rulings = b0.take(j + _ENDS, axis=0) - a0.take(at_row, axis=0)
        lengths = norm(rulings)
        reach = samples.slope.take(j) * (np.maximum(lengths[0], lengths[1]) + samples.chord.take(j))
        keep = change.take(index) | (lower.take(index) <= reach)
        at = index[keep] + r[keep] + _ENDS  # (r, c) and (r, c + 1) in f
        found.append((at_row[keep], j[keep], f.take(at), rulings.compress(keep, axis=1),
                      lengths.compress(keep, axis=1)))
    if len(found) == 1:
        rows, cols, f_ends, rulings, lengths = found[0]
    else:  # (the ends' values along their second axis)
        rows, cols, f_ends, rulings, lengths = (
            np.concatenate(x, axis=0 if x[0].ndim == 1 else 1) for x in zip(*found, strict=True))
    at_corner = samples.pair.take(cols)
    corner_rows, corner_cols = rows[at_corner], cols[at_corner]
    if len(corner_rows):
        keep = ~at_corner
        rows, cols = rows[keep], cols[keep]
        f_ends, rulings, lengths = f_ends[:, keep], rulings[:, keep], lengths[:, keep]
    # judge what the sift left (it used the rulings' own lengths), subdividing where a
    # root pair may hide; f' there is det[R, Â', B''] = B'' · (R × Â'), for these only
    # (at both ends at once, B'' at the far end as seen from the left)
    cols_next = cols + 1
    seconds = np.array([samples.second.take(cols, axis=0), samples.left_second.take(cols_next, axis=0)])
    d_ends = dot(cross(rulings, units.take(rows, axis=0)), seconds)
    none = np.empty(0)
    f_low, f_high = f_ends
    first = Pieces(rows, samples.at.take(cols), samples.at.take(cols_next), f_low, f_high, *d_ends,
                   *([none] * 7))
    corners = _per_strip(stations, samples.stack, corner_rows, corner_cols)
    runs = _runs(stations, samples, zeros)
    return Sifted(units, first, samples.curvature.take(cols), cols, lengths, samples, corners, runs)


def _batches(stations: Stack, samples: Stack) -> list[tuple[IntArray, list[tuple[int, int, int]]]]:
    """The stacked station rows in batches of at most :data:`CELLS` padded cells, each
    with its pieces ``(strip, first row, end row)``: every strip's rows in its own blocks
    of at most :data:`BLOCK` samples, a batch holding whole blocks."""
    batches: list[tuple[IntArray, list[tuple[int, int, int]]]] = []
    pieces: list[tuple[int, int, int]] = []
    widest = 0
    for strip, (low, high, m) in enumerate(zip(stations.starts.tolist(), stations.offsets[1:].tolist(),
                                               samples.counts.tolist(), strict=True)):
        block = max(1, BLOCK // m)
        for first in range(low, high, block):
            last = min(first + block, high)
            rows = last - pieces[0][1] if pieces else 0
            if pieces and (rows * max(widest, m) > CELLS):
                batches.append((np.arange(pieces[0][1], pieces[-1][2]), pieces))
                pieces, widest = [], 0
            pieces.append((strip, first, last))
            widest = max(widest, m)
    if pieces:
        batches.append((np.arange(pieces[0][1], pieces[-1][2]), pieces))
    return batches


def _per_strip(
    stations: Stack, samples: Stack, rows: IntArray, cols: IntArray
) -> list[tuple[IntArray, IntArray]]:
    """Stacked station rows and sample columns (increasing rows) as each strip's own."""
    bounds = stations.groups(rows).tolist()
    shifts = zip(stations.starts.tolist(), samples.starts.tolist(), strict=True)
    return [(rows[low:high] - row_shift, cols[low:high] - col_shift)
            for (low, high), (row_shift, col_shift) in zip(pairwise(bounds), shifts, strict=True)]


def _runs(
    stations: Stack, samples: _Samples, zeros: list[tuple[IntArray, IntArray]]
) -> list[tuple[IntArray, IntArray, IntArray, BoolArray]]:
    """Per strip, the runs of zero samples along a station's row: their rows, first and
    last columns, and whether each is flat (of positive extent: its two ends are
    candidates; a single zero sample is a root)."""
    if not zeros:
        none = np.empty(0, dtype=np.int64)
        return [(none, none, none, np.empty(0, dtype=bool))] * len(stations)
    rows, cols = (np.concatenate(parts) for parts in zip(*zeros, strict=True))
    start = np.ones(len(rows), dtype=bool)
    start[1:] = (rows[1:] != rows[:-1]) | (cols[1:] != cols[:-1] + 1)
    end = np.ones(len(rows), dtype=bool)
    end[:-1] = start[1:]
    run_rows, first, last = rows[start], cols[start], cols[end]
    strip = np.searchsorted(stations.offsets, run_rows, side="right") - 1
    shift = samples.stack.starts[strip]
    flat = samples.t[last + shift] > samples.t[first + shift]
    bounds = stations.groups(run_rows).tolist()
    return [
        (run_rows[low:high] - row_shift, first[low:high], last[low:high], flat[low:high])
        for (low, high), row_shift in zip(pairwise(bounds), stations.starts.tolist(), strict=True)
    ]
