"""A trimmed surface: an underlying surface and the trim loops that bound the part kept.

A Rhino brep face is a NURBS surface with trim loops in its parameter plane: one outer
loop, and inner loops around holes. :class:`TrimmedSurface` keeps both. It evaluates as
its underlying surface (points and derivatives at any (u, v), vectorised, exactly as the
NURBS kernel does), and says which parameters lie in the kept part (:meth:`inside`), so
a node that works on a design (Rationalise) can work inside the trim. Loops are closed
polylines in (u, v) in [0, 1]², counter-clockwise for the outer loop and clockwise for
holes, made by pulling the face's 3D edges back onto the surface.

The trim region is a shapely polygon, so shapely is imported when a trimmed surface is
made: a graph without one (the flagship) does not import it on the way to its first frame.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike

from .curve_base import FloatArray
from .surface_base import Surface, uv_grid
from .vec_ops import cross2

#: Dunavant's 7-point rule on a triangle (degree 5): barycentric points and weights.
_RULE_POINTS = np.array([
    [1 / 3, 1 / 3, 1 / 3],
    [0.0597158717, 0.4701420641, 0.4701420641], [0.4701420641, 0.0597158717, 0.4701420641],
    [0.4701420641, 0.4701420641, 0.0597158717],
    [0.7974269853, 0.1012865073, 0.1012865073], [0.1012865073, 0.7974269853, 0.1012865073],
    [0.1012865073, 0.1012865073, 0.7974269853],
])
_RULE_WEIGHTS = np.array([0.225, *[0.1323941527] * 3, *[0.1259391805] * 3])


class TrimmedSurface(Surface):
    """``surface`` kept inside ``outer`` and outside every one of ``holes`` ((k, 2) arrays of
    (u, v) on the surface's unit square, closed or not)."""

    def __init__(self, surface: Surface, outer: ArrayLike, holes: Sequence[ArrayLike] = ()) -> None:
        self.surface = surface
        self.outer = _ring(outer, counter_clockwise=True)
        self.holes = [_ring(hole, counter_clockwise=False) for hole in holes]
        from shapely import Polygon

        self.region = Polygon(self.outer, self.holes)
        if not self.region.is_valid or self.region.area <= 0.0:
            raise ValueError("the trim loops do not bound a region of the surface")
        self.closed_u, self.closed_v = surface.closed_u, surface.closed_v

    def __repr__(self) -> str:
        return f"TrimmedSurface({self.surface!r}, {len(self.holes)} holes)"

    def derivatives(self, u: ArrayLike, v: ArrayLike, order: int = 1) -> list[FloatArray]:
        return self.surface.derivatives(u, v, order)

    @property
    def loops(self) -> list[FloatArray]:
        """The outer loop, then the holes: closed (u, v) polylines (last point = first)."""
        return [self.outer, *self.holes]

    @property
    def parameter_share(self) -> float:
        """The share of the unit square the kept part covers."""
        return float(self.region.area)

    def inside(self, u: ArrayLike, v: ArrayLike) -> np.ndarray:
        """Whether each (u, v) lies in the kept part (on a loop counts as inside)."""
        from shapely import contains_xy

        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        return contains_xy(self.region, u, v) | contains_xy(self.region.boundary.buffer(1e-12), u, v)

    def mesh_arrays(self, nu: int = 33, nv: int = 33) -> tuple[FloatArray, np.ndarray, FloatArray]:
        """The underlying surface's grid mesh without the triangles outside the trim (by their
        centres): what the viewport draws and Bake's mesh forms show."""
        points, faces, normals = self.surface.mesh_arrays(nu, nv)
        u, v = uv_grid(nu, nv)
        keep = self.inside(u[faces].mean(axis=1), v[faces].mean(axis=1))
        return points, faces[keep], normals

    def area_and_centroid(self, rtol: float = 1e-11) -> tuple[float, FloatArray]:
        """Area and centroid of the kept part: the trimmed (u, v) region cut into triangles
        (shapely's constrained Delaunay), each split 64 ways, Dunavant's degree-5 rule on
        each; exact to the trim loops' polygons and the rule (``rtol`` is not used)."""
        from shapely import constrained_delaunay_triangles, get_coordinates

        del rtol
        corners = get_coordinates(constrained_delaunay_triangles(self.region)).reshape(-1, 4, 2)[:, :3]
        for _ in range(3):  # each triangle into 4, three times
            a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
            ab, bc, ca = (a + b) / 2, (b + c) / 2, (c + a) / 2
            corners = np.concatenate([np.stack(t, axis=1) for t in
                                      ((a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca))])
        e1, e2 = corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0]
        flat = 0.5 * np.abs(cross2(e1, e2))
        uv = np.einsum("qk,tkd->tqd", _RULE_POINTS, corners).reshape(-1, 2)
        point, su, sv = self.derivatives(uv[:, 0], uv[:, 1], 1)
        element = np.linalg.norm(np.cross(su, sv), axis=1).reshape(len(corners), -1)
        weights = element * _RULE_WEIGHTS * flat[:, None]
        area = float(weights.sum())
        centroid = (weights.reshape(-1, 1) * point).sum(axis=0) / area
        return area, centroid

    def area(self, rtol: float = 1e-11) -> float:
        return self.area_and_centroid(rtol)[0]

    def loops_3d(self) -> list[FloatArray]:
        """The trim loops on the surface, as 3D polylines."""
        return [self.point_at(loop[:, 0], loop[:, 1]) for loop in self.loops]


def _ring(points: ArrayLike, counter_clockwise: bool) -> FloatArray:
    ring = np.asarray(points, dtype=float)
    if ring.ndim != 2 or ring.shape[1] != 2 or len(ring) < 3 or not np.isfinite(ring).all():
        raise ValueError("a trim loop must be at least three finite (u, v) points")
    if not np.array_equal(ring[0], ring[-1]):
        ring = np.vstack([ring, ring[:1]])
    x, y = ring[:, 0], ring[:, 1]
    signed = 0.5 * float(np.dot(x[:-1], y[1:]) - np.dot(x[1:], y[:-1]))
    return ring if (signed > 0) == counter_clockwise else ring[::-1].copy()
