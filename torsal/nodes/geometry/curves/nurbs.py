"""NURBS curves of any degree: rational weights, clamped, unclamped or periodic knots.

Evaluation is scipy's :class:`~scipy.interpolate.BSpline` run on homogeneous coordinates
``(w·P, w)``; scipy has no rational B-splines, so the projection back to 3D and the
derivatives of the quotient (the generalised quotient rule) are written here.
"""

from __future__ import annotations

from functools import lru_cache
from math import comb, sqrt

import numpy as np
from numpy.typing import ArrayLike
from scipy.interpolate import BSpline

from ..array_types import FloatArray
from ..curve_base import Curve, turning_points
from ..spline_eval import SplineValues, evaluation_parameters
from ..vec_ops import bounds
from ..vectors import as_points
from .knots import check_knots, clamped_uniform_knots, periodic_knots


@lru_cache(maxsize=64)
def _unit_weights(count: int) -> FloatArray:
    """``count`` weights of 1, read-only (one array shared by the polynomial curves of that size)."""
    weights = np.ones(count)
    weights.setflags(write=False)
    return weights


class NurbsCurve(Curve):
    """A non-uniform rational B-spline curve, reparameterised to t in [0, 1].

    Args:
        control_points: ``(n, 3)`` (or ``(n, 2)``) control points.
        degree: polynomial degree, at least 1; needs ``n >= degree + 1`` points.
        knots: ``None`` for a clamped knot vector with uniform interior knots; otherwise
            the full ``n + degree + 1`` knots (or the ``n + degree - 1`` of Rhino's
            convention). With ``periodic=True``, the ``n + 1`` breakpoints of one period.
        weights: ``n`` positive weights; ``None`` for a polynomial (non-rational) curve.
        periodic: close the curve smoothly: the first ``degree`` control points (and
            weights) are repeated after the last, knots are extended periodically, and
            the curve is C^(degree-1) across its seam.

    The original knot domain ``[knots[degree], knots[n]]`` is kept in :attr:`domain`;
    ``t = 0`` and ``t = 1`` map to its ends and derivatives are scaled by the chain rule.
    For a periodic curve :attr:`control_points`, :attr:`weights` and :attr:`knots` are
    the full (wrapped) arrays that evaluation uses.

    >>> square = NurbsCurve([[0, 0], [1, 0], [1, 1], [0, 1]], degree=1, periodic=True)
    >>> square.point_at(0.5).tolist()
    [1.0, 1.0, 0.0]
    """

    #: Derivatives from the definition, not differences of positions (:func:`.vec_ops.differenced`).
    exact_derivatives = True

    def __init__(
        self,
        control_points: ArrayLike,
        degree: int = 3,
        knots: ArrayLike | None = None,
        weights: ArrayLike | None = None,
        periodic: bool = False,
    ) -> None:
        points = as_points(control_points)
        count = len(points)
        if int(degree) != degree or degree < 1:
            raise ValueError(f"A NURBS curve's degree must be a whole number >= 1; got {degree}.")
        degree = int(degree)
        if count < degree + 1:
            raise ValueError(
                f"A degree-{degree} curve needs at least {degree + 1} control points; got {count}."
            )
        if not np.all(np.isfinite(points)):
            raise ValueError("A control point has a non-finite coordinate.")
        w = None if weights is None else np.asarray(weights, dtype=float).reshape(-1)
        if w is not None:
            if len(w) != count:
                raise ValueError(f"Expected {count} weights, one per control point; got {len(w)}.")
            if not np.all(np.isfinite(w) & (w > 0)):
                raise ValueError("Every weight must be a positive finite number.")
        if periodic:
            breaks = np.arange(count + 1.0) if knots is None else np.asarray(knots, float)
            if breaks.shape != (count + 1,) or np.any(np.diff(breaks) <= 0):
                raise ValueError(
                    f"A periodic curve with {count} control points needs {count + 1} strictly "
                    "increasing breakpoints."
                )
            full_knots = periodic_knots(breaks, degree)
            points = np.concatenate([points, points[:degree]])
            if w is not None:
                w = np.concatenate([w, w[:degree]])
        elif knots is None:
            full_knots = clamped_uniform_knots(count, degree)
        else:
            full_knots = check_knots(knots, count, degree)
        self._setup(points, w, full_knots, degree, periodic)

    def _setup(
        self,
        points: FloatArray,
        weights: FloatArray | None,
        knots: FloatArray,
        degree: int,
        periodic: bool,
    ) -> None:
        """Store full (already wrapped) arrays and build the homogeneous spline."""
        if weights is not None and np.ptp(weights) == 0:
            weights = None  # equal weights cancel: a polynomial curve
        # the spline runs on control points relative to their box's centre (kept in
        # _anchor): derivatives, lengths and areas then round relative to the curve's
        # size, wherever it sits; only positions add the anchor back
        low, high = bounds(points)
        anchor = 0.5 * (high + low)  # (vec_ops.anchor, from the same bounds)
        local = points - anchor
        coefficients = local if weights is None else np.column_stack([local * weights[:, None], weights])
        self._set_spline(points, weights, knots, degree, periodic, anchor, coefficients)
        if periodic:
            self.closed = True
        else:
            self._set_closed((high - low).max())  # (vec_ops.extent)

    def _set_spline(
        self,
        points: FloatArray,
        weights: FloatArray | None,
        knots: FloatArray,
        degree: int,
        periodic: bool,
        anchor: FloatArray,
        coefficients: FloatArray,
    ) -> None:
        """:meth:`_setup` once the ``anchor`` (the centre of the control points' box) and
        the spline's ``coefficients`` are known, all but whether the curve is closed."""
        self.degree: int = degree
        self.knots: FloatArray = knots
        self.control_points: FloatArray = points
        self.weights: FloatArray = _unit_weights(len(points)) if weights is None else weights
        self.is_rational: bool = weights is not None
        self.periodic: bool = periodic
        self._basis_key: tuple[int, bool, bytes] | None = None  # (basis_key, made when asked for)
        count = len(points)
        a, b = self.domain = (float(knots[degree]), float(knots[count]))
        # u = a + (b − a)·t, spared on most curves (u is t: a unit domain changes no bit)
        self._unit_domain = a == 0.0 and b == 1.0
        self._offset, self._scale = a, b - a
        self._anchor: FloatArray = anchor
        self._anchor.setflags(write=False)
        # 'periodic' extrapolation wraps t outside [0, 1] around a periodic curve; the
        # knots and coefficients are checked already (construct_fast skips scipy's checks)
        knots = np.ascontiguousarray(knots, dtype=float)
        coefficients = np.ascontiguousarray(coefficients, dtype=float)
        #: what the spline combines: the local control points (times the weights, and the
        #: weights, for a rational curve), read by :mod:`.shared_knots`
        self._coefficients: FloatArray = coefficients
        self._spline = BSpline.construct_fast(
            knots, coefficients, degree, extrapolate="periodic" if periodic else True
        )
        self._values = SplineValues(self._spline)
        for array in (self.knots, self.control_points, self.weights):
            array.setflags(write=False)

    def _set_closed(self, span: float) -> None:
        """Whether an open curve's ends meet, within 1e-12 of its control points' extent
        ``span`` (from its :attr:`end_points`)."""
        gap = self.end_points[0] - self.end_points[1]
        self.closed = bool(sqrt(gap.dot(gap)) <= 1e-12 * max(span, 1.0))  # as np.linalg.norm(gap)

    @classmethod
    def from_arrays(
        cls,
        control_points: ArrayLike,
        knots: ArrayLike,
        degree: int,
        weights: ArrayLike | None = None,
        periodic: bool = False,
    ) -> NurbsCurve:
        """A curve from full arrays as produced by another curve (no wrapping, light checks).

        ``periodic`` only marks the curve as periodic (smooth seam, wrapped evaluation);
        the caller guarantees the arrays already are.
        """
        curve = cls.__new__(cls)
        points = as_points(control_points)
        full = check_knots(knots, len(points), degree)
        w = None if weights is None else np.asarray(weights, dtype=float).reshape(-1)
        NurbsCurve._setup(curve, points, w, full, int(degree), periodic)
        return curve

    @property
    def basis_key(self) -> tuple[int, bool, bytes]:
        """What the curve's B-spline basis depends on: its degree, whether it is rational
        and its knots' bits (curves with one key are evaluated together, :mod:`.shared_knots`)."""
        key = self._basis_key
        if key is None:
            key = self._basis_key = (self.degree, self.is_rational, self.knots.tobytes())
        return key

    # -- evaluation -------------------------------------------------------------------

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        """Points and derivatives with respect to t, by the rational quotient rule.

        With ``A(u) = Σ wᵢPᵢNᵢ(u)`` and ``w(u) = Σ wᵢNᵢ(u)`` the curve is ``C = A / w`` and
        ``C⁽ᵏ⁾ = (A⁽ᵏ⁾ − Σᵢ₌₁ᵏ C(k,i) w⁽ⁱ⁾ C⁽ᵏ⁻ⁱ⁾) / w``. Each order then gains a factor
        ``(b − a)`` for the map ``u = a + (b − a)·t``.
        """
        result = self.local_derivatives(t, order)
        points = result[0]  # (a new array: the anchor is added in place, the same sums)
        points += self._anchor
        return result

    @property
    def anchor(self) -> FloatArray:
        """The centre of the control points' bounding box: see :meth:`local_derivatives`."""
        return self._anchor

    def local_derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        """:meth:`derivatives` with the points relative to :attr:`anchor` (not rounded to
        the world position: the rounding is relative to the curve's size)."""
        u, scale = self._knot_parameters(t)
        degree = self.degree
        if not self.is_rational:
            # every order at once (u converted once), zeros above the degree
            result = self._values.orders_of(u, (order if order < degree else degree) + 1)
            if scale != 1.0:  # (a factor of 1 changes no bit)
                result[1:] = [c * scale**k for k, c in enumerate(result[1:], start=1)]
            if order > degree:
                result.extend(np.zeros((len(u), 3)) for _ in range(order - degree))
            return result
        # the quotient rule on coordinate rows (4, n) rather than on (n, 4) points: every
        # operation then runs along contiguous rows, not n times over 3 coordinates
        values, n = self._values, len(u)
        rows = np.empty((order + 1, 4, n))
        values.rows(u, min(order, degree) + 1, rows)
        rows[degree + 1 :] = 0.0  # (the derivatives above the degree)
        result = quotient_rule(rows, order)
        if scale != 1.0:  # (a factor of 1 changes no bit)
            result = [c * scale**k for k, c in enumerate(result)]
        points = np.empty((order + 1, n, 3))
        for k, c in enumerate(result):
            points[k] = c.T
        return list(points)

    def point_at(self, t: ArrayLike) -> FloatArray:
        """Points at parameters ``t``: ``(n, 3)`` for an array, ``(3,)`` for a scalar
        (:meth:`derivative_at` of order 0: for a polynomial curve no list of orders)."""
        return self.derivative_at(t, 0)

    def derivative_at(self, t: ArrayLike, order: int = 1) -> FloatArray:
        """The ``order``-th derivative alone; a polynomial curve evaluates no lower order."""
        if self.is_rational:
            if order == 0:
                return super().derivative_at(t, order)
            scalar = np.ndim(t) == 0
            d = self.local_derivatives(np.atleast_1d(np.asarray(t, dtype=float)), order)[order]
            return d[0] if scalar else d  # (derivatives() would only move the points)
        u, scale = self._knot_parameters(t)
        d = self._polynomial_derivative(u, order, scale)
        if order == 0:
            d += self._anchor
        return d[0] if np.ndim(t) == 0 else d

    def _knot_parameters(self, t: ArrayLike) -> tuple[FloatArray, float]:
        """Knot parameters ``u = a + (b − a)·t`` for ``t``, and ``b − a``; ``u`` is a 1-D
        contiguous float64 array (what the spline evaluation takes as it is)."""
        t = evaluation_parameters(t)
        if self._unit_domain:  # most curves (u is t: spare the two passes over it)
            return t, 1.0
        return self._offset + self._scale * t, self._scale

    def _polynomial_derivative(self, u: FloatArray, k: int, scale: float) -> FloatArray:
        """``C⁽ᵏ⁾`` of a polynomial (non-rational) curve at knot parameters ``u``, per unit t
        (for k = 0 relative to :attr:`anchor`)."""
        if k > self.degree:
            return np.zeros((len(u), 3))
        value = self._values.value_of(u, k)
        return value if k == 0 or scale == 1.0 else value * scale**k

    def _breakpoints(self) -> FloatArray:
        # computed once (the knots are read-only) and handed out read-only
        breaks = self.__dict__.get("_breaks")
        if breaks is None:
            a, b = self.domain
            inside = self.knots[self.degree + 1 : len(self.control_points)]  # (the others lie outside)
            inside = inside[(inside > a) & (inside < b)]
            if len(inside):  # the distinct ones (the knots increase)
                inside = inside[np.concatenate([[True], inside[1:] > inside[:-1]])]
                breaks = np.concatenate([[0.0], (inside - a) / (b - a), [1.0]])
            else:  # one span (a Bézier curve)
                breaks = np.array([0.0, 1.0])
            breaks.setflags(write=False)
            self._breaks = breaks
        return breaks

    def _find_kinks(self) -> FloatArray:
        """Where the tangent turns (see :meth:`Curve.kinks`): only an inner knot of
        multiplicity ≥ degree can be a corner (the curve is C^(degree − multiplicity)
        elsewhere), and the ones where the tangent turns are (a re-weighted arc's double
        knots, a degree-1 curve's vertices)."""
        a, b = self.domain
        values, counts = np.unique(self.knots[(self.knots > a) & (self.knots < b)], return_counts=True)
        return turning_points(self, (values[counts >= self.degree] - a) / (b - a))

    # -- exact operations ---------------------------------------------------------------

    def reversed(self) -> NurbsCurve:
        """The same curve traversed backwards, exactly: knots mirrored, points reversed."""
        a, b = self.domain
        return NurbsCurve.from_arrays(
            self.control_points[::-1],
            (a + b) - self.knots[::-1],
            self.degree,
            self.weights[::-1] if self.is_rational else None,
            self.periodic,
        )

    def transformed(self, matrix: ArrayLike) -> NurbsCurve:
        """The curve under a 4×4 transform, exactly, including perspective transforms.

        NURBS are projectively invariant: transforming the homogeneous control points
        ``(w·x, w·y, w·z, w)`` transforms the curve, and the new weights are the last
        coordinate. They must stay positive (the curve must not cross the vanishing plane).
        """
        m = np.asarray(matrix, dtype=float)
        if m.shape != (4, 4):
            raise ValueError(f"Expected a 4×4 transform matrix, got shape {m.shape}.")
        homogeneous = np.column_stack([self.control_points, np.ones(len(self.control_points))])
        image = (homogeneous * self.weights[:, None]) @ m.T
        weights = image[:, 3]
        if np.any(weights <= 0):
            raise ValueError("The transform sends part of the curve to infinity.")
        return NurbsCurve.from_arrays(
            image[:, :3] / weights[:, None], self.knots, self.degree, weights, self.periodic
        )

    def to_nurbs(self) -> NurbsCurve:
        """This curve (it already is a NURBS curve)."""
        return self

    def __repr__(self) -> str:
        kind = "periodic" if self.periodic else "rational" if self.is_rational else "polynomial"
        return (
            f"{type(self).__name__}(degree={self.degree}, control_points={len(self.control_points)}, {kind})"
        )


def quotient_rule(rows: FloatArray, order: int) -> list[FloatArray]:
    """The derivatives of orders 0 to ``order`` of a rational curve, each as coordinate
    rows ``(3, n)``, from those of its homogeneous form ``rows`` ``(order + 1, 4, n)``
    (x·w, y·w, z·w, w): Leibniz's rule for C = A / w solved order by order."""
    w = rows[:, 3]
    w0 = w[0]
    result: list[FloatArray] = [rows[0, :3] / w0]
    for k in range(1, order + 1):
        # (a binomial coefficient of 1 multiplies exactly: it is left out)
        numerator = rows[k, :3] - (w[1] if k == 1 else k * w[1]) * result[k - 1]
        for i in range(2, k + 1):
            factor = comb(k, i)
            numerator -= (w[i] if factor == 1 else factor * w[i]) * result[k - i]
        result.append(numerator / w0)
    return result
