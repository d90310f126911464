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

from collections.abc import Sequence
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike

from .curve_base import Curve, FloatArray
from .curves import Line, NurbsCurve, Polyline
from .ruled import RuledSurface, _uniform

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

    #: the coefficients (c3, c2, c1, c0) of the interpolants fitted with this one, joined
    #: (:meth:`_many`), and where this one's start among them
    joined: tuple[FloatArray, FloatArray, FloatArray, FloatArray]
    first: int = 0

    def __init__(self, u: FloatArray, p: FloatArray) -> None:
        self.u = u
        self.c3, self.c2, self.c1, self.c0 = self.joined = _pchip(_Pieces([_Steps(u)]), p, p[1:] - p[:-1])

    @classmethod
    def _many(cls, pieces: _Pieces, p: FloatArray, dp: FloatArray) -> list[Pace]:
        """One interpolant per run of ``pieces`` (points ``p``, chords ``dp``, run after
        run), fitted in one pass: each run's coefficients are the ones it gets alone
        (every step is elementwise). Their arrays are views of the joined ones."""
        c3, c2, c1, c0 = joined = _pchip(pieces, p, dp)
        paces = []
        for steps, low, high in zip(pieces.steps, pieces.offsets[:-1].tolist(), pieces.offsets[1:].tolist(),
                                    strict=True):
            pace = cls.__new__(cls)
            pace.u = steps.u
            pace.c3, pace.c2, pace.c1, pace.c0 = c3[low:high], c2[low:high], c1[low:high], c0[low:high]
            pace.joined, pace.first = joined, low
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
    harmonic mean."""

    def __init__(self, u: FloatArray) -> None:
        h = u[1:] - u[:-1]
        self.u, self.h = u, h
        self.increasing: bool | None = None  # (known for the uniform ones)
        if len(u) > 2:
            self.w1, self.w2 = 2.0 * h[1:] + h[:-1], h[1:] + 2.0 * h[:-1]
            self.w_sum = self.w1 + self.w2

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


class _Pieces:
    """Several runs of points one after another in flat arrays, run ``r`` at the
    parameters of ``steps[r]`` (two or more points): where each run's pieces (the spans
    between consecutive points) and inner points lie, for :func:`_pchip`."""

    def __init__(self, steps: Sequence[_Steps]) -> None:
        self.steps = steps
        sizes = np.array([len(s.h) for s in steps], dtype=np.int64)  # pieces per run
        self.offsets = np.zeros(len(steps) + 1, dtype=np.int64)  # run r's: offsets[r]:offsets[r + 1]
        np.cumsum(sizes, out=self.offsets[1:])
        run = np.repeat(np.arange(len(steps)), sizes)
        # each piece's first point among the points (run r's points start at offsets[r] + r)
        self.left = np.arange(self.offsets[-1]) + run
        self.h = np.concatenate([s.h for s in steps] or [np.empty(0)])
        # the pieces followed by one of the same run: an inner point lies between them
        self.before = np.flatnonzero(run[1:] == run[:-1])
        self.inner = self.left[self.before] + 1
        longer = [s for s in steps if len(s.h) > 1]  # (three points or more: inner points)
        self.w1 = np.concatenate([s.w1 for s in longer] or [np.empty(0)])
        self.w2 = np.concatenate([s.w2 for s in longer] or [np.empty(0)])
        self.w_sum = np.concatenate([s.w_sum for s in longer] or [np.empty(0)])
        first, stop = self.offsets[:-1], self.offsets[1:]
        self.short = first[sizes == 1]  # the one piece of each two-point run
        self.first, self.last = first[sizes > 1], stop[sizes > 1] - 1  # the longer runs' end pieces


def _pchip(
    pieces: _Pieces, p: FloatArray, dp: FloatArray
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """The PCHIP cubics' coefficients (c3, c2, c1, c0) on ``pieces``, the flat points ``p``
    (run after run), whose chords (point after point within each run) are ``dp``: see
    :class:`Pace`."""
    h = pieces.h
    m = dp / h
    slopes = np.empty(len(p))
    # a run of two points: both slopes are its chord's
    short = pieces.short
    slopes[pieces.left[short]] = m[short]
    slopes[pieces.left[short] + 1] = m[short]
    if len(pieces.first):
        before = pieces.before  # the piece before each inner point (the one after is next)
        m0, m1 = m[before], m[before + 1]
        with np.errstate(divide="ignore", invalid="ignore"):
            harmonic = pieces.w_sum / (pieces.w1 / m0 + pieces.w2 / m1)
        # 0 where the neighbouring chords' slopes differ in sign or one is 0 (or NaN)
        slopes[pieces.inner] = np.where(np.sign(m1) * np.sign(m0) > 0, harmonic, 0.0)
        first, last = pieces.first, pieces.last
        slopes[pieces.left[first]] = _end_slopes(h[first], h[first + 1], m[first], m[first + 1])
        slopes[pieces.left[last] + 1] = _end_slopes(h[last], h[last - 1], m[last], m[last - 1])
    # the cubic on [u_i, u_i+1] in z = u − u_i: ((c3·z + c2)·z + c1)·z + c0
    starts = slopes[pieces.left]
    bend = (starts + slopes[pieces.left + 1] - 2.0 * m) / h
    return bend / h, (m - starts) / h - bend, starts, p[pieces.left]


def _end_slopes(h0: FloatArray, h1: FloatArray, m0: FloatArray, m1: FloatArray) -> FloatArray:
    """PCHIP's slope at the end of each run, from the end step and chord slope (``h0``,
    ``m0``) and the next ones (``h1``, ``m1``): the one-sided three-point estimate, kept
    monotone (0 where its sign is not the end chord's, NaN included; 3× the end chord's
    slope where it would overshoot)."""
    d = ((2.0 * h0 + h1) * m0 - h0 * m1) / (h0 + h1)
    sign0 = np.sign(m0)
    over = (sign0 != np.sign(m1)) & (np.abs(d) > 3.0 * np.abs(m0))
    return np.where(np.sign(d) != sign0, 0.0, np.where(over, 3.0 * m0, d))


_UNPACED = "a curve rail needs increasing u and non-decreasing curve parameters"


#: Most Newton steps :meth:`CurveRail.crossings` takes on the pace (quadratic from the
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
    def _pairs(
        cls, jobs: Sequence[tuple[Curve, FloatArray, Curve, FloatArray]]
    ) -> list[tuple[tuple[CurveRail, CurveRail], bool] | ValueError]:
        """``CurveRail(curve_a, u, s)`` and ``CurveRail(curve_b, u, t)`` of every ``(curve_a,
        s, curve_b, t)`` of ``jobs`` (``s`` and ``t`` ``(n,)`` arrays, ``n`` ≥ 2, at the
        evenly spaced ``u = _Steps.uniform(n).u``), their checks and paces made in one pass
        for all; and whether both rails' parameters are non-decreasing numbers (no NaN),
        which the checks alone do not say. A job whose parameters run back gets the
        ValueError :class:`CurveRail` raises."""
        if not jobs:
            return []
        rows = [unwrap_cyclic(q) if curve.closed else q
                for a, s, b, t in jobs for curve, q in ((a, s), (b, t))]
        pieces = _Pieces([_Steps.uniform(len(q)) for q in rows])
        p = np.concatenate(rows)
        dp = p[pieces.left + 1] - p[pieces.left]
        pairs = pieces.offsets[:-1:2]  # (each job's two rows' pieces, one after the other)
        rising = (np.minimum.reduceat(dp, pairs) >= 0.0).tolist()  # (false where a NaN is)
        backward = np.logical_or.reduceat(dp < 0.0, pairs).tolist()
        increasing = [steps.increasing for steps in pieces.steps[::2]]  # (steps: _Steps.uniform)
        ok = [up and not back for up, back in zip(increasing, backward, strict=True)]
        if not all(ok):  # (the paces of those alone)
            kept = [q for job, good in enumerate(ok) if good for q in rows[2 * job : 2 * job + 2]]
            pieces = _Pieces([_Steps.uniform(len(q)) for q in kept])
            p = np.concatenate(kept or [np.empty(0)])
            dp = p[pieces.left + 1] - p[pieces.left]
        paces = iter(Pace._many(pieces, p, dp))
        rows_of = iter(pieces.steps)
        low = 0
        made: list[tuple[tuple[CurveRail, CurveRail], bool] | ValueError] = []
        for (curve_a, _, curve_b, _), good, up in zip(jobs, ok, rising, strict=True):
            if not good:
                made.append(ValueError(_UNPACED))
                continue
            rails = []
            for curve in (curve_a, curve_b):
                u = next(rows_of).u
                rail = cls.__new__(cls)
                rail._set(curve, u, p[low : low + len(u)], next(paces))
                low += len(u)
                rails.append(rail)
            made.append(((rails[0], rails[1]), up))
        return made

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
        crossing = self.crossings(self.curve._breakpoints())
        return np.unique(np.clip(np.concatenate([self.params, crossing, [0.0, 1.0]]), 0.0, 1.0))

    def _find_kinks(self) -> FloatArray:
        """Where the pace crosses one of the curve's kinks (a closed curve's seam when it
        is a corner): the rail turns there as the curve does, and nowhere else (σ is C¹
        and a stretch where it stands still keeps the rail on one point)."""
        return np.unique(np.clip(self.crossings(self.curve.kinks()), 0.0, 1.0))

    def crossings(self, inner: FloatArray) -> FloatArray:
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
    surface = ruled_between_all([(curve_a, s, curve_b, t, points)])[0]
    if isinstance(surface, ValueError):
        raise surface
    return surface


def ruled_between_all(
    jobs: Sequence[tuple[Curve, ArrayLike, Curve, ArrayLike, tuple[FloatArray, FloatArray] | None]],
) -> list[RuledSurface | ValueError]:
    """:func:`ruled_between` of every ``(curve_a, s, curve_b, t, points)`` of ``jobs``,
    the rails' paces of all fitted in one pass (:meth:`CurveRail._pairs`) and their ends
    compared at once: each surface is the one it gets alone, bit for bit; a job
    :func:`ruled_between` refuses gets its ValueError in its place."""
    out: list[RuledSurface | ValueError | None] = []
    fit = []  # (where in out, the job with s and t as arrays)
    for curve_a, s, curve_b, t, points in jobs:
        s = np.asarray(s, dtype=float)
        t = np.asarray(t, dtype=float)
        n = len(s)
        if n < 2 or len(t) != n:
            out.append(ValueError("a strip needs at least two rulings, one s and one t each"))
            continue
        if s.shape != (n,) or t.shape != (n,):
            out.append(ValueError(_UNPACED))
            continue
        fit.append((len(out), (curve_a, s, curve_b, t, points)))
        out.append(None)
    placed = []  # (where in out, the job, its rails)
    for (index, job), pair in zip(fit, CurveRail._pairs([job[:4] for _, job in fit]), strict=True):
        if isinstance(pair, ValueError):
            out[index] = pair
        else:
            placed.append((index, job, pair))
    made = _on_rails([(job, pair) for _, job, pair in placed])
    for (index, _, _), surface in zip(placed, made, strict=True):
        out[index] = surface
    return out  # type: ignore[return-value]  (every job's is filled in)


def _on_rails(
    fit: list[tuple[tuple[Curve, FloatArray, Curve, FloatArray, tuple[FloatArray, FloatArray] | None],
                    tuple[tuple[CurveRail, CurveRail], bool]]],
) -> list[RuledSurface]:
    """The surfaces of :func:`ruled_between_all` on their ``(rails, rising)``: their ruling
    lines (one array for all, each surface a view of its rows) and whether they are closed."""
    if not fit:
        return []
    offsets = np.zeros(len(fit) + 1, dtype=np.int64)
    np.cumsum([len(job[1]) for job, _ in fit], out=offsets[1:])
    lines = np.empty((int(offsets[-1]), 2, 3))
    bounds = offsets.tolist()
    for ((curve_a, s, curve_b, t, points), ((rail_a, rail_b), rising)), low, high in zip(
        fit, bounds[:-1], bounds[1:], strict=True
    ):
        for side, (curve, rail, given) in enumerate(((curve_a, rail_a, s), (curve_b, rail_b, t))):
            if points is None or not isinstance(curve, POINTWISE):
                lines[low:high, side] = curve.point_at(rail._wrapped(rail.curve_params))
                continue
            p = rail.curve_params
            # the rail runs through the given points where its parameters are the given ones:
            # rising numbers in [0, 1] on an open curve are (nothing to unwrap or clip)
            if not (rising and not curve.closed and p[0] >= 0.0 and p[-1] <= 1.0):
                at = rail._wrapped(p)
                if not np.array_equal(at, given):
                    lines[low:high, side] = curve.point_at(at)
                    continue
            lines[low:high, side] = points[side]
    # the rails' ends are the first and last rulings' (to rounding): closed round u when
    # both rails return to their start, as RuledSurface judges it from its rails' ends,
    # without evaluating the rails again (a strip's rails are built on every re-solve)
    # A(s0), B(t0), A(s_last), B(t_last) of each surface
    ends = np.concatenate([lines[offsets[:-1]], lines[offsets[1:] - 1]], axis=1)
    size = (ends.max(axis=1) - ends.min(axis=1)).max(axis=1)
    size = np.where(size == 0.0, 1.0, size)
    gaps = np.abs(ends[:, :2] - ends[:, 2:]).max(axis=2)
    closed = (gaps <= (1e-12 * size)[:, None]).all(axis=1).tolist()
    surfaces = []
    for (_, ((rail_a, rail_b), _)), closed_u, low, high in zip(
        fit, closed, bounds[:-1], bounds[1:], strict=True
    ):
        surface = RuledSurface.__new__(RuledSurface)
        surface._setup(rail_a, rail_b, closed_u)
        surface.ruling_parameters = rail_a.params
        surface.ruling_lines = lines[low:high]
        surfaces.append(surface)
    return surfaces
