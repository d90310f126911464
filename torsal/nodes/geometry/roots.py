"""Vectorised one-dimensional root finding inside brackets.

:func:`refine_roots` solves many bracketed equations at once (of either slope); it is
Newton's method inside a shrinking bracket, bisecting where Newton would leave it, and
stops as soon as a step is below rounding. It is the one solver: the ruling-developable
kernel uses it directly, closest points and arc-length inversion through
:func:`safeguarded_newton` (increasing functions, no rounding scale). (An earlier
safeguarded Newton rejected a step onto a bracket end and then bisected ~40 times
whenever an iterate had landed within rounding of the root: 933 of 2·10⁴ closest-point
problems were still bisecting after 5 iterations.)
:func:`roots_in_samples` brackets every sign change of a sampled function and refines
them all with scipy's vectorised Chandrupatla solver (``scipy.optimize.elementwise``).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy.optimize import elementwise

from .array_types import FloatArray, IntArray

#: Relative step below which a root counts as converged (~3e-14: past this, Newton's next
#: step would be below rounding). The caller keeps the last *evaluated* point, within
#: this step of the root, so that everything it computed there stays consistent.
STEP = 128.0 * np.finfo(float).eps
#: |f| below this times its terms' size is zero to rounding.
ZERO = 8.0 * np.finfo(float).eps


def refine_roots(
    function: Callable[[FloatArray, IntArray], tuple[FloatArray, FloatArray, FloatArray]],
    low: FloatArray,
    high: FloatArray,
    f_low: FloatArray,
    start: FloatArray | None = None,
    max_iterations: int = 100,
    xtol: float = 0.0,
) -> FloatArray:
    """One root of ``f`` inside each bracket ``[low, high]`` where ``f`` changes sign.

    ``function(x, index)`` returns ``(f, f', scale)`` at ``x`` for the brackets ``index``
    (those still iterating), in one vectorised call per iteration; ``scale`` is the size
    of the terms ``f`` is summed from, so that ``|f| <= 8·eps·scale`` is zero to rounding
    and stops the iteration (Newton would only jitter in the noise from there). ``f_low``
    is ``f(low)`` (only its sign is used). Converges quadratically at simple roots and by
    bisection onto jumps (a root of a discontinuous ``f`` is the jump). A step or
    bracket below ``xtol`` (absolute, besides the relative :data:`STEP`) also stops.
    """
    low, high = np.asarray(low, dtype=float), np.asarray(high, dtype=float)
    if start is None:
        x = 0.5 * (low + high)
    else:  # (np.clip is slow on small arrays)
        x = np.minimum(np.maximum(np.asarray(start, dtype=float), low), high)
    active = np.arange(len(x))
    low_sign = None  # the brackets are copied (they shrink in place) once a step needs them
    with np.errstate(divide="ignore", invalid="ignore"):
        for _ in range(max_iterations):
            if len(active) == 0:
                break
            # all of them (the first step): a slice reads and writes them without gathering
            at = slice(None) if len(active) == len(x) else active
            xa = x[at].copy()
            f, df, scale = function(xa, active)
            zero = np.abs(f) <= ZERO * scale
            if zero.all():  # the usual end: every start or step was on its root, to rounding
                break
            if low_sign is None:
                low, high = low.copy(), high.copy()
                low_sign = np.sign(np.asarray(f_low, dtype=float))
            on_low_side = np.sign(f) == low_sign[at]
            lo = np.where(on_low_side, xa, low[at])
            hi = np.where(on_low_side | (f == 0), high[at], xa)
            low[at], high[at] = lo, hi
            newton = xa - f / df
            inside = np.isfinite(newton) & (newton >= lo) & (newton <= hi)
            step_to = np.where(inside, newton, 0.5 * (lo + hi))
            tiny = np.maximum(STEP * np.maximum(np.abs(xa), 1e-300), xtol)
            done = zero | (inside & (np.abs(newton - xa) <= tiny)) | (hi - lo <= tiny)
            x[at] = np.where(zero, xa, step_to)
            active = active[~done]
    return x


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
    subset still iterating). :func:`refine_roots` without a rounding scale: it stops when
    the Newton step or the bracket is below ``xtol`` or rounding, or ``f`` is exactly 0.
    Each iteration is one vectorised call.
    """

    def with_scale(x: FloatArray, index: IntArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        f, df = function(x, index)
        return f, df, np.zeros_like(f)

    low = np.asarray(low, dtype=float)
    return refine_roots(with_scale, low, high, -np.ones_like(low), start, max_iterations, xtol)


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
