"""Rationalise's strips sampled on a grid, and a grid's area: shared by its tests."""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

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


def gaps_to_edge(strip, v: float, points: np.ndarray) -> np.ndarray:
    """Distance of each point from the strip's edge at ``v``: the polyline of its points at
    20001 parameters, its rulings' (where the edge turns from a boundary onto the cut at the
    design's edge) and more where its chords are longer than 1/20000 of it, from the
    nearest vertex's two chords."""
    t = np.union1d(np.linspace(0, 1, 20001), np.asarray(strip.ruling_parameters, dtype=float))
    edge = strip.point_at(t, np.full_like(t, v))
    chord = float(np.linalg.norm(np.diff(edge, axis=0), axis=1).sum()) / 20000
    for _ in range(8):  # where the edge runs fast (a rail hurrying past a fan), halved chords
        long = np.linalg.norm(np.diff(edge, axis=0), axis=1) > chord
        if not long.any():
            break
        t = np.union1d(t, 0.5 * (t[:-1] + t[1:])[long])
        edge = strip.point_at(t, np.full_like(t, v))
    _, k = cKDTree(edge).query(points)
    best = np.full(len(points), np.inf)
    for first in (np.maximum(k - 1, 0), np.minimum(k, len(edge) - 2)):
        a, d = edge[first], edge[first + 1] - edge[first]
        dd = np.einsum("ij,ij->i", d, d)  # (0 where the edge stands still: a fan's apex)
        w = np.clip(np.einsum("ij,ij->i", points - a, d) / np.where(dd > 0, dd, 1.0), 0, 1)
        best = np.minimum(best, np.linalg.norm(a + w[:, None] * d - points, axis=1))
    return best


def distance_to_strip(strip, points: np.ndarray) -> np.ndarray:
    """Distance from each point to ``strip``: the nearest of 801 × 41 of its points, then
    Gauss–Newton on |S(u, v) − P|² with central-difference derivatives, clamped to [0, 1]²."""
    u0, v0 = np.meshgrid(np.linspace(0, 1, 801), np.linspace(0, 1, 41), indexing="ij")
    u0, v0 = u0.ravel(), v0.ravel()
    _, index = cKDTree(strip.point_at(u0, v0)).query(points)
    u, v = u0[index].copy(), v0[index].copy()
    h = 1e-6
    best = np.linalg.norm(strip.point_at(u, v) - points, axis=1)
    for _ in range(12):
        s = strip.point_at(u, v)
        su = (strip.point_at(np.minimum(u + h, 1), v) - strip.point_at(np.maximum(u - h, 0), v)) / (
            np.minimum(u + h, 1) - np.maximum(u - h, 0))[:, None]
        sv = (strip.point_at(u, np.minimum(v + h, 1)) - strip.point_at(u, np.maximum(v - h, 0))) / (
            np.minimum(v + h, 1) - np.maximum(v - h, 0))[:, None]
        d = s - points
        a11, a12, a22 = (np.einsum("ij,ij->i", x, y) for x, y in ((su, su), (su, sv), (sv, sv)))
        b1, b2 = np.einsum("ij,ij->i", su, d), np.einsum("ij,ij->i", sv, d)
        det = a11 * a22 - a12 * a12 + 1e-30
        u = np.clip(u - (a22 * b1 - a12 * b2) / det, 0, 1)
        v = np.clip(v - (a11 * b2 - a12 * b1) / det, 0, 1)
        best = np.minimum(best, np.linalg.norm(strip.point_at(u, v) - points, axis=1))
    return best
