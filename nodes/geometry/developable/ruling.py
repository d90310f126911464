"""The developable strip between two space curves: solving for its rulings.

Geometry
--------
A developable surface has one tangent plane along each ruling. If the strip is bounded
by curves A(s) and B(t) and a ruling joins A(s) to B(t), both curves are tangent to the
surface at the ruling's ends, so the ruling R = B(t) − A(s) and the two tangents A'(s),
B'(t) lie in one plane (the ruling is *torsal*)::

    f_s(t) = det[B(t) − A(s), A'(s), B'(t)] = 0.

For each station s on A this is one equation in t. Its roots are the candidate
partners. A root is kept only if its normals are *consistently oriented* (see
:mod:`.warp`: with both curves running the same way and rulings that do not cross, the
sheet's normals N1 = R × A' and N2 = R × B' point to the same side, so the signed warp
is ~0, not ~π), and one root per station is chosen so that t never decreases.

The orientation test is what tells the strip from impostors. Along a branch of roots
with slope dt/ds, the sheet's normal at B is (dt/ds)·(B' × R), so flipped normals mean
either t running backwards (a sheet folded through itself: the rulings cross) or the
edge of regression (the sheet's cusp) lying between the two curves. In particular the
determinant vanishes wherever A'(s) ∥ B'(t), whatever the ruling: when the tangents
point the *same* way that root is a genuine torsal ruling (two curves in parallel
planes are joined exactly there); when they point *opposite* ways the normals are
opposite and the root is rejected (for two coaxial circles, the double cone through
their common centre instead of the frustum between them). Flipped roots on a
decreasing branch are what a curve B running the other way produces, and the message
then says to reverse B.

Algorithm (all stations at once)
--------------------------------
1. Stations: ``Segments + 1`` parameters on A, evenly spaced in arc length
   (:mod:`.stations`).
2. Sampling: B is sampled on every smooth span, with both one-sided values at its
   corners, and the whole ``stations × samples`` matrix of f and of f_t is one thin
   matrix product (see :func:`_brackets`).
3. Certified isolation (:mod:`.isolation`): every sample interval where f changes sign
   or comes within reach of zero is judged with a bound on f_tt from B's derivatives,
   and split until each piece provably holds no root, exactly one simple root (a
   bracket), or a double root to rounding. So no root of f is missed between samples —
   not two roots close together at an inflection of a section, nor where A' and B'
   become parallel, nor at a curve's end (the guarantee and its one assumption are in
   that module). *Flat runs*, where f is zero on consecutive samples (A and B coplanar
   there, e.g. two straight pieces in one plane), contribute their two ends instead; a
   sign change across a corner of B is a root at the corner (the rulings fan through
   it: a cone).
4. Refinement: every bracket is refined to machine precision at once, by Newton's
   method kept inside the brackets (:mod:`.brackets`) with f_t = det[R, A', B''],
   starting from the root of the cubic that matches f and f_t at the bracket's ends —
   usually two evaluations of B in all.
5. Selection: the monotone dynamic programme of :mod:`.selection` follows one branch of
   roots, predicting each step from the branch slope dt/ds = −f_s/f_t, with
   f_s = det[R, A'', B'].
6. Planar pieces: where the chosen partners lie in a flat run the strip is planar and
   any pairing is developable; it is drawn as two triangles (a fan of rulings through a
   point of B, then a fan through a point of A), split along the shorter diagonal; a
   piece whose edges have corners is a polygon, cut into such fans from the corners
   along diagonals that stay inside it (:func:`_strip_triangulation`). Fans
   through a point of A also arise where B is straight and A curved (the ZVE roof: a
   triangle leaning on a straight edge) or at a corner of A: there t jumps between two
   neighbouring stations, the fan's apex s* is found by solving f for s, and rulings
   are added through A(s*) at about the station spacing.
7. Stations with no consistently oriented root get the plain loft's partner (in arc
   length between their neighbours' partners) or else the least-warped sample of B
   there, if its warp is within ``warp_tolerance``. The others admit no torsal ruling:
   each run of them is closed by flat triangles between the two stretches of A and B
   (:mod:`.fans`), and so are the ends of B beyond the first and last ruling and any
   stretch of B that t jumps over with no torsal fan to cover it. Their rulings are
   flagged (``fan``), the strip has no holes and stays developable (every triangle is
   flat), and the message gives the share of the strip's area they take.
8. Check: every output ruling's warp is measured from the curves at its (s, t) — end
   points and exact tangents, :func:`.warp.warp_angles`, NaN where no normal is defined
   — and ``valid`` is that warp within the tolerance (never NaN). A station taken as
   torsal that fails the check joins the fans and the strip is closed again.
9. A closed B whose seam is away from the strip's start is solved again from A(0)'s
   partner, so that t can run once round B through its seam.
"""

from __future__ import annotations

from bisect import bisect_right
from dataclasses import dataclass, replace
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..closest import sample_parameters
from ..curve_base import Curve, FloatArray
from ..curves import Line, NurbsCurve, Polyline
from ..vec_ops import cross, det, dot, extent, norm, position_rounding, unit
from .brackets import refine_roots
from .end_cones import Rulings, smooth_ends
from .fans import area_share, creased_fans, fan_share, zigzag
from .isolation import IntervalBounds, Pieces, interval_bounds, isolate, third_bound
from .selection import monotone_path
from .stations import LengthMap, Spacing, station_parameters
from .warp import in_plane_tangent, warp_angles

BoolArray = NDArray[np.bool_]
IntArray = NDArray[np.int64]

#: A sample is zero (flat) where |det[R, Â', B̂']| <= FLAT·|R|: coplanar to 1e-10 rad.
FLAT = 1e-10
#: A jump of the unit tangent larger than this (rad) at a breakpoint is a corner.
CORNER_ANGLE = 1e-7
#: Parameter offset for one-sided evaluation beside a corner.
SIDE = 1e-11
#: Most candidates kept per station for the selection.
MAX_CANDIDATES = 8
#: Most rounds of checking the torsal rulings and closing the stations that fail.
MAX_CHECKS = 3

ROOT, CORNER, FLAT_END = 0, 1, 2


@dataclass(frozen=True)
class RulingResult:
    """The rulings of a developable strip between curves A and B, in order along the strip.

    Rulings run from ``A(s)`` to ``B(t)``. There is one per station on A (``Segments + 1``
    of them, marked in ``stations``) plus the rulings of any fan through a single point of
    A (a planar triangle), which repeat that point's s, and of the flat triangles that
    close the strip where no torsal ruling exists (marked in ``fan``, with the stations
    there); so ``len(s) >= Segments + 1``.
    Neither ``s`` nor ``t`` ever decreases, so rulings do not cross — except that on a
    closed curve B, t increases *cyclically*: from the strip's start it runs up to 1,
    wraps through B's seam to 0 and rises again.
    """

    s: FloatArray  #: parameters on curve A, in [0, 1]
    t: FloatArray  #: partner parameters on curve B, in [0, 1]
    starts: FloatArray  #: (n, 3) points A(s)
    ends: FloatArray  #: (n, 3) points B(t)
    #: warp angle per ruling, rad, in [0, π]: the angle between the end normals R × A'
    #: and R × B', recomputed from the output (NaN where a normal is not defined)
    warp: FloatArray
    signed_warp: FloatArray  #: angle from N1 to N2 about the ruling, rad, in (−π, π] (or NaN)
    valid: BoolArray  #: the recomputed warp is within the tolerance (never where it is NaN)
    message: str | None  #: how much of the strip is closed by flat triangles, or None
    stations: BoolArray  #: True for the Segments + 1 station rulings, False for added fan rulings
    #: True for the rulings of the flat triangles that close the strip where no torsal
    #: ruling exists (gap stations and the rulings added there), False for torsal ones
    fan: BoolArray
    fan_share: float  #: share of the strip's area in those triangles, 0 to 1
    #: share of the area in fans that crease the sheet (apexes on both curves, see
    #: :func:`.fans.creased_fans`); a single cone closing a strip's end is smooth and not counted
    creased_share: float = 0.0

    @property
    def max_warp(self) -> float:
        """Largest warp angle, rad."""
        return float(self.warp.max(initial=0.0))


# -- sampling B ----------------------------------------------------------------------------


def _jumps(left: FloatArray, right: FloatArray) -> BoolArray:
    """Whether the unit tangent turns by more than CORNER_ANGLE from ``left`` to ``right``."""
    left, right = unit(left), unit(right)
    return np.arctan2(norm(cross(left, right)), dot(left, right)) > CORNER_ANGLE


