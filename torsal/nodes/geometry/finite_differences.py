"""High-order finite differences for curves known only through a function of t.

A 9-point stencil (error O(h⁸)) gives the k-th derivative at every requested t in one
vectorised call of the function. Near the ends of [0, 1] the stencil slides inwards so
the function is never called outside its domain (one-sided stencils are less accurate:
larger error constants). The step h is chosen once per derivative order by halving it
and keeping the h where successive estimates agree best — the point where truncation
error (falling as h⁸) meets rounding error (growing as ε/hᵏ).
"""

from __future__ import annotations

from collections.abc import Callable
from itertools import pairwise
from math import factorial

import numpy as np

from .array_types import FloatArray

#: Half-width of the stencil: 2·HALF_WIDTH + 1 points.
HALF_WIDTH = 4
#: Candidate steps, as exponents of 2 (h = 2^-e) in the normalised parameter t.
STEP_EXPONENTS = np.arange(4, 22)


def stencil_weights(offsets: FloatArray, order: int) -> FloatArray:
    """Weights ``w`` with ``Σ w_j f(x + o_j h) ≈ h^order f^(order)(x)`` for offsets ``o_j``.

    Solves the moment conditions ``Σ w_j o_j^m / m! = δ(m, order)`` for m below the
    stencil size. The offsets are small integers, so the Vandermonde system is solved
    once per stencil shape, not per point.
    """
    o = np.asarray(offsets, dtype=float)
    m = np.arange(len(o))
    vandermonde = o[None, :] ** m[:, None] / np.array([factorial(i) for i in m])[:, None]
    rhs = (m == order).astype(float)
    return np.linalg.solve(vandermonde, rhs)


def _shifted_weights(order: int) -> FloatArray:
    """Weights for the stencil shifted by s = -HALF_WIDTH..HALF_WIDTH, shape (2W+1, 2W+1)."""
    base = np.arange(-HALF_WIDTH, HALF_WIDTH + 1)
    return np.stack([stencil_weights(base + s, order) for s in range(-HALF_WIDTH, HALF_WIDTH + 1)])


def derivative(
    function: Callable[[FloatArray], FloatArray], t: FloatArray, order: int, step: float
) -> FloatArray:
    """The ``order``-th derivative of ``function`` (t in [0, 1] → (n, 3)) at ``t``.

    ``step`` must satisfy ``2·HALF_WIDTH·step <= 1`` so a stencil fits inside [0, 1].
    """
    t = np.asarray(t, dtype=float)
    base = np.arange(-HALF_WIDTH, HALF_WIDTH + 1)
    # slide the stencil right near t = 0 and left near t = 1 to stay inside [0, 1]
    low = np.ceil(HALF_WIDTH - t / step - 1e-9)
    high = np.floor((1.0 - t) / step - HALF_WIDTH + 1e-9)
    shift = np.clip(0, low, high).clip(-HALF_WIDTH, HALF_WIDTH).astype(int)
    nodes = np.clip(t[:, None] + (base[None, :] + shift[:, None]) * step, 0.0, 1.0)
    values = function(nodes.reshape(-1)).reshape(len(t), len(base), -1)
    weights = _shifted_weights(order)[shift + HALF_WIDTH]
    return np.einsum("nj,njc->nc", weights, values) / step**order


def best_step(function: Callable[[FloatArray], FloatArray], order: int) -> float:
    """The step h for :func:`derivative` of ``order`` where successive halvings agree best.

    Probes 33 parameters (ends included); for each candidate h the error estimate is
    ``max |D(h) − D(h/2)|``. That difference shrinks like h⁸ while truncation dominates and
    grows again once rounding dominates; its minimum marks the best h.
    """
    probes = np.linspace(0.0, 1.0, 33)
    estimates = [derivative(function, probes, order, 2.0**-e) for e in STEP_EXPONENTS]
    change = [np.abs(a - b).max() for a, b in pairwise(estimates)]
    return float(2.0 ** -STEP_EXPONENTS[int(np.argmin(change))])
