"""Freeform test designs for developable.Rationalise, in closed form, and an independent
closest-point search on them.

Each design is a height field z = f(x, y) over a rectangle with its first and second
derivatives written by hand in this file (a test checks them against differences), and the
distance of a point from the design is found here by a Newton iteration on
½|S(x, y) − P|² with those exact derivatives (from the nearest of a dense sample grid,
cKDTree), clamped to the rectangle — nothing of Rationalise's own closest-point search or
Deviation is used.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from torsal.nodes.geometry.surface_base import Surface, broadcast_uv


@dataclass(frozen=True)
class Design:
    """z = f(x, y) on [x0, x1] × [y0, y1], in the design's own units."""

    name: str
    jet: Callable[[np.ndarray, np.ndarray], tuple]  #: (f, fx, fy, fxx, fxy, fyy), written by hand
    x: tuple[float, float]
    y: tuple[float, float]
    unit: float = 1.0  #: one metre in the design's units (1000 for a design in mm)

    def height(self, x: np.ndarray, y: np.ndarray, which: int = 0) -> np.ndarray:
        return np.asarray(self.jet(x, y)[which], dtype=float)

    def heights(self, x: np.ndarray, y: np.ndarray, count: int = 6) -> list[np.ndarray]:
        """f and its derivatives up to the ``count``-th of (f, fx, fy, fxx, fxy, fyy), from
        one evaluation of the jet."""
        jet = self.jet(x, y)
        return [np.broadcast_to(np.asarray(jet[k], dtype=float), np.shape(x)) for k in range(count)]

    def surface(self) -> HeightSurface:
        return HeightSurface(self)

    @property
    def size(self) -> float:
        return float(np.hypot(self.x[1] - self.x[0], self.y[1] - self.y[0]))

    def points(self, x: np.ndarray, y: np.ndarray) -> np.ndarray:
        return np.column_stack([x, y, self.height(x, y)])

    def distance(self, points: np.ndarray, grid: int = 301) -> np.ndarray:
        """Distance from each point to the design (Newton from the nearest grid sample)."""
        return self.nearest(points, grid)[2]

    def nearest(self, points: np.ndarray, grid: int = 301) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Each point's closest point on the design, (x, y), and its distance (Newton from
        the nearest grid sample). Where the closest point lies on the rectangle's edge the
        coordinate held there is left out of the step (projected Newton: a step clamped to
        the edge after a full two-dimensional step would move the free coordinate by the
        held one's coupling and stop beside the edge's closest point, over-reporting)."""
        gx, gy = (a.ravel() for a in np.meshgrid(np.linspace(*self.x, grid), np.linspace(*self.y, grid)))
        _, index = cKDTree(self.points(gx, gy)).query(points)
        x, y = gx[index].copy(), gy[index].copy()
        for _ in range(40):
            f, fx, fy, fxx, fxy, fyy = self.heights(x, y)
            d = np.column_stack([x, y, f]) - points
            gradient_x = d[:, 0] + d[:, 2] * fx
            gradient_y = d[:, 1] + d[:, 2] * fy
            h11 = 1 + fx * fx + d[:, 2] * fxx
            h12 = fx * fy + d[:, 2] * fxy
            h22 = 1 + fy * fy + d[:, 2] * fyy
            det = h11 * h22 - h12 * h12
            bad = (det <= 1e-12) | (h11 <= 1e-12) | (h22 <= 1e-12)  # Gauss–Newton where not positive
            h11, h12, h22 = (np.where(bad, a, b) for a, b in ((1 + fx * fx, h11), (fx * fy, h12),
                                                                (1 + fy * fy, h22)))
            det = h11 * h22 - h12 * h12
            # held at an edge: on it, and the descent direction points out of the rectangle
            hold_x = ((x <= self.x[0]) & (gradient_x > 0)) | ((x >= self.x[1]) & (gradient_x < 0))
            hold_y = ((y <= self.y[0]) & (gradient_y > 0)) | ((y >= self.y[1]) & (gradient_y < 0))
            step_x = np.where(hold_y, gradient_x / h11, (h22 * gradient_x - h12 * gradient_y) / det)
            step_y = np.where(hold_x, gradient_y / h22, (h11 * gradient_y - h12 * gradient_x) / det)
            x = np.clip(x - np.where(hold_x, 0.0, step_x), *self.x)
            y = np.clip(y - np.where(hold_y, 0.0, step_y), *self.y)
        return x, y, np.linalg.norm(self.points(x, y) - points, axis=1)

    def edge(self, count: int = 400) -> np.ndarray:
        """Points along the design's boundary, all four sides."""
        t = np.linspace(0.0, 1.0, count)
        (x0, x1), (y0, y1) = self.x, self.y
        xs = np.concatenate([x0 + t * (x1 - x0), np.full(count, x1), x1 - t * (x1 - x0), np.full(count, x0)])
        ys = np.concatenate([np.full(count, y0), y0 + t * (y1 - y0), np.full(count, y1), y1 - t * (y1 - y0)])
        return self.points(xs, ys)

    def area(self, count: int = 801) -> float:
        """The design's area by the trapezoid rule on sympy's exact area element."""
        xs, ys = np.linspace(*self.x, count), np.linspace(*self.y, count)
        gx, gy = np.meshgrid(xs, ys, indexing="ij")
        element = np.sqrt(1 + self.height(gx, gy, 1) ** 2 + self.height(gx, gy, 2) ** 2)
        return float(np.trapezoid(np.trapezoid(element, ys, axis=1), xs))


