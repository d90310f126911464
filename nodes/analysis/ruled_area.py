"""The area of a ruled surface, quickly: Gauss–Legendre along the rails' smooth spans.

On S(u, v) = (1 − v)·A(u) + v·B(u) the area element is |c0(u) + v·c1(u)| with
c0 = A′ × D, c1 = (B′ − A′) × D and D = B − A: in v the square root of a quadratic,
smooth on either side of its minimum (where it may touch zero, as at a cone's apex),
and in u smooth between the rails' breakpoints (a spline rail's knots). So a
Gauss–Legendre rule per rail span in u, and per side of the minimum in v, is at
rounding level with a few nodes, where the generic adaptive cubature on square cells
refines every one of a 400-ruling loft's spans down to tiny squares (tens of seconds).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from nodes.geometry.ruled import RuledSurface
from nodes.geometry.surface_base import Surface

FloatArray = NDArray[np.float64]

#: Gauss–Legendre nodes per rail span (u) and per side of the minimum (v).
ORDER_U, ORDER_V = 10, 10


def _gauss(order: int) -> tuple[FloatArray, FloatArray]:
    x, w = np.polynomial.legendre.leggauss(order)
    return 0.5 * (x + 1.0), 0.5 * w


def _spans(surface: RuledSurface) -> FloatArray:
    breaks = np.concatenate([surface.curve_a._breakpoints(), surface.curve_b._breakpoints(), [0.0, 1.0]])
    breaks = np.unique(np.clip(breaks, 0.0, 1.0))
    # split long spans so that a rail that is one smooth piece is still well resolved
    fine = np.linspace(0.0, 1.0, 33)
    return np.unique(np.concatenate([breaks, fine]))


def ruled_area(surface: Surface) -> float:
    """Area of ``surface``: by the rule above for a :class:`RuledSurface`, else its own
    (adaptive) :meth:`~nodes.geometry.surface_base.Surface.area`."""
    if not isinstance(surface, RuledSurface):
        return surface.area()
    edges = _spans(surface)
    xu, wu = _gauss(ORDER_U)
    width = np.diff(edges)
    u = (edges[:-1, None] + width[:, None] * xu[None, :]).ravel()
    weight_u = (width[:, None] * wu[None, :]).ravel()
    da = surface.curve_a.derivatives(u, 1)
    db = surface.curve_b.derivatives(u, 1)
    d = db[0] - da[0]
    c0 = np.cross(da[1], d)
    c1 = np.cross(db[1] - da[1], d)
    aa = np.einsum("ij,ij->i", c1, c1)
    bb = np.einsum("ij,ij->i", c0, c1)
    with np.errstate(divide="ignore", invalid="ignore"):
        split = np.where(aa > 0, np.clip(-bb / aa, 0.0, 1.0), 0.0)
    xv, wv = _gauss(ORDER_V)
    total = np.zeros(len(u))
    for lo, hi in ((np.zeros_like(split), split), (split, np.ones_like(split))):
        v = lo[:, None] + (hi - lo)[:, None] * xv[None, :]
        element = np.linalg.norm(c0[:, None, :] + v[..., None] * c1[:, None, :], axis=2)
        total += (hi - lo) * (element @ wv)
    return float(np.dot(weight_u, total))
