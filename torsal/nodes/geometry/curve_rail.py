"""Rails that run *on* given curves: the ruled surface between two curves through chosen rulings.

A developable strip found between curves A and B is a set of rulings A(s_i) → B(t_i).
Lofting splines through the ruling ends (:meth:`RuledSurface.from_rulings`) makes a
surface whose edges only pass *through* those points: between rulings they leave the
curves, so two strips that share a curve do not share an edge, and the surface's
tangent plane along a ruling is that of the spline, not of the curves the rulings were
made torsal on.

Here the rails are the curves themselves, reparameterised: rail A is u ↦ A(σ(u)) with σ
the monotone piecewise-cubic (PCHIP) interpolant through (u_i, s_i), and the same for
B. So

- the isocurve u = u_i is exactly ruling i (to rounding);
- both edges lie on A and B everywhere, so neighbouring strips meet exactly;
- the rail's tangent at u_i is σ'(u_i)·A'(s_i), parallel to A's own tangent: the surface's
  tangent plane along ruling i is the one the ruling was solved for, and a warp
  recomputed from the surface is the curves' warp;
- a stretch where s stands still (a fan of rulings through one point of A) keeps the
  rail on that point (PCHIP never overshoots a flat run).

On a closed curve a parameter that runs on through the seam (t rising to 1, then again
from 0) is unwrapped before interpolating and wrapped back when evaluated.

σ is scipy's ``PchipInterpolator`` (Fritsch–Carlson slopes, Moler's one-sided three-point
ends, extrapolating with the end pieces), written out in :class:`Pace`: a strip's rails
are built on every re-solve, and the general interpolator's set-up costs more than the
rest of the rail. :func:`ruled_between` fits both rails' paces in one pass, at ruling
parameters whose steps are made once per ruling count.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike

from .curve_base import Curve, FloatArray
from .curves import Line, NurbsCurve, Polyline
from .ruled import RuledSurface, _uniform
from .vec_ops import extent

#: Curves whose points do not depend on which other parameters, or which derivatives, are
#: evaluated with them (each point is computed alone, the same way at every order), so a
#: point from one evaluation is the point another would give, bit for bit.
POINTWISE = (NurbsCurve, Line, Polyline)


def unwrap_cyclic(t: FloatArray) -> FloatArray:
    """Parameters on a closed curve made non-decreasing by adding a turn after each drop
    of more than half the parameter range (the seam)."""
    t = np.asarray(t, dtype=float)
    drops = t[1:] - t[:-1] < -0.5  # (np.diff, without its set-up)
    return t + np.concatenate([[0.0], np.cumsum(drops)])


class Pace:
    """The monotone piecewise-cubic interpolant (PCHIP) through ``(u_i, p_i)``, ``u``
    increasing, with its derivatives: the same interpolant as scipy's
    ``PchipInterpolator(u, p, extrapolate=True)`` (to rounding).

    The slope at an inner point is 0 where the neighbouring chords' slopes differ in sign
    or one is 0, else their weighted harmonic mean; at the ends it is the one-sided
    three-point estimate, set to 0 where its sign differs from the end chord's and to 3×
    that chord's slope where it would overshoot (a straight line through two points).
    Monotone data give a monotone interpolant; a run of equal values stays flat.
    """

    def __init__(self, u: FloatArray, p: FloatArray) -> None:
        c3, c2, c1, c0 = _pchip(_Steps(u), p[None], (p[1:] - p[:-1])[None])
        self.u, self.c3, self.c2, self.c1, self.c0 = u, c3[0], c2[0], c1[0], c0[0]

    @classmethod
    def _rows(cls, steps: _Steps, p: FloatArray, dp: FloatArray) -> list[Pace]:
        """One interpolant per row of ``p`` ``(k, n)``, all at the same parameters
        (``steps``; chords ``dp``), fitted in one pass: the rows' coefficients are the ones
        each would get alone (every step is elementwise)."""
        c3, c2, c1, c0 = _pchip(steps, p, dp)
        paces = []
        for row in range(len(p)):
            pace = cls.__new__(cls)
            pace.u, pace.c3, pace.c2, pace.c1, pace.c0 = steps.u, c3[row], c2[row], c1[row], c0[row]
            paces.append(pace)
        return paces

    def __call__(self, x: FloatArray, nu: int = 0) -> FloatArray:
        """The interpolant's ``nu``-th derivative at ``x``."""
        return self.derivatives(np.asarray(x, dtype=float), nu)[nu]

    def derivatives(self, x: FloatArray, order: int) -> list[FloatArray]:
        """The interpolant and its derivatives up to ``order`` (at most 3) at ``x``; the end
        pieces extend beyond the first and last points."""
        i = np.minimum(np.maximum(np.searchsorted(self.u, x, side="right") - 1, 0), len(self.u) - 2)
        z = x - self.u[i]
        c3, c2, c1 = self.c3[i], self.c2[i], self.c1[i]
        out = [((c3 * z + c2) * z + c1) * z + self.c0[i]]
        if order >= 1:
            out.append((3.0 * c3 * z + 2.0 * c2) * z + c1)
        if order >= 2:
            out.append(6.0 * c3 * z + 2.0 * c2)
        if order >= 3:
            out.append(6.0 * c3 + 0.0 * z)
        return out


