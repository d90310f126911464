"""Rails that do not overshoot: the interpolating spline, with its tangents limited
where the ruling ends are spaced unevenly.

A loft's rails pass through the ruling ends at evenly spaced parameters u_i (see
:mod:`.ruled`). Where consecutive ends are spaced very unevenly — a ruling end that
barely moves on one rail while the other advances, or stays put for a fan of rulings
through one point — the C² cubic spline through them must swing out to keep its
curvature continuous: it doubles back past a point and returns (an S-shaped loop), or
wanders around the fan's apex instead of staying on it. The loft then overlaps itself,
its development does too, and a cut outline drawn from it wiggles.

The cure keeps the spline wherever it behaves and changes it only around the nodes
where it does not. Written in Hermite form, span i of a cubic runs from p_i to
p_{i+1} (chord c_i, parameter step h_i) with end tangents d_i, d_{i+1}. If both
tangents' components along the chord, times h_i / |c_i|, lie in [0, 3], the span's
projection on its chord is monotone (the square [0, 3]² lies in Fritsch and Carlson's
monotonicity region), so it cannot double back; bounding |d| h by 3 |c| too keeps it
from bulging sideways. Every node whose spline tangent breaks these bounds on either
of its spans gets instead the geometric tangent

    m_i = unit(ĉ_{i−1} + ĉ_i) · H(|c_{i−1}| / h_{i−1}, |c_i| / h_i)

(H the harmonic mean, as in Fritsch and Butland's monotone interpolation), which
meets them always: its component along either chord is ≥ 0 (the two unit chords'
sum never points backwards along one of them) and |m| h ≤ 2 |c|. The result is C¹ (C²
across the spans left alone, which keep the spline's own cubic), and for evenly spaced
smooth data no tangent is touched and the spline is returned as is.

A zero chord (two rulings through one point: a fan) is a span where the rail stands
still, tangents 0, so the loft over a fan is exactly the cone through its apex. The
points between fans are interpolated run by run, each run by its own spline (limited
as above): one spline through the repeated apex would swing out around it, and a rail
slowed to a stop there would leave it in the direction of its next control point, a
kink of up to ~20° in the edge. So the rail reaches the apex with the tangent of the
run before and leaves it with that of the run after (continuous in position there,
and in direction as far as the two runs agree).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from scipy.interpolate import BSpline, make_interp_spline

from torsal.nodes.geometry.array_types import FloatArray

#: Chords shorter than this share of a rail's size count as zero (a fan's apex).
ZERO_CHORD = 1e-12
#: Largest |d|·h / |c|: a tangent longer than three chords' worth swings a span out.
REACH = 3.0
#: Rounding allowance on the bounds, so evenly spaced straight data never trips them.
SLACK = 1e-9


def _points(points: FloatArray) -> FloatArray:
    """``(n, columns)`` as ``(n, rails, 3)`` when the columns are 3D points, else one rail."""
    columns = points.shape[1]
    return points.reshape(len(points), columns // 3, 3) if columns % 3 == 0 else points[:, None, :]


def _norm(a: FloatArray) -> FloatArray:
    return np.sqrt(np.einsum("...i,...i->...", a, a))


def _fits(tangent: FloatArray, chord: FloatArray, length: FloatArray, step: FloatArray,
          zero: FloatArray) -> NDArray[np.bool_]:
    """Whether ``tangent`` at an end of spans (chord, length, step) keeps them monotone and
    within reach; rows ``(spans, rails, 3)``, lengths ``(spans, rails)``, steps ``(spans, 1)``.
    No spline tangent fits a zero chord: only m = 0 keeps the rail on the fan's apex."""
    along = np.einsum("...i,...i->...", tangent, chord) * step  # (d·c) h = (d·ĉ) h |c|
    reach = _norm(tangent) * step
    square = length * length
    return (along >= -SLACK * square) & (reach <= (REACH + SLACK) * length) & ~zero


def _geometric(chords: FloatArray, lengths: FloatArray, steps: FloatArray, closed: bool) -> FloatArray:
    """The fallback tangents m_i (module docstring) at every node, ``(nodes, rails, 3)``;
    at the ends of an open rail the chord's own slope."""
    units = chords / np.where(lengths > 0, lengths, 1.0)[..., None]
    speed = lengths / steps  # |c| / h per span
    if closed:
        before, after = np.roll(units, 1, axis=0), units
        slow, fast = np.roll(speed, 1, axis=0), speed
    else:
        before = np.concatenate([units[:1], units])
        after = np.concatenate([units, units[-1:]])
        slow = np.concatenate([speed[:1], speed])
        fast = np.concatenate([speed, speed[-1:]])
    total = before + after
    size = _norm(total)
    with np.errstate(invalid="ignore", divide="ignore"):
        harmonic = np.where(slow * fast > 0, 2 * slow * fast / (slow + fast), 0.0)
    direction = total / np.where(size > 1e-12, size, 1.0)[..., None]
    tangents = np.where((size > 1e-12)[..., None], direction * harmonic[..., None], 0.0)
    return np.concatenate([tangents, tangents[:1]]) if closed else tangents


