"""Ruled strips as triangle meshes, and the Hausdorff distance between two of them.

A strip given by its rulings (starts P_i, ends Q_i) is the union of the bilinear patches
``(1 − v)[(1 − u)P_i + u P_{i+1}] + v[(1 − u)Q_i + u Q_{i+1}]`` between consecutive
rulings — what a loft through the rulings is. Each patch is triangulated finely and the
distance from sample points to the other strip is exact point-to-triangle distance.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

Array = np.ndarray


def strip_points(starts: Array, ends: Array, ku: int, kv: int) -> Array:
    """``(rulings − 1, ku + 1, kv + 1, 3)`` grid points of every bilinear patch."""
    u = np.linspace(0.0, 1.0, ku + 1)
    v = np.linspace(0.0, 1.0, kv + 1)
    p0, p1, q0, q1 = starts[:-1], starts[1:], ends[:-1], ends[1:]
    bottom = p0[:, None, :] + u[None, :, None] * (p1 - p0)[:, None, :]
    top = q0[:, None, :] + u[None, :, None] * (q1 - q0)[:, None, :]
    return bottom[:, :, None, :] + v[None, None, :, None] * (top - bottom)[:, :, None, :]


def isotropic_steps(starts: Array, ends: Array, ku: int = 2) -> int:
    """Steps along the rulings that make the triangles about as long as they are wide."""
    steps = np.linalg.norm(np.diff(starts, axis=0), axis=1) + np.linalg.norm(np.diff(ends, axis=0), axis=1)
    width = np.median(steps)
    length = np.linalg.norm(ends - starts, axis=1).max()
    return int(np.clip(np.ceil(length / max(width / (2 * ku), 1e-12)), 1, 400))


def strip_triangles(starts: Array, ends: Array, ku: int = 2, kv: int | None = None) -> Array:
    """``(t, 3, 3)`` triangles of the strip, each patch split into 2·ku·kv triangles."""
    g = strip_points(starts, ends, ku, kv or isotropic_steps(starts, ends, ku))
    a, b = g[:, :-1, :-1], g[:, 1:, :-1]
    c, d = g[:, 1:, 1:], g[:, :-1, 1:]
    first = np.stack([a, b, c], axis=-2).reshape(-1, 3, 3)
    second = np.stack([a, c, d], axis=-2).reshape(-1, 3, 3)
    return np.concatenate([first, second])


def point_triangle_distance(p: Array, tri: Array) -> Array:
    """Distance from points ``(n, 3)`` to triangles ``(n, 3, 3)`` (row by row), exact."""
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    ab, ac, ap = b - a, c - a, p - a
    d1, d2 = np.einsum("ij,ij->i", ab, ap), np.einsum("ij,ij->i", ac, ap)
    bp, cp = p - b, p - c
    d3, d4 = np.einsum("ij,ij->i", ab, bp), np.einsum("ij,ij->i", ac, bp)
    d5, d6 = np.einsum("ij,ij->i", ab, cp), np.einsum("ij,ij->i", ac, cp)
    va, vb, vc = d3 * d6 - d5 * d4, d5 * d2 - d1 * d6, d1 * d4 - d3 * d2
    with np.errstate(divide="ignore", invalid="ignore"):
        # interior projection by default, then the Voronoi regions of edges and vertices
        denom = va + vb + vc
        v, w = vb / denom, vc / denom
        closest = a + v[:, None] * ab + w[:, None] * ac
        on_bc = (va <= 0) & (d4 - d3 >= 0) & (d5 - d6 >= 0)
        t_bc = (d4 - d3) / ((d4 - d3) + (d5 - d6))
        closest = np.where(on_bc[:, None], b + t_bc[:, None] * (c - b), closest)
        on_ac = (vb <= 0) & (d2 >= 0) & (d6 <= 0)
        t_ac = d2 / (d2 - d6)
        closest = np.where(on_ac[:, None], a + t_ac[:, None] * ac, closest)
        on_ab = (vc <= 0) & (d1 >= 0) & (d3 <= 0)
        t_ab = d1 / (d1 - d3)
        closest = np.where(on_ab[:, None], a + t_ab[:, None] * ab, closest)
        closest = np.where(((d6 >= 0) & (d5 <= d6))[:, None], c, closest)
        closest = np.where(((d3 >= 0) & (d4 <= d3))[:, None], b, closest)
        closest = np.where(((d1 <= 0) & (d2 <= 0))[:, None], a, closest)
    # degenerate (zero-area) triangles: fall back to the nearest vertex
    degenerate = ~np.isfinite(closest).all(axis=1)
    if degenerate.any():
        corners = tri[degenerate]
        nearest = np.argmin(np.linalg.norm(corners - p[degenerate, None, :], axis=2), axis=1)
        closest[degenerate] = corners[np.arange(len(nearest)), nearest]
    return np.linalg.norm(p - closest, axis=1)


def distance_to_strip(points: Array, triangles: Array, candidates: int = 32) -> Array:
    """Distance from each point to the nearest of ``triangles`` (checked among the
    ``candidates`` triangles with the nearest centroids, which suffices for fine meshes)."""
    tree = cKDTree(triangles.mean(axis=1))
    _, index = tree.query(points, k=candidates)
    p = np.repeat(points, candidates, axis=0)
    d = point_triangle_distance(p, triangles[index.reshape(-1)])
    return d.reshape(len(points), candidates).min(axis=1)


def hausdorff(first: tuple[Array, Array], second: tuple[Array, Array]) -> float:
    """Symmetric Hausdorff distance between two strips given as (starts, ends), sampled
    at the corners of triangles about as long as they are wide."""
    result = 0.0
    for x, y in ((first, second), (second, first)):
        points = strip_points(*x, 1, max(1, isotropic_steps(*x, 1) // 2)).reshape(-1, 3)
        result = max(result, float(distance_to_strip(points, strip_triangles(*y)).max()))
    return result


def crossing_pairs(starts: Array, ends: Array) -> int:
    """How many pairs of the strip's flat triangles cross each other, counted here with none
    of the toolbox's code: each piece between consecutive rulings A_i B_i and A_i+1 B_i+1 is
    the triangles (A_i, A_i+1, B_i) and (A_i+1, B_i+1, B_i), those of no area dropped (one
    of them in a fan); two triangles cross when an edge of one passes through the inside of
    the other (Möller–Trumbore, 1e-9 inside every barycentric and edge bound). Pairs that
    share a vertex only touch there and are not counted."""
    size = float(np.linalg.norm(np.ptp(np.vstack([starts, ends]), axis=0))) or 1.0
    a0, a1, b0, b1 = starts[:-1], starts[1:], ends[:-1], ends[1:]
    corners = np.concatenate([np.stack([a0, a1, b0], axis=1), np.stack([a1, b1, b0], axis=1)])
    area = np.linalg.norm(np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]), axis=1)
    tri = corners[area > 1e-12 * size * size]
    n = len(tri)
    # pairs sharing a vertex (within 1e-12 of the size) only touch
    gap = np.linalg.norm(tri[:, None, :, None, :] - tri[None, :, None, :, :], axis=-1).min(axis=(2, 3))
    far = gap > 1e-12 * size
    origin, e1, e2 = tri[:, 0], tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    crossed = np.zeros((n, n), dtype=bool)
    for u, v in ((0, 1), (1, 2), (2, 0)):  # every edge of triangle i against triangle j
        o = tri[:, u][:, None, :]
        d = (tri[:, v] - tri[:, u])[:, None, :]
        h = np.cross(d, e2[None, :, :])
        det = np.einsum("ijk,jk->ij", h, e1)
        with np.errstate(divide="ignore", invalid="ignore"):
            inv = 1.0 / det
            sv = o - origin[None, :, :]
            bu = inv * np.einsum("ijk,ijk->ij", sv, h)
            q = np.cross(sv, e1[None, :, :])
            bv = inv * np.einsum("ijk,ijk->ij", np.broadcast_to(d, q.shape), q)
            along = inv * np.einsum("ijk,jk->ij", q, e2)
        eps = 1e-9
        crossed |= (np.abs(det) > 1e-15 * size**3) & (bu > eps) & (bv > eps) & (bu + bv < 1 - eps) & (
            along > eps) & (along < 1 - eps)
    crossed &= far
    return int(np.count_nonzero(np.triu(crossed | crossed.T, 1)))
