"""Where to sample a ruled surface's rulings so that its edges' chord polylines are as long
as the edges: the sampling behind IsoMapping's promise (:func:`.unroll.unroll_surface`).

An unrolled strip keeps every chord's length, so each flat edge is as long as the chord
polyline through the sampled rulings' ends. On a smooth edge that polyline falls short of
the arc length by C/k² at k rulings a segment: :func:`edge_subdivisions` finds the even
count that meets a tolerance (Richardson on two samplings), :func:`edge_parameters` the
count per segment where the edges run fast over a few segments only (fans).

Kinks. The C/k² law holds only where the edge is smooth between samples. Across a corner
of an edge (a NURBS rail's double knot, a polyline's vertex) a chord cuts the corner off
and falls short by a share of its own length, wherever the samples fall: the sum converges
like 1/k, and the Richardson estimates, which assume 1/k², say it has converged long
before it has (a strip on two re-weighted NURBS arcs, nine kinks of up to 2.6 rad: its
flat edges stayed 6e-6 of its size short with 23,149 rulings). So every sampling here
holds a ruling at each of the surface's kinks (:meth:`.surface_base.Surface.ruling_kinks`)
besides the planned ones: the edges are then smooth between samples and the law holds.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from .array_types import FloatArray, IntArray
from .vec_ops import extent, linalg_norm
from .watch import watch_check

if TYPE_CHECKING:
    from .surface_base import Surface

#: Most rulings :func:`edge_subdivisions` samples along a strip.
MAX_RULINGS = 1 << 12
#: Most refined samplings :func:`edge_subdivisions` tries before it gives up.
REFINEMENTS = 4
#: Most rulings :func:`edge_parameters` plans along a strip (a strip's kinks come on top).
MAX_ADAPTIVE_RULINGS = 1 << 15
#: The share of the tolerance :func:`edge_parameters` aims at (the C/k² law is an estimate).
ADAPTIVE_MARGIN = 0.8
#: :func:`edge_parameters` samples per segment where that takes at most this share of the
#: rulings evenly spaced ones would need (the rails' error is concentrated: fans; measured
#: 0.30 and 0.88 on two strips with fans, 1.01 on a full cylinder).
UNEVEN = 0.9
#: Most rounds of estimates :func:`edge_parameters` makes.
ADAPTIVE_ROUNDS = 4
#: A kink this close (in the parameter) to a planned ruling is sampled by that ruling: the
#: corner it leaves out is at most this share of the edge's pace long.
KINK_SNAP = 1e-10


def _look() -> None:
    """A look at the cancel token (see :mod:`.watch`)."""
    check = watch_check()
    if check:
        check()


def rulings_at(surface: Surface, u: FloatArray) -> FloatArray:
    """The surface's rulings ``(n, 2, 3)`` at parameters ``u`` across them (as
    :meth:`~.surface_base.Surface.rulings` at evenly spaced ones)."""
    direction = surface.ruling_direction
    if direction is None:
        raise ValueError("surface has no straight rulings")
    zeros, ones = np.zeros(len(u)), np.ones(len(u))
    if direction == "v":
        start, end = surface.point_at(u, zeros), surface.point_at(u, ones)
    else:
        start, end = surface.point_at(zeros, u), surface.point_at(ones, u)
    return np.stack([start, end], axis=1)


def _rail_lengths(rulings: FloatArray) -> FloatArray:
    """Lengths ``(2,)`` of the two chord polylines through the rulings' starts and ends."""
    return linalg_norm(np.diff(rulings, axis=0)).sum(axis=0)


class Sampling(NamedTuple):
    """Rulings sampled across a surface: the planned ones and one at each kink."""

    u: FloatArray  #: their parameters across the rulings, increasing
    rulings: FloatArray  #: ``(n, 2, 3)`` start and end points
    grid: IntArray | None  #: the planned ones' indices among them (None: all are planned)


