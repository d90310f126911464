"""Lines of curvature of a design, traced as rings round a centre (D-strip boundaries).

A strip tangent to the design along a line of curvature has its rulings along the other
principal direction (the two are conjugate), and it never creases there: where the
normal curvature along the line changes sign the line crosses a parabolic line along a
principal direction, where II(t, ·) vanishes as a whole (:mod:`.asymptotic`). Boundaries
along one family of curvature lines are the D-strip layout of Pottmann, Schiftner, Bo et
al. 2008 (docs/geometry.md, "Rationalise: which strips and why").

Directions are taken in the design's *plan*: its parameters scaled by the design's mean
speeds along u and v (:func:`plan_scale`), so that on a height field over a rectangle the
plan is the rectangle itself and polar angles mean what they look like.

:func:`principal_plan_directions` gives both principal directions at (u, v) as unit
vectors of the plan (from :meth:`~torsal.nodes.geometry.surface_base.Surface.curvature`),
ordered as k1 ≥ k2. :func:`trace_rings` follows one family round a centre: each line as
its polar radius r(θ) in the plan, solved by scipy's ``solve_ivp`` from a seed radius on
one ray, as the ODE dr/dθ = r·(d·e_r)/(d·e_θ) (d the family's direction: no sign to
choose, so the family is followed without a memory of the last step). A line that turns
to run along a ray (near an umbilic, or a family that is not ring-like there) stops the
solve, and :func:`trace_rings` says so.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike
from scipy.integrate import solve_ivp

from ..array_types import FloatArray
from ..curvature import principal_curvatures
from ..surface_base import Surface
from .outline_cut import ExtendedSurface

#: Relative accuracy of the traced radii (solve_ivp's rtol; atol from the plan's size).
RTOL = 1e-9
#: A ring stops where its direction is within this angle (rad) of the ray through it.
STEEP = np.radians(5.0)


def plan_scale(design: Surface, samples: int = 17) -> FloatArray:
    """The design's mean speeds along u and v: (u, v) times these is the plan (about the
    design's own lengths)."""
    g = np.linspace(0.0, 1.0, samples)
    u, v = (a.ravel() for a in np.meshgrid(g, g, indexing="ij"))
    _, su, sv = design.derivatives(u, v, 1)
    return np.array([np.linalg.norm(su, axis=1).mean(), np.linalg.norm(sv, axis=1).mean()])


def principal_plan_directions(design: Surface, u: ArrayLike, v: ArrayLike, scale: ArrayLike
                              ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """k1 ≥ k2 at (u, v) and their principal directions as unit vectors ``(n, 2)`` of the
    plan (parameters times ``scale``): the 3D directions written on Su, Sv (the first
    fundamental form solved) and scaled. (u, v) outside [0, 1]² is taken on the design
    continued by its Taylor expansion (:class:`~.outline_cut.ExtendedSurface`)."""
    u, v = np.broadcast_arrays(np.atleast_1d(np.asarray(u, dtype=float)),
                               np.atleast_1d(np.asarray(v, dtype=float)))
    surface = ExtendedSurface(design) if np.any((u < 0) | (u > 1) | (v < 0) | (v > 1)) else design
    _, su, sv, suu, suv, svv = surface.derivatives(u.ravel(), v.ravel(), 2)
    found = principal_curvatures(su, sv, suu, suv, svv)
    e, f, g = (np.einsum("ij,ij->i", a, b) for a, b in ((su, su), (su, sv), (sv, sv)))
    det = e * g - f * f
    scale = np.asarray(scale, dtype=float)
    out = []
    for d in (found.direction1, found.direction2):
        a, b = np.einsum("ij,ij->i", su, d), np.einsum("ij,ij->i", sv, d)
        du, dv = (g * a - f * b) / det, (e * b - f * a) / det
        plan = np.column_stack([du * scale[0], dv * scale[1]])
        out.append(plan / np.linalg.norm(plan, axis=1, keepdims=True))
    return found.k1, found.k2, out[0], out[1]


def ring_family(design: Surface, centre: ArrayLike, radius: float, scale: ArrayLike,
                samples: int = 16) -> int:
    """Which principal family (0: k1's, 1: k2's) runs round ``centre`` (a plan point) on
    the circle of ``radius`` about it: the one more nearly along the circle, on average."""
    theta = np.linspace(0.0, 2.0 * np.pi, samples, endpoint=False)
    scale = np.asarray(scale, dtype=float)
    plan = np.asarray(centre, dtype=float) + radius * np.column_stack([np.cos(theta), np.sin(theta)])
    _, _, d1, d2 = principal_plan_directions(design, plan[:, 0] / scale[0], plan[:, 1] / scale[1], scale)
    across = np.column_stack([-np.sin(theta), np.cos(theta)])
    return 0 if np.mean(np.abs(np.einsum("ij,ij->i", d1, across))) >= np.mean(
        np.abs(np.einsum("ij,ij->i", d2, across))) else 1


def trace_rings(design: Surface, centre: ArrayLike, radii: ArrayLike, theta: ArrayLike, family: int,
                scale: ArrayLike, start: float = 0.0) -> FloatArray:
    """The lines of curvature of ``family`` (0: k1's, 1: k2's) through the plan points at
    ``radii`` from ``centre`` on the ray at angle ``start``, as their radii at the angles
    ``theta`` (increasing, containing ``start`` or not): ``(len(radii), len(theta))``.
    All lines are solved together (one ODE system). Raises ``ValueError`` where a line
    turns within :data:`STEEP` of a ray (it is no ring there) or reaches the centre."""
    centre = np.asarray(centre, dtype=float)
    scale = np.asarray(scale, dtype=float)
    radii = np.asarray(radii, dtype=float)
    theta = np.asarray(theta, dtype=float)
    size = float(np.max(radii))

    def slope(t: float, r: FloatArray) -> FloatArray:
        c, s = np.cos(t), np.sin(t)
        plan = centre + r[:, None] * np.array([c, s])
        d = principal_plan_directions(design, plan[:, 0] / scale[0], plan[:, 1] / scale[1], scale)[2 + family]
        radial, angular = d @ np.array([c, s]), d @ np.array([-s, c])
        if np.any(np.abs(angular) < np.sin(STEEP)) or np.any(r <= 0.0):
            raise ValueError(f"a line of curvature turns along the ray at angle {t:.3f} rad: "
                             "it is no ring there")
        return r * radial / angular

    out = np.empty((len(radii), len(theta)))
    for side in (theta >= start, theta < start):
        if not side.any():
            continue
        ts = theta[side] if theta[side][0] >= start else theta[side][::-1]
        span = (start, float(ts[-1]))
        if span[0] == span[1]:
            out[:, side] = radii[:, None]
            continue
        solved = solve_ivp(slope, span, radii, t_eval=ts, rtol=RTOL, atol=RTOL * size, method="DOP853")
        if not solved.success:
            raise ValueError(f"the lines of curvature could not be traced: {solved.message}")
        out[:, side] = solved.y if theta[side][0] >= start else solved.y[:, ::-1]
    return out