class HeightSurface(Surface):
    """A :class:`Design` as a kernel surface on [0, 1]² with its exact derivatives."""

    def __init__(self, design: Design) -> None:
        self.design = design

    def __repr__(self) -> str:
        return f"HeightSurface({self.design.name})"

    def derivatives(self, u, v, order: int = 1):
        self._check_order(order)
        s, t = broadcast_uv(u, v)
        (x0, x1), (y0, y1) = self.design.x, self.design.y
        a, b = x1 - x0, y1 - y0
        x, y = x0 + s * a, y0 + t * b
        h = self.design.heights(x, y, 6 if order == 2 else 3 if order == 1 else 1)
        zero, one = np.zeros_like(x), np.ones_like(x)
        out = [np.column_stack([x, y, h[0]])]
        if order >= 1:
            out += [np.column_stack([a * one, zero, a * h[1]]), np.column_stack([zero, b * one, b * h[2]])]
        if order >= 2:
            out += [np.column_stack([zero, zero, a * a * h[3]]), np.column_stack([zero, zero, a * b * h[4]]),
                    np.column_stack([zero, zero, b * b * h[5]])]
        return out


def _saddle(x, y):
    """(p² − q²)/24 in axes p, q turned 30° from x, y: its curvature lines cross the grid."""
    c, s = np.cos(np.pi / 6), np.sin(np.pi / 6)
    p, q = c * x + s * y, -s * x + c * y
    return ((p * p - q * q) / 24, (p * c + q * s) / 12, (p * s - q * c) / 12, (c * c - s * s) / 12 + 0 * x,
            2 * c * s / 12 + 0 * x, (s * s - c * c) / 12 + 0 * x)


def _dome(x, y):
    return 3 - (x * x + y * y) / 20, -x / 10, -y / 10, -0.1 + 0 * x, 0 * x, -0.1 + 0 * x


def _wave(x, y):
    """A wave along x + y/2 on a wave along y: it bends both ways, curvature lines crossing the grid."""
    a, b = 0.5, 0.6
    p = a * (x + 0.5 * y)
    return (0.7 * np.sin(p) + 0.5 * np.sin(b * y), 0.7 * a * np.cos(p),
            0.35 * a * np.cos(p) + 0.5 * b * np.cos(b * y),
            -0.7 * a * a * np.sin(p), -0.35 * a * a * np.sin(p),
            -0.175 * a * a * np.sin(p) - 0.5 * b * b * np.sin(b * y))


def _monkey(x, y):
    return ((x**3 - 3 * x * y * y) / 400, (3 * x * x - 3 * y * y) / 400, -6 * x * y / 400, 6 * x / 400,
            -6 * y / 400, -6 * x / 400)


def _bump(x, y, cx, s2):
    """2·exp(−((x − cx)² + y²)/s2) and its derivatives."""
    e = 2 * np.exp(-((x - cx) ** 2 + y * y) / s2)
    gx, gy = -2 * (x - cx) / s2, -2 * y / s2
    return e, e * gx, e * gy, e * (gx * gx - 2 / s2), e * gx * gy, e * (gy * gy - 2 / s2)


def _bumps(x, y):
    return tuple(a + b for a, b in zip(_bump(x, y, -4.5, 18), _bump(x, y, 4.5, 18), strict=True))


def _canopy(x, y):
    a, c = 0.35, 1.6
    e = 2.5 * np.exp((y - 5) / c)
    return (0.25 * np.sin(a * x) + e, 0.25 * a * np.cos(a * x), e / c, -0.25 * a * a * np.sin(a * x), 0 * x,
            e / (c * c))


def _umbilic(x, y):
    return ((x * x + y * y) / 20 + (x**3 - 3 * x * y * y) / 900, x / 10 + (3 * x * x - 3 * y * y) / 900,
            y / 10 - 6 * x * y / 900, 0.1 + 6 * x / 900, -6 * y / 900, 0.1 - 6 * x / 900)


def _in_mm(jet):
    """A design in metres drawn in millimetres: z(x, y) = 1000·f(x/1000, y/1000)."""

    def scaled(x, y):
        f, fx, fy, fxx, fxy, fyy = jet(x / MM, y / MM)
        return MM * f, fx, fy, fxx / MM, fxy / MM, fyy / MM

    return scaled


MM = 1000.0

DESIGNS = {
    "saddle": Design("saddle", _saddle, (-6.0, 6.0), (-4.0, 4.0)),
    "dome": Design("dome", _dome, (-5.0, 5.0), (-5.0, 5.0)),
    "wave": Design("wave", _wave, (-8.0, 8.0), (-4.5, 4.5)),
    "monkey": Design("monkey", _monkey, (-7.0, 7.0), (-7.0, 7.0)),
    "bumps": Design("bumps", _bumps, (-9.0, 9.0), (-6.0, 6.0)),
    "canopy": Design("canopy", _canopy, (-8.0, 8.0), (-5.0, 5.0)),
    "umbilic": Design("umbilic", _umbilic, (-5.0, 5.0), (-5.0, 5.0)),
    "wave-mm": Design("wave-mm", _in_mm(_wave), (-8 * MM, 8 * MM), (-4.5 * MM, 4.5 * MM), unit=MM),
}
