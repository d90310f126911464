"""Surfaces with closed-form curvature and developments, for the analysis node tests.

Each ParametricSurface gets analytic derivative callables, so what the tests measure
is the nodes, not finite differences.
"""

from __future__ import annotations

import math

import numpy as np

from torsal.nodes.geometry.curves import ParametricCurve
from torsal.nodes.geometry.developable import cylinder_rulings, tangent_developable_rulings
from torsal.nodes.geometry.parametric_surface import ParametricSurface
from torsal.nodes.geometry.ruled import RuledSurface


def _z(x: np.ndarray) -> np.ndarray:
    return np.zeros_like(x)


def hypar(size: float = 1.0, rise: float = 1.0) -> ParametricSurface:
    """z = rise·x·y over [−size, size]²: for rise 1, K = −1/(1 + x² + y²)²."""
    e = rise
    return ParametricSurface(
        lambda x, y: (x, y, e * x * y), (-size, size), (-size, size),
        first_derivatives=lambda x, y: ((1 + _z(x), _z(x), e * y), (_z(x), 1 + _z(x), e * x)),
        second_derivatives=lambda x, y: ((_z(x),) * 3, (_z(x), _z(x), e + _z(x)), (_z(x),) * 3),
    )


def hypar_gaussian(p: np.ndarray) -> np.ndarray:
    return -1.0 / (1.0 + p[:, 0] ** 2 + p[:, 1] ** 2) ** 2


HELICOID_C = 0.5


def helicoid() -> ParametricSurface:
    """(v cos u, v sin u, c·u), u over a turn, v from −1 to 1: K = −c²/(c² + v²)²."""
    c = HELICOID_C
    return ParametricSurface(
        lambda u, v: (v * np.cos(u), v * np.sin(u), c * u), (0.0, 2 * math.pi), (-1.0, 1.0),
        first_derivatives=lambda u, v: ((-v * np.sin(u), v * np.cos(u), c + _z(u)),
                                        (np.cos(u), np.sin(u), _z(u))),
        second_derivatives=lambda u, v: ((-v * np.cos(u), -v * np.sin(u), _z(u)),
                                         (-np.sin(u), np.cos(u), _z(u)), (_z(u),) * 3),
    )


def helicoid_gaussian(p: np.ndarray) -> np.ndarray:
    v2 = p[:, 0] ** 2 + p[:, 1] ** 2
    return -(HELICOID_C**2) / (HELICOID_C**2 + v2) ** 2


def capsule() -> ParametricSurface:
    """A unit-radius cylinder 0.2 high (t from 0 to ½) capped by a hemisphere (t from ½
    to 1): half the parameter square but a sixth of the area is single-curved."""

    def point(t: np.ndarray, a: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        phi = np.clip(t - 0.5, 0.0, None) * math.pi
        rho = np.where(t <= 0.5, 1.0, np.cos(phi))
        z = np.where(t <= 0.5, 0.4 * t, 0.2 + np.sin(phi))
        return rho * np.cos(a), rho * np.sin(a), z

    return ParametricSurface(point, (0.0, 1.0), (0.0, 2 * math.pi))


def helix(radius: float, rise: float, turns: float) -> ParametricCurve:
    """(R cos t, R sin t, c·t) for t from 0 to 2π·turns, with exact derivatives."""
    return ParametricCurve(
        lambda t: np.column_stack([radius * np.cos(t), radius * np.sin(t), rise * t]),
        (0.0, 2 * math.pi * turns),
        derivatives=(
            lambda t: np.column_stack([-radius * np.sin(t), radius * np.cos(t), rise + 0 * t]),
            lambda t: np.column_stack([-radius * np.cos(t), -radius * np.sin(t), 0 * t]),
        ),
    )


def tangent_developable(radius: float, rise: float, turns: float, length: float, cut: float = 0.0,
                        segments: int = 400) -> RuledSurface:
    """The tangent developable of a helix, lofted through ``segments + 1`` rulings."""
    r = tangent_developable_rulings(helix(radius, rise, turns), segments, length, cut)
    return RuledSurface.from_rulings(r.starts, r.ends)


def tilted_cylinder(direction: tuple[float, float, float] = (1.0, 2.0, 3.0)) -> RuledSurface:
    """A general cylinder: a wavy space curve extruded along ``direction`` (height 2)."""
    curve = ParametricCurve(
        lambda t: np.column_stack([np.cos(t) + 0.2 * np.cos(3 * t), np.sin(t), 0.3 * np.sin(2 * t)]),
        (0.0, math.pi),
    )
    r = cylinder_rulings(curve, direction, 2.0, 60)
    return RuledSurface.from_rulings(r.starts, r.ends)
