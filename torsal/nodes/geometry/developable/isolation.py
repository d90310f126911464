"""Certified root isolation for the coplanarity function, all stations at once.

For a station A(s) with unit tangent Â', the partners t on curve B are the roots of

    f(t) = det[B(t) − A, Â', B'(t)],   f'(t) = det[B − A, Â', B''],
    f''(t) = det[B', Â', B''] + det[B − A, Â', B'''].

The solver samples B at t_0 < t_1 < … and knows f at every station–sample pair. A sign
change between two samples brackets a root; but two roots close together (where a
section has an inflection, where A' and B' become parallel, near a curve's end) give no
sign change and would be missed. This module decides, for every sample interval, which
of three things holds, and subdivides the intervals where it cannot decide yet.

The bound
---------
On an interval [t_j, t_j+1] of width h, in its unit coordinate u = (t − t_j)/h, the
curvature of f is bounded by

    M = h²·(β1·β2 + D·β3) >= |d²f/du²|,

with D a bound on the ruling length |B − A| over the interval (the diameter of both
curves' samples to sift all intervals at once, then, for the few that need a closer
look, the longer of the rulings to the interval's two ends; plus the chord slack
h·β1/2) and β_k bounds on |B⁽ᵏ⁾| over the interval, read from its two ends:
β3 = max |B'''| at the ends + |ΔB'''| between them, β2 = max |B''| + h·β3/2,
β1 = max |B'| + h·β2/2. The last two follow from the first by the mean value theorem;
β3 is exact whenever B''' is affine on the interval (polynomial spans of degree <= 4,
straight pieces) and otherwise carries a margin of one whole change of B''' across the
interval — curves whose third derivative swings more than that within one sample
interval (far under-sampled) are outside the guarantee. A bound over an interval holds
on its parts, so the halves of a split interval keep its β3 (and B''' is never evaluated
again: subdivision needs only B, B' and B'').

The guarantee
-------------
With M, and f, f' at both ends (f0, f1, e0 = h·f'(t_j), e1 = h·f'(t_j+1)), the lower
bounds q0(u) = f0 + e0·u − M·u²/2 and q1(u) = f1 − e1·(1 − u) − M·(1 − u)²/2 hold for
σ·f (σ the sign of f0). When f0, f1 have the same sign, σ·f > 0 on the whole interval
if max(q0, q1) > 0 on it; both are concave and their difference is linear in u, so that
holds iff it holds at the ends (it does: q0(0) = σf0, q1(1) = σf1) and at the one point
where q0 = q1 — **certified empty**. When f0, f1 have opposite signs the interval holds
exactly one root, a simple one, if σ'·f' > 0 throughout (σ' the sign of f1 − f0), which
holds when σ'e0 > 0, σ'e1 > 0 and σ'(e0 + e1) > M — **certified single**. Every other
interval is split (at the extremum of the cubic through f0, f1, e0, e1, or in half) and
its halves judged again, until each is certified or narrower than :data:`NARROWEST`:
what is left then is a double root to rounding (a touching point of f), returned as a
root at the least |f| found. So is a piece whose f is within its rounding of zero at both
ends (f is zero to rounding all along it), and a piece is certified empty only when f
stays farther than its rounding from zero (a touching point whose f rounds to the wrong
side is not lost). So, under the bound above, *every root of f on B is found*:
every root lies in a single bracket or is a double root, and no interval certified
empty holds one.

Cost: a cheap filter discards every interval where |f| at both ends exceeds h/2·D·β2
(f cannot reach zero from either end over half the interval) without computing f', first
with the diameter for D, then with the rulings' own lengths.
Only the few intervals near roots are judged with f'; the fewer still that are not
certified at once are subdivided, vectorised over all of them per level.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from torsal.nodes.geometry.array_types import BoolArray, IntArray

from ..curve_base import FloatArray
from ..roots import ZERO
from ..vec_ops import cross, dot, flatnonzero, norm

#: An uncertain interval narrower than this (in t) is a double root to rounding.
NARROWEST = 1e-13
#: Most subdivision levels (each at least halves the interval: 1/128 → 1e-13 in ~40).
MAX_LEVELS = 64
#: Most pieces judged, per first sample interval, over all levels. Curves within the
#: guarantee split a few intervals a few times (well under 1 a interval); a curve far
#: outside it (a stray vertex at 1e12 m) would split hundreds of thousands: it stops
#: here, as when the levels run out, and Valid (recomputed) tells what was found.
PIECES_PER_INTERVAL = 16


@dataclass
class IntervalBounds:
    """Per sample interval: ``curvature`` M (bound on |d²f/du²|) and ``reach`` (bound on
    |f'|·h/2: how far f can move from the nearer end) and ``third`` (β3, the bound on
    |B'''| they rest on)."""

    curvature: FloatArray
    reach: FloatArray
    third: FloatArray
    slope: FloatArray  #: h/2·β2: reach is slope·(length + chord)
    chord: FloatArray  #: h/2·β1: how far B moves from the nearer end


def third_bound(low: FloatArray, high: FloatArray) -> FloatArray:
    """β3 of the module docstring from the vectors B''' at the intervals' two ends."""
    at_low, at_high, change = norm(np.array([low, high, high - low]))  # (row by row, as alone)
    return np.maximum(at_low, at_high) + change


def interval_bounds(
    width: FloatArray,
    speed: tuple[FloatArray, FloatArray],
    second: tuple[FloatArray, FloatArray],
    b3: FloatArray,
    length: FloatArray | float,
) -> IntervalBounds:
    """The bounds of the module docstring for intervals of ``width`` h.

    ``speed`` and ``second`` are |B'| and |B''| at the intervals' low and high ends and
    ``b3`` is β3 (:func:`third_bound`). ``length`` bounds |B − A| at the two ends (the
    diameter of both curves, or the larger of the two rulings' lengths).
    """
    half = 0.5 * width
    b2 = np.maximum(second[0], second[1]) + half * b3
    slope = half * b2
    b1 = np.maximum(speed[0], speed[1]) + slope
    chord = half * b1
    reach_r = length + chord  # |B − A| anywhere inside
    curvature = width * width * (b1 * b2 + reach_r * b3)
    return IntervalBounds(curvature, slope * reach_r, b3, slope, chord)


def certified_empty(
    f0: FloatArray, f1: FloatArray, e0: FloatArray, e1: FloatArray, m: FloatArray,
    margin: FloatArray | float = 0.0,
) -> BoolArray:
    """Whether f (same sign at both ends) provably keeps its sign on the interval, by
    more than ``margin`` (the rounding of f: a bound within it does not tell a touching
    point of f from none)."""
    sign = np.where(f0 < 0, -1.0, 1.0)
    g0, g1, e0, e1 = sign * f0, sign * f1, sign * e0, sign * e1
    denominator = m + e1 - e0
    half_m = 0.5 * m
    with np.errstate(divide="ignore", invalid="ignore"):
        u = (g0 - g1 + e1 + half_m) / denominator
    inside = (u >= 0.0) & (u <= 1.0) & (denominator != 0)
    low = g0 + u * (e0 - half_m * u)
    return (g0 > margin) & (g1 > margin) & (~inside | (low > margin))


def certified_single(
    f0: FloatArray, f1: FloatArray, e0: FloatArray, e1: FloatArray, m: FloatArray
) -> BoolArray:
    """Whether f (opposite signs at the ends) provably has exactly one, simple, root."""
    sign = np.where(f1 > f0, 1.0, -1.0)
    e0, e1 = sign * e0, sign * e1
    return (e0 > 0) & (e1 > 0) & (e0 + e1 > m)


@dataclass
class Pieces:
    """Station–interval pairs still to judge: station ``row``, ends ``x0 < x1`` and, at
    both ends, f, f' (per unit t) and the lengths of B' and B'', and the interval's β3."""

    row: IntArray
    x0: FloatArray
    x1: FloatArray
    f0: FloatArray
    f1: FloatArray
    d0: FloatArray
    d1: FloatArray
    speed0: FloatArray
    speed1: FloatArray
    second0: FloatArray
    second1: FloatArray
    bound3: FloatArray
    r0: FloatArray  #: |B − A| at the two ends
    r1: FloatArray

    def take(self, keep: BoolArray | IntArray) -> Pieces:
        """The pieces ``keep`` (a mask or indices); B-data not filled in stays empty."""
        return Pieces(*(_part(getattr(self, name), keep) for name in _PIECE_FIELDS))

    def brackets(self, keep: BoolArray | IntArray) -> tuple[FloatArray, ...]:
        """Row, ends, f and f' at both ends of the pieces ``keep``: what a bracket keeps."""
        ends = self.x0[keep], self.x1[keep], self.f0[keep], self.f1[keep], self.d0[keep], self.d1[keep]
        return (self.row[keep], *ends)


def _part(values: FloatArray, keep: BoolArray | IntArray) -> FloatArray:
    return values if len(values) == 0 else values[keep]


_PIECE_FIELDS = tuple(Pieces.__dataclass_fields__)


@dataclass
class Isolated:
    """What :func:`isolate` found: brackets holding one root each, and double roots."""

    rows: IntArray
    low: FloatArray
    high: FloatArray
    f_low: FloatArray
    f_high: FloatArray
    d_low: FloatArray
    d_high: FloatArray
    double_rows: IntArray
    double_t: FloatArray


def _split_points(p: Pieces) -> FloatArray:
    """Where to split each piece: at the extremum of the cubic Hermite interpolant of f
    (where a hidden root pair would sit) when it lies well inside, else in the middle."""
    h = p.x1 - p.x0
    e0, e1 = p.d0 * h, p.d1 * h
    rise = p.f1 - p.f0
    # cubic f0 + e0·u + c2·u² + c3·u³; its slope e0 + 2·c2·u + 3·c3·u² = 0
    c2 = 3.0 * rise - 2.0 * e0 - e1
    c3 = e0 + e1 - 2.0 * rise
    a, b, c = 3.0 * c3, 2.0 * c2, e0
    with np.errstate(divide="ignore", invalid="ignore"):
        disc = np.sqrt(np.maximum(b * b - 4.0 * a * c, 0.0))
        q = -0.5 * (b + np.where(b < 0, -disc, disc))
        u1 = np.where(a != 0, q / a, np.nan)
        u2 = np.where(q != 0, c / q, np.nan)
    # of the two critical points, the one where |cubic| is least
    def value(u: FloatArray) -> FloatArray:
        return np.abs(p.f0 + u * (e0 + u * (c2 + u * c3)))

    u1 = np.where((u1 > 0.1) & (u1 < 0.9), u1, np.nan)
    u2 = np.where((u2 > 0.1) & (u2 < 0.9), u2, np.nan)
    with np.errstate(invalid="ignore"):
        u = np.where(np.isnan(u2) | (value(u1) <= value(u2)), u1, u2)
    u = np.where(np.isnan(u) | (np.sign(p.f0) != np.sign(p.f1)), 0.5, u)
    return p.x0 + u * h


def _judge(
    p: Pieces, curvature: FloatArray, noise: FloatArray | float = 0.0
) -> tuple[BoolArray, BoolArray, BoolArray]:
    """Masks of the pieces that are brackets (one root, or too narrow to split), touching
    points (a double root to rounding) and still uncertain; the rest are empty.

    ``noise`` is the rounding of f on each piece (:func:`_noise`): a piece is empty only
    when f provably stays farther than that from zero, and one whose f is within it at
    both ends and that is not a certified bracket is a touching point already (f is zero
    to rounding all along it: splitting it further would only follow the rounding)."""
    h = p.x1 - p.x0
    e0, e1 = p.d0 * h, p.d1 * h
    change = np.signbit(p.f0) != np.signbit(p.f1)
    narrow = h <= NARROWEST
    bracket = change & (narrow | certified_single(p.f0, p.f1, e0, e1, curvature))
    open_ = ~(change | certified_empty(p.f0, p.f1, e0, e1, curvature, noise))
    quiet = (np.abs(p.f0) <= noise) & (np.abs(p.f1) <= noise)
    touching = (open_ | (change & ~bracket)) & (narrow | quiet)
    return bracket, touching, (change | open_) & ~(bracket | touching)


def _noise(p: Pieces, a0: FloatArray) -> FloatArray | float:
    """The rounding of f = det[B − A, Â', B'] on each piece, from the size of its terms
    (|A| + |B| <= 2|A| + |B − A|, times |B'|; Â' is a unit vector), or 0 where the
    pieces do not carry B's speeds yet (the first sift's pieces: far wider than a
    touching point's rounding)."""
    if len(p.speed0) == 0:
        return 0.0
    size = 2.0 * norm(a0[p.row]) + np.maximum(p.r0, p.r1)
    return ZERO * size * np.maximum(p.speed0, p.speed1)


def isolate(
    first: Pieces,
    curvature: FloatArray,
    evaluate: Callable[[FloatArray], list[FloatArray]] | Callable[[FloatArray, IntArray], list[FloatArray]],
    a0: FloatArray,
    a1: FloatArray,
    ends: Callable[[Pieces, IntArray], Pieces] | None = None,
    strip_of: IntArray | None = None,
) -> Isolated:
    """Judge and subdivide the pieces ``first`` (whose f'' bounds are ``curvature``) until
    each is certified (module docstring).

    ``evaluate(t)`` returns B and its first two derivatives at parameters ``t``; ``a0``
    and ``a1`` are the stations' points and unit tangents. ``ends(first, index)``, if
    given, returns the pieces ``index`` of ``first`` with their B-data (speed and second
    derivative and ruling lengths at both ends, β3) filled in: ``first`` need not carry them, since
    only the few pieces that are split read them.

    With ``strip_of`` (the strip of every station row) the stations are those of several
    strips, each isolated as if alone: each strip has its own budget of pieces, and
    ``evaluate(t, rows)`` gets the pieces' station rows too (to evaluate each strip's B).
    """
    found: list[tuple[FloatArray, ...]] = []
    doubles: list[tuple[IntArray, FloatArray]] = []
    pieces = first
    # the work a curve far outside the guarantee gets (a few intervals may need all levels),
    # per strip
    count = len(strip_of) and int(strip_of.max()) + 1 if strip_of is not None else 1
    budget = np.maximum(PIECES_PER_INTERVAL * _per_strip(first.row, strip_of, count), 8 * MAX_LEVELS)
    for level in range(MAX_LEVELS):
        budget -= _per_strip(pieces.row, strip_of, count)
        if (budget < 0).any():  # as when the levels run out (below): what still changes sign is kept
            spent = budget < 0
            out = spent if strip_of is None else spent[strip_of[pieces.row]]
            found.append(pieces.brackets(out & (np.signbit(pieces.f0) != np.signbit(pieces.f1))))
            if out.all():
                break
            curvature, pieces = curvature[~out], pieces.take(~out)
        bracket, touching, uncertain = _judge(pieces, curvature, _noise(pieces, a0))
        if bracket.any():
            found.append(pieces.brackets(bracket))
        if touching.any():
            p = pieces
            row, x0, x1, f0, f1 = (v[touching] for v in (p.row, p.x0, p.x1, p.f0, p.f1))
            doubles.append((row, np.where(np.abs(f0) <= np.abs(f1), x0, x1)))
        if not uncertain.any():
            break
        if level == 0 and ends is not None:
            # judge again with the bound from the rulings' own lengths before splitting
            pieces = ends(pieces, flatnonzero(uncertain))
            curvature = _curvature(pieces)
            continue
        pieces = pieces.take(uncertain)
        if strip_of is None:
            pieces, curvature = _split(pieces, evaluate, a0, a1)
        else:
            pieces, curvature = _split(pieces, lambda x, rows=pieces.row: evaluate(x, rows), a0, a1)
    else:  # levels exhausted (never on curves within the guarantee): keep what changes sign
        found.append(pieces.brackets(np.signbit(pieces.f0) != np.signbit(pieces.f1)))
    if len(found) == 1:  # the usual case: all were judged at once
        rows, low, high, f_low, f_high, d_low, d_high = found[0]
    elif found:
        rows, low, high, f_low, f_high, d_low, d_high = (np.concatenate(x) for x in zip(*found, strict=True))
    else:
        rows, low, high, f_low, f_high, d_low, d_high = np.empty(0, dtype=np.int64), *([np.empty(0)] * 6)
    if doubles:
        double_rows, double_t = (np.concatenate(x) for x in zip(*doubles, strict=True))
        # a touching point on a split is found from both sides: keep it once
        order = np.lexsort((double_t, double_rows))
        double_rows, double_t = double_rows[order], double_t[order]
        again = np.zeros(len(order), dtype=bool)
        again[1:] = (double_rows[1:] == double_rows[:-1]) & (double_t[1:] - double_t[:-1] <= NARROWEST)
        double_rows, double_t = double_rows[~again], double_t[~again]
    else:
        double_rows, double_t = np.empty(0, dtype=np.int64), np.empty(0)
    return Isolated(rows, low, high, f_low, f_high, d_low, d_high, double_rows, double_t)


def _per_strip(rows: IntArray, strip_of: IntArray | None, count: int) -> IntArray:
    """How many of the pieces of station rows ``rows`` each strip has."""
    if strip_of is None:
        return np.array([len(rows)])
    return np.bincount(strip_of[rows], minlength=count)


def _split(
    pieces: Pieces,
    evaluate: Callable[[FloatArray], list[FloatArray]],
    a0: FloatArray,
    a1: FloatArray,
) -> tuple[Pieces, FloatArray]:
    """Every piece cut in two (:func:`_split_points`), and the halves' f'' bounds."""
    x = _split_points(pieces)
    b0, b1, b2 = evaluate(x)
    i = pieces.row
    plane = cross(b0 - a0[i], a1[i])  # det[R, Â', X] = X · (R × Â')
    f, d = dot(plane, b1), dot(plane, b2)
    speed, second, r = norm(b1), norm(b2), norm(b0 - a0[i])
    p = pieces
    halves = Pieces(
        np.concatenate([i, i]),
        np.concatenate([p.x0, x]),
        np.concatenate([x, p.x1]),
        np.concatenate([p.f0, f]),
        np.concatenate([f, p.f1]),
        np.concatenate([p.d0, d]),
        np.concatenate([d, p.d1]),
        np.concatenate([p.speed0, speed]),
        np.concatenate([speed, p.speed1]),
        np.concatenate([p.second0, second]),
        np.concatenate([second, p.second1]),
        np.concatenate([p.bound3, p.bound3]),  # a bound over the whole holds on its halves
        np.concatenate([p.r0, r]),
        np.concatenate([r, p.r1]),
    )
    return halves, _curvature(halves)


def _curvature(p: Pieces) -> FloatArray:
    """M of every piece, from its own ends' data."""
    width = p.x1 - p.x0
    length = np.maximum(p.r0, p.r1)
    return interval_bounds(width, (p.speed0, p.speed1), (p.second0, p.second1), p.bound3, length).curvature
