"""Ruled surfaces S(u, v) = (1 − v)·A(u) + v·B(u): straight lines between two rails.

Two constructions:

* ``RuledSurface(curve_a, curve_b)`` — the rails are any two kernel curves.
* ``RuledSurface.from_rulings(starts, ends)`` — the loft every developable node
  outputs. Ruling i sits at u_i = i/(n − 1) and the rails are splines *through* the
  ruling end points at those parameters (cubic, not-a-knot; quadratic/linear for
  3/2 rulings; periodic when the last ruling repeats the first), so the isocurve
  v ↦ S(u_i, v) is exactly ruling i (to rounding, ~1e-15 of the coordinates) and
  the surface is linear in v. Derivatives are analytic from the splines.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import BSpline, make_interp_spline

from .curve_base import Curve
from .curves.line import Line
from .surface_base import Surface, broadcast_uv

FloatArray = NDArray[np.float64]


class SplineRail(Curve):
    """The interpolating spline through ``points`` at parameters ``params`` in [0, 1].

    Degree min(3, n − 1), not-a-knot ends, or periodic (``closed=True``, which needs
    the last point to repeat the first and at least 4 points). Evaluated with
    scipy's BSpline, with exact derivatives up to order 3.
    """

    def __init__(self, params: ArrayLike, points: ArrayLike, closed: bool = False) -> None:
        t = np.asarray(params, dtype=float)
        pts = np.array(points, dtype=float)
        if len(t) < 2 or len(t) != len(pts):
            raise ValueError("a rail needs at least two points, one parameter each")
        self.closed = bool(closed) and len(t) >= 4
        if self.closed:
            pts[-1] = pts[0]  # exactly, as the periodic condition requires
            spline = make_interp_spline(t, pts, k=3, bc_type="periodic")
        else:
            spline = make_interp_spline(t, pts, k=min(3, len(t) - 1))
        self.params, self.points = t, pts
        mode: bool | str = "periodic" if self.closed else True
        self._splines: list[BSpline] = [spline]
        for _ in range(3):
            k = self._splines[-1].k
            self._splines.append(
                self._splines[-1].derivative()
                if k > 0
                else BSpline(spline.t, np.zeros_like(spline.c), spline.k)
            )
        for s in self._splines:
            s.extrapolate = mode

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        t = np.atleast_1d(np.asarray(t, dtype=float)).ravel()
        if order > 3:
            raise ValueError("rail derivatives are available to order 3")
        out = [np.asarray(s(t), dtype=float) for s in self._splines[: order + 1]]
        return [o.reshape(len(t), 3) for o in out]

    def _breakpoints(self) -> FloatArray:
        knots = self._splines[0].t
        return np.unique(np.clip(knots, 0.0, 1.0))


class RuledSurface(Surface):
    """S(u, v) = (1 − v)·A(u) + v·B(u) between two curves (rails) A and B.

    u follows the rails' own parameter; the rulings are the isocurves u = const
    (``ruling_direction == "v"``). Use :meth:`from_rulings` to loft given lines.
    """

    def __init__(self, curve_a: Curve, curve_b: Curve) -> None:
        self.curve_a = curve_a
        self.curve_b = curve_b
        self.ruling_parameters: FloatArray | None = None
        self.ruling_lines: FloatArray | None = None
        ends = np.vstack([curve_a.point_at(np.array([0.0, 1.0])), curve_b.point_at(np.array([0.0, 1.0]))])
        size = float(np.ptp(ends, axis=0).max()) or 1.0
        self.closed_u = bool(getattr(curve_a, "closed", False) and getattr(curve_b, "closed", False)) or bool(
            np.abs(ends[0] - ends[1]).max() <= 1e-12 * size
            and np.abs(ends[2] - ends[3]).max() <= 1e-12 * size
        )
        self.closed_v = False

    def __repr__(self) -> str:
        if self.ruling_lines is not None:
            return f"RuledSurface({len(self.ruling_lines)} rulings)"
        return f"RuledSurface({self.curve_a!r}, {self.curve_b!r})"

    @classmethod
    def from_rulings(cls, starts: ArrayLike | Sequence[Curve], ends: ArrayLike | None = None) -> RuledSurface:
        """The ruled surface whose rulings are exactly the given lines.

        ``starts`` and ``ends`` are ``(n, 3)`` arrays of ruling end points; or pass a
        single ``(n, 2, 3)`` array, or a sequence of line curves (their ``start`` and
        ``end`` points are used). Ruling i becomes the isocurve u = i/(n − 1),
        running from v = 0 at its start to v = 1 at its end. When the last ruling
        repeats the first (to 1e-12 of the size) the rails are closed periodic
        splines.
        """
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
        if not (np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
            raise ValueError("ruling end points must be finite")
        params = np.linspace(0.0, 1.0, n)
        size = float(np.ptp(np.vstack([a, b]), axis=0).max()) or 1.0
        closed = n >= 4 and bool(
            np.abs(a[0] - a[-1]).max() <= 1e-12 * size and np.abs(b[0] - b[-1]).max() <= 1e-12 * size
        )
        surface = cls(SplineRail(params, a, closed), SplineRail(params, b, closed))
        surface.ruling_parameters = params
        surface.ruling_lines = np.stack([a, b], axis=1)
        surface.closed_u = closed
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

    def derivatives(self, u: ArrayLike, v: ArrayLike, order: int = 1) -> list[FloatArray]:
        self._check_order(order)
        s, t = broadcast_uv(u, v)
        da = self.curve_a.derivatives(s, order)
        db = self.curve_b.derivatives(s, order)
        w = t[:, None]
        span = db[0] - da[0]
        out = [da[0] + w * span]
        if order >= 1:
            out += [da[1] + w * (db[1] - da[1]), span]
        if order == 2:
            out += [da[2] + w * (db[2] - da[2]), db[1] - da[1], np.zeros_like(span)]
        return out
