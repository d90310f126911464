"""Evaluating a scipy :class:`~scipy.interpolate.BSpline` of points at many parameters, and
several derivative orders at once.

:class:`SplineValues` converts the parameters once for every order asked for and calls the
spline through its public ``__call__`` (scipy's private evaluation routine, which spared
the call's bookkeeping, is not used: the strips of a solve are evaluated together now, so
that bookkeeping is paid once per solve rather than once per strip).
"""

from __future__ import annotations

import numpy as np
from scipy.interpolate import BSpline

from .array_types import FloatArray


class SplineValues:
    """``values(u, nu)`` is ``spline(u, nu=nu)`` for one-dimensional ``u``: ``(len(u), k)``.

    The methods ending in ``_of`` take ``x`` as it is: a 1-D C-contiguous float64 array
    (:func:`evaluation_parameters`), for callers that convert their parameters once.
    """

    __slots__ = ("degree", "spline")

    def __init__(self, spline: BSpline) -> None:
        self.spline = spline
        self.degree = int(spline.k)

    def __call__(self, u: FloatArray, nu: int = 0) -> FloatArray:
        return self.value_of(evaluation_parameters(u), nu)

    def value_of(self, x: FloatArray, nu: int = 0) -> FloatArray:
        """``spline(x, nu=nu)`` for ``x`` already 1-D, contiguous and float64."""
        return self.spline(x, nu=nu)

    def orders(self, u: FloatArray, orders: int) -> list[FloatArray]:
        """``[spline(u, nu=k) for k in range(orders)]``, ``u`` converted once for all of them."""
        return self.orders_of(evaluation_parameters(u), orders)

    def orders_of(self, x: FloatArray, orders: int) -> list[FloatArray]:
        """:meth:`orders` for ``x`` already 1-D, contiguous and float64."""
        return [self.spline(x, nu=k) for k in range(orders)]

    def rows(self, u: FloatArray, orders: int, out: FloatArray) -> None:
        """``out[k] = spline(u, nu=k).T`` for k below ``orders``: ``out`` is ``(≥ orders, k, len(u))``
        (``u`` converted once for all of them)."""
        x = evaluation_parameters(u)
        for k in range(orders):
            out[k] = self.spline(x, nu=k).T


def evaluation_parameters(u: FloatArray) -> FloatArray:
    """``u`` as the 1-D C-contiguous float64 array the evaluation routine takes (``u`` itself
    when it already is one)."""
    x = np.ascontiguousarray(u, dtype=np.float64)
    return x if x.ndim == 1 else x.reshape(-1)


def spline_values(spline: BSpline, u: FloatArray, nu: int = 0) -> FloatArray:
    """``spline(u, nu=nu)`` through :class:`SplineValues` (for a spline evaluated once; keep
    a :class:`SplineValues` for one evaluated many times)."""
    return SplineValues(spline)(u, nu)