def _limited(params: FloatArray, p: FloatArray, d: FloatArray, closed: bool) -> tuple[FloatArray, bool]:
    """Node tangents ``(n, rails, 3)``: the spline's ``d`` where they fit both spans at the
    node, the fallback elsewhere; and whether any was replaced."""
    chords = np.diff(p, axis=0)
    lengths = _norm(chords)
    steps = np.diff(params)[:, None]
    zero = np.zeros(lengths.shape, dtype=bool)
    good = np.ones(d.shape[:2], dtype=bool)
    good[:-1] &= _fits(d[:-1], chords, lengths, steps, zero)  # against the span after the node
    good[1:] &= _fits(d[1:], chords, lengths, steps, zero)  # and the span before it
    if closed:  # the last node is the first one
        good[0] &= good[-1]
        good[-1] = good[0]
    if good.all():
        return d, False
    tangents = np.where(good[..., None], d, _geometric(chords, lengths, steps, closed))
    if closed:
        tangents[-1] = tangents[0]  # C¹ across the seam exactly
    return tangents, True


def _runs(zero: NDArray[np.bool_], closed: bool) -> list[NDArray[np.int64]]:
    """The nodes of each maximal run of consecutive nonzero chords, in order (on a closed
    rail the indices may pass its last node: take them modulo the number of spans)."""
    spans = len(zero)
    if closed:
        first = int(np.flatnonzero(zero)[0]) + 1  # a run starts after a zero chord
        unwrapped = first + np.arange(spans)
    else:
        unwrapped = np.arange(spans)
    runs, current = [], []
    for index in unwrapped.tolist():
        if zero[index % spans]:
            if current:
                runs.append(np.array([*current, current[-1] + 1]))
            current = []
        else:
            current.append(index)
    if current:
        runs.append(np.array([*current, current[-1] + 1]))
    return runs


def _fan_tangents(params: FloatArray, p: FloatArray, zero: NDArray[np.bool_], closed: bool
                  ) -> tuple[FloatArray, FloatArray]:
    """Start and end tangents ``(spans, 3)`` of every span of one rail with zero chords: 0 on
    those (the rail stays on the fan's apex), and on each run of nonzero chords between
    them the limited tangents of the interpolating spline through that run alone (the
    repeated apex would make a spline through all the points swing out near it)."""
    spans = len(zero)
    start, end = np.zeros((spans, 3)), np.zeros((spans, 3))
    for run in _runs(zero, closed):
        index = run % spans if closed else run
        u = params[index] + (run // spans if closed else 0)
        q = p[index]
        spline = make_interp_spline(u, q, k=min(3, len(run) - 1))
        d = np.asarray(spline(u, nu=1), dtype=float)
        tangents, _ = _limited(u, q[:, None, :], d[:, None, :], closed=False)
        span = index[:-1]
        start[span], end[span] = tangents[:-1, 0], tangents[1:, 0]
    return start, end


def bezier_spline(params: FloatArray, points: FloatArray, start: FloatArray, end: FloatArray) -> BSpline:
    """The piecewise cubic through ``points`` at ``params`` whose span i leaves point i with
    tangent ``start[i]`` and reaches point i + 1 with tangent ``end[i]``, as a B-spline with
    triple interior knots (its coefficients are the spans' Bézier points); C¹ where
    ``end[i − 1] == start[i]``."""
    h = np.diff(params)[:, None]
    spans = len(h)
    coefficients = np.empty((3 * spans + 1, points.shape[1]))
    coefficients[0:-1:3] = points[:-1]
    coefficients[1::3] = points[:-1] + start * h / 3.0
    coefficients[2::3] = points[1:] - end * h / 3.0
    coefficients[-1] = points[-1]
    knots = np.concatenate([np.full(4, params[0]), np.repeat(params[1:-1], 3), np.full(4, params[-1])])
    return BSpline(knots, coefficients, 3)


def without_overshoot(
    spline: BSpline, params: FloatArray, points: FloatArray, closed: bool
) -> BSpline | None:
    """The spline with its tangents limited where it overshoots (module docstring), or
    None when no tangent needed limiting (keep ``spline`` as it is).

    ``points`` ``(n, columns)`` are the interpolated points at ``params`` (several 3D
    rails side by side when the columns are a multiple of 3: each rail is limited on its
    own); ``closed`` means the last point repeats the first and the spline is periodic.
    A rail with zero chords (a fan of rulings through one point) stands still on them
    and is interpolated on each run of points between them on its own.
    """
    if spline.k < 2 or len(params) < 3:
        return None  # a polyline (or a single segment) cannot overshoot
    p = _points(points)
    lengths = _norm(np.diff(p, axis=0))
    size = np.ptp(p, axis=0).max(axis=-1)  # per rail
    zero = lengths <= ZERO_CHORD * np.where(size > 0, size, 1.0)
    d = _points(np.asarray(spline(params, nu=1), dtype=float))
    if not zero.any():
        tangents, changed = _limited(params, p, d, closed)
        if not changed:
            return None
        flat = tangents.reshape(len(params), -1)
        return bezier_spline(params, points, flat[:-1], flat[1:])
    shape = (len(lengths), *p.shape[1:])
    starts, ends = np.empty(shape), np.empty(shape)
    for rail in range(p.shape[1]):
        if zero[:, rail].any():
            starts[:, rail], ends[:, rail] = _fan_tangents(params, p[:, rail], zero[:, rail], closed)
        else:
            tangents, _ = _limited(params, p[:, rail : rail + 1], d[:, rail : rail + 1], closed)
            starts[:, rail], ends[:, rail] = tangents[:-1, 0], tangents[1:, 0]
    return bezier_spline(params, points, starts.reshape(len(lengths), -1), ends.reshape(len(lengths), -1))
