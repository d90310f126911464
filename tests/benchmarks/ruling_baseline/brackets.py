"""Refining many bracketed roots at once: Newton's method inside a shrinking bracket.

Like :func:`~..roots.safeguarded_newton`, but for functions of either slope (the sign of
``f`` at each bracket's low end says which side is which), accepting a Newton step that
lands on a bracket end, and stopping as soon as a step is below rounding. (The shared
solver rejects a step onto the bracket end and then bisects ~40 times whenever an
iterate has landed within rounding of the root: a third of all brackets here.)
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from nodes.geometry.curve_base import FloatArray

IntArray = NDArray[np.int64]

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
) -> FloatArray:
    """One root of ``f`` inside each bracket ``[low, high]`` where ``f`` changes sign.

    ``function(x, index)`` returns ``(f, f', scale)`` at ``x`` for the brackets ``index``
    (those still iterating), in one vectorised call per iteration; ``scale`` is the size
    of the terms ``f`` is summed from, so that ``|f| <= 8·eps·scale`` is zero to rounding
    and stops the iteration (Newton would only jitter in the noise from there). ``f_low``
    is ``f(low)`` (only its sign is used). Converges quadratically at simple roots and by
    bisection onto jumps (a root of a discontinuous ``f`` is the jump).
    """
    low = np.array(low, dtype=float)  # copies: the brackets shrink in place
    high = np.array(high, dtype=float)
    low_sign = np.sign(np.asarray(f_low, dtype=float))
    if start is None:
        x = 0.5 * (low + high)
    else:  # (np.clip is slow on small arrays)
        x = np.minimum(np.maximum(np.asarray(start, dtype=float), low), high)
    active = np.arange(len(x))
    with np.errstate(divide="ignore", invalid="ignore"):
        for _ in range(max_iterations):
            if len(active) == 0:
                break
            xa = x[active]
            f, df, scale = function(xa, active)
            zero = np.abs(f) <= ZERO * scale
            if zero.all():  # the usual end: every start or step was on its root, to rounding
                break
            on_low_side = np.sign(f) == low_sign[active]
            lo = np.where(on_low_side, xa, low[active])
            hi = np.where(on_low_side | (f == 0), high[active], xa)
            low[active], high[active] = lo, hi
            newton = xa - f / df
            inside = np.isfinite(newton) & (newton >= lo) & (newton <= hi)
            step_to = np.where(inside, newton, 0.5 * (lo + hi))
            tiny = STEP * np.maximum(np.abs(xa), 1e-300)
            done = zero | (inside & (np.abs(newton - xa) <= tiny)) | (hi - lo <= tiny)
            x[active] = np.where(zero, xa, step_to)
            active = active[~done]
    return x