class Samples:
    """A surface's rulings, each evenly spaced count sampled once (the estimates of
    :func:`edge_subdivisions` and :func:`edge_parameters` start from the same two), with
    the rulings at its kinks, sampled once, put among every sampling."""

    def __init__(self, surface: Surface) -> None:
        self.surface = surface
        self._kept: dict[int, FloatArray] = {}
        kinks = np.asarray(surface.ruling_kinks(), dtype=float)
        self.kinks = np.unique(kinks[(kinks > 0.0) & (kinks < 1.0)])
        self._at_kinks = rulings_at(surface, self.kinks) if len(self.kinks) else None

    def rulings(self, count: int) -> FloatArray:
        """``count`` evenly spaced rulings (without the kinks')."""
        if count not in self._kept:
            self._kept[count] = self.surface.rulings(count)
        return self._kept[count]

    def even(self, count: int) -> Sampling:
        """``count`` evenly spaced rulings and the kinks'."""
        return self._merged(np.linspace(0.0, 1.0, count), self.rulings(count))

    def at(self, u: FloatArray) -> Sampling:
        """The rulings at ``u`` (increasing, from 0 to 1) and the kinks'."""
        return self._merged(u, rulings_at(self.surface, u))

    def _merged(self, u: FloatArray, rulings: FloatArray) -> Sampling:
        if self._at_kinks is None:
            return Sampling(u, rulings, None)
        kinks = self.kinks
        at = np.searchsorted(u, kinks)  # (0 < kink < 1 = u[-1]: 1 ≤ at ≤ len(u) − 1)
        gap = np.minimum(kinks - u[at - 1], u[at] - kinks)
        new = gap > KINK_SNAP
        if not new.any():
            return Sampling(u, rulings, None)
        at = at[new]
        grid = np.arange(len(u)) + np.searchsorted(at, np.arange(len(u)), side="right")
        merged = np.insert(u, at, kinks[new]), np.insert(rulings, at, self._at_kinks[new], axis=0)
        return Sampling(merged[0], merged[1], grid)


