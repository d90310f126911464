"""Evaluating a scipy :class:`~scipy.interpolate.BSpline` of points without its per-call overhead.

A kernel solve evaluates small curves hundreds of times (a ruling strip's edges at a few
dozen parameters each time), and ``BSpline.__call__`` spends several times longer on
array-API bookkeeping (``asarray`` and device checks, also on every read of the spline's
``t`` and ``c``) than on the evaluation itself. :class:`SplineValues` reads the knots and
coefficients once and calls the evaluation routine ``BSpline.__call__`` ends in, with the
same arguments, so the values are the same bit for bit. Where that routine is not there
(another scipy), or the spline is periodic (its parameters are wrapped first) or not a
real ``(n, k)`` spline along axis 0, it calls the spline as usual.
"""

from __future__ import annotations

import numpy as np
from scipy.interpolate import BSpline

from .array_types import FloatArray

try:  # the routine BSpline.__call__ evaluates with (scipy >= 1.15)
    from scipy.interpolate import _dierckx

    _evaluate = _dierckx.evaluate_spline
except (ImportError, AttributeError):  # pragma: no cover - another scipy: the public call
    _evaluate = None


class SplineValues:
    """``values(u, nu)`` is ``spline(u, nu=nu)`` for one-dimensional ``u``: ``(len(u), k)``.

    ``knots`` and ``coefficients``, when the caller has them at hand, are the spline's own
    ``t`` and ``c`` (as float64 arrays), spared their reads through the spline's properties.
    The methods ending in ``_of`` take ``x`` as it is: a 1-D C-contiguous float64 array
    (:func:`evaluation_parameters`), for callers that convert their parameters once.
    """

    __slots__ = ("coefficients", "degree", "knots", "spline")

    def __init__(
        self, spline: BSpline, knots: FloatArray | None = None, coefficients: FloatArray | None = None
    ) -> None:
        self.spline = spline
        c = spline.c if coefficients is None else coefficients
        direct = (
            _evaluate is not None and spline.extrapolate is True and spline.axis == 0
            and c.ndim == 2 and c.dtype == np.float64
        )
        t = spline.t if knots is None else knots
        self.knots = np.ascontiguousarray(t, dtype=np.float64) if direct else None
        self.coefficients = np.ascontiguousarray(c) if direct else None
        self.degree = int(spline.k)

    def __call__(self, u: FloatArray, nu: int = 0) -> FloatArray:
        return self.value_of(evaluation_parameters(u), nu)

    def value_of(self, x: FloatArray, nu: int = 0) -> FloatArray:
        """``spline(x, nu=nu)`` for ``x`` already 1-D, contiguous and float64."""
        if self.knots is None:
            return self.spline(x, nu=nu)
        return _evaluate(self.knots, self.coefficients, self.degree, x, nu, True)

    def orders(self, u: FloatArray, orders: int) -> list[FloatArray]:
        """``[spline(u, nu=k) for k in range(orders)]``, ``u`` converted once for all of them."""
        return self.orders_of(evaluation_parameters(u), orders)

    def orders_of(self, x: FloatArray, orders: int) -> list[FloatArray]:
        """:meth:`orders` for ``x`` already 1-D, contiguous and float64."""
        knots, coefficients, degree = self.knots, self.coefficients, self.degree
        if knots is None:
            return [self.spline(x, nu=k) for k in range(orders)]
        return [_evaluate(knots, coefficients, degree, x, k, True) for k in range(orders)]

    def rows(self, u: FloatArray, orders: int, out: FloatArray) -> None:
        """``out[k] = spline(u, nu=k).T`` for k below ``orders``: ``out`` is ``(≥ orders, k, len(u))``
        (``u`` converted once for all of them)."""
        x = evaluation_parameters(u)
        if self.knots is None:
            for k in range(orders):
                out[k] = self.spline(x, nu=k).T
            return
        for k in range(orders):
            out[k] = _evaluate(self.knots, self.coefficients, self.degree, x, k, True).T


def evaluation_parameters(u: FloatArray) -> FloatArray:
    """``u`` as the 1-D C-contiguous float64 array the evaluation routine takes (``u`` itself
    when it already is one)."""
    x = np.ascontiguousarray(u, dtype=np.float64)
    return x if x.ndim == 1 else x.reshape(-1)


def spline_values(spline: BSpline, u: FloatArray, nu: int = 0) -> FloatArray:
    """``spline(u, nu=nu)`` through :class:`SplineValues` (for a spline evaluated once; keep
    a :class:`SplineValues` for one evaluated many times)."""
    return SplineValues(spline)(u, nu)