class _Steps:
    """What PCHIP takes of the parameters ``u`` alone, the same for every interpolant at
    them: the steps ``h`` and, for three or more points, the weights of the inner slopes'
    harmonic mean and the end steps."""

    def __init__(self, u: FloatArray) -> None:
        h = u[1:] - u[:-1]
        self.u, self.h = u, h
        self.increasing: bool | None = None  # (known for the uniform ones)
        if len(u) > 2:
            self.w1, self.w2 = 2.0 * h[1:] + h[:-1], h[1:] + 2.0 * h[:-1]
            self.w_sum = self.w1 + self.w2
            self.first, self.last = h[:2].tolist(), h[-1:-3:-1].tolist()  # (h0, h1), (h_last, h_next)

    @staticmethod
    @lru_cache(maxsize=64)
    def uniform(n: int) -> _Steps:
        """The steps of the ``n`` ≥ 2 evenly spaced parameters :func:`_uniform`, made once
        per count (every strip's rails have them), read-only; with ``increasing``, whether
        no step is 0 or less (the check of :class:`CurveRail`)."""
        steps = _Steps(_uniform(n))
        steps.increasing = not (steps.h <= 0.0).any()
        for array in vars(steps).values():
            if isinstance(array, np.ndarray):
                array.setflags(write=False)
        return steps


def _pchip(
    steps: _Steps, p: FloatArray, dp: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """The PCHIP cubics' coefficients (c3, c2, c1, c0) on the pieces between the points of
    each row of ``p`` ``(k, n)`` (one interpolant per row, all at the parameters of
    ``steps``), whose chords are ``dp = p[:, 1:] − p[:, :-1]``: see :class:`Pace`."""
    h = steps.h
    m = dp / h
    slopes = np.empty(p.shape)
    if p.shape[1] == 2:
        slopes[:] = m
    else:
        with np.errstate(divide="ignore", invalid="ignore"):
            harmonic = steps.w_sum / (steps.w1 / m[:, :-1] + steps.w2 / m[:, 1:])
        sign = np.sign(m)
        # 0 where the neighbouring chords' slopes differ in sign or one is 0 (or NaN)
        slopes[:, 1:-1] = np.where(sign[:, 1:] * sign[:, :-1] > 0, harmonic, 0.0)
        (h0, h1), (h_last, h_next) = steps.first, steps.last
        for row, chords in zip(slopes, m.tolist(), strict=True):
            row[0] = _end_slope(h0, h1, chords[0], chords[1])
            row[-1] = _end_slope(h_last, h_next, chords[-1], chords[-2])
    # the cubic on [u_i, u_i+1] in z = u − u_i: ((c3·z + c2)·z + c1)·z + c0
    starts = slopes[:, :-1]
    bend = (starts + slopes[:, 1:] - 2.0 * m) / h
    return bend / h, (m - starts) / h - bend, starts, p[:, :-1]


def _end_slope(h0: float, h1: float, m0: float, m1: float) -> float:
    """PCHIP's slope at an end, from the end step and chord slope (``h0``, ``m0``) and the
    next ones (``h1``, ``m1``): the one-sided three-point estimate, kept monotone."""
    d = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1)
    if _sign(d) != _sign(m0):
        return 0.0
    if _sign(m0) != _sign(m1) and abs(d) > 3.0 * abs(m0):
        return 3.0 * m0
    return d


def _sign(x: float) -> float:
    """``np.sign`` of a float: −1, 0 or 1, and NaN (unequal to every sign) for NaN."""
    return math.nan if x != x else (x > 0) - (x < 0)


_UNPACED = "a curve rail needs increasing u and non-decreasing curve parameters"


#: Most Newton steps :meth:`CurveRail._crossings` takes on the pace (quadratic from the
#: interpolated start: two or three reach rounding).
CROSSING_STEPS = 6


