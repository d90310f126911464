"""Closest points on a curve, for many query points at once: the global minimum.

Samples (:func:`search_parameters`, cached on the curve): at least 16 per smooth span (so
the knots are samples), then subdivided until every chord is within 1/1000 of the curve's
size of the curve and the curve's tangent, at both ends and the middle of every sample
interval, is within :data:`MAX_TURN` of its chord. So each interval is a nearly straight
piece whose arc is at most :data:`ARC_BOUND` times its chord.

Candidates: the distance to the curve is 1-Lipschitz in arc length, so the interval
holding the global minimum (distance D) has an end within D + arc/2 of the query, and D
is at most the distance d₀ to the nearest sample. Every interval with an end within
d₀ + its half arc is therefore a candidate, and the candidates always include the global
minimum's interval. They are found with one k-d tree search for each query's 12 nearest
samples, and a ball search (radius d₀ + the longest half arc) for the queries that have
more samples than that in the ball.

Refinement: in a candidate interval where ``g(t) = (C(t) − P)·C'(t)`` goes from negative
to positive (a minimum of the distance inside), Newton's method on ``g = 0`` with
``g' = |C'|² + (C − P)·C''``, from the secant's root and safeguarded by the interval as
a bracket. Any other interval's best is one of its ends, a sample no nearer than the
nearest one, which stands for them all (and covers the curve's end points). The nearest
of these wins.

So the search is exact whenever ``g`` changes sign across the global minimum's interval,
which it does if the distance has one minimum there: always so when the query is nearer
than ``|C'|² / |C''|`` (about the radius of curvature) over the interval, where
``|C − P|²`` is convex. Only a query farther than that, on the inside of a turn, could
see a minimum and a maximum of the distance within one interval of a few degrees' turn;
none did among 10,000 random queries on a random rational cubic checked against brute
force (tests/nodes/geometry/curves/test_curve_closest_point.py, tests/benchmarks/bench_curves.py).
"""

from __future__ import annotations

from functools import lru_cache
from itertools import chain
from typing import NamedTuple, Protocol

import numpy as np
from scipy.spatial import cKDTree

from .array_types import FloatArray, IntArray
from .curve_protocol import ParametricCurve
from .roots import safeguarded_newton
from .tessellate import tessellation_parameters
from .vec_ops import anchor

#: Largest angle between the tangent (at an interval's ends and middle) and its chord.
MAX_TURN = np.radians(5.0)
#: Bound on an interval's arc length over its chord: 1/cos of three times MAX_TURN (the
#: tangent is only measured at three points of each interval), rounded up.
ARC_BOUND = 1.04
#: Longest chord between samples, as a fraction of the curve's size (the k-d tree's ball
#: about each query reaches this far past the nearest sample: short chords keep it small).
MAX_CHORD = 1 / 100
#: Most search samples on one curve.
MAX_SAMPLES = 100_000


def sample_parameters(curve: ParametricCurve, per_span: int = 16, minimum: int = 128) -> FloatArray:
    """Parameters spread over every smooth span of the curve, at least ``minimum`` of them."""
    breaks = tuple(curve._breakpoints().tolist())
    if len(breaks) > _CACHED_BREAKS:  # a long key costs more than the work it saves
        return _spread.__wrapped__(breaks, per_span, minimum)
    return _spread(breaks, per_span, minimum).copy()


#: Curves with at most this many breakpoints share their sample layouts (see :func:`_spread`).
_CACHED_BREAKS = 64


