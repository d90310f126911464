"""Adaptive integration over the unit square, for surface areas and centroids.

``integrate_unit_square`` is a vectorised adaptive tensor Gauss–Legendre cubature:
every cell is integrated with an ``order × order`` rule and again as four children;
the difference is the cell's error estimate. Cells whose estimate is within their
share of the tolerance (proportional to their area) keep the children's value, the
others are split. All cells of one refinement level are evaluated in a single
vectorised call, so the integrand is called a handful of times, not per cell.

The start grid is a 4 × 4 grid of squares, or any rectangular grid given by its
breaks: a spline surface passes its knots, so that no cell straddles a knot, where
the area element is not smooth (a cell across a knot converges only slowly: a bumpy
24 × 24 bicubic surface took 55 s on power-of-two cells, 0.1 s from its knot grid).

For smooth integrands (the area element |Su × Sv| of a smooth surface) an 8-point
rule on the start grid is already at rounding level, and the estimate is pessimistic
(it measures the parent's error, the children are far better).

Long integrals can be stopped and watched: ``check`` is called between blocks of
cells (it raises to stop, e.g. a node's ``check_cancelled``) and ``progress`` is given
the fraction of the square already integrated to tolerance; both default to those of
an enclosing :func:`~.watch.watched` block.
"""

from __future__ import annotations

import functools
from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike

from .array_types import FloatArray
from .watch import watch_check, watch_progress, watched

__all__ = [
    "CHUNK_POINTS", "gauss_legendre_01", "integrate_unit_square", "span_gauss", "watch_check", "watched",
]


Integrand = Callable[[FloatArray, FloatArray], FloatArray]
Check = Callable[[], None]
Progress = Callable[[float], None]


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


#: Most Gauss points evaluated in one call of the integrand (memory stays bounded, and
#: ``check`` is called between calls: 2¹³ points of a bumpy 48 × 48 bicubic NURBS take
#: 10-20 ms, so Esc is seen within the 50 ms issue 16 asks; 2¹⁵ took up to 200 ms).
CHUNK_POINTS = 1 << 13


