"""Knot vectors for B-splines: clamped-uniform, periodic extension and validation.

scipy's :class:`~scipy.interpolate.BSpline` evaluates any knot vector but does not build
clamped or periodic ones for given control points, nor check user input; that is here.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ..array_types import FloatArray


def clamped_uniform_knots(count: int, degree: int) -> FloatArray:
    """Clamped knot vector on [0, 1] for ``count`` control points, interior knots equally spaced.

    End knots have multiplicity ``degree + 1`` so the curve starts and ends at its first
    and last control points.
    """
    interior = np.linspace(0.0, 1.0, count - degree + 1)[1:-1]
    return np.concatenate([np.zeros(degree + 1), interior, np.ones(degree + 1)])


def periodic_knots(breakpoints: ArrayLike, degree: int) -> FloatArray:
    """Full knot vector of a periodic B-spline from one period's ``n + 1`` breakpoints.

    The ``n`` spacings repeat with period ``breakpoints[-1] - breakpoints[0]``: ``degree``
    knots are added on each side, giving ``n + 2·degree + 1`` knots for ``n + degree``
    (wrapped) control points. The curve's domain is ``[breakpoints[0], breakpoints[-1]]``.
    """
    b = np.asarray(breakpoints, dtype=float)
    n = len(b) - 1
    period = b[-1] - b[0]
    index = np.arange(-degree, n + degree + 1)
    # knot i = b[i mod n] + (i div n)·period, for i from -degree to n + degree
    return b[np.mod(index, n)] + np.floor_divide(index, n) * period


def check_knots(knots: ArrayLike, count: int, degree: int) -> FloatArray:
    """Validate a full knot vector for ``count`` control points, or raise ``ValueError``.

    Accepts the full ``count + degree + 1`` knots or the ``count + degree - 1`` of the
    Rhino/openNURBS convention (which omits one knot at each end; they are duplicated).
    """
    k = np.asarray(knots, dtype=float).reshape(-1)
    if len(k) == count + degree - 1:
        k = np.concatenate([k[:1], k, k[-1:]])
    if len(k) != count + degree + 1:
        raise ValueError(
            f"A degree-{degree} curve with {count} control points needs {count + degree + 1} "
            f"knots; got {len(k)}."
        )
    if not np.all(np.isfinite(k)):
        raise ValueError("The knot vector contains a non-finite value.")
    if np.any(np.diff(k) < 0):
        raise ValueError("The knot vector must be non-decreasing.")
    if not k[degree] < k[count]:
        raise ValueError("The knot vector's domain is empty (all active knots are equal).")
    interior = k[degree + 1 : count]
    if len(interior):
        _, multiplicity = np.unique(interior, return_counts=True)
        if multiplicity.max() > degree:
            raise ValueError(
                f"An interior knot repeats more than the degree ({degree}) times; "
                "the curve would break apart there."
            )
    return k
