"""Mesh-backed surfaces: imported geometry (OBJ, STL, PLY, GLB …) as a trimesh mesh.

A mesh has no (u, v) parameterisation, so ``MeshSurface`` is not a
:class:`~nodes.geometry.surface_base.Surface`; it offers the same *queries* that make
sense without one, with the same names and result types: ``area``,
``area_and_centroid``, ``bounding_box``, ``closest_point``, ``curvature`` (per vertex,
a discrete estimator — see :func:`nodes.geometry.curvature.mesh_vertex_curvature`),
``normals``, ``to_mesh`` and ``is_ruled`` (always False).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import trimesh
from numpy.typing import ArrayLike, NDArray
from scipy.spatial import cKDTree

from .curvature import SurfaceCurvature, mesh_vertex_curvature
from .vec_ops import position_rounding

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class MeshClosestPoint:
    """Result of :meth:`MeshSurface.closest_point` for m query points."""

    points: FloatArray  #: (m, 3) closest points on the mesh
    distances: FloatArray  #: (m,)
    faces: NDArray[np.intp]  #: (m,) index of the triangle each closest point lies on


class MeshSurface:
    """A triangle mesh used as a surface.

    Example:
        >>> import trimesh
        >>> ball = MeshSurface(trimesh.creation.icosphere(subdivisions=3))
        >>> round(ball.area(), 2)
        12.51
    """

    is_ruled = False
    ruling_direction = None

    def __init__(self, mesh: trimesh.Trimesh) -> None:
        if not isinstance(mesh, trimesh.Trimesh):
            raise TypeError("MeshSurface wraps a trimesh.Trimesh")
        if len(mesh.faces) == 0:
            raise ValueError("the mesh has no faces")
        self.mesh = mesh
        self._curvature: dict[tuple[str, int], SurfaceCurvature] = {}

    def __repr__(self) -> str:
        return f"MeshSurface({len(self.mesh.vertices)} vertices, {len(self.mesh.faces)} faces)"

    @property
    def points(self) -> FloatArray:
        """Vertex positions, ``(V, 3)``."""
        return np.asarray(self.mesh.vertices, dtype=float)

    @property
    def normals(self) -> FloatArray:
        """Unit vertex normals (area-weighted face normals), ``(V, 3)``."""
        return np.asarray(self.mesh.vertex_normals, dtype=float)

    def area(self) -> float:
        """Total triangle area."""
        return float(self.mesh.area)

    def area_and_centroid(self) -> tuple[float, FloatArray]:
        """Area and area centroid (of the surface, not of the enclosed volume)."""
        weights = self.mesh.area_faces
        centroid = (self.mesh.triangles_center * weights[:, None]).sum(axis=0) / weights.sum()
        return float(weights.sum()), centroid

    def bounding_box(self) -> FloatArray:
        """``[[xmin, ymin, zmin], [xmax, ymax, zmax]]``."""
        return np.asarray(self.mesh.bounds, dtype=float).copy()

    def curvature(self, method: str = "quadric", rings: int = 2) -> SurfaceCurvature:
        """Discrete curvature at every vertex (k1 ≥ k2, directions, K, H, normal).

        Computed once per (method, rings) and kept: the mesh is treated as immutable.
        """
        key = (method, rings)
        if key not in self._curvature:
            self._curvature[key] = mesh_vertex_curvature(self.mesh, method=method, rings=rings)
        return self._curvature[key]

    def closest_point(self, points: ArrayLike) -> MeshClosestPoint:
        """Exact closest points on the triangles.

        Candidate triangles for a query P are those whose centroid lies within
        d₀ + r of P, where d₀ is the distance to the nearest vertex (an upper bound
        of the answer) and r the largest centroid-to-corner distance of any
        triangle; every triangle that could hold the answer is among them. The
        candidates are then measured exactly with trimesh's vectorised
        point–triangle projection.
        """
        query = np.atleast_2d(np.asarray(points, dtype=float))
        triangles = np.asarray(self.mesh.triangles, dtype=float)
        centres = triangles.mean(axis=1)
        reach = float(np.linalg.norm(triangles - centres[:, None], axis=2).max())
        d0, _ = cKDTree(self.mesh.vertices).query(query)
        # the slack covers the rounding of the centres and distances (more far from the origin)
        slack = reach * 1e-9 + 1e-12 + position_rounding(centres)
        candidates = cKDTree(centres).query_ball_point(query, d0 + reach + slack)
        counts = np.array([len(c) for c in candidates])
        faces = np.concatenate([np.asarray(c, dtype=np.intp) for c in candidates])
        owner = np.repeat(np.arange(len(query)), counts)
        found = trimesh.triangles.closest_point(triangles[faces], query[owner])
        dist = np.linalg.norm(found - query[owner], axis=1)
        # Minimum per query over its candidates: sort by (owner, distance).
        order = np.lexsort((dist, owner))
        first = np.concatenate([[0], np.cumsum(counts)[:-1]])
        best = order[first]
        return MeshClosestPoint(points=found[best], distances=dist[best], faces=faces[best])

    def to_mesh(self) -> trimesh.Trimesh:
        """The wrapped mesh (a copy)."""
        return self.mesh.copy()
