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
sum never points backwards along one of them) and |m| h ≤ 2 |c|. A zero chord (two
rulings through one point) gives m = 0 at both of its nodes, so the rail stays at the
point across the span: the loft over a fan is exactly the cone through its apex. The
result is C¹ (C² across the spans left alone, which keep the spline's own cubic), and
for evenly spaced smooth data no tangent is touched and the spline is returned as is.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from scipy.interpolate import BSpline

FloatArray = NDArray[np.float64]

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
    """The fallback tangents m_i (module docstring) at every node, ``(nodes, rails, 3)``."""
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
    return np.where((size > 1e-12)[..., None], direction * harmonic[..., None], 0.0)


def hermite_spline(params: FloatArray, points: FloatArray, tangents: FloatArray) -> BSpline:
    """The C¹ piecewise cubic through ``points`` at ``params`` with ``tangents`` there, as a
    B-spline with double interior knots (its coefficients are the inner Bézier points)."""
    h = np.diff(params)[:, None]
    inner = np.empty((2 * (len(params) - 1), points.shape[1]))
    inner[0::2] = points[:-1] + tangents[:-1] * h / 3.0
    inner[1::2] = points[1:] - tangents[1:] * h / 3.0
    coefficients = np.vstack([points[:1], inner, points[-1:]])
    knots = np.concatenate([np.full(4, params[0]), np.repeat(params[1:-1], 2), np.full(4, params[-1])])
    return BSpline(knots, coefficients, 3)


def without_overshoot(
    spline: BSpline, params: FloatArray, points: FloatArray, closed: bool
) -> BSpline | None:
    """The spline with its tangents limited where it overshoots (module docstring), or
    None when no tangent needed limiting (keep ``spline`` as it is).

    ``points`` ``(n, columns)`` are the interpolated points at ``params`` (several 3D
    rails side by side when the columns are a multiple of 3: each rail is limited on its
    own); ``closed`` means the last point repeats the first and the spline is periodic.
    """
    if spline.k < 2 or len(params) < 3:
        return None  # a polyline (or a single segment) cannot overshoot
    p = _points(points)
    d = _points(np.asarray(spline(params, nu=1), dtype=float))
    chords = np.diff(p, axis=0)
    lengths = _norm(chords)
    size = np.ptp(p, axis=0).max(axis=-1)  # per rail
    zero = lengths <= ZERO_CHORD * np.where(size > 0, size, 1.0)
    steps = np.diff(params)[:, None]
    # every node's spline tangent against the span after it and the span before it
    ahead = _fits(d[:-1], chords, lengths, steps, zero)
    behind = _fits(d[1:], chords, lengths, steps, zero)
    good = np.ones(d.shape[:2], dtype=bool)
    good[:-1] &= ahead
    good[1:] &= behind
    if closed:  # the last node is the first one
        good[0] &= good[-1]
        good[-1] = good[0]
    if good.all():
        return None
    fallback = _geometric(chords, lengths, steps, closed)
    if closed:
        fallback = np.concatenate([fallback, fallback[:1]])
    tangents = np.where(good[..., None], d, fallback)
    if closed:
        tangents[-1] = tangents[0]  # C¹ across the seam exactly
    tangents = tangents.reshape(len(params), -1)
    return hermite_spline(params, points, tangents)
