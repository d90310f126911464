"""The pieces of a damped Newton descent over a surface's parameter square [0, 1]².

Two searches walk a surface's parameters downhill from many starts at once: the closest
point to a query (:meth:`~.surface_base.Surface.closest_point`) and the extremes of a
coordinate (:mod:`.surface_box`). They differ in what they minimise and in how they make
its Hessian safe; they share how a step is taken on the square:

- :func:`pinned_step`: the Newton step, with a parameter held on its bound while the
  descent would leave the square (an active set: on an edge the search is the 1-D one
  along it); a closed direction has no bound.
- :func:`project`: a point back onto the square, clipped, or wrapped across the seam of a
  closed direction.
- :func:`backtrack`: the step halved until the objective does not grow; a start where no
  halving helps stays where it is.
- :func:`step_length`: how far a step moved, counted across a seam the short way.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .array_types import FloatArray

#: The objective at the starts picked by ``pending`` (indices into the current starts),
#: evaluated at parameters ``(u, v)`` of those starts.
Objective = Callable[[np.ndarray, FloatArray, FloatArray], FloatArray]


def pinned_step(u: FloatArray, v: FloatArray, g_u: FloatArray, g_v: FloatArray, h_uu: FloatArray,
                h_uv: FloatArray, h_vv: FloatArray, closed_u: bool,
                closed_v: bool) -> tuple[FloatArray, FloatArray]:
    """The Newton step ``(du, dv)`` for gradient ``g`` and Hessian ``h`` at ``(u, v)``.

    A parameter on its bound whose descent leaves the square does not move, and the other
    takes the 1-D Newton step along the edge. A singular Hessian gives no step (0, not NaN).
    """
    pin_u = (((u <= 0.0) & (g_u > 0.0)) | ((u >= 1.0) & (g_u < 0.0))) & (not closed_u)
    pin_v = (((v <= 0.0) & (g_v > 0.0)) | ((v >= 1.0) & (g_v < 0.0))) & (not closed_v)
    det = h_uu * h_vv - h_uv * h_uv
    with np.errstate(divide="ignore", invalid="ignore"):  # (a flat stretch: no step)
        du = np.where(pin_v, -g_u / h_uu, -(h_vv * g_u - h_uv * g_v) / det)
        dv = np.where(pin_u, -g_v / h_vv, -(h_uu * g_v - h_uv * g_u) / det)
    return np.nan_to_num(np.where(pin_u, 0.0, du)), np.nan_to_num(np.where(pin_v, 0.0, dv))


def project(u: FloatArray, v: FloatArray, closed_u: bool, closed_v: bool) -> tuple[FloatArray, FloatArray]:
    """``(u, v)`` onto the square: clipped, or wrapped across the seam of a closed direction."""
    u = np.mod(u, 1.0) if closed_u else np.clip(u, 0.0, 1.0)
    v = np.mod(v, 1.0) if closed_v else np.clip(v, 0.0, 1.0)
    return u, v


def backtrack(objective: Objective, f0: FloatArray, u: FloatArray, v: FloatArray, du: FloatArray,
              dv: FloatArray, closed_u: bool, closed_v: bool, halvings: int,
              slack: float = 0.0, floor: float = 0.0) -> tuple[FloatArray, FloatArray]:
    """The parameters after the step ``(du, dv)`` from ``(u, v)``, halved while the
    objective grows past ``f0 · (1 + slack) + floor``; after ``halvings`` halvings a start
    that still grows stays where it was."""
    new_u, new_v = project(u + du, v + dv, closed_u, closed_v)
    step = np.ones_like(u)
    pending = np.arange(len(u))
    for _ in range(halvings):
        worse = objective(pending, new_u[pending], new_v[pending]) > f0[pending] * (1.0 + slack) + floor
        pending = pending[worse]
        if not len(pending):
            break
        step[pending] *= 0.5
        new_u[pending], new_v[pending] = project(u[pending] + step[pending] * du[pending],
                                                 v[pending] + step[pending] * dv[pending],
                                                 closed_u, closed_v)
    new_u[pending], new_v[pending] = u[pending], v[pending]  # no descent: stay
    return new_u, new_v


def step_length(u: FloatArray, v: FloatArray, new_u: FloatArray, new_v: FloatArray,
                closed_u: bool, closed_v: bool) -> FloatArray:
    """The larger of the two parameters' moves, a move across a seam counted the short way."""
    step_u, step_v = np.abs(new_u - u), np.abs(new_v - v)
    if closed_u:  # a step across the seam is short, not ~1
        step_u = np.minimum(step_u, 1.0 - step_u)
    if closed_v:
        step_v = np.minimum(step_v, 1.0 - step_v)
    return np.maximum(step_u, step_v)
