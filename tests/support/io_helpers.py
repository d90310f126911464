"""Small geometry and file helpers for the io tests."""

from __future__ import annotations

import numpy as np
import rhino3dm as rh

from torsal.nodes.geometry.curves import Polyline


def rectangle(x: float, y: float, w: float, h: float, z: float = 0.0) -> Polyline:
    """A closed axis-aligned rectangle (model units) with its lower-left corner at (x, y)."""
    return Polyline([[x, y, z], [x + w, y, z], [x + w, y + h, z], [x, y + h, z]], closed=True)


def polygon_area(points: np.ndarray) -> float:
    x, y = points[:, 0], points[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def random_panels(count: int, seed: int = 7) -> list[Polyline]:
    """Convex-ish quadrilaterals 0.1–0.9 m wide, turned at random, scattered in XY."""
    rng = np.random.default_rng(seed)
    panels = []
    for _ in range(count):
        w, h = rng.uniform(0.1, 0.9), rng.uniform(0.05, 0.4)
        a = rng.uniform(0, 2 * np.pi)
        corners = np.array([[0, 0], [w, 0], [0.8 * w, h], [0.1 * w, 0.9 * h]])
        turn = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
        corners = corners @ turn.T + rng.uniform(-5, 5, 2)
        panels.append(Polyline(np.column_stack([corners, np.zeros(4)]), closed=True))
    return panels


def rhino_points(curve: rh.Curve, t: np.ndarray) -> np.ndarray:
    """A rhino3dm curve evaluated at normalised parameters t in [0, 1] of its domain."""
    a, b = curve.Domain.T0, curve.Domain.T1
    return np.array([[p.X, p.Y, p.Z] for p in (curve.PointAt(a + (b - a) * x) for x in t.tolist())])


def rhino_surface_points(surface: rh.Surface, u: np.ndarray, v: np.ndarray) -> np.ndarray:
    du, dv = surface.Domain(0), surface.Domain(1)
    return np.array([
        [p.X, p.Y, p.Z]
        for p in (
            surface.PointAt(du.T0 + (du.T1 - du.T0) * a, dv.T0 + (dv.T1 - dv.T0) * b)
            for a, b in zip(u.tolist(), v.tolist(), strict=True)
        )
    ])