class CurveRail(Curve):
    """``C(σ(u))``: curve C run at the pace of the monotone interpolant σ through
    ``(u_i, p_i)`` (``params`` → ``curve_params``, non-decreasing). Exact derivatives to
    order 3 by the chain rule."""

    def __init__(self, curve: Curve, params: ArrayLike, curve_params: ArrayLike) -> None:
        u = np.asarray(params, dtype=float)
        p = np.asarray(curve_params, dtype=float)
        if curve.closed:
            p = unwrap_cyclic(p)
        if len(u) < 2 or u.shape != p.shape or (u[1:] - u[:-1] <= 0).any() or (p[1:] - p[:-1] < 0).any():
            raise ValueError(_UNPACED)
        self._set(curve, u, p, Pace(u, p))

    def _set(self, curve: Curve, u: FloatArray, p: FloatArray, pace: Pace) -> None:
        self.curve = curve
        self.params, self.curve_params = u, p
        self._pace = pace
        self.closed = False  # the rail covers the stretch of the curve between its rulings

    @classmethod
    def _pair(
        cls, curve_a: Curve, s: FloatArray, curve_b: Curve, t: FloatArray, steps: _Steps
    ) -> tuple[tuple[CurveRail, CurveRail], bool]:
        """``CurveRail(curve_a, u, s)`` and ``CurveRail(curve_b, u, t)`` (``s``, ``t`` and
        ``u = steps.u`` ``(n,)`` arrays, ``n`` ≥ 2), their checks and paces made in one pass
        for both; and whether both rails' parameters are non-decreasing numbers (no NaN),
        which the checks alone do not say."""
        rows = [unwrap_cyclic(q) if curve.closed else q for curve, q in ((curve_a, s), (curve_b, t))]
        p = np.concatenate(rows).reshape(2, -1)
        dp = p[:, 1:] - p[:, :-1]
        rising = bool(dp.min() >= 0.0)  # (false where a NaN is)
        if not steps.increasing or (not rising and (dp < 0.0).any()):  # (steps: _Steps.uniform)
            raise ValueError(_UNPACED)
        rails = []
        for curve, row, pace in zip((curve_a, curve_b), p, Pace._rows(steps, p, dp), strict=True):
            rail = cls.__new__(cls)
            rail._set(curve, steps.u, row, pace)
            rails.append(rail)
        return (rails[0], rails[1]), rising

    def _pace_derivatives(self, u: FloatArray, order: int) -> list[FloatArray]:
        return self._pace.derivatives(u, order)

    def _wrapped(self, p: FloatArray) -> FloatArray:
        if self.curve.closed:
            return np.mod(p, 1.0)
        return np.clip(p, 0.0, 1.0)

    def _compose(self, values: list[FloatArray], pace: list[FloatArray], order: int) -> list[FloatArray]:
        out = [values[0]]
        d1 = pace[1][:, None] if order >= 1 else None
        if order >= 1:
            out.append(values[1] * d1)
        if order >= 2:
            d2 = pace[2][:, None]
            out.append(values[2] * d1**2 + values[1] * d2)
        if order >= 3:
            d3 = pace[3][:, None]
            out.append(values[3] * d1**3 + 3.0 * values[2] * d1 * d2 + values[1] * d3)
        return out

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        if order > 3:
            raise ValueError("curve rail derivatives are available to order 3")
        u = np.atleast_1d(np.asarray(t, dtype=float)).reshape(-1)
        pace = self._pace_derivatives(u, order)
        return self._compose(self.curve.derivatives(self._wrapped(pace[0]), order), pace, order)

    @property
    def anchor(self) -> FloatArray:
        return self.curve.anchor

    def local_derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        if order > 3:
            raise ValueError("curve rail derivatives are available to order 3")
        u = np.atleast_1d(np.asarray(t, dtype=float)).reshape(-1)
        pace = self._pace_derivatives(u, order)
        return self._compose(self.curve.local_derivatives(self._wrapped(pace[0]), order), pace, order)

    def _breakpoints(self) -> FloatArray:
        """The ruling parameters, and where the pace crosses one of the curve's own
        breakpoints (or its seam) — between them the rail is smooth."""
        crossing = self._crossings(self.curve._breakpoints())
        return np.unique(np.clip(np.concatenate([self.params, crossing, [0.0, 1.0]]), 0.0, 1.0))

    def _find_kinks(self) -> FloatArray:
        """Where the pace crosses one of the curve's kinks (a closed curve's seam when it
        is a corner): the rail turns there as the curve does, and nowhere else (σ is C¹
        and a stretch where it stands still keeps the rail on one point)."""
        return np.unique(np.clip(self._crossings(self.curve.kinks()), 0.0, 1.0))

    def _crossings(self, inner: FloatArray) -> FloatArray:
        """The u where the pace crosses the curve parameters ``inner`` (each turn of them
        on a closed curve), strictly between the first and last ruling's."""
        u, p = self.params, self.curve_params
        turns = np.arange(np.floor(p[0]), np.ceil(p[-1]) + 1.0)
        marks = (turns[:, None] + inner[None, :]).ravel() if self.curve.closed else inner
        marks = marks[(marks > p[0]) & (marks < p[-1])]
        # σ is monotone: its inverse at the marks, by interpolation on the ruling spans,
        # then Newton steps on the PCHIP itself, kept within the ruling span (a sample put
        # δu off a kink leaves a share of δu's arc short: to rounding, they converge)
        crossing = np.interp(marks, p, u)
        span = np.clip(np.searchsorted(u, crossing, side="right") - 1, 0, len(u) - 2)
        low, high = u[span], u[span + 1]
        for _ in range(CROSSING_STEPS):
            with np.errstate(divide="ignore", invalid="ignore"):
                step = (self._pace(crossing) - marks) / self._pace(crossing, nu=1)
            step = np.where(np.isfinite(step), step, 0.0)
            crossing = np.clip(crossing - step, low, high)
            if not np.any(np.abs(step) > 1e-15):
                break
        return crossing

    def __repr__(self) -> str:
        return f"CurveRail({self.curve!r}, {len(self.params)} rulings)"