def edge_subdivisions(
    samples: Samples, segments: int, subdivisions: int, tolerance: float
) -> tuple[int, Sampling, float]:
    """About the fewest rulings per segment (at least ``subdivisions``) for which both rails'
    chord polylines are within ``tolerance`` (relative to the strip's size) of the rails'
    arc lengths, the sampled rulings (with the kinks') and that estimated relative error.

    A chord polyline of a smooth rail falls short of its arc length by C/k² at k rulings
    per segment, so the chord sums L(k₁) and L(k₂) of two samplings give the error of the
    finer one as |L(k₂) − L(k₁)| / ((k₂/k₁)² − 1) (Richardson). Starting from
    ``subdivisions`` and twice that, the next k is the one that law asks for (at least
    1.5 times the last). A rail that is not smooth enough for the law between the samples
    (a cusp at an edge of regression; kinks are sampled) does not settle within
    :data:`REFINEMENTS` samplings, and one that asks for more than :data:`MAX_RULINGS`
    rulings is not sampled further: then the first sampling is returned, with its error.
    """
    longest = max(MAX_RULINGS // segments, 2 * subdivisions)
    k1 = first = subdivisions
    coarse = start = samples.even(segments * k1 + 1)
    size = float(extent(coarse.rulings.reshape(-1, 3)).max()) or 1.0
    k2 = 2 * k1
    first_error = np.inf
    check = watch_check()
    for _ in range(REFINEMENTS):
        if check:
            check()
        fine = samples.even(segments * k2 + 1)
        step = np.abs(_rail_lengths(fine.rulings) - _rail_lengths(coarse.rulings))
        error = float(step.max() / ((k2 / k1) ** 2 - 1.0) / size)
        if not np.isfinite(error):
            break
        if k1 == first:
            first_error = error * (k2 / k1) ** 2
            if first_error <= tolerance:  # the first sampling was already enough
                return k1, coarse, first_error
        if error <= tolerance:
            return k2, fine, error
        wanted = int(np.ceil(k2 * np.sqrt(error / tolerance) * 1.2))
        if k2 >= longest or wanted > 1.2 * longest:  # (by the law, the cap cannot get there)
            break
        k1, coarse, k2 = k2, fine, min(max(wanted, int(np.ceil(1.5 * k2))), longest)
    return first, start, first_error


def edge_parameters(
    samples: Samples, segments: int, subdivisions: int, tolerance: float
) -> tuple[Sampling, IntArray, IntArray | None, float, bool] | None:
    """Rulings at which both rails' chord polylines are within ``tolerance`` (relative to
    the strip's size) of their arc lengths (with the kinks'); the indices of the segments'
    ends among them (the rulings the user asked for); where the rulings are spread
    evenly, the indices of ``subdivisions`` of them per segment and of the kinks' (the
    development's map: see :func:`.unroll.unroll_surface`), else None (the map keeps
    them all); their estimated error, Σ C_j / k_j² relative to the size (the worse
    rail's in each segment: an upper bound for either rail's); and whether the cap
    stopped the refinement (the law then asked for more rulings than it allows: an
    edge with a corner no kink marks converges only like 1/k, and its estimate is low).

    Each segment j's chord error is estimated from two samplings (``k_j`` and ``2k_j``
    rulings in it: C_j/k_j² by Richardson, the worse of its two rails), starting from
    ``subdivisions`` a segment.

    - Where the rails run fast over a few segments (a fan sweeping along a curve while
      the other curve's point stands still), evenly spaced rulings waste most of their
      samples elsewhere: segment j is given k_j ∝ C_j^(1/3) rulings — the counts that meet
      the tolerance in the fewest rulings — with a margin.
    - Where that saves little (at most :data:`UNEVEN` of what evenly spaced rulings need:
      a full cone's rim is as curved everywhere), every segment gets the even count,
      √(Σ C_j / tolerance), rounded up to a multiple of ``subdivisions``, so the
      ``subdivisions`` a segment the map keeps are evenly spaced too.

    The counts are estimated again from their own two samplings until those say the
    tolerance is met (a rail whose pace changes sharply is not yet in the C/k² regime at
    ``subdivisions`` a segment), at most :data:`ADAPTIVE_ROUNDS` times; the counts of the
    last round stand, or as many in the same proportions as :data:`MAX_ADAPTIVE_RULINGS`
    allows. None when the chord sums are not finite."""
    counts = np.full(segments, subdivisions, dtype=np.int64)
    spread: bool | None = None
    capped = False
    size = float(np.ptp(samples.rulings(segments * subdivisions + 1).reshape(-1, 3), axis=0).max()) or 1.0
    target = ADAPTIVE_MARGIN * tolerance * size
    for _ in range(ADAPTIVE_ROUNDS):
        sampling, requested, sums = _per_segment(samples, counts)
        finer = _per_segment(samples, 2 * counts)[2]
        _look()
        error_fine = np.abs(finer - sums).max(axis=1) / 3.0  # per segment, the worse rail, at 2k_j
        if not np.isfinite(error_fine).all():
            return None
        constant = error_fine * (2 * counts) ** 2
        if spread is not None and 4.0 * error_fine.sum() <= tolerance * size:  # these counts are enough
            break
        cube = np.cbrt(constant)
        total = float(cube.sum())
        if total == 0.0:
            return None
        # minimise Σ k_j subject to Σ C_j / k_j² = target: k_j = C_j^(1/3) · (Σ C^(1/3) / target)^(1/2)
        wanted = np.maximum(np.ceil(cube * np.sqrt(total / target)), subdivisions).astype(np.int64)
        # evenly spaced rulings would need segments · √(Σ C / target)
        even = int(np.ceil(np.sqrt(float(constant.sum()) / target) / subdivisions)) * subdivisions
        if spread is None:
            spread = bool(wanted.sum() > UNEVEN * segments * even)
        if spread:
            wanted = np.full(segments, max(even, subdivisions), dtype=np.int64)
        wanted = np.maximum(wanted, counts)
        if wanted.sum() + 1 > MAX_ADAPTIVE_RULINGS:  # as near as the cap allows, in the same proportions
            capped = True
            if counts.sum() >= MAX_ADAPTIVE_RULINGS // 2:
                break
            room = (MAX_ADAPTIVE_RULINGS - 1) / wanted.sum()
            step = subdivisions if spread else 1
            counts = np.maximum(np.floor(wanted * room / step).astype(np.int64) * step, counts)
            sampling, requested, _ = _per_segment(samples, counts)
            break
        counts = wanted
    else:
        sampling, requested, _ = _per_segment(samples, counts)
    error = float((constant / counts.astype(float) ** 2).sum()) / size
    panelled = None
    if spread:
        planned = int(counts.sum()) + 1
        panelled = np.arange(0, planned, counts[0] // subdivisions)
        if sampling.grid is not None:  # the kinks' rulings too, so panels follow the corners
            kinks = np.setdiff1d(np.arange(len(sampling.u)), sampling.grid)
            panelled = np.union1d(sampling.grid[panelled], kinks)
    return sampling, requested, panelled, error, capped


def _per_segment(samples: Samples, counts: IntArray) -> tuple[Sampling, IntArray, FloatArray]:
    """The rulings with ``counts[j]`` evenly spaced in each segment j (and the kinks'), the
    segments' ends among them and each segment's two chord sums ``(segments, 2)``."""
    segments = len(counts)
    requested = np.concatenate([[0], np.cumsum(counts)])
    if np.all(counts == counts[0]):  # evenly spaced: perhaps sampled already
        sampling = samples.even(int(requested[-1]) + 1)
    else:
        u = np.empty(int(requested[-1]) + 1)
        segment = np.repeat(np.arange(segments), counts)
        within = np.arange(len(segment)) - requested[segment]
        u[:-1] = (segment + within / counts[segment]) / segments
        u[-1] = 1.0
        sampling = samples.at(u)
    if sampling.grid is not None:
        requested = sampling.grid[requested]
    chords = np.linalg.norm(np.diff(sampling.rulings, axis=0), axis=2)  # (rulings − 1, 2)
    return sampling, requested, np.add.reduceat(chords, requested[:-1], axis=0)
