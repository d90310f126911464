"""Ruled surfaces S(u, v) = (1 − v)·A(u) + v·B(u): straight lines between two rails.

Two constructions:

* ``RuledSurface(curve_a, curve_b)`` — the rails are any two kernel curves.
* ``RuledSurface.from_rulings(starts, ends)`` — the loft every developable node
  outputs. Ruling i sits at u_i = i/(n − 1) and the rails are splines *through* the
  ruling end points at those parameters (cubic, not-a-knot; quadratic/linear for
  3/2 rulings; periodic when the last ruling repeats the first; tangents limited
  where unevenly spaced ends would make the spline overshoot, see
  :mod:`.rail_tangents`), so the isocurve
  v ↦ S(u_i, v) is exactly ruling i (to rounding, ~1e-15 of the coordinates) and
  the surface is linear in v. Derivatives are analytic from the splines.

  Both rails are one spline through the ``(n, 6)`` array of ruling ends, solved on
  first use: a node that lofts its rulings on every solve pays for the spline only
  when the surface is evaluated (drawn, meshed, measured), and then once, not twice.

The area (and centroid) is integrated by Gauss rules on the rails' smooth spans in u
and on either side of the area element's minimum in v (see :meth:`RuledSurface.area`).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike
from scipy.interpolate import BSpline, make_interp_spline

from .area import gauss_legendre_01, span_gauss
from .array_types import FloatArray
from .curve_base import Curve
from .curves.line import Line
from .rail_tangents import without_overshoot
from .surface_base import Surface, broadcast_uv
from .vec_ops import anchor, derivative_noise, differenced, extent, position_rounding

#: Gauss–Legendre orders whose area estimates must agree (to ``rtol``) per attempt.
_AREA_ORDERS = (12, 16)
#: The fewest pieces the u interval is cut into for the area, whatever the breakpoints.
_AREA_PIECES = 16
#: More u spans than this and the area is left to the generic adaptive cubature.
_AREA_MAX_SPANS = 200_000
#: How many times a span whose two rules disagree may be cut in four.
_AREA_LEVELS = 12


def _uniform(count: int) -> FloatArray:
    """``np.linspace(0, 1, count)``, bit for bit, at a fraction of its cost."""
    params = np.arange(count) * (1.0 / (count - 1))
    params[-1] = 1.0
    return params


def _periodic_uniform_spline(points: FloatArray) -> BSpline:
    """The periodic cubic spline through ``points`` (the last repeating the first) at
    evenly spaced parameters 0 … 1: as scipy's ``make_interp_spline(..., bc_type="periodic")``,
    whose general solver takes ~10–100 ms, where on uniform knots the system is circulant
    — c[j−1] + 4·c[j] + c[j+1] = 6·y[j] (indices mod m) — and one FFT solves it."""
    y = points[:-1]
    m = len(y)
    eigenvalues = (4.0 + 2.0 * np.cos(2.0 * np.pi * np.arange(m) / m)) / 6.0
    d = np.fft.ifft(np.fft.fft(y, axis=0) / eigenvalues[:, None], axis=0).real
    knots = np.arange(-3, m + 4) / m
    knots[3], knots[m + 3] = 0.0, 1.0  # exactly
    coefficients = np.concatenate([d[-1:], d, d[:2]])
    return BSpline(knots, coefficients, 3, extrapolate="periodic")


class _Interpolant:
    """The interpolating spline through the rows of ``points`` at ``params``, solved on
    first use (one spline for any number of columns: both rails of a loft share one).
    Cubic, with its tangents limited where unevenly spaced points would make it
    overshoot (:mod:`.rail_tangents`); ``degree=1``: the polyline through the points.

    The spline is solved and evaluated on the points relative to :attr:`anchor` (the
    centre of their box, the same for every group of three columns), so derivatives and
    the differences of the two rails round relative to the rails' size, not to their
    distance from the origin (site coordinates)."""

    def __init__(self, params: FloatArray, points: FloatArray, closed: bool, degree: int = 3) -> None:
        self.params, self.points, self.closed, self.degree = params, points, closed, degree
        columns = points.shape[1]
        centre = anchor(points.reshape(-1, 3)) if columns % 3 == 0 else anchor(points)
        self.anchor: FloatArray = np.tile(centre, columns // len(centre))
        self._local: BSpline | None = None
        self._spline: BSpline | None = None

    def solve_local(self) -> BSpline:
        """The spline through the points relative to :attr:`anchor` (solved on the first call)."""
        if self._local is None:
            local = self.points - self.anchor
            uniform = np.array_equal(self.params, _uniform(len(self.params)))
            if self.degree == 1:
                spline = make_interp_spline(self.params, local, k=1)
            elif self.closed and uniform:
                spline = _periodic_uniform_spline(local)
            elif self.closed:
                spline = make_interp_spline(self.params, local, k=3, bc_type="periodic")
            else:
                spline = make_interp_spline(self.params, local, k=min(3, len(self.params) - 1))
            spline = without_overshoot(spline, self.params, local, self.closed) or spline
            spline.extrapolate = "periodic" if self.closed else True
            self._local = spline
        return self._local

    def solve(self) -> BSpline:
        """The spline in world coordinates (for export; evaluation uses :meth:`solve_local`)."""
        if self._spline is None:
            local = self.solve_local()
            self._spline = BSpline(local.t, local.c + self.anchor, local.k, extrapolate=local.extrapolate)
        return self._spline

    def local_derivatives(self, t: FloatArray, order: int) -> list[FloatArray]:
        """Values relative to :attr:`anchor` and derivatives up to ``order`` at ``t``,
        each ``(len(t), columns)``."""
        spline = self.solve_local()
        columns = self.points.shape[1]
        return [
            np.asarray(spline(t, nu=k), dtype=float) if k <= spline.k else np.zeros((len(t), columns))
            for k in range(order + 1)
        ]

    def derivatives(self, t: FloatArray, order: int) -> list[FloatArray]:
        """Values and derivatives up to ``order`` at ``t``, each ``(len(t), columns)``."""
        result = self.local_derivatives(t, order)
        result[0] = result[0] + self.anchor
        return result


class SplineRail(Curve):
    """The interpolating spline through ``points`` at parameters ``params`` in [0, 1].

    Degree min(3, n − 1), not-a-knot ends, or periodic (``closed=True``, which needs
    the last point to repeat the first and at least 4 points). Evaluated with
    scipy's BSpline, with exact derivatives up to order 3.
    """

    #: Derivatives from the definition, not differences of positions (:func:`.vec_ops.differenced`).
    exact_derivatives = True

    def __init__(self, params: ArrayLike, points: ArrayLike, closed: bool = False) -> None:
        t = np.asarray(params, dtype=float)
        pts = np.array(points, dtype=float)
        if len(t) < 2 or len(t) != len(pts):
            raise ValueError("a rail needs at least two points, one parameter each")
        self.closed = bool(closed) and len(t) >= 4
        if self.closed:
            pts[-1] = pts[0]  # exactly, as the periodic condition requires
        self.params, self.points = t, pts
        self._source = _Interpolant(t, pts, self.closed)
        self._columns = slice(0, 3)
        self._source.solve_local()  # now: a bad parameter sequence fails here, not later

    @classmethod
    def _pair(
        cls, params: FloatArray, a: FloatArray, b: FloatArray, closed: bool, degree: int = 3
    ) -> tuple[SplineRail, SplineRail]:
        """Two rails through ``a`` and ``b`` that share one (lazily solved) spline."""
        closed = closed and len(params) >= 4
        both = np.concatenate([a, b], axis=1)
        if closed:
            both[-1] = both[0]
        source = _Interpolant(params, both, closed, degree)
        rails = []
        for columns in (slice(0, 3), slice(3, 6)):
            rail = cls.__new__(cls)
            rail.closed, rail.params, rail.points = closed, params, both[:, columns]
            rail._source, rail._columns = source, columns
            rails.append(rail)
        return rails[0], rails[1]

    @property
    def spline(self) -> BSpline:
        """This rail as one scipy BSpline (3 columns)."""
        spline = self._source.solve()
        if self._columns == slice(0, spline.c.shape[1]):
            return spline
        return BSpline(spline.t, spline.c[:, self._columns], spline.k, extrapolate=spline.extrapolate)

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        t = np.atleast_1d(np.asarray(t, dtype=float)).ravel()
        if order > 3:
            raise ValueError("rail derivatives are available to order 3")
        return [d[:, self._columns] for d in self._source.derivatives(t, order)]

    @property
    def anchor(self) -> FloatArray:
        return self._source.anchor[self._columns]

    def local_derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        t = np.atleast_1d(np.asarray(t, dtype=float)).ravel()
        if order > 3:
            raise ValueError("rail derivatives are available to order 3")
        return [d[:, self._columns] for d in self._source.local_derivatives(t, order)]

    def _breakpoints(self) -> FloatArray:
        return np.unique(np.clip(self._source.solve_local().t, 0.0, 1.0))


#: Below this ratio |c1| / |c0| the area element along a ruling is nearly constant (an
#: analytic function with its nearest singularity over 1000 ruling lengths away) and a
#: 16-point Gauss rule is exact to rounding; above it the closed form loses at most
#: ~1000 ulps to cancellation.
_SMOOTH_RULING = 1e-3


def ruling_integrals(c0: FloatArray, c1: FloatArray) -> tuple[FloatArray, FloatArray]:
    """``∫₀¹ |c0 + v·c1| dv`` and ``∫₀¹ v·|c0 + v·c1| dv`` for rows of ``(n, 3)`` vectors.

    Along a ruling of a ruled surface the area element |Su × Sv| is |c0 + v·c1|: the
    root of a quadratic, with a kink where the ruling meets the edge of regression (on a
    developable, where c0 ∥ c1). Written as √a·√(x² + r²) with a = |c1|²,
    x = v − m about its minimum m = −c0·c1/a and r = |c0 × c1|/a, both integrals
    have closed forms, ½√a·[x·s + r²·asinh(x/r)] and √a·s³/3 + m·I₀ with
    s = √(x² + r²), exact across the kink; where c1 is negligible the element is smooth
    and Gauss–Legendre is used instead.
    """
    a = np.einsum("ij,ij->i", c1, c1)
    length0 = np.sqrt(np.einsum("ij,ij->i", c0, c0))
    closed = np.sqrt(a) > _SMOOTH_RULING * length0
    i0, i1 = np.empty(len(a)), np.empty(len(a))
    if closed.any():
        p, q, aa = c0[closed], c1[closed], a[closed]
        m = -np.einsum("ij,ij->i", p, q) / aa
        r = np.linalg.norm(np.cross(p, q), axis=1) / aa
        root_a = np.sqrt(aa)

        def ends(x: FloatArray) -> tuple[FloatArray, FloatArray]:
            s = np.sqrt(x * x + r * r)
            with np.errstate(divide="ignore", invalid="ignore"):
                log_part = np.where(r > 0, r * r * np.arcsinh(x / np.where(r > 0, r, 1.0)), 0.0)
            return 0.5 * (x * s + log_part), s**3 / 3.0

        (p1, q1), (p0, q0) = ends(1.0 - m), ends(-m)
        i0[closed] = root_a * (p1 - p0)
        i1[closed] = root_a * (q1 - q0) + m * i0[closed]
    if (~closed).any():
        x, w = gauss_legendre_01(16)
        element = np.linalg.norm(c0[~closed, None, :] + x[None, :, None] * c1[~closed, None, :], axis=2)
        i0[~closed] = element @ w
        i1[~closed] = element @ (w * x)
    return i0, i1


def _shared_source(curve_a: Curve, curve_b: Curve) -> _Interpolant | None:
    """The one spline behind both rails of a loft (columns 0–2 and 3–5), if they share it."""
    if (
        isinstance(curve_a, SplineRail)
        and isinstance(curve_b, SplineRail)
        and curve_a._source is curve_b._source
        and curve_a._columns == slice(0, 3)
        and curve_b._columns == slice(3, 6)
    ):
        return curve_a._source
    return None


class RuledSurface(Surface):
    """S(u, v) = (1 − v)·A(u) + v·B(u) between two curves (rails) A and B.

    u follows the rails' own parameter; the rulings are the isocurves u = const
    (``ruling_direction == "v"``). Use :meth:`from_rulings` to loft given lines.
    """

    def __init__(self, curve_a: Curve, curve_b: Curve) -> None:
        ends = np.vstack([curve_a.point_at(np.array([0.0, 1.0])), curve_b.point_at(np.array([0.0, 1.0]))])
        size = float(extent(ends).max()) or 1.0
        closed_u = bool(getattr(curve_a, "closed", False) and getattr(curve_b, "closed", False)) or bool(
            np.abs(ends[0] - ends[1]).max() <= 1e-12 * size
            and np.abs(ends[2] - ends[3]).max() <= 1e-12 * size
        )
        self._setup(curve_a, curve_b, closed_u)

    def _setup(self, curve_a: Curve, curve_b: Curve, closed_u: bool) -> None:
        self.curve_a = curve_a
        self.curve_b = curve_b
        self.ruling_parameters: FloatArray | None = None
        self.ruling_lines: FloatArray | None = None
        self.closed_u = closed_u
        self.closed_v = False
        self._both = _shared_source(curve_a, curve_b)

    def __repr__(self) -> str:
        if self.ruling_lines is not None:
            return f"RuledSurface({len(self.ruling_lines)} rulings)"
        return f"RuledSurface({self.curve_a!r}, {self.curve_b!r})"

    @classmethod
    def from_rulings(
        cls, starts: ArrayLike | Sequence[Curve], ends: ArrayLike | None = None, degree: int = 3
    ) -> RuledSurface:
        """The ruled surface whose rulings are exactly the given lines.

        ``starts`` and ``ends`` are ``(n, 3)`` arrays of ruling end points; or pass a
        single ``(n, 2, 3)`` array, or a sequence of line curves (their ``start`` and
        ``end`` points are used). Ruling i becomes the isocurve u = i/(n − 1),
        running from v = 0 at its start to v = 1 at its end. When the last ruling
        repeats the first (to 1e-12 of the size) the rails are closed periodic
        splines. The rails' spline is solved when the surface is first evaluated.
        ``degree=1`` makes the rails the polylines through the ruling ends: the surface
        is then the chain of quads between consecutive rulings (a paper strip's faces).
        """
        if degree not in (1, 3):
            raise ValueError(f"rails are cubic (degree 3) or polylines (degree 1), not degree {degree}")
        if ends is None and isinstance(starts, Sequence) and starts and isinstance(starts[0], Curve):
            starts = np.array([[line.start, line.end] for line in starts])  # type: ignore[union-attr]
        a = np.asarray(starts, dtype=float)
        if ends is None:
            if a.ndim != 3 or a.shape[1:] != (2, 3):
                raise ValueError("rulings must be an (n, 2, 3) array of [start, end] points")
            a, b = a[:, 0], a[:, 1]
        else:
            b = np.asarray(ends, dtype=float)
        if a.shape != b.shape or a.ndim != 2 or a.shape[1] != 3:
            raise ValueError("starts and ends must be (n, 3) arrays of the same length")
        n = len(a)
        if n < 2:
            raise ValueError("a ruled surface needs at least two rulings")
        lines = np.empty((n, 2, 3))  # np.stack([a, b], axis=1), without its overhead
        lines[:, 0], lines[:, 1] = a, b
        if not np.isfinite(lines).all():
            raise ValueError("ruling end points must be finite")
        params = _uniform(n)
        size = float(extent(lines.reshape(-1, 3)).max()) or 1.0
        closed = n >= 4 and bool(np.abs(lines[0] - lines[-1]).max() <= 1e-12 * size)
        surface = cls.__new__(cls)
        surface._setup(*SplineRail._pair(params, a, b, closed, degree), closed)
        surface.ruling_parameters = params
        surface.ruling_lines = lines
        return surface

    def ruling_curves(self, count: int | None = None) -> list[Line]:
        """The rulings as :class:`Line` curves: with ``count=None`` the given ones
        (for a surface made :meth:`from_rulings`), else ``count`` evenly spaced in u."""
        if count is None:
            if self.ruling_lines is None:
                raise ValueError("this ruled surface was not made from rulings: give a count")
            lines = self.ruling_lines
        else:
            lines = self.rulings(count)
        return [Line(a, b) for a, b in lines]

    @property
    def ruling_direction(self) -> str:  # type: ignore[override]
        """Always ``"v"``: the isocurves u = const are the rulings."""
        return "v"

    def ruling_kinks(self) -> FloatArray:
        """Where either rail turns a corner (:meth:`.curve_base.Curve.kinks`: a NURBS
        curve's C0 knots, a polyline's vertices, a rail on such a curve where its pace
        crosses them). A rail held on one point (a cone's apex) has none: its derivatives
        are rounding noise, whose directions mean nothing."""
        probe = self.rulings(9)
        size = float(extent(probe.reshape(-1, 3)).max())
        rails = [rail for side, rail in enumerate((self.curve_a, self.curve_b))
                 if float(extent(probe[:, side]).max()) > 1e-9 * size + position_rounding(probe)]
        kinks = np.concatenate([np.empty(0), *(rail.kinks() for rail in rails)])
        return np.unique(kinks[(kinks >= 0.0) & (kinks < 1.0)])

    def _rails(self, u: FloatArray, order: int) -> tuple[list[FloatArray], list[FloatArray]]:
        """Derivatives of rail A and of rail B at ``u`` (one evaluation for a loft's pair),
        the points of each relative to rail A's anchor (see :meth:`_rail_anchors`)."""
        offset = self._rail_anchors[1]
        if self._both is not None:
            both = self._both.local_derivatives(u, order)
            return [d[:, :3] for d in both], [d[:, 3:] for d in both]
        da = self.curve_a.local_derivatives(u, order)
        db = self.curve_b.local_derivatives(u, order)
        db[0] = db[0] + offset
        return da, db

    @property
    def _rail_anchors(self) -> tuple[FloatArray, FloatArray]:
        """Rail A's anchor (the origin of :meth:`_rails`' points) and rail B's relative to it.

        Rulings B − A and area elements are computed from points relative to the rails'
        anchors, so they round relative to the surface's size wherever it sits."""
        anchors = self.__dict__.get("_anchors")
        if anchors is None:
            if self._both is not None:
                origin = self._both.anchor[:3]
                anchors = (origin, np.zeros(3))
            else:
                origin = np.asarray(self.curve_a.anchor, dtype=float)
                anchors = (origin, np.asarray(self.curve_b.anchor, dtype=float) - origin)
            self._anchors = anchors
        return anchors

    def derivatives(self, u: ArrayLike, v: ArrayLike, order: int = 1) -> list[FloatArray]:
        self._check_order(order)
        s, t = broadcast_uv(u, v)
        da, db = self._rails(s, order)
        w = t[:, None]
        span = db[0] - da[0]
        out = [self._rail_anchors[0] + (da[0] + w * span)]
        if order >= 1:
            out += [da[1] + w * (db[1] - da[1]), span]
        if order == 2:
            out += [da[2] + w * (db[2] - da[2]), db[1] - da[1], np.zeros_like(span)]
        return out

    # ------------------------------------------------------------------ integrals

    def area(self, rtol: float = 1e-11) -> float:
        """Surface area: see :meth:`area_and_centroid`."""
        return self.area_and_centroid(rtol)[0]

    def area_and_centroid(self, rtol: float = 1e-11) -> tuple[float, FloatArray]:
        """Area and area centroid: exact along each ruling, Gauss rules across them.

        The area element is |Su × Sv| = |c0(u) + v·c1(u)| with c0 = A′ × D,
        c1 = (B′ − A′) × D and D = B − A: in v the root of a quadratic, integrated in
        closed form (:func:`ruling_integrals`, exact even where a ruling crosses the
        edge of regression and the element has a kink), and in u smooth between the
        rails' breakpoints (a loft's ruling parameters). So a Gauss rule per rail span
        in u (at least 16 spans) is at rounding level with a few nodes, where the
        generic adaptive cubature on square cells refines towards every knot (minutes
        for a strip with fans of rulings). On each span, rules of order 12 and 16 must
        agree to the span's share of ``rtol``; spans where they do not (a ruling meeting
        the edge of regression makes the element only C¹ in u there) are cut in four,
        up to :data:`_AREA_LEVELS` times.

        >>> strip = RuledSurface.from_rulings([[0, 0, 0], [2, 0, 0]], [[0, 1, 0], [2, 1, 0]])
        >>> round(strip.area(), 12)
        2.0
        """
        edges = np.unique(
            np.clip(
                np.concatenate(
                    [
                        self.curve_a._breakpoints(),
                        self.curve_b._breakpoints(),
                        np.linspace(0.0, 1.0, _AREA_PIECES + 1),
                    ]
                ),
                0.0,
                1.0,
            )
        )
        lows, highs = edges[:-1], edges[1:]
        area, moment = 0.0, np.zeros(3)
        scale = 0.0  # the area's size, from the first pass: the tolerance is relative to it
        # far from the origin the rails' points are rounded to an ulp of their coordinates
        # (1.2e-7 m at 1e9 m): the rules cannot agree closer than that relative to the
        # strip's extent, and asking more refines to the span limit for nothing
        probe = self.derivatives(*np.meshgrid(np.linspace(0.0, 1.0, 5), [0.0, 1.0]), 0)[0]
        rounding = position_rounding(probe) / (float(extent(probe).max()) or 1.0)
        # and where the rails' derivatives are differences of such points (a curve given as a
        # function of its world coordinates), they are noisy far above that: the rules then
        # agree to that noise at best (each span still keeps its finer rule's value). Exact
        # derivatives (NURBS, a design's parameter lines) are not: stopping there left a
        # strip's area 3.9e-8 off at 1e6 m
        if differenced(self.curve_a) or differenced(self.curve_b):
            rounding = max(rounding, derivative_noise(probe.reshape(-1, 3)))
        tolerance = max(rtol, 1e-13, rounding)
        for level in range(_AREA_LEVELS):
            (coarse, _), (fine, fine_moment) = (self._gauss_spans(lows, highs, n) for n in _AREA_ORDERS)
            scale = scale or float(np.abs(fine).sum())
            # a span is done when its two rules agree to its share of the tolerance; on the
            # first spans to rtol even far out: there two rules can agree to the rounding
            # while both miss a feature between their nodes (a canopy strip's span next to
            # its fans, 1.3e-8 of its area off, accepted at 1e6 m where rounding was asked)
            share = max(rtol, 1e-13) if level == 0 else tolerance
            done = np.abs(fine - coarse) <= share * scale * (highs - lows)
            area += float(fine[done].sum())
            moment += fine_moment[done].sum(axis=0)
            lows, highs = lows[~done], highs[~done]
            if not len(lows) or 4 * len(lows) > _AREA_MAX_SPANS:
                break
            # the others (a ruling meeting the edge of regression there) are cut in four
            cuts = lows[:, None] + (highs - lows)[:, None] * np.arange(5)[None, :] / 4
            lows, highs = cuts[:, :-1].ravel(), cuts[:, 1:].ravel()
        if len(lows):
            if scale == 0.0 or 4 * len(lows) > _AREA_MAX_SPANS:
                return super().area_and_centroid(max(rtol, rounding))
            area += float(fine[~done].sum())  # kept at the finest level reached
            moment += fine_moment[~done].sum(axis=0)
        if area <= 0.0:
            return super().area_and_centroid(max(rtol, rounding))
        return area, self._rail_anchors[0] + moment / area

    def _gauss_spans(self, lows: FloatArray, highs: FloatArray, order: int) -> tuple[FloatArray, FloatArray]:
        """Area and first moment ∫∫ S |Su × Sv| on each u span [lows, highs] (exact in v,
        by an ``order``-point Gauss rule in u): ``(spans,)`` and ``(spans, 3)``."""
        u, weight_u = span_gauss(lows, highs, order)
        area, moment = np.empty(len(u)), np.empty((len(u), 3))
        for lo in range(0, len(u), 4096):  # blocks of u nodes bound the memory
            block = slice(lo, lo + 4096)
            (a0, a1), (b0, b1) = self._rails(u[block], 1)
            d = b0 - a0
            i0, i1 = ruling_integrals(np.cross(a1, d), np.cross(b1 - a1, d))  # exact along rulings
            weight = weight_u[block]
            area[block] = weight * i0
            moment[block] = (weight * i0)[:, None] * a0 + (weight * i1)[:, None] * d
        return area.reshape(-1, order).sum(axis=1), moment.reshape(-1, order, 3).sum(axis=1)