def _is_linear(curve: Curve) -> bool:
    return isinstance(curve, Line | Polyline) or (
        isinstance(curve, NurbsCurve) and curve.degree == 1 and not curve.is_rational
    )


class _Rotated(Curve):
    """A closed curve started from parameter ``shift`` instead of its seam: C((t + shift) mod 1)."""

    closed = True

    def __init__(self, curve: Curve, shift: float) -> None:
        self.curve, self.shift = curve, float(shift)

    def original(self, t: FloatArray) -> FloatArray:
        """The wrapped curve's parameter for parameters ``t`` of this one."""
        u = np.asarray(t, dtype=float) + self.shift
        return np.where(u >= 1.0, u - 1.0, u)

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        return self.curve.derivatives(self.original(np.atleast_1d(np.asarray(t, dtype=float))), order)

    def _breakpoints(self) -> FloatArray:
        moved = self.curve._breakpoints() - self.shift
        return np.unique(np.concatenate([[0.0, 1.0], np.where(moved < 0, moved + 1.0, moved)]))


@dataclass
class _Grid:
    """Samples of curve B: nominal parameters, where they are evaluated (a corner's first
    copy just before it), and B and its first three derivatives there."""

    t: FloatArray
    at: FloatArray
    pair: BoolArray  #: (m−1,) samples j and j+1 are the two sides of one corner
    points: FloatArray
    tangents: FloatArray
    second: FloatArray  #: B'' there
    third: FloatArray  #: B''' there
    left_second: FloatArray  #: B'' and B''' as seen from the left (they differ at knots)
    left_third: FloatArray

    def interval_bounds(self, diameter: float) -> IntervalBounds:
        """The bounds of f'' and of f's reach on every sample interval (:mod:`.isolation`);
        the zero-width intervals between the two sides of a corner get reach −1 (never
        looked at: a sign change there is a corner root)."""
        width = self.at[1:] - self.at[:-1]
        speed = norm(self.tangents)
        second = norm(self.second)
        left_second = second if self.left_second is self.second else norm(self.left_second)
        bounds = interval_bounds(
            width,
            (speed[:-1], speed[1:]),
            (second[:-1], left_second[1:]),
            third_bound(self.third[:-1], self.left_third[1:]),
            diameter,
        )
        bounds.reach[self.pair] = -1.0
        return bounds


def _sample_grid(curve: Curve, minimum: int) -> tuple[_Grid, FloatArray]:
    """Samples of B (a straight span needs only its ends: f is linear in t there) and its
    corners, found and sampled on both sides in the same evaluation."""
    t = sample_parameters(curve, per_span=1 if _is_linear(curve) else 2, minimum=minimum)
    breaks = curve._breakpoints()[1:-1]
    m = len(t)
    if not len(breaks):  # one smooth span
        points, tangents, second, third = curve.derivatives(t, 3)
        smooth = _Grid(t, t, np.zeros(m - 1, dtype=bool), points, tangents, second, third, second, third)
        return smooth, breaks
    points, tangents, second, third = curve.derivatives(np.concatenate([t, breaks - SIDE]), 3)
    # samples include every breakpoint; compare each with its left neighbour's tangent
    at_break = np.searchsorted(t, breaks)
    kink = _jumps(tangents[m:], tangents[at_break])
    kinks = breaks[kink]
    # from the left, a smooth breakpoint shows its left-hand derivatives
    left = np.arange(m)
    left[at_break[~kink]] = m + np.flatnonzero(~kink)
    if not len(kinks):
        right = np.arange(m)
        t_all, at, pair = t, t, np.zeros(m - 1, dtype=bool)
    else:
        # a corner gets two samples: its left copy just before its right copy
        index = at_break[kink]
        right = np.insert(np.arange(m), index, m + np.flatnonzero(kink))
        left = np.insert(left, index, m + np.flatnonzero(kink))
        t_all = np.insert(t, index, kinks)
        at = np.insert(t, index, kinks - SIDE)
        pair = np.diff(t_all) == 0
    on_right = points[right], tangents[right], second[right], third[right]
    grid = _Grid(t_all, at, pair, *on_right, second[left], third[left])
    return grid, kinks


# -- brackets and candidates -----------------------------------------------------------------


@dataclass
class _Brackets:
    """Sample intervals worth a closer look: where the determinant of station ``rows``
    changes sign between samples ``cols`` and ``cols + 1`` or may come near zero (with
    its values there), and the samples where it is zero."""

    rows: IntArray
    cols: IntArray
    f_low: FloatArray
    f_high: FloatArray
    zeros: IntArray  #: flat indices ``row * m + col`` of zero samples, increasing


