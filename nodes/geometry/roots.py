"""Vectorised one-dimensional root finding inside brackets.

:func:`safeguarded_newton` solves many increasing equations at once; it is Newton's
method where Newton behaves and bisection where it would leave the bracket. It is used
for closest points and arc-length inversion, where the derivative is at hand.
:func:`roots_in_samples` brackets every sign change of a sampled function and refines
them all with scipy's vectorised Chandrupatla solver (``scipy.optimize.elementwise``).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import elementwise

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


def safeguarded_newton(
    function: Callable[[FloatArray, IntArray], tuple[FloatArray, FloatArray]],
    low: FloatArray,
    high: FloatArray,
    start: FloatArray,
    xtol: float = 1e-15,
    max_iterations: int = 100,
) -> FloatArray:
    """Roots of increasing functions, one per bracket ``[low, high]``, with ``f(low) <= 0 <= f(high)``.

    ``function(x, index)`` returns ``(f, f')`` at ``x`` for the problems ``index`` (the
    subset still iterating). Iterates until the Newton step or the bracket is below
    ``xtol`` or ``f`` is exactly 0. Each iteration is one vectorised call.
    """
    x = np.clip(np.asarray(start, dtype=float).copy(), low, high)
    low = np.asarray(low, dtype=float).copy()
    high = np.asarray(high, dtype=float).copy()
    active = np.arange(len(x))
    for _ in range(max_iterations):
        if len(active) == 0:
            break
        xa = x[active]
        f, df = function(xa, active)
        below = f < 0
        low[active] = np.where(below, xa, low[active])
        high[active] = np.where(below, high[active], xa)
        lo, hi = low[active], high[active]
        with np.errstate(divide="ignore", invalid="ignore"):
            newton = xa - f / df
        ok = (df > 0) & (newton > lo) & (newton < hi) & np.isfinite(newton)
        root = f == 0
        step_to = np.where(root, xa, np.where(ok, newton, 0.5 * (lo + hi)))
        x[active] = step_to
        done = root | (np.abs(step_to - xa) <= xtol) | (hi - lo <= xtol)
        active = active[~done]
    return x


def roots_in_samples(
    function: Callable[[FloatArray], FloatArray],
    samples: FloatArray,
    xtol: float = 1e-15,
) -> FloatArray:
    """All roots of a scalar ``function`` of t that change sign between consecutive samples.

    ``function`` maps an array of t to an array of values (any shape in, same shape
    out). Samples where the value is exactly zero are roots themselves; a run of zero
    samples (the function vanishing on an interval) contributes its two ends. Roots
    that touch zero without changing sign between samples are not found.
    """
    t = np.asarray(samples, dtype=float)
    values = function(t)
    zero = values == 0
    # the two ends of every run of exact zeros
    starts = zero & ~np.concatenate([[False], zero[:-1]])
    ends = zero & ~np.concatenate([zero[1:], [False]])
    exact = t[starts | ends]
    change = np.nonzero(np.sign(values[:-1]) * np.sign(values[1:]) < 0)[0]
    if len(change):
        result = elementwise.find_root(
            function,
            (t[change], t[change + 1]),
            tolerances={"xatol": xtol, "xrtol": 4 * np.finfo(float).eps, "fatol": 0.0},
        )
        refined = np.asarray(result.x, dtype=float)
    else:
        refined = np.empty(0)
    return np.unique(np.concatenate([exact, refined]))
