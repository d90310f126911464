"""Adaptive integration over the unit square, for surface areas and centroids.

``integrate_unit_square`` is a vectorised adaptive tensor Gauss–Legendre cubature:
every cell is integrated with an ``order × order`` rule and again as four children;
the difference is the cell's error estimate. Cells whose estimate is within their
share of the tolerance (proportional to their area) keep the children's value, the
others are split. All cells of one refinement level are evaluated in a single
vectorised call, so the integrand is called a handful of times, not per cell.

For smooth integrands (the area element |Su × Sv| of a smooth surface) an 8-point
rule on a 4 × 4 start grid is already at rounding level, and the estimate is
pessimistic (it measures the parent's error, the children are far better).
"""

from __future__ import annotations

import functools
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

Integrand = Callable[[FloatArray, FloatArray], FloatArray]


@functools.lru_cache(maxsize=32)
def gauss_legendre_01(order: int) -> tuple[FloatArray, FloatArray]:
    """Gauss–Legendre nodes and weights of ``order`` on [0, 1] (cached, read-only)."""
    nodes, weights = np.polynomial.legendre.leggauss(order)
    nodes, weights = 0.5 * (nodes + 1.0), 0.5 * weights
    nodes.flags.writeable = weights.flags.writeable = False
    return nodes, weights


def span_gauss(lows: FloatArray, highs: FloatArray, order: int) -> tuple[FloatArray, FloatArray]:
    """Nodes and weights of an ``order``-point Gauss rule on each interval [lows, highs],
    flattened interval by interval: ``(spans · order,)`` each."""
    x, w = gauss_legendre_01(order)
    width = (highs - lows)[:, None]
    return (lows[:, None] + width * x).ravel(), (width * w).ravel()


#: Most cells whose Gauss points are evaluated in one call of the integrand.
CHUNK_CELLS = 8192


def _cells_integral(
    func: Integrand,
    u0: FloatArray,
    v0: FloatArray,
    size: FloatArray,
    nodes: FloatArray,
    weights: FloatArray,
) -> FloatArray:
    """Tensor Gauss rule on square cells [u0, u0+size] × [v0, v0+size]; → (cells, k).
    Cells are evaluated :data:`CHUNK_CELLS` at a time, so memory stays bounded."""
    if len(u0) > CHUNK_CELLS:
        return np.concatenate([
            _cells_integral(func, u0[i:i + CHUNK_CELLS], v0[i:i + CHUNK_CELLS], size[i:i + CHUNK_CELLS],
                            nodes, weights)
            for i in range(0, len(u0), CHUNK_CELLS)
        ])
    g = len(nodes)
    uu = u0[:, None, None] + size[:, None, None] * nodes[None, :, None]
    vv = v0[:, None, None] + size[:, None, None] * nodes[None, None, :]
    uu, vv = np.broadcast_arrays(uu, vv)
    values = np.asarray(func(uu.ravel(), vv.ravel()), dtype=float)
    values = values.reshape(len(u0), g, g, -1)
    w2 = weights[:, None] * weights[None, :]
    return np.einsum("cijk,ij->ck", values, w2) * (size * size)[:, None]


def integrate_unit_square(
    func: Integrand,
    rtol: float = 1e-11,
    atol: float = 0.0,
    order: int = 8,
    start: int = 4,
    max_level: int = 12,
    max_cells: int = 200_000,
) -> FloatArray:
    """Integrate ``func(u, v)`` over [0, 1]², adaptively.

    ``func`` takes two equal-length 1-D arrays and returns ``(n,)`` or ``(n, k)``
    values; the result is a ``(k,)`` array (``k = 1`` for scalar integrands). The
    iteration stops when every cell's error estimate is below its area share of
    ``max(atol, rtol·|I|)`` (componentwise maximum), or when ``max_level`` or
    ``max_cells`` is reached.
    """
    nodes, weights = gauss_legendre_01(order)
    grid = np.arange(start) / start
    u0, v0 = (a.ravel() for a in np.meshgrid(grid, grid, indexing="ij"))
    size = np.full(u0.shape, 1.0 / start)
    parent = _cells_integral(func, u0, v0, size, nodes, weights)
    total = parent.sum(axis=0)
    accepted = np.zeros_like(total)
    for _ in range(max_level):
        half = 0.5 * size
        cu = np.concatenate([u0, u0 + half, u0, u0 + half])
        cv = np.concatenate([v0, v0, v0 + half, v0 + half])
        ch = np.concatenate([half] * 4)
        children = _cells_integral(func, cu, cv, ch, nodes, weights)
        n = len(u0)
        child_sum = children.reshape(4, n, -1).sum(axis=0)
        error = np.max(np.abs(child_sum - parent), axis=1)
        total = accepted + child_sum.sum(axis=0)
        tolerance = max(atol, rtol * float(np.max(np.abs(total))))
        done = error <= tolerance * (size * size)
        accepted = accepted + child_sum[done].sum(axis=0)
        # the next level would evaluate 4 children of each of the 4 kept children
        if done.all() or 16 * np.count_nonzero(~done) > max_cells:
            return accepted + child_sum[~done].sum(axis=0)
        keep = np.tile(~done, 4)
        u0, v0, size, parent = cu[keep], cv[keep], ch[keep], children[keep]
    return accepted + parent.sum(axis=0)