def _brackets(a0: FloatArray, a1: FloatArray, grid: _Grid, reach: FloatArray) -> _Brackets:
    """Intervals where f = det[B_j − A_i, Â'_i, B'_j] (unit tangent of A) changes sign or
    may reach zero — |f| at an end within ``reach`` (see :mod:`.isolation`) — over all
    station–sample pairs.

    By the cyclic symmetry of the triple product,
    ``det[B − A, Â', B'] = Â'·(B' × B) − (A × Â')·B'``, so the whole matrix is one
    (n×6)(6×m) product. Coordinates are taken about a common centre to keep the terms
    small. It is formed in blocks of rows: a block that small keeps OpenBLAS on one
    thread (threads cost more than they save on a product this thin, and stall when the
    machine is busy) and lets every block reuse the memory of the last.
    """
    b0, b1 = grid.points, grid.tangents
    n, m = len(a0), len(b0)
    size = float(norm(extent(np.concatenate([a0, b0]))))  # the diagonal of the bounding box
    centre = 0.5 * (a0[n // 2] + b0[m // 2])  # about the middle of both curves
    units = unit(a1)
    left = np.concatenate([units, cross(units, a0 - centre)], axis=1)
    right = np.empty((6, m))
    right[:3], right[3:] = cross(b1, b0 - centre).T, b1.T
    speed_b = norm(b1)
    # a flat run is coplanar to FLAT, or to the rounding of the positions themselves far
    # from the origin (site coordinates: the input points carry ~1e-7 m at 1e9 m)
    rounding = max(position_rounding(a0), position_rounding(b0))
    flat_scale = (FLAT * size + rounding) * speed_b
    block = max(1, 40_000 // right.shape[1])
    found: list[tuple[IntArray, ...]] = []
    zeros: list[IntArray] = []
    for first in range(0, n, block):  # blocks bound memory and threads; each is vectorised
        f = left[first : first + block] @ right
        negative = np.signbit(f)
        size_f = np.abs(f)
        look = (negative[:, :-1] != negative[:, 1:]) | (np.minimum(size_f[:, :-1], size_f[:, 1:]) <= reach)
        maybe = np.flatnonzero(size_f <= flat_scale)
        if len(maybe):  # rare: test the candidates against their own ruling length
            r, c = np.divmod(maybe, m)
            exact = maybe[size_f.flat[maybe] <= (FLAT * norm(b0[c] - a0[r + first]) + rounding) * speed_b[c]]
            if len(exact):
                zero = np.zeros(f.shape, dtype=bool)
                zero.flat[exact] = True
                look &= ~(zero[:, :-1] | zero[:, 1:])
                zeros.append(exact + first * m)
        r, c = np.divmod(np.flatnonzero(look), m - 1)
        found.append((r + first, c, f[r, c], f[r, c + 1]))
    joined = found[0] if len(found) == 1 else [np.concatenate(x) for x in zip(*found, strict=True)]
    zero_flat = np.concatenate(zeros) if zeros else np.empty(0, dtype=np.int64)
    return _Brackets(*joined, zero_flat)


def _cubic_start(
    x0: FloatArray, x1: FloatArray, f0: FloatArray, f1: FloatArray, d0: FloatArray, d1: FloatArray
) -> FloatArray:
    """A first guess for each bracket's root, good to O(h⁴): the root of the cubic that
    matches f and f' at both ends of the bracket (two Newton steps on that cubic from
    the secant's root), so that one Newton step on f reaches rounding."""
    h = x1 - x0
    d0, d1 = d0 * h, d1 * h  # slopes in the bracket's unit coordinate
    rise = f1 - f0
    # the cubic f0 + u·(d0 + u·(c2 + u·c3)) and its slope d0 + u·(2·c2 + 3·c3·u)
    c2 = 3.0 * rise - 2.0 * d0 - d1
    c3 = d0 + d1 - 2.0 * rise
    c2_twice, c3_thrice = 2.0 * c2, 3.0 * c3
    with np.errstate(divide="ignore", invalid="ignore"):
        u = np.minimum(np.maximum(-f0 / rise, 0.0), 1.0)  # (np.clip is slow on small arrays)
        for _ in range(2):
            step = (f0 + u * (d0 + u * (c2 + u * c3))) / (d0 + u * (c2_twice + u * c3_thrice))
            u = np.where(np.isfinite(step), np.minimum(np.maximum(u - step, 0.0), 1.0), u)
    return x0 + u * h


def _rounding_scale(size_a: FloatArray, b0: FloatArray, speed_a: FloatArray, b1: FloatArray) -> FloatArray:
    """Size of the rounding error of det[B − A, A', B'] from |A|, B, |A'|, B': positions are
    rounded relative to their own magnitude, not to the ruling's length."""
    return (size_a + norm(b0)) * speed_a * norm(b1)


def _oriented(
    r: FloatArray,
    ta: FloatArray,
    tb: FloatArray,
    rr: FloatArray | None = None,
    aa: FloatArray | None = None,
    bb: FloatArray | None = None,
) -> BoolArray:
    """Whether N1 = R × A' and N2 = R × B' point to the same side (or one vanishes).

    N1·N2 = |R|²(A'·B') − (R·A')(R·B') and |N|² = |R|²|T|² − (R·T)² (Lagrange's identity).
    ``rr``, ``aa``, ``bb`` are |R|², |A'|², |B'|² when the caller has them.
    """
    rr = dot(r, r) if rr is None else rr
    aa = dot(ta, ta) if aa is None else aa
    bb = dot(tb, tb) if bb is None else bb
    ra, rb = dot(r, ta), dot(r, tb)
    n1n1 = np.maximum(rr * aa - ra * ra, 0.0)
    n2n2 = np.maximum(rr * bb - rb * rb, 0.0)
    return rr * dot(ta, tb) - ra * rb >= -1e-9 * np.sqrt(n1n1 * n2n2)


@dataclass
class _Candidates:
    """Candidate partners, one entry each, sorted by station then t."""

    row: IntArray
    t: FloatArray
    kind: IntArray
    slope: FloatArray  #: dt/ds of the branch (0 at corners and flat ends)
    low: FloatArray  #: flat run extent (NaN for roots and corners)
    high: FloatArray
    points: FloatArray  #: (k, 3) B(t)
    tangents: FloatArray  #: (k, 3) tangent of B there (the in-plane one at a corner)
    oriented: BoolArray  #: normals point to the same side (signed warp ~0, not ~π)

    def subset(self, keep: BoolArray | IntArray) -> _Candidates:
        return _Candidates(*(getattr(self, name)[keep] for name in _FIELDS))


_FIELDS = tuple(_Candidates.__dataclass_fields__)


def _find_candidates(
    curve_b: Curve, grid: _Grid, a0: FloatArray, a1: FloatArray, a2: FloatArray
) -> _Candidates:
    """All candidate partners of all stations: refined roots (every root of f, isolated
    with the guarantee of :mod:`.isolation`), corner roots, flat-run ends."""
    m = len(grid.t)
    units = unit(a1)
    diameter = float(norm(extent(np.concatenate([a0, grid.points]))))
    bounds = grid.interval_bounds(diameter)
    found = _brackets(a0, units, grid, bounds.reach)
    rows, cols, f_low, f_high = found.rows, found.cols, found.f_low, found.f_high
    corner_rows = corner_cols = run_rows = run_first = run_last = np.empty(0, dtype=np.int64)
    if grid.pair.any():
        at_corner = grid.pair[cols]
        corner_rows, corner_cols = rows[at_corner], cols[at_corner]
        keep = ~at_corner
        rows, cols, f_low, f_high = rows[keep], cols[keep], f_low[keep], f_high[keep]
    if len(found.zeros):
        # runs of zero samples along a row: a run of positive extent is flat (its two ends
        # are candidates), a single zero sample is a root
        z = found.zeros
        run_start = np.ones(len(z), dtype=bool)
        run_start[1:] = (np.diff(z) != 1) | (z[1:] % m == 0)
        run_end = np.ones(len(z), dtype=bool)
        run_end[:-1] = run_start[1:]
        run_rows, run_first = np.divmod(z[run_start], m)
        run_last = z[run_end] % m
    flat = grid.t[run_last] > grid.t[run_first] if len(run_last) else np.empty(0, dtype=bool)

    # sift again with the rulings' own lengths in place of the diameter (a sign change
    # is always kept), then judge what is left, subdividing where a root pair may hide
    r_low = grid.points[cols] - a0[rows]
    r_high = grid.points[cols + 1] - a0[rows]
    length_low, length_high = norm(r_low), norm(r_high)
    reach = bounds.slope[cols] * (np.maximum(length_low, length_high) + bounds.chord[cols])
    keep = (np.signbit(f_low) != np.signbit(f_high)) | (np.minimum(np.abs(f_low), np.abs(f_high)) <= reach)
    if not keep.all():
        rows, cols, f_low, f_high = rows[keep], cols[keep], f_low[keep], f_high[keep]
        r_low, r_high = r_low[keep], r_high[keep]
        length_low, length_high = length_low[keep], length_high[keep]
    # f' there is det[R, Â', B''] = B'' · (R × Â'), gathered for these intervals only
    ua = units[rows]
    d_low = dot(cross(r_low, ua), grid.second[cols])
    d_high = dot(cross(r_high, ua), grid.left_second[cols + 1])
    none = np.empty(0)
    first = Pieces(rows, grid.at[cols], grid.at[cols + 1], f_low, f_high, d_low, d_high, *([none] * 7))

    def ends(pieces: Pieces, index: IntArray) -> Pieces:
        c = cols[index]
        return replace(
            pieces.take(index),
            speed0=norm(grid.tangents[c]),
            speed1=norm(grid.tangents[c + 1]),
            second0=norm(grid.second[c]),
            second1=norm(grid.left_second[c + 1]),
            bound3=bounds.third[c],
            r0=length_low[index],
            r1=length_high[index],
        )

    def evaluate_b(x: FloatArray) -> list[FloatArray]:
        return curve_b.derivatives(x, 2)

    isolated = isolate(first, bounds.curvature[cols], evaluate_b, a0, units, ends)
    rows = isolated.rows
    point_rows = np.concatenate([run_rows[~flat], isolated.double_rows])
    point_t = np.concatenate([grid.t[run_first[~flat]], isolated.double_t])

    # refine every bracket at once: Newton with f_t = det[R, A', B''], bisection fallback;
    # each bracket's last evaluation (at its root, to rounding) is kept for what follows
    root_rows = np.concatenate([rows, point_rows]) if len(point_rows) else rows
    k = len(rows)
    root_t = np.concatenate([np.empty(k), point_t]) if len(point_rows) else np.empty(k)
    b0, b1 = np.empty((2, len(root_rows), 3))
    f, f_t = np.empty((2, len(root_rows)))
    speed_a, size_a = norm(a1), norm(a0)

    def evaluate(x: FloatArray, index: IntArray, i: IntArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        c0, c1, c2 = curve_b.derivatives(x, 2)
        plane = cross(c0 - a0[i], a1[i])  # det[R, A', X] = X · (R × A')
        value, slope = dot(plane, c1), dot(plane, c2)
        root_t[index], b0[index], b1[index], f[index], f_t[index] = x, c0, c1, value, slope
        return value, slope, _rounding_scale(size_a[i], c0, speed_a[i], c1)

    def coplanarity(x: FloatArray, index: IntArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        return evaluate(x, index, rows[index])

    if k:
        i = isolated
        start = _cubic_start(i.low, i.high, i.f_low, i.f_high, i.d_low, i.d_high)
        refine_roots(coplanarity, i.low, i.high, i.f_low, start)
    if len(point_rows):
        evaluate(root_t[k:], np.arange(k, len(root_rows)), point_rows)

    # the slope dt/ds = −f_s/f_t of each smooth root's branch
    r = b0 - a0[root_rows]
    f_s = det(r, a2[root_rows], b1)
    slope = np.minimum(np.maximum(-f_s / np.where(f_t == 0, 1e-300, f_t), -1e6), 1e6)
    rr, bb, aa = dot(r, r), dot(b1, b1), speed_a[root_rows] ** 2
    # converged onto a jump of B' that is not a flagged corner: f is far from zero there
    jumped = np.abs(f) > 1e-7 * np.sqrt(rr * aa * bb)
    kind = np.where(jumped, CORNER, ROOT)
    slope[jumped] = 0.0
    nan = np.full(len(root_rows), np.nan)
    candidates = _Candidates(
        root_rows, root_t, kind, slope, nan, nan, b0, b1, _oriented(r, a1[root_rows], b1, rr, aa, bb)
    )
    if len(corner_rows) == 0 and not flat.any():
        return candidates.subset(np.lexsort((candidates.t, candidates.row)))

    # roots at corners of B: the tangent plane turns about the corner (a cone through it)
    corner_points = grid.points[corner_cols + 1]
    corner_tangents = in_plane_tangent(
        corner_points - a0[corner_rows],
        a1[corner_rows],
        grid.tangents[corner_cols],
        grid.tangents[corner_cols + 1],
    )
    # the two ends of every flat run
    flat_rows = np.repeat(run_rows[flat], 2)
    flat_cols = np.column_stack([run_first[flat], run_last[flat]]).reshape(-1)
    extra_rows = np.concatenate([corner_rows, flat_rows])
    extra_points = np.concatenate([corner_points, grid.points[flat_cols]])
    extra_tangents = np.concatenate([corner_tangents, grid.tangents[flat_cols]])
    corner_nan = np.full(len(corner_rows), np.nan)
    extra = _Candidates(
        extra_rows,
        np.concatenate([grid.t[corner_cols], grid.t[flat_cols]]),
        np.concatenate([np.full(len(corner_rows), CORNER), np.full(len(flat_rows), FLAT_END)]),
        np.zeros(len(extra_rows)),
        np.concatenate([corner_nan, np.repeat(grid.t[run_first[flat]], 2)]),
        np.concatenate([corner_nan, np.repeat(grid.t[run_last[flat]], 2)]),
        extra_points,
        extra_tangents,
        _oriented(extra_points - a0[extra_rows], a1[extra_rows], extra_tangents),
    )
    both = _Candidates(
        *(np.concatenate([getattr(candidates, name), getattr(extra, name)]) for name in _FIELDS)
    )
    return both.subset(np.lexsort((both.t, both.row)))


def _pad(c: _Candidates, n: int) -> tuple[FloatArray, FloatArray, IntArray]:
    """Candidates as ``(n, K)`` arrays (NaN padded) and the index of each cell's candidate."""
    # drop duplicates (a flat end that is also a root) and keep at most MAX_CANDIDATES
    first = np.ones(len(c.row), dtype=bool)
    first[1:] = (c.row[1:] != c.row[:-1]) | (c.t[1:] - c.t[:-1] > 1e-13)
    keep = np.flatnonzero(first)
    rows = c.row[keep]
    column = np.arange(len(rows)) - np.searchsorted(rows, rows, side="left")
    fits = column < MAX_CANDIDATES
    keep, rows, column = keep[fits], rows[fits], column[fits]
    k = max(int(column.max(initial=-1)) + 1, 1)
    t = np.full((n, k), np.nan)
    slope = np.full((n, k), np.nan)
    index = np.full((n, k), -1, dtype=np.int64)
    t[rows, column] = c.t[keep]
    slope[rows, column] = c.slope[keep]
    index[rows, column] = keep
    return t, slope, index


def _longest_monotone(t: FloatArray) -> BoolArray:
    """Mask of a longest non-decreasing subsequence (patience sorting)."""
    tails: list[float] = []
    tail_index: list[int] = []
    parent = np.full(len(t), -1, dtype=np.int64)
    for i, x in enumerate(t.tolist()):  # fallback only: when the selection had to step back
        j = bisect_right(tails, x)
        if j == len(tails):
            tails.append(x)
            tail_index.append(i)
        else:
            tails[j] = x
            tail_index[j] = i
        parent[i] = tail_index[j - 1] if j > 0 else -1
    keep = np.zeros(len(t), dtype=bool)
    i = tail_index[-1] if tail_index else -1
    while i >= 0:
        keep[i] = True
        i = parent[i]
    return keep


def _neighbours(partnered: BoolArray) -> tuple[IntArray, IntArray]:
    """The stations with a partner, and where each other station falls among them: ``i``
    such that its nearest partnered neighbours are ``stations[i − 1]`` and ``stations[i]``
    (there is none before it when i = 0, none after it when i = len(stations))."""
    stations = np.flatnonzero(partnered)
    return stations, np.searchsorted(stations, np.flatnonzero(~partnered))


# -- the solve ---------------------------------------------------------------------------------


class _Strip:
    """One solve of :func:`ruling_developable`: the state its steps share."""

    def __init__(
        self, curve_a: Curve, curve_b: Curve, segments: int, tolerance: float, spacing: Spacing, samples: int
    ) -> None:
        self.curve_a, self.curve_b = curve_a, curve_b
        self.segments, self.tolerance, self.spacing = segments, tolerance, spacing
        self.map_a = LengthMap(curve_a)
        if not self.map_a.total > 0:
            raise ValueError("Curve A has zero length: there is nothing to place rulings along.")
        self.s = station_parameters(curve_a, segments + 1, spacing, self.map_a)
        n = len(self.s)
        breaks = curve_a._breakpoints()[1:-1]
        if len(breaks):
            a0, a1, a2 = curve_a.derivatives(np.concatenate([self.s, breaks - SIDE, breaks + SIDE]), 2)
            self.a0, self.a1, self.a2 = a0[:n], a1[:n], a2[:n]
            self.kinks_a = breaks[_jumps(a1[n : n + len(breaks)], a1[n + len(breaks) :])]
        else:  # one smooth span: no corners
            self.a0, self.a1, self.a2 = curve_a.derivatives(self.s, 2)
            self.kinks_a = breaks
        self.grid, self.kinks_b = _sample_grid(curve_b, samples)
        #: pairs of stations (i, i + 1) between which t jumps over a stretch of B that no
        #: torsal fan covers (set by :meth:`a_fans`)
        self.holes: list[int] = []
        if not self._chords_b[-1] > 0:
            raise ValueError("Curve B has zero length: there is nothing to place rulings along.")

    def length_b(self, t: FloatArray) -> FloatArray:
        """Arc length along B to each ``t``, as the length of the polyline through B's samples
        (exact on straight pieces, within ~1e-5 elsewhere: ample for placing the plain loft's
        rulings at invalid stations and a fan's rulings at about the station spacing)."""
        return np.interp(t, self.grid.t, self._chords_b)

    def parameter_b(self, length: FloatArray) -> FloatArray:
        """The inverse of :meth:`length_b`."""
        return np.interp(length, self._chords_b, self.grid.t)

    @cached_property
    def _chords_b(self) -> FloatArray:
        points = self.grid.points
        chords = np.empty(len(points))
        chords[0] = 0.0
        np.cumsum(norm(points[1:] - points[:-1]), out=chords[1:])
        return chords

    @cached_property
    def station_lengths(self) -> FloatArray:
        """Arc length along A to each station."""
        if self.spacing == "length":
            return np.arange(len(self.s)) * (self.map_a.total / (len(self.s) - 1))
        return self.map_a.length_at(self.s)

    # -- steps 2–5: candidates and the monotone choice ---------------------------------------

    def choose(self) -> tuple[IntArray, _Candidates]:
        """The chosen candidate per station (−1 where none) and the consistently oriented
        candidates."""
        n = len(self.s)
        found = _find_candidates(self.curve_b, self.grid, self.a0, self.a1, self.a2)
        good = found if found.oriented.all() else found.subset(found.oriented)
        chosen = np.full(n, -1, dtype=np.int64)
        if len(good.row) and (good.row[1:] > good.row[:-1]).all() and (good.t[1:] >= good.t[:-1]).all():
            # at most one candidate per station, in order along B: nothing to choose
            chosen[good.row] = np.arange(len(good.row))
            return chosen, good
        t_pad, slope_pad, index_pad = _pad(good, n)
        rows = np.flatnonzero(~np.isnan(t_pad).all(axis=1))
        if len(rows):
            s = self.s[rows]
            pick = monotone_path(t_pad[rows], slope_pad[rows], s[1:] - s[:-1])
            chosen[rows] = index_pad[rows, pick]
            t = good.t[chosen[rows]]
            if (t[1:] - t[:-1] < -1e-12).any():  # the selection had to step back: keep a monotone subset
                chosen[rows[~_longest_monotone(t)]] = -1
        return chosen, good

    # -- step 6: planar pieces ------------------------------------------------------------------

    def flat_fans(self, t: FloatArray, chosen: IntArray, good: _Candidates) -> tuple[list, BoolArray]:
        """Two triangles for every run of stations inside one planar piece.

        Rewrites ``t`` there and returns the fans ``(s*, t_low, t_high)`` through a point
        of A, and a mask of the stations of planar pieces.
        """
        n = len(t)
        has = chosen >= 0
        is_flat = np.zeros(n, dtype=bool)
        is_flat[has] = good.kind[chosen[has]] == FLAT_END
        fans: list[tuple[float, float, float]] = []
        if not is_flat.any():
            return fans, is_flat
        low = np.where(is_flat, good.low[chosen], np.nan)
        high = np.where(is_flat, good.high[chosen], np.nan)
        # consecutive flat stations whose flat intervals overlap form one planar piece
        joins = is_flat[1:] & is_flat[:-1] & (low[1:] <= high[:-1]) & (low[:-1] <= high[1:])
        begins = np.flatnonzero(is_flat & ~np.concatenate([[False], joins]))
        finishes = np.flatnonzero(is_flat & ~np.concatenate([joins, [False]]))
        for i0, i1 in zip(begins, finishes, strict=True):  # one pass per planar piece (few)
            t_in = low[i0] if i0 == 0 or np.isnan(t[i0 - 1]) else max(low[i0], t[i0 - 1])
            t_out = high[i1] if i1 == n - 1 or np.isnan(t[i1 + 1]) else min(high[i1], t[i1 + 1])
            t_out = max(t_out, t_in)
            corners_a = self.kinks_a[(self.kinks_a > self.s[i0]) & (self.kinks_a < self.s[i1])]
            corners_b = self.kinks_b[(self.kinks_b > t_in) & (self.kinks_b < t_out)]
            if len(corners_a) or len(corners_b):  # a polygon, not a quad
                fans += self._polygon_fans(t, i0, i1, corners_a, t_in, corners_b, t_out)
                continue
            b_in, b_out = self.curve_b.point_at(np.array([t_in, t_out]))
            # the shorter diagonal: a fan through B(t_in) then one through A(s_i1), or a fan
            # through A(s_i0) then one through B(t_out)
            if norm(self.a0[i1] - b_in) <= norm(self.a0[i0] - b_out):
                t[i0 : i1 + 1] = t_in
                fans.append((float(self.s[i1]), float(t_in), float(t_out)))
            else:
                t[i0 : i1 + 1] = t_out
                fans.append((float(self.s[i0]), float(t_in), float(t_out)))
        return fans, is_flat

    def _polygon_fans(
        self,
        t: FloatArray,
        i0: int,
        i1: int,
        corners_a: FloatArray,
        t_in: float,
        corners_b: FloatArray,
        t_out: float,
    ) -> list[tuple[float, float, float]]:
        """Fans for a planar piece whose edges have corners: a polygon, cut into triangles
        that each join an edge of one curve (between corners) to a corner of the other.

        Rewrites ``t`` for stations ``i0..i1`` (each takes the corner of B its triangle
        leans on) and returns the fans through corners of A; see :func:`_strip_triangulation`.
        """
        sa = np.concatenate([[self.s[i0]], corners_a, [self.s[i1]]])
        tb = np.concatenate([[t_in], corners_b, [t_out]])
        stations = self.s[i0 : i1 + 1]
        piece = t[i0 : i1 + 1]
        fans = []
        i = j = 0
        for along_a in _strip_triangulation(self.curve_a.point_at(sa), self.curve_b.point_at(tb)):
            if along_a:  # triangle A_i A_i+1 B_j: the stations between lean on B_j
                piece[(stations >= sa[i]) & (stations <= sa[i + 1])] = tb[j]
                i += 1
            else:  # triangle A_i B_j B_j+1: a fan through A_i
                fans.append((float(sa[i]), float(tb[j]), float(tb[j + 1])))
                j += 1
        return fans

    # -- step 7: stations without a torsal partner ------------------------------------------------

    def near_partners(self, t: FloatArray) -> None:
        """Give every station without a partner one whose warp is within the tolerance
        (the strip is torsal to within it there), if it has one between its neighbours'
        partners: the plain loft's (in arc length between those neighbours) if that is
        within it, else the least-warped sample of B. The others stay NaN, to be closed
        by fans."""
        gap = np.isnan(t)
        missing = np.flatnonzero(gap)
        if len(missing) == 0:
            return
        partnered, window = _neighbours(~gap)
        # the neighbours' partners, padded with B's ends: [window] is the one before, [window + 1] after
        padded = np.concatenate([[0.0], t[partnered], [1.0]])
        lo, hi = padded[window], padded[window + 1]
        length_a = self.station_lengths
        padded = np.concatenate([[0.0], length_a[partnered], [self.map_a.total]])
        a_lo, a_hi = padded[window], padded[window + 1]
        span = a_hi - a_lo
        fraction = np.where(span > 0, (length_a[missing] - a_lo) / np.where(span > 0, span, 1.0), 0.0)
        b_lo, b_hi = self.length_b(np.concatenate([lo, hi])).reshape(2, -1)
        loft = np.minimum(np.maximum(self.parameter_b(b_lo + fraction * (b_hi - b_lo)), lo), hi)
        points, tangents = self.curve_b.derivatives(loft, 1)
        loft_warp = warp_angles(self.a0[missing], points, self.a1[missing], tangents)
        # else the least angle between the end normals among B's samples in the window
        grid = self.grid
        angle = _normal_angles(self.a0[missing], self.a1[missing], grid.points, grid.tangents)
        inside = (grid.t[None, :] >= lo[:, None]) & (grid.t[None, :] <= hi[:, None])
        angle = np.where(inside & ~np.isnan(angle), angle, np.inf)
        best = np.argmin(angle, axis=1)
        sample_ok = angle[np.arange(len(missing)), best] <= self.tolerance
        with np.errstate(invalid="ignore"):
            loft_ok = loft_warp <= self.tolerance
        t[missing] = np.where(loft_ok, loft, np.where(sample_ok, grid.t[best], np.nan))
        # consecutive stations in one window may have picked samples out of order
        known = ~np.isnan(t)
        t[known] = np.maximum.accumulate(t[known])

    def close_gaps(self, t: FloatArray) -> list[tuple[FloatArray, FloatArray]]:
        """Close every run of stations still without a partner (NaN in ``t``) with flat
        triangles (:mod:`.fans`), and the stretches of B beyond the first and the last
        ruling with fans through A's ends.

        A stretch of B between two torsal stations that no torsal fan covers (t jumps
        there: :meth:`a_fans` lists it in ``holes``) is closed the same way.

        Sets ``t`` at the gap stations and returns the added rulings as ``(s, t)`` arrays.
        """
        n = len(t)
        gap = np.isnan(t)
        added: list[tuple[FloatArray, FloatArray]] = []
        for i in self.holes:  # one pass per stretch of B that t jumps over (rare)
            if gap[i] or gap[i + 1]:
                continue  # closed with the gap around it
            tb = self.gap_parameters(float(t[i]), float(t[i + 1]))
            a, b = zigzag(self.station_lengths[i : i + 2], self.length_b(tb))
            inner = slice(1, len(a) - 1)  # the two stations' own rulings are there already
            added.append((self.s[i + a[inner]], tb[b[inner]]))
        begins = np.flatnonzero(gap & ~np.concatenate([[False], gap[:-1]]))
        finishes = np.flatnonzero(gap & ~np.concatenate([gap[1:], [False]]))
        closed = self.curve_b.closed
        for i0, i1 in zip(begins, finishes, strict=True):  # one pass per gap (few)
            k0, k1 = max(i0 - 1, 0), min(i1 + 1, n - 1)
            t_lo = float(t[i0 - 1]) if i0 > 0 else 0.0
            t_hi = float(t[i1 + 1]) if i1 < n - 1 else (float(t[0]) if closed and i0 > 0 else 1.0)
            if t_hi < t_lo and not closed:
                t_hi = t_lo
            if t_hi < t_lo:  # through the seam of a closed B
                before, after = self.gap_parameters(t_lo, 1.0), self.gap_parameters(0.0, t_hi)[1:]
                tb = np.concatenate([before, after])
                lb = np.concatenate([self.length_b(before), self.length_b(after) + self._chords_b[-1]])
            else:
                tb = self.gap_parameters(t_lo, t_hi)
                lb = self.length_b(tb)
            i, j = zigzag(self.station_lengths[k0 : k1 + 1], lb)
            station = k0 + i
            # the first ruling from each gap station is its station ruling; the rest are added
            first = np.ones(len(i), dtype=bool)
            first[1:] = i[1:] != i[:-1]
            is_gap = (station >= i0) & (station <= i1)
            t[station[first & is_gap]] = tb[j[first & is_gap]]
            extra = ~(first & is_gap)
            if i0 > 0:
                extra[0] = False  # the torsal ruling before the gap
            if i1 < n - 1:
                extra[-1] = False  # and after it
            if extra.any():
                added.append((self.s[station[extra]], tb[j[extra]]))
        if not closed:
            if t[0] > 0.0:
                tb = self.gap_parameters(0.0, float(t[0]))[:-1]
                added.append((np.zeros(len(tb)), tb))
            if t[-1] < 1.0:
                tb = self.gap_parameters(float(t[-1]), 1.0)[1:]
                added.append((np.ones(len(tb)), tb))
        return added

    def gap_parameters(self, t_low: float, t_high: float) -> FloatArray:
        """Parameters on B from ``t_low`` to ``t_high`` at about the station spacing, with
        every corner of B between them."""
        t = self.fan_parameters(t_low, t_high)
        corners = self.kinks_b[(self.kinks_b > t_low) & (self.kinks_b < t_high)]
        return np.unique(np.concatenate([t, corners])) if len(corners) else t

    # -- step 6 (continued): fans through a point of A ---------------------------------------------

    def a_fans(
        self, t: FloatArray, slope: FloatArray, regular: BoolArray
    ) -> list[tuple[float, float, float]]:
        """Fans through single points of A, found where t jumps between two stations.

        Along one branch t steps by about Δs·(mean slope); a much larger step means the
        strip's path in the (s, t) square runs vertically in between: a fan of rulings
        from one point A(s*) to a stretch of B (a triangle on a straight piece of B, or a
        cone at a corner of A). s* solves f(s, t_mid) = 0 for s, or is the corner of A.
        """
        s = self.s
        dt = t[1:] - t[:-1]
        predicted = 0.5 * (s[1:] - s[:-1]) * (slope[:-1] + slope[1:])
        jump = regular[:-1] & regular[1:] & (dt > 1e-10) & (np.abs(dt - predicted) > 0.25 * dt)
        pairs = np.flatnonzero(jump)
        if len(pairs) == 0:
            return []
        # a hole, if no torsal fan covers it, only where the step is over twice both neighbouring
        # ones (the slope is a poor guide where f_t vanishes, as at an inflection)
        before = np.concatenate([[np.nan], dt[:-1]])
        after = np.concatenate([dt[1:], [np.nan]])
        neighbours = np.fmax(before, after)
        with np.errstate(invalid="ignore"):
            dwarfs = dt > 2.0 * neighbours  # (never with no neighbour to compare)
        t_mid = 0.5 * (t[pairs] + t[pairs + 1])
        bm0, bm1 = self.curve_b.derivatives(t_mid, 1)
        f_left = det(bm0 - self.a0[pairs], self.a1[pairs], bm1)
        f_right = det(bm0 - self.a0[pairs + 1], self.a1[pairs + 1], bm1)
        apex = np.full(len(pairs), np.nan)
        which = np.flatnonzero(f_left * f_right < 0)
        if len(which):

            def coplanarity(x: FloatArray, index: IntArray) -> tuple[FloatArray, FloatArray, FloatArray]:
                c0, c1, c2 = self.curve_a.derivatives(x, 2)
                k = which[index]
                r = bm0[k] - c0
                # f and f_s = det[R, A'', B'] (the term det[−A', A', B'] vanishes)
                return (
                    det(r, c1, bm1[k]),
                    det(r, c2, bm1[k]),
                    _rounding_scale(norm(c0), bm0[k], norm(c1), bm1[k]),
                )

            low, high = s[pairs[which]], s[pairs[which] + 1]
            apex[which] = refine_roots(coplanarity, low, high, f_left[which])
            # a root that converged onto a corner of A (a jump of f) or onto a station is that point
            for exact in (self.kinks_a, s):
                if len(exact):
                    nearest = exact[np.argmin(np.abs(apex[:, None] - exact[None, :]), axis=1)]
                    apex = np.where(np.abs(apex - nearest) <= 1e-12, nearest, apex)
        fans = []
        for k, i in enumerate(pairs):  # one pass per possible fan (rare)
            s_star = float(apex[k])
            if np.isnan(s_star):
                inside = self.kinks_a[(self.kinks_a >= s[i]) & (self.kinks_a <= s[i + 1])]
                if len(inside) == 0:
                    if dwarfs[i]:
                        self.holes.append(int(i))
                    continue
                s_star = float(inside[0])
            extent = self._fan_extent(s_star, float(t[i]), float(t[i + 1]))
            if extent is not None:
                fans.append((s_star, *extent))
            elif dwarfs[i]:
                self.holes.append(int(i))
        return fans

    def _fan_extent(self, s_star: float, t0: float, t1: float) -> tuple[float, float] | None:
        """The stretch of B inside [t0, t1] over which rulings from A(s*) are torsal."""
        c0 = self.curve_a.point_at(s_star)
        sides = self.curve_a.derivatives(np.clip([s_star - SIDE, s_star + SIDE], 0.0, 1.0), 1)[1]
        window = (self.grid.t >= t0) & (self.grid.t <= t1)
        ts = np.unique(np.concatenate([[t0, t1], self.grid.t[window]]))
        # at a corner of B the stretch may end with the tangent from either side
        at_kink = np.isin(ts, self.kinks_b)
        b0, b1 = self.curve_b.derivatives(np.concatenate([ts, ts[at_kink] - SIDE]), 1)
        r = b0 - c0
        r = np.concatenate([r[: len(ts)], r[: len(ts)][at_kink]])
        scale = norm(r) * norm(b1)
        scale = np.where(scale > 0, scale, 1.0)
        g_left = det(r, unit(sides[0]), b1) / scale
        g_right = det(r, unit(sides[1]), b1) / scale
        # torsal: flat (B straight there), or between the two one-sided tangents of a corner
        torsal_all = (np.abs(g_left) <= 1e-9) | (np.abs(g_right) <= 1e-9) | (g_left * g_right < 0)
        torsal = torsal_all[: len(ts)]
        torsal[at_kink] |= torsal_all[len(ts) :]
        if torsal.sum() < 2:
            return None
        first = int(np.argmax(torsal))
        last = len(ts) - 1 - int(np.argmax(torsal[::-1]))
        if not torsal[first : last + 1].all() or ts[last] <= ts[first]:
            return None
        return float(ts[first]), float(ts[last])

    def fan_parameters(self, t_low: float, t_high: float) -> FloatArray:
        """Parameters on B for a fan's rulings, at about the station spacing along A."""
        spacing = self.map_a.total / self.segments
        lb = self.length_b(np.array([t_low, t_high]))
        # at most one fan ruling per station (B far longer than A — a stray vertex at 1e12 —
        # must not ask for billions); and at least the fan's two bounding rulings
        wanted = (lb[1] - lb[0]) / spacing if spacing > 0 else 1.0
        count = max(2, int(np.ceil(min(wanted, self.segments + 1) - 1e-9)) + 1)
        t = self.parameter_b(np.linspace(lb[0], lb[1], count))
        t[0], t[-1] = t_low, t_high
        return np.maximum.accumulate(t)

    # -- assembly -----------------------------------------------------------------------------------

    def merge(
        self, t: FloatArray, gap: BoolArray, fans: list, added: list[tuple[FloatArray, FloatArray]]
    ) -> tuple[FloatArray, FloatArray, IntArray, BoolArray]:
        """All rulings ordered along the strip: the stations, every torsal fan's rulings
        ``(s*, t_low, t_high)`` and the rulings ``added`` to close gaps.

        Returns s, t, per ruling the station it is (−1 for an added ruling) and whether
        it closes a gap (the gap stations ``gap`` and the ``added`` rulings).
        """
        n = len(self.s)
        if not fans and not added:
            return self.s, t, np.arange(n), gap.copy()
        s_parts, t_parts, gap_parts = [self.s], [t], [gap]
        for s_star, t_low, t_high in fans:
            ts = self.fan_parameters(t_low, t_high)
            s_parts.append(np.full(len(ts), s_star))
            t_parts.append(ts)
            gap_parts.append(np.zeros(len(ts), dtype=bool))
        for s_add, t_add in added:
            s_parts.append(s_add)
            t_parts.append(t_add)
            gap_parts.append(np.ones(len(s_add), dtype=bool))
        s_all, t_all, gap_all = np.concatenate(s_parts), np.concatenate(t_parts), np.concatenate(gap_parts)
        order = np.lexsort((np.arange(len(s_all)) >= n, t_all, s_all))
        repeat = np.zeros(len(order), dtype=bool)
        repeat[1:] = (np.diff(s_all[order]) <= 1e-14) & (np.diff(t_all[order]) <= 1e-14)
        # of two equal rulings keep the station (an added ruling sorts after its equal station)
        later_station = np.flatnonzero(repeat & (order < n))
        order[later_station - 1] = order[later_station]
        order = order[~repeat]
        return s_all[order], t_all[order], np.where(order < n, order, -1), gap_all[order]

    def measured(
        self, s: FloatArray, t: FloatArray, source: IntArray, chosen: IntArray, good: _Candidates
    ) -> tuple[FloatArray, FloatArray, FloatArray]:
        """The output rulings A(s) → B(t) and their signed warp, measured from the curves:
        the end points and exact tangents at (s, t), :func:`.warp.warp_angles` of those
        (NaN where no normal is defined), with the tangent at a corner taken in the plane
        of the ruling where the corner straddles it (:func:`_corner_tangent`), and an end
        shared with both neighbouring rulings (the apex of a fan of flat triangles)
        taking the other end's plane. Nothing of the solve enters but the curves'
        evaluations at those very parameters (a station's, a refined root's), which are
        reused rather than repeated. Returns starts, ends and the signed warp."""
        k = len(s)
        station = source >= 0
        rows = source[station]
        if len(rows) == k:  # no added rulings
            starts, ta = self.a0[rows], self.a1[rows]
        else:
            starts, ta = np.empty((2, k, 3))
            starts[station], ta[station] = self.a0[rows], self.a1[rows]
            starts[~station], ta[~station] = self.curve_a.derivatives(s[~station], 1)
        # B where a station's chosen root still stands (a flat end or corner is re-evaluated)
        root = np.full(k, -1)
        picked = chosen[rows]
        root[station] = np.where(picked >= 0, picked, -1)
        kept = root >= 0
        kept[kept] = (good.t[root[kept]] == t[kept]) & (good.kind[root[kept]] == ROOT)
        if kept.all():
            ends, tb = good.points[root], good.tangents[root]
        else:
            ends, tb = np.empty((2, k, 3))
            ends[kept], tb[kept] = good.points[root[kept]], good.tangents[root[kept]]
            ends[~kept], tb[~kept] = self.curve_b.derivatives(t[~kept], 1)
        ruling = ends - starts
        if len(self.kinks_b):
            at_b = np.isin(t, self.kinks_b)
            if at_b.any():
                left = self.curve_b.derivatives(t[at_b] - SIDE, 1)[1]
                tb[at_b] = _corner_tangent(ruling[at_b], ta[at_b], left, tb[at_b])
        if len(self.kinks_a):
            at_a = np.min(np.abs(s[:, None] - self.kinks_a[None, :]), axis=1) <= 1e-12
            if at_a.any():
                around = np.clip(np.concatenate([s[at_a] - SIDE, s[at_a] + SIDE]), 0.0, 1.0)
                sides = self.curve_a.derivatives(around, 1)[1]
                ta[at_a] = _corner_tangent(ruling[at_a], tb[at_a], *np.split(sides, 2))
        signed = warp_angles(starts, ends, ta, tb, signed=True, apex_a=_fan_apex(s), apex_b=_fan_apex(t))
        return starts, ends, signed


def ruling_developable(
    curve_a: Curve,
    curve_b: Curve,
    segments: int,
    warp_tolerance: float = 0.01,
    *,
    spacing: Spacing = "length",
    samples: int = 128,
) -> RulingResult:
    """The developable strip between two curves, as rulings from A to B.

    Args:
        curve_a: the base curve; ``segments + 1`` stations are placed along it.
        curve_b: the partner curve. Both should run the same way (from the same end of
            the strip); otherwise almost no ruling is torsal and the strip is mostly flat
            triangles (:func:`.alternatives.better_pairing` says whether reversing B helps).
        segments: number of rulings minus one (at least 1).
        warp_tolerance: largest warp angle (rad) a ruling may have and count as valid,
            e.g. 0.01; for a sheet allowed a warp factor of k rad/m over rulings about
            L long, k·L.
        spacing: ``"length"`` (default) spaces the stations evenly in arc length along A,
            ``"parameter"`` evenly in its parameter.
        samples: how many samples of B start the root isolation (at least this many and
            two per smooth span of B); roots closer together are separated by subdivision,
            so more samples only trade matrix work for fewer subdivisions.

    Returns:
        A :class:`RulingResult`. On curves cut from a developable the rulings are the true
        ones to rounding (partner error ~1e-14, warp ~1e-14 rad).

    See the module docstring for the geometry and the algorithm. Two coplanar segments
    bound a planar quad, drawn as two triangles: a fan through B(0) from the three
    stations, then a fan through A(1) whose rulings are about as far apart on B:

    >>> from nodes.geometry.curves import Line
    >>> r = ruling_developable(Line([0, 0, 0], [2, 0, 0]), Line([0, 1, 0], [3, 2, 0]), 2)
    >>> r.s.tolist(), r.t.round(3).tolist(), r.message
    ([0.0, 0.5, 1.0, 1.0, 1.0, 1.0, 1.0], [0.0, 0.0, 0.0, 0.25, 0.5, 0.75, 1.0], None)
    """
    if int(segments) != segments or segments < 1:
        raise ValueError(f"Segments must be a whole number >= 1; got {segments}.")
    tolerance = float(warp_tolerance)
    if not (np.isfinite(tolerance) and tolerance >= 0):
        raise ValueError(f"The warp tolerance must be a number >= 0 (rad); got {warp_tolerance}.")
    samples = max(int(samples), 8)
    result = _solve(curve_a, curve_b, int(segments), tolerance, spacing, samples)
    if curve_b.closed and result.fan.any():
        # B's seam may sit away from where the strip starts: restart B at A(0)'s partner
        # (or, when A is closed too, at the partner of its end, the same point)
        station = result.t[result.stations]
        torsal = (result.valid & ~result.fan)[result.stations]
        shift = station[0] if torsal[0] else station[-1] if curve_a.closed and torsal[-1] else None
        if shift is not None and 1e-9 < shift < 1.0 - 1e-9:
            rotated = _Rotated(curve_b, shift)
            again = _solve(curve_a, rotated, int(segments), tolerance, spacing, samples)
            if again.fan_share < result.fan_share:
                return replace(again, t=rotated.original(again.t))
    return result


def _solve(
    curve_a: Curve, curve_b: Curve, segments: int, tolerance: float, spacing: Spacing, samples: int
) -> RulingResult:
    """One solve of :func:`ruling_developable` as the module docstring describes it."""
    strip = _Strip(curve_a, curve_b, segments, tolerance, spacing, samples)
    n = len(strip.s)

    chosen, good = strip.choose()
    has = chosen >= 0
    t = np.full(n, np.nan)
    slope = np.zeros(n)
    t[has], slope[has] = good.t[chosen[has]], good.slope[chosen[has]]
    fans, planar = strip.flat_fans(t, chosen, good)
    regular = has & ~planar
    strip.near_partners(t)
    fans += strip.a_fans(t, slope, regular)

    for _ in range(MAX_CHECKS):
        gap = np.isnan(t)
        closed_t = t.copy()
        added = strip.close_gaps(closed_t)
        kept = _outside_gaps(fans, strip.s, gap)
        s_out, t_out, source, fan = strip.merge(closed_t, gap, kept, added)
        # the warp of the output, from the curves' exact tangents (NaN where undefined)
        starts, ends, signed = strip.measured(s_out, t_out, source, chosen, good)
        warp = np.abs(signed)
        with np.errstate(invalid="ignore"):
            valid = warp <= tolerance  # NaN (no normal defined) is never valid
        # a station ruling taken as torsal that fails the check is a gap after all
        failed = source[(source >= 0) & ~fan & ~valid]
        if len(failed) == 0:
            break
        t[failed] = np.nan
    # each end's fans as one smooth cone, joining the torsal rulings at the ruling through
    # the curve's end point, where that ruling exists (see .end_cones)
    smoothed = smooth_ends(curve_a, curve_b, Rulings(s_out, t_out, source, fan))
    if len(smoothed.s) != len(s_out) or not np.array_equal(smoothed.s, s_out):
        starts2, ends2, signed2 = strip.measured(smoothed.s, smoothed.t, smoothed.source, chosen, good)
        with np.errstate(invalid="ignore"):
            valid2 = np.abs(signed2) <= tolerance
        torsal = ~smoothed.fan
        kept_torsal = np.count_nonzero(valid2 & torsal) >= np.count_nonzero(valid & ~fan)
        if kept_torsal and valid2[torsal & (smoothed.source < 0)].all():
            s_out, t_out, source, fan = smoothed.s, smoothed.t, smoothed.source, smoothed.fan
            starts, ends, signed, valid = starts2, ends2, signed2, valid2
            warp = np.abs(signed)
    share = fan_share(starts, ends, fan)
    creased = area_share(starts, ends, creased_fans(starts, ends, fan))
    message = _message(int(np.count_nonzero(fan[source >= 0])), n, tolerance, share, creased)
    return RulingResult(
        s_out, t_out, starts, ends, warp, signed, valid, message, source >= 0, fan, share, creased
    )


def _outside_gaps(fans: list, s: FloatArray, gap: BoolArray) -> list:
    """The torsal fans ``(s*, t_low, t_high)`` whose apex is neither inside a gap's stretch
    of A (from the torsal station before the gap to the one after it) nor a gap station."""
    if not fans or not gap.any():
        return fans
    n = len(s)
    begins = np.flatnonzero(gap & ~np.concatenate([[False], gap[:-1]]))
    finishes = np.flatnonzero(gap & ~np.concatenate([gap[1:], [False]]))
    low, high = s[np.maximum(begins - 1, 0)], s[np.minimum(finishes + 1, n - 1)]
    through_gap = s[gap]
    return [
        fan for fan in fans if not (np.any((low < fan[0]) & (fan[0] < high)) or np.any(through_gap == fan[0]))
    ]


def _strip_triangulation(a: FloatArray, b: FloatArray) -> list[bool]:
    """Triangles for the planar polygon a[0] … a[-1], b[-1] … b[0] whose every diagonal
    joins a vertex of chain ``a`` to one of chain ``b``: the moves, True to advance along
    ``a`` (triangle a_i a_i+1 b_j), False along ``b`` (triangle a_i b_j b_j+1).

    Each step takes the shorter new diagonal among the moves whose triangle turns the way
    the polygon does and whose diagonal crosses no edge of the polygon (so a chain that
    bends towards the other, as a V, is fanned from its corner instead of being cut off).
    """
    polygon = np.concatenate([a, b[::-1]])
    # the polygon's normal (Newell) and two axes of its plane, for signed areas and crossings
    normal = cross(polygon, np.roll(polygon, -1, axis=0)).sum(axis=0)
    normal = normal / max(float(norm(normal)), 1e-300)
    x_axis = unit(polygon[np.argmax(norm(polygon - polygon[0]))] - polygon[0])
    flat = np.column_stack([polygon @ x_axis, polygon @ cross(normal, x_axis)])
    fa, fb = flat[: len(a)], flat[len(a) :][::-1]
    size = float(np.ptp(flat, axis=0).max()) or 1.0
    edges = np.stack([flat, np.roll(flat, -1, axis=0)], axis=1)

    def area(p: FloatArray, q: FloatArray, r: FloatArray) -> float:
        return float((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]))

    def crosses(p: FloatArray, q: FloatArray) -> bool:
        """Whether segment pq properly crosses an edge of the polygon (shared ends do not count)."""
        e0, e1 = edges[:, 0], edges[:, 1]
        d = q - p
        side0 = d[0] * (e0[:, 1] - p[1]) - d[1] * (e0[:, 0] - p[0])
        side1 = d[0] * (e1[:, 1] - p[1]) - d[1] * (e1[:, 0] - p[0])
        e = e1 - e0
        side_p = e[:, 0] * (p[1] - e0[:, 1]) - e[:, 1] * (p[0] - e0[:, 0])
        side_q = e[:, 0] * (q[1] - e0[:, 1]) - e[:, 1] * (q[0] - e0[:, 0])
        tiny = 1e-12 * size * size
        return bool(np.any((side0 * side1 < -tiny * tiny) & (side_p * side_q < -tiny * tiny)))

    moves: list[bool] = []
    i = j = 0
    while i < len(a) - 1 or j < len(b) - 1:
        options = []  # (invalid, diagonal length, move)
        if i < len(a) - 1:
            diagonal = (fa[i + 1], fb[j])
            bad = area(fa[i], fa[i + 1], fb[j]) <= 1e-12 * size * size or crosses(*diagonal)
            options.append((bad, float(np.hypot(*(diagonal[1] - diagonal[0]))), True))
        if j < len(b) - 1:
            diagonal = (fa[i], fb[j + 1])
            bad = area(fa[i], fb[j + 1], fb[j]) <= 1e-12 * size * size or crosses(*diagonal)
            options.append((bad, float(np.hypot(*(diagonal[1] - diagonal[0]))), False))
        move = min(options)[2]
        moves.append(move)
        i, j = (i + 1, j) if move else (i, j + 1)
    return moves


def _normal_angles(a: FloatArray, ta: FloatArray, b: FloatArray, tb: FloatArray) -> FloatArray:
    """The angle (0 to π) between N1 = R × A'_i and N2 = R × B'_j with R = B_j − A_i, for
    every i and j: ``(len(a), len(b))``.

    All of it comes from (i, j) matrix products: |R|², R·A', R·B' and A'·B' give
    N1·N2 = |R|²(A'·B') − (R·A')(R·B') (Lagrange's identity), and N1 × N2 = R·det[R, A', B']
    with det[R, A', B'] = A'·(B' × B) − (A × A')·B'. Coordinates are taken about a
    common centre, as in :func:`_brackets`.
    """
    centre = 0.5 * (a[len(a) // 2] + b[len(b) // 2])
    a, b = a - centre, b - centre
    aa, bb = np.einsum("ij,ij->i", a, a), np.einsum("ij,ij->i", b, b)
    rr = np.maximum(bb[None, :] - 2.0 * (a @ b.T) + aa[:, None], 0.0)
    ra = ta @ b.T - np.einsum("ij,ij->i", a, ta)[:, None]
    rb = np.einsum("ij,ij->i", b, tb)[None, :] - a @ tb.T
    triple = ta @ cross(tb, b).T - cross(a, ta) @ tb.T
    return np.arctan2(np.sqrt(rr) * np.abs(triple), rr * (ta @ tb.T) - ra * rb)


def _corner_tangent(ruling: FloatArray, other: FloatArray, left: FloatArray, right: FloatArray) -> FloatArray:
    """The tangent of a curve at a corner for rulings ending there: the in-plane blend of
    :func:`.warp.in_plane_tangent`, or, where that runs along the ruling (no normal), the
    one-sided tangent that gives a defined normal with the smaller warp."""
    tangent = in_plane_tangent(ruling, other, left, right)
    along = norm(cross(ruling, tangent)) <= 1e-10 * norm(ruling)
    if along.any():
        r, o = ruling[along], other[along]
        sides = unit(left[along]), unit(right[along])
        zero = np.zeros_like(r)
        warps = [warp_angles(zero, r, o, side) for side in sides]
        pick_left = ~np.isnan(warps[0]) & (np.isnan(warps[1]) | (warps[0] <= warps[1]))
        tangent[along] = np.where(pick_left[:, None], sides[0], sides[1])
    return tangent


def _fan_apex(parameters: FloatArray) -> BoolArray:
    """Rulings whose end is shared with both neighbouring rulings: the apex of a fan."""
    same = parameters[1:] == parameters[:-1]
    apex = np.zeros(len(parameters), dtype=bool)
    apex[1:-1] = same[:-1] & same[1:]
    return apex


def _message(fan_stations: int, n: int, tolerance: float, share: float, creased: float = 0.0) -> str | None:
    """How much of the strip had to be closed by flat triangles; None when none."""
    if fan_stations == 0 and share == 0.0:
        return None
    area = f"{100 * share:.3g} % of the strip's area"
    if creased == 0.0:
        where = f"at {fan_stations} of {n} stations" if fan_stations else "beyond the last torsal ruling"
        return (
            f"closed by smooth cones through single points of the curves {where}, where no ruling "
            f"tangent to both curves exists ({area}; the sheet stays smooth and developable)"
        )
    if creased < share:
        area = f"{area}, {100 * creased:.3g} % in creased fans"
    if fan_stations == 0:
        return f"no torsal ruling reaches part of curve B: it is closed by flat triangles ({area})"
    return (
        f"no torsal ruling within {tolerance:g} rad at {fan_stations} of {n} stations: "
        f"closed by flat triangles ({area})"
    )