def _cells_integral(
    func: Integrand,
    u0: FloatArray,
    v0: FloatArray,
    du: FloatArray,
    dv: FloatArray,
    nodes: FloatArray,
    weights: FloatArray,
    check: Check | None = None,
) -> FloatArray:
    """Tensor Gauss rule on cells [u0, u0+du] × [v0, v0+dv]; → (cells, k).
    Cells are evaluated :data:`CHUNK_POINTS` Gauss points at a time."""
    g = len(nodes)
    chunk = max(1, CHUNK_POINTS // (g * g))
    if len(u0) > chunk:
        return np.concatenate([
            _cells_integral(func, u0[i:i + chunk], v0[i:i + chunk], du[i:i + chunk], dv[i:i + chunk],
                            nodes, weights, check)
            for i in range(0, len(u0), chunk)
        ])
    if check is not None:
        check()
    uu = u0[:, None, None] + du[:, None, None] * nodes[None, :, None]
    vv = v0[:, None, None] + dv[:, None, None] * nodes[None, None, :]
    uu, vv = np.broadcast_arrays(uu, vv)
    values = np.asarray(func(uu.ravel(), vv.ravel()), dtype=float)
    values = values.reshape(len(u0), g, g, -1)
    w2 = weights[:, None] * weights[None, :]
    return np.einsum("cijk,ij->ck", values, w2) * (du * dv)[:, None]


def _start_breaks(breaks: ArrayLike | None, start: int) -> FloatArray:
    """Sorted distinct breaks in [0, 1] including both ends (``start`` equal cells if None)."""
    if breaks is None:
        return np.linspace(0.0, 1.0, start + 1)
    b = np.unique(np.clip(np.asarray(breaks, dtype=float).ravel(), 0.0, 1.0))
    return np.unique(np.concatenate([[0.0, 1.0], b]))


def integrate_unit_square(
    func: Integrand,
    rtol: float = 1e-11,
    atol: float = 0.0,
    order: int = 8,
    start: int = 4,
    max_level: int = 12,
    max_cells: int = 200_000,
    breaks_u: ArrayLike | None = None,
    breaks_v: ArrayLike | None = None,
    check: Check | None = None,
    progress: Progress | None = None,
    noise: float = 0.0,
) -> FloatArray:
    """Integrate ``func(u, v)`` over [0, 1]², adaptively.

    ``func`` takes two equal-length 1-D arrays and returns ``(n,)`` or ``(n, k)``
    values; the result is a ``(k,)`` array (``k = 1`` for scalar integrands). The
    start cells are the grid of ``breaks_u`` × ``breaks_v`` (the ends 0 and 1 are
    added), or ``start × start`` squares. The iteration stops when every cell's error
    estimate is below its area share of ``max(atol, rtol·|I|)`` (componentwise
    maximum), or when ``max_level`` or ``max_cells`` is reached. ``check()`` is
    called between blocks of cells (it stops the integral by raising); ``progress``
    receives the fraction of the square done.

    ``noise`` (relative to |I|, per unit of area) is the integrand's rounding noise: a
    cell whose error estimate is below that share and did not shrink when its parent was
    halved is at the noise and kept, as it is (refining it would only multiply cells: an
    integrand made of positions far from the origin, 1e6 m and more, differenced). A
    smooth cell's estimate falls by orders of magnitude per halving, so it is never taken
    for noise while it is still converging.
    """
    check = check if check is not None else watch_check()
    progress = progress if progress is not None else watch_progress()
    nodes, weights = gauss_legendre_01(order)
    bu, bv = _start_breaks(breaks_u, start), _start_breaks(breaks_v, start)
    iu, iv = (a.ravel() for a in np.meshgrid(np.arange(len(bu) - 1), np.arange(len(bv) - 1), indexing="ij"))
    u0, v0 = bu[iu], bv[iv]
    du, dv = bu[iu + 1] - u0, bv[iv + 1] - v0
    parent = _cells_integral(func, u0, v0, du, dv, nodes, weights, check)
    accepted = np.zeros(parent.shape[1])
    done_area = 0.0
    # each cell's share of its parent's error estimate (none for the start cells)
    inherited = np.full(len(u0), np.inf)
    for _ in range(max_level):
        hu, hv = 0.5 * du, 0.5 * dv
        cu = np.concatenate([u0, u0 + hu, u0, u0 + hu])
        cv = np.concatenate([v0, v0, v0 + hv, v0 + hv])
        cdu, cdv = np.concatenate([hu] * 4), np.concatenate([hv] * 4)
        children = _cells_integral(func, cu, cv, cdu, cdv, nodes, weights, check)
        n = len(u0)
        child_sum = children.reshape(4, n, -1).sum(axis=0)
        error = np.max(np.abs(child_sum - parent), axis=1)
        total = accepted + child_sum.sum(axis=0)
        tolerance = max(atol, rtol * float(np.max(np.abs(total))))
        cell_area = du * dv
        done = error <= tolerance * cell_area
        if noise > 0.0:
            floor = noise * float(np.max(np.abs(total))) * cell_area
            done |= (error >= 0.5 * inherited) & (error <= floor)
        accepted = accepted + child_sum[done].sum(axis=0)
        done_area += float(cell_area[done].sum())
        if progress is not None:
            progress(min(done_area, 1.0))
        # the next level would evaluate 4 children of each of the 4 kept children
        if done.all() or 16 * np.count_nonzero(~done) > max_cells:
            return accepted + child_sum[~done].sum(axis=0)
        keep = np.tile(~done, 4)
        u0, v0, du, dv, parent = cu[keep], cv[keep], cdu[keep], cdv[keep], children[keep]
        inherited = np.tile(0.25 * error, 4)[keep]
    return accepted + parent.sum(axis=0)
