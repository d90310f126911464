"""Rationalise's strips sampled on a grid, and a grid's area: shared by its tests."""

from __future__ import annotations

import numpy as np

from tests.support.node_helpers import out


def items(result, port: str) -> list:
    return out(result, port)[(0,)]


def grid(strip, nu: int = 121, nv: int = 21) -> np.ndarray:
    u, v = np.meshgrid(np.linspace(0, 1, nu), np.linspace(0, 1, nv), indexing="ij")
    return strip.point_at(u.ravel(), v.ravel()).reshape(nu, nv, 3)


def grid_area(points: np.ndarray) -> float:
    """The area of a grid of points, two triangles a cell."""
    a, b, c, d = points[:-1, :-1], points[1:, :-1], points[1:, 1:], points[:-1, 1:]
    return float(0.5 * (np.linalg.norm(np.cross(b - a, c - a), axis=-1)
                        + np.linalg.norm(np.cross(c - a, d - a), axis=-1)).sum())