@lru_cache(maxsize=64)
def _spread(breaks: tuple[float, ...], per_span: int, minimum: int) -> FloatArray:
    """:func:`sample_parameters` for given breakpoints (curves rebuilt on every solve with
    the same knots share it)."""
    edges = np.array(breaks)
    count = max(per_span, -(-minimum // (len(edges) - 1)))
    inner = edges[:-1, None] + np.linspace(0, 1, count, endpoint=False)[None, :] * np.diff(edges)[:, None]
    return np.concatenate([inner.reshape(-1), [1.0]])


def _cosine_to_chord(tangents: FloatArray, chords: FloatArray) -> FloatArray:
    """Cosine of the angle between each tangent and its chord (1 where either is zero)."""
    lengths = np.linalg.norm(tangents, axis=1) * np.linalg.norm(chords, axis=1)
    dots = np.einsum("ij,ij->i", tangents, chords)
    return np.where(lengths > 0, dots / np.where(lengths > 0, lengths, 1.0), 1.0)


def turning_parameters(curve: ParametricCurve, t: FloatArray, max_chord: float, max_turn: float = MAX_TURN,
                       max_points: int = MAX_SAMPLES) -> FloatArray:
    """``t`` subdivided until the tangent at every interval's ends and middle is within
    ``max_turn`` of the interval's chord and no chord is longer than ``max_chord``
    (intervals shorter than 1e-12 in t are left). Each round measures only the halves
    of the intervals the last round split."""
    limit = np.cos(max_turn)
    low, high = t[:-1], t[1:]
    added = []
    count = len(t)
    while len(low) and count < max_points:
        n = len(low)
        middle = 0.5 * (low + high)
        # each interval's end tangents from inside it (a kink at a knot is no turn)
        points, tangents = curve.derivatives(np.concatenate([low, np.nextafter(high, low), middle]), 1)
        chords = points[n : 2 * n] - points[:n]
        worst = np.minimum.reduce([
            _cosine_to_chord(tangents[:n], chords),
            _cosine_to_chord(tangents[n : 2 * n], chords),
            _cosine_to_chord(tangents[2 * n :], chords),
        ])
        long = np.einsum("ij,ij->i", chords, chords) > max_chord**2
        split = np.nonzero(((worst < limit) | long) & (high - low > 1e-12))[0][: max_points - count]
        added.append(middle[split])
        count += len(split)
        low, high = np.concatenate([low[split], middle[split]]), np.concatenate([middle[split], high[split]])
    return np.sort(np.concatenate([t, *added]))


def search_parameters(curve: ParametricCurve) -> FloatArray:
    """Samples dense enough to tell the curve's turns and folds apart.

    At least 16 per smooth span and 128 in all, then subdivided until every chord is
    within 1/1000 of the curve's size of the curve (so a curve with many turns in one
    span, a long helix given by a function, gets several samples per turn) and until the
    tangent turns by at most :data:`MAX_TURN` against every chord (so a tight turn gets
    samples through it however small it is).
    """
    t = sample_parameters(curve)
    points = curve.point_at(t)
    size = float(np.linalg.norm(np.ptp(points, axis=0)))
    if not size > 0:
        return t
    t = tessellation_parameters(curve, 1e-3 * size, initial=t, max_points=MAX_SAMPLES)
    return turning_parameters(curve, t, MAX_CHORD * size)


class SearchSamples(NamedTuple):
    """A curve's search samples and what the search needs of them (cached on the curve)."""

    parameters: FloatArray  #: (n + 1,) increasing, 0 and 1 included
    points: FloatArray  #: (n + 1, 3) the curve's points, about ``origin``
    tangents: FloatArray  #: (n + 1, 3) C' at the samples, from the right (leaving them)
    arriving: FloatArray  #: (n + 1, 3) C' at the samples from the left (row 0: from the right)
    half_arcs: FloatArray  #: (n,) a bound on half of each interval's arc length
    reach: FloatArray  #: (n + 1,) the longer half arc of each sample's two intervals
    moments: FloatArray  #: (n + 1,) C·C' at the samples (g = C·C' − P·C'), from the right
    arriving_moments: FloatArray  #: (n + 1,) the same from the left
    origin: FloatArray  #: (3,) the samples' anchor
    tree: cKDTree  #: of ``points``


class SearchableCurve(ParametricCurve, Protocol):
    """A curve that keeps its search samples (as :class:`~.curve_base.Curve` does, cached)."""

    @property
    def _search_parameters(self) -> FloatArray: ...

    @property
    def _search_samples(self) -> SearchSamples: ...


def search_samples(curve: SearchableCurve) -> SearchSamples:
    """The :class:`SearchSamples` of ``curve``'s :func:`search_parameters`."""
    t = curve._search_parameters
    points, tangents = curve.derivatives(t, 1)
    arriving = tangents.copy()  # C' from the left: differs at a kink (a knot of full multiplicity)
    arriving[1:] = curve.derivatives(np.nextafter(t[1:], t[:-1]), 1)[1]
    origin = anchor(points)
    local = points - origin
    half_arcs = 0.5 * ARC_BOUND * np.linalg.norm(np.diff(local, axis=0), axis=1)
    reach = np.maximum(np.concatenate([[0.0], half_arcs]), np.concatenate([half_arcs, [0.0]]))
    moments = np.einsum("ij,ij->i", local, tangents)
    arriving_moments = np.einsum("ij,ij->i", local, arriving)
    return SearchSamples(t, local, tangents, arriving, half_arcs, reach, moments, arriving_moments, origin,
                         cKDTree(local))


def nearest_sample(samples: FloatArray, points: FloatArray) -> np.ndarray:
    """Index of the nearest sample to each point, by a k-d tree of the samples.

    Both are taken about the samples' anchor, so that at site coordinates (1e6 m) the
    distances keep their digits. (Brute force took 2.9 s for 4,000 samples and 10⁵
    queries; the tree takes tens of milliseconds.)"""
    if len(points) == 0:
        return np.zeros(0, dtype=np.int64)
    origin = anchor(samples)
    tree = cKDTree(samples - origin)
    result = np.zeros(len(points), dtype=np.int64)  # a non-finite query gets sample 0
    finite = np.isfinite(points).all(axis=1)
    result[finite] = tree.query(points[finite] - origin, k=1)[1]
    return result


#: Nearest samples taken per query in one k-d tree search; a query with more samples than
#: this in its ball gets a ball search of its own.
_NEAREST = 12


def _samples_within(
    samples: SearchSamples, points: FloatArray, pad: FloatArray
) -> tuple[FloatArray, IntArray, IntArray, IntArray, FloatArray]:
    """For each query, the nearest sample's distance d₀ and index; and every (query, sample,
    distance) with the sample within d₀ + the half arc of one of its intervals (+ ``pad``).

    One search for the nearest :data:`_NEAREST` samples answers most queries; those whose
    ball (radius d₀ + the longest half arc) holds more get a ball search each."""
    tree = samples.tree
    k = min(_NEAREST, tree.n)
    distances, index = tree.query(points, k=k)
    distances, index = distances.reshape(len(points), k), index.reshape(len(points), k)
    nearest, first = distances[:, 0], index[:, 0]
    radii = nearest + samples.reach.max() + pad
    full = np.nonzero(distances[:, -1] <= radii)[0] if k < tree.n else np.zeros(0, dtype=np.int64)
    rows = np.broadcast_to(np.arange(len(points))[:, None], index.shape)
    keep = np.ones(len(points), dtype=bool)
    keep[full] = False
    rows, index, distances = rows[keep].reshape(-1), index[keep].reshape(-1), distances[keep].reshape(-1)
    if len(full):
        balls = tree.query_ball_point(points[full], radii[full], return_sorted=False)
        counts = np.fromiter(map(len, balls), dtype=np.int64, count=len(balls))
        more = np.fromiter(chain.from_iterable(balls), dtype=np.int64, count=int(counts.sum()))
        owners = np.repeat(full, counts)
        gaps = samples.points[more] - points[owners]
        rows = np.concatenate([rows, owners])
        index = np.concatenate([index, more])
        distances = np.concatenate([distances, np.sqrt(np.einsum("ij,ij->i", gaps, gaps))])
    hit = distances <= nearest[rows] + samples.reach[index] + pad[rows]
    return nearest, first, rows[hit], index[hit], distances[hit]


def closest_parameters(curve: SearchableCurve, points: FloatArray) -> FloatArray:
    """Parameter of the closest point on ``curve`` to each of ``points`` ``(m, 3)``.

    A non-finite query gets 0.
    """
    samples = curve._search_samples
    ts, tangents, half_arcs = samples.parameters, samples.tangents, samples.half_arcs
    result = np.zeros(len(points))
    finite = np.nonzero(np.isfinite(points).all(axis=1))[0]
    if len(finite) == 0 or len(ts) < 2:
        return result
    query = points[finite] - samples.origin
    # pad the distances for rounding
    pad = 1e-12 * (np.abs(samples.points).max() + np.abs(query).max(axis=1))
    nearest, j, row, sample, distance = _samples_within(samples, query, pad)
    result[finite] = ts[j]
    # g = (C − P)·C' at each sample in the ball and its neighbours: an interval where g goes
    # from − to + holds a minimum; it is a candidate if an end is within d₀ + its half arc.
    # The nearest sample is the answer for every other stretch of the curve.
    last = len(ts) - 1  # the last sample
    moment, arriving, moment_in = samples.moments, samples.arriving, samples.arriving_moments
    p = query[row]
    g = moment[sample] - np.einsum("ij,ij->i", p, tangents[sample])  # leaving the sample
    g_in = moment_in[sample] - np.einsum("ij,ij->i", p, arriving[sample])  # arriving at it
    before = np.maximum(sample - 1, 0)
    after = np.minimum(sample + 1, last)
    g_before = moment[before] - np.einsum("ij,ij->i", p, tangents[before])
    g_after = moment_in[after] - np.einsum("ij,ij->i", p, arriving[after])
    reach = nearest[row] + pad[row]
    left = (sample > 0) & (g_before < 0) & (g_in > 0) & (distance <= reach + half_arcs[before])
    own = half_arcs[np.minimum(sample, last - 1)]
    right = (sample < last) & (g < 0) & (g_after > 0) & (distance <= reach + own)
    key = np.sort(np.concatenate([row[left] * last + before[left], row[right] * last + sample[right]]))
    if len(key) == 0:
        return result
    key = key[np.concatenate([[True], key[1:] != key[:-1]])]  # each (query, interval) once
    row, interval = key // last, key % last
    owner = points[finite[row]]
    lo, hi = ts[interval], ts[interval + 1]
    g_lo = moment[interval] - np.einsum("ij,ij->i", query[row], tangents[interval])
    g_hi = moment_in[interval + 1] - np.einsum("ij,ij->i", query[row], arriving[interval + 1])

    def gradient(x: FloatArray, index: IntArray) -> tuple[FloatArray, FloatArray]:
        c, d1, d2 = curve.derivatives(x, 2)
        offset = c - owner[index]
        return np.einsum("ij,ij->i", offset, d1), (
            np.einsum("ij,ij->i", d1, d1) + np.einsum("ij,ij->i", offset, d2)
        )

    root = safeguarded_newton(gradient, lo, hi, lo + (hi - lo) * g_lo / (g_lo - g_hi))
    found = np.linalg.norm(curve.point_at(root) - owner, axis=1)
    order = np.lexsort((found, row))
    first = order[np.concatenate([[True], row[order][1:] != row[order][:-1]])]
    better = first[found[first] <= nearest[row[first]] + pad[row[first]]]
    result[finite[row[better]]] = root[better]
    return result
