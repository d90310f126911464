"""Evaluating a scipy :class:`~scipy.interpolate.BSpline` of points without its per-call overhead.

A kernel solve evaluates small curves hundreds of times (a ruling strip's edges at a few
dozen parameters each time), and ``BSpline.__call__`` spends several times longer on
array-API bookkeeping (``asarray``, device checks, reshapes) than on the evaluation
itself. :func:`spline_values` calls the evaluation routine ``BSpline.__call__`` ends in,
with the same arguments, so the values are the same bit for bit; where that routine is
not there (another scipy), or the spline is periodic (its parameters are wrapped
first), it calls the spline as usual.
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


def spline_values(spline: BSpline, u: FloatArray, nu: int = 0) -> FloatArray:
    """``spline(u, nu=nu)`` for a spline with real ``(n, k)`` coefficients along axis 0 and
    one-dimensional ``u``: ``(len(u), k)``."""
    c = spline.c
    if (
        _evaluate is None
        or spline.extrapolate is not True
        or spline.axis != 0
        or c.ndim != 2
        or c.dtype != np.float64
        or not c.flags.c_contiguous
        or not spline.t.flags.c_contiguous
    ):
        return spline(u, nu=nu)
    x = np.ascontiguousarray(u, dtype=np.float64).reshape(-1)
    return _evaluate(spline.t, c, spline.k, x, nu, True)
