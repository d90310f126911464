"""A surface's tight axis-aligned bounding box: where each coordinate is least and greatest.

Over the parameter square a coordinate x(u, v) is extreme at a corner, on an edge where
its derivative along the edge is zero, or inside where both partial derivatives are.
Each of the six extremes is found as such a zero, never by comparing values alone:
derivatives carry no offset, so a surface at site coordinates (1e6 m) gets as tight a
box as at the origin, and a shallow extreme (a coordinate that changes by 1e-8 of the
size over a tenth of an edge) is found where it is, not where a descent on the value
stops making progress.

- **Edges** (and corners): on each edge, sampled evenly and on its breakpoints (a NURBS
  surface's knots) and wherever a rail turns a corner
  (:meth:`~.surface_base.Surface.ruling_kinks`: a polyline strip's every vertex), every
  sign change of a coordinate's derivative along it is refined by a safeguarded Newton
  search in its bracket (:func:`.roots.refine_roots`); the samples are candidates too.
- **Inside**: from the grid sample best for the extreme, and from the best sample off
  the square's boundary, a safeguarded Newton search on the coordinate measured from
  the surface's anchor, all twelve at once: the exact Hessian (shifted to be positive
  definite where it is not), a step no longer than a quarter of the square, a
  backtracking line search that never lets the coordinate worsen, coordinates pinned
  on the square's boundary while the descent leaves it (an active set: on an edge the
  search is the 1-D one along it) and wrapped across the seam of a closed direction.
  On a ruled surface a coordinate is linear along each ruling, so its extremes are on
  the edges where rulings end: the inside is searched only from a best grid sample
  inside the square (a parameter that folds back along a ruling).

Every candidate is a point of the surface, so the box is never larger than the surface;
the grid samples are candidates too.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike

from .array_types import FloatArray
from .curve_protocol import ParametricCurve
from .roots import refine_roots
from .square_descent import backtrack, pinned_step, step_length
from .vec_ops import anchor, extent


class BoxedSurface(Protocol):
    """What the box needs of a surface (:class:`~.surface_base.Surface` uses this module, so
    it is named by its structure, not imported)."""

    closed_u: bool
    closed_v: bool

    @property
    def ruling_direction(self) -> str | None: ...

    def derivatives(self, u: ArrayLike, v: ArrayLike, order: int = 1) -> list[FloatArray]: ...

    def edges(self) -> Sequence[ParametricCurve]: ...

    def ruling_kinks(self) -> FloatArray: ...

#: Newton iterations at most (a converging search takes a handful).
NEWTON_STEPS = 40
#: A step shorter than this (in parameter units) has converged.
NEWTON_STOP = 1e-14
#: Longest Newton step (parameter units): the Hessian far from the extreme says little.
LONGEST_STEP = 0.25
#: Halvings of a step that worsens the coordinate before the search stays where it is.
BACKTRACKS = 40
#: Edge samples per grid interval (the derivative's sign changes are bracketed on them).
EDGE_DENSITY = 4
#: Where in each interval between edge samples the derivative is read: this share of it
#: from either end (so a corner's two sides are told apart).
EDGE_NUDGE = 1e-9

#: The six extremes, in the box's order: (axis, sign) with sign +1 for a minimum.
_AXES = np.array([0, 0, 1, 1, 2, 2])
_SIGNS = np.array([1.0, -1.0, 1.0, -1.0, 1.0, -1.0])


def surface_bounding_box(surface: BoxedSurface, samples: int = 32) -> FloatArray:
    """``[[xmin, ymin, zmin], [xmax, ymax, zmax]]`` of ``surface`` over [0, 1]², tight to the
    rounding of its positions; starts from a ``(samples + 1)²`` grid (see the module)."""
    grid = np.linspace(0.0, 1.0, samples + 1)
    gu, gv = (a.ravel() for a in np.meshgrid(grid, grid, indexing="ij"))
    points = surface.derivatives(gu, gv, 0)[0]
    direction = surface.ruling_direction
    kinks = surface.ruling_kinks() if direction is not None else np.empty(0)
    across = "u" if direction == "v" else "v"  # the parameter the edges along the rails run in
    candidates = [points]
    for edge in surface.edges():
        corners = kinks if getattr(edge, "direction", None) == across else kinks[:0]
        if getattr(edge, "reverse", False):
            corners = 1.0 - corners
        candidates.append(_edge_extremes(edge, EDGE_DENSITY * samples, corners))
    if np.isfinite(points).all():
        candidates.append(_inside_extremes(surface, gu, gv, points))
    stacked = np.vstack(candidates)
    return np.stack([stacked.min(axis=0), stacked.max(axis=0)])


def _edge_extremes(edge: ParametricCurve, intervals: int, corners: FloatArray) -> FloatArray:
    """The points of an edge curve at its samples (``intervals`` even steps, its
    breakpoints and its ``corners``) and wherever a coordinate's derivative along it
    changes sign between two of them.

    The derivative is read just inside each interval (1e-9 of it from either end), so a
    derivative that jumps at a corner is read on each interval's own side: a polyline's
    straight pieces hold no root, its vertices are samples."""
    marks = np.clip(np.r_[edge._breakpoints(), corners], 0.0, 1.0)
    t = np.union1d(np.linspace(0.0, 1.0, intervals + 1), marks)
    nudge = EDGE_NUDGE * np.diff(t)
    low, high = t[:-1] + nudge, t[1:] - nudge
    speed = edge.derivatives(np.concatenate([low, high]), 1)[1]
    at_low, at_high = speed[: len(low)], speed[len(low):]
    bracket, axis = np.nonzero(np.sign(at_low) * np.sign(at_high) < 0)

    def coordinate_speed(x: FloatArray, index: np.ndarray) -> tuple[FloatArray, FloatArray, FloatArray]:
        _, first, second = edge.derivatives(x, 2)
        rows, axes = np.arange(len(x)), axis[index]
        return first[rows, axes], second[rows, axes], np.linalg.norm(first, axis=1)

    roots = (refine_roots(coordinate_speed, low[bracket], high[bracket], at_low[bracket, axis])
             if len(bracket) else t[:0])
    return edge.point_at(np.concatenate([t, roots]))


def _inside_extremes(surface: BoxedSurface, gu: FloatArray, gv: FloatArray, points: FloatArray) -> FloatArray:
    """Every point the Newton searches for the six extremes reach (see the module)."""
    inner = (gu > 0.0) & (gu < 1.0) & (gv > 0.0) & (gv < 1.0)
    if not inner.any():  # a 2 × 2 grid
        inner[:] = True
    signed = _SIGNS[:, None] * points[:, _AXES].T  # (6, samples): the value each extreme minimises
    best = np.argmin(signed, axis=1)
    if surface.ruling_direction is None:
        start = np.concatenate([best, np.flatnonzero(inner)[np.argmin(signed[:, inner], axis=1)]])
        rows = np.arange(12) % 6
    else:  # linear along the rulings: inside only where the grid says so (a parameter folding back)
        rows = np.flatnonzero(inner[best])
        start = best[rows]
        if not len(rows):
            return points[:0]
    origin = anchor(points)
    size = float(np.linalg.norm(extent(points))) or 1.0
    u, v = _newton(surface, gu[start], gv[start], _AXES[rows], _SIGNS[rows] / size, origin)
    return surface.derivatives(u, v, 0)[0]


def _newton(surface: BoxedSurface, u: FloatArray, v: FloatArray, axes: np.ndarray, scales: FloatArray,
            origin: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Minimise f = scale·(S(u, v)[axis] − origin[axis]) over the square from each (u, v)."""
    u, v = u.copy(), v.copy()
    active = np.arange(len(u))
    lifted = origin[axes]

    def coordinate(pending: np.ndarray, pu: FloatArray, pv: FloatArray) -> FloatArray:
        """The scaled coordinate each active start ``pending`` minimises, at (pu, pv)."""
        value = surface.derivatives(pu, pv, 0)[0]
        rows = active[pending]
        return scales[rows] * (value[np.arange(len(pending)), axes[rows]] - lifted[rows])

    for _ in range(NEWTON_STEPS):
        ua, va, ax, sc = u[active], v[active], axes[active], scales[active]
        pick = np.arange(len(active))
        s, su, sv, suu, suv, svv = surface.derivatives(ua, va, 2)
        f0 = sc * (s[pick, ax] - lifted[active])
        g_u, g_v = sc * su[pick, ax], sc * sv[pick, ax]
        h_uu, h_uv, h_vv = sc * suu[pick, ax], sc * suv[pick, ax], sc * svv[pick, ax]
        # shift the Hessian to positive definite: its least eigenvalue raised to a share
        # of its largest (or of the gradient, where the Hessian vanishes: a plane, a ruling)
        half_trace, gap = 0.5 * (h_uu + h_vv), np.hypot(0.5 * (h_uu - h_vv), h_uv)
        least, largest = half_trace - gap, np.abs(half_trace) + gap
        floor = 1e-6 * np.maximum(largest, np.hypot(g_u, g_v)) + 1e-300
        shift = np.maximum(floor - least, 0.0)
        h_uu, h_vv = h_uu + shift, h_vv + shift
        du, dv = pinned_step(ua, va, g_u, g_v, h_uu, h_uv, h_vv, surface.closed_u, surface.closed_v)
        longest = np.maximum(np.abs(du), np.abs(dv))
        cut = np.minimum(1.0, LONGEST_STEP / np.where(longest > 0.0, longest, 1.0))
        # never let the coordinate worsen
        new_u, new_v = backtrack(coordinate, f0, ua, va, du * cut, dv * cut, surface.closed_u,
                                 surface.closed_v, halvings=BACKTRACKS)
        moved = step_length(ua, va, new_u, new_v, surface.closed_u, surface.closed_v)
        u[active], v[active] = new_u, new_v
        active = active[moved > NEWTON_STOP]
        if not len(active):
            break
    return u, v