def ruled_between(
    curve_a: Curve,
    s: ArrayLike,
    curve_b: Curve,
    t: ArrayLike,
    points: tuple[FloatArray, FloatArray] | None = None,
) -> RuledSurface:
    """The ruled surface whose rulings are A(s_i) → B(t_i) at u_i = i/(n − 1) and whose
    edges run on A and B (see the module). ``s`` and ``t`` are non-decreasing (``t`` may
    run on through B's seam when B is closed, as RulingDevelopable's partners do).
    ``points`` are A(s) and B(t) where the caller has them from the curves' own
    evaluation (a curve of :data:`POINTWISE` types only: they are used where the rails'
    parameters are ``s`` and ``t`` themselves, and the curves evaluated again elsewhere).

    >>> from torsal.nodes.geometry.curves import Line
    >>> a, b = Line([0, 0, 0], [2, 0, 0]), Line([0, 1, 0], [2, 1, 0])
    >>> strip = ruled_between(a, [0, 0.5, 1], b, [0, 0.5, 1])
    >>> round(strip.area(), 12), strip.point_at(0.25, 0.0).round(12).tolist()
    (2.0, [0.5, 0.0, 0.0])
    """
    s = np.asarray(s, dtype=float)
    t = np.asarray(t, dtype=float)
    n = len(s)
    if n < 2 or len(t) != n:
        raise ValueError("a strip needs at least two rulings, one s and one t each")
    if s.shape != (n,) or t.shape != (n,):
        raise ValueError(_UNPACED)
    steps = _Steps.uniform(n)  # at u = np.linspace(0, 1, n), bit for bit (read-only, shared)
    u = steps.u
    (rail_a, rail_b), rising = CurveRail._pair(curve_a, s, curve_b, t, steps)
    lines = np.empty((n, 2, 3))
    for side, (curve, rail, given) in enumerate(((curve_a, rail_a, s), (curve_b, rail_b, t))):
        if points is None or not isinstance(curve, POINTWISE):
            lines[:, side] = curve.point_at(rail._wrapped(rail.curve_params))
            continue
        p = rail.curve_params
        # the rail runs through the given points where its parameters are the given ones:
        # rising numbers in [0, 1] on an open curve are (nothing to unwrap or clip)
        if not (rising and not curve.closed and p[0] >= 0.0 and p[-1] <= 1.0):
            at = rail._wrapped(p)
            if not np.array_equal(at, given):
                lines[:, side] = curve.point_at(at)
                continue
        lines[:, side] = points[side]
    # the rails' ends are the first and last rulings' (to rounding): closed round u when
    # both rails return to their start, as RuledSurface judges it from its rails' ends,
    # without evaluating the rails again (a strip's rails are built on every re-solve)
    ends = lines[:: n - 1].reshape(4, 3)  # A(s0), B(t0), A(s_last), B(t_last)
    size = float(extent(ends).max()) or 1.0
    gap_a, gap_b = np.abs(ends[:2] - ends[2:]).max(axis=1).tolist()
    closed_u = gap_a <= 1e-12 * size and gap_b <= 1e-12 * size
    surface = RuledSurface.__new__(RuledSurface)
    surface._setup(rail_a, rail_b, closed_u)
    surface.ruling_parameters = u
    surface.ruling_lines = lines
    return surface
