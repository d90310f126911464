"""A NURBS surface fitted to a triangle mesh that is a height field over its mean plane.

Designs often arrive as meshes (OBJ, STL, PLY from a modeller or a scan). Nodes that need
(u, v) parameters — Rationalise, isocurves — cannot work on a mesh; :func:`fit_mesh` gives
them a bicubic NURBS surface within a set distance of it:

1. the mean plane of the vertices (principal axes: the normal is the direction of least
   spread), in which the mesh must be a height field — every triangle facing the same side
   of the plane (a roof, a canopy, a scan of a shell), else it is refused;
2. the heights fitted by least squares with FITPACK's ``LSQBivariateSpline`` on a grid of
   interior knots refined (doubled) until every vertex, every triangle's centroid and the
   midpoint of every edge lie within ``tolerance`` of the surface, measured along the
   plane's normal (an upper bound of the true distance);
3. the spline written as a NURBS surface: x and y run linearly with u and v (their control
   points are the knots' Greville abscissae, which reproduce a linear function exactly),
   z has the fitted coefficients.

The surface spans the mesh's footprint's bounding rectangle in the plane; a mesh whose
footprint leaves much of that rectangle empty is refused (the fit there would be a guess).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import trimesh
from scipy.interpolate import LSQBivariateSpline

from .nurbs_surface import NurbsSurface

#: The share of the footprint's bounding rectangle the mesh must cover.
COVERAGE = 0.95

#: The finest knot grid tried (interior knots per direction).
LARGEST_GRID = 64


@dataclass(frozen=True)
class MeshFit:
    """A surface fitted to a mesh and how far the mesh is from it (along the plane's normal)."""

    surface: NurbsSurface
    deviation: float
    knots: int  #: interior knots per direction


def fit_mesh(mesh: trimesh.Trimesh, tolerance: float) -> MeshFit:
    """The bicubic NURBS surface within ``tolerance`` of ``mesh`` (see the module), or a
    ValueError that says why the mesh cannot be fitted."""
    vertices = np.asarray(mesh.vertices, dtype=float)
    faces = np.asarray(mesh.faces, dtype=np.int64)
    if len(faces) == 0 or not np.isfinite(vertices).all():
        raise ValueError("the mesh has no faces, or a coordinate that is not a finite number")
    centre = vertices.mean(axis=0)
    _, spread, axes = np.linalg.svd(vertices - centre, full_matrices=False)
    if not spread[1] > 1e-9 * spread[0]:
        raise ValueError("the mesh is a line or a point: it spans no plane")
    frame = axes  # rows: along, across, normal
    local = (vertices - centre) @ frame.T
    normals = np.cross(local[faces[:, 1]] - local[faces[:, 0]], local[faces[:, 2]] - local[faces[:, 0]])
    facing = normals[:, 2]
    if np.count_nonzero(facing < 0) > np.count_nonzero(facing > 0):
        facing = -facing
    if not np.all(facing > 1e-12 * np.linalg.norm(normals, axis=1).max()):
        raise ValueError("the mesh folds over itself seen from its mean plane (a wall, an overhang or a "
                         "closed shape): only a mesh that is one height field over a plane can be fitted")
    x, y, z = local.T
    lo, hi = local.min(axis=0), local.max(axis=0)
    footprint = float(np.abs(facing).sum()) / 2.0
    rectangle = float((hi[0] - lo[0]) * (hi[1] - lo[1]))
    if footprint < COVERAGE * rectangle:
        raise ValueError(f"the mesh covers {footprint / rectangle:.0%} of its footprint's bounding "
                         f"rectangle (at least {COVERAGE:.0%} is needed): trim it to a rectangle first")
    edges = np.asarray(mesh.edges_unique, dtype=np.int64)
    probes = np.vstack([local, local[faces].mean(axis=1), local[edges].mean(axis=1)])
    count = 2
    while True:
        tx = np.linspace(lo[0], hi[0], count + 2)[1:-1]
        ty = np.linspace(lo[1], hi[1], count + 2)[1:-1]
        try:
            spline = LSQBivariateSpline(x, y, z, tx, ty, bbox=[lo[0], hi[0], lo[1], hi[1]], kx=3, ky=3)
        except ValueError:  # too few points for this many knots: the previous grid stands
            break
        off = np.abs(spline.ev(probes[:, 0], probes[:, 1]) - probes[:, 2])
        best = (spline, float(off.max()), count)
        if best[1] <= tolerance or count >= LARGEST_GRID:
            break
        count *= 2
    spline, deviation, count = best
    full_u, full_v = (np.asarray(k, dtype=float) for k in spline.get_knots())  # full, ends ×4
    greville_u = np.array([full_u[i + 1:i + 4].mean() for i in range(len(full_u) - 4)])
    greville_v = np.array([full_v[j + 1:j + 4].mean() for j in range(len(full_v) - 4)])
    heights = np.asarray(spline.get_coeffs()).reshape(len(greville_u), len(greville_v))
    gu, gv = np.meshgrid(greville_u, greville_v, indexing="ij")
    net = np.stack([gu, gv, heights], axis=-1) @ frame + centre
    return MeshFit(NurbsSurface(net, 3, 3, full_u, full_v), deviation, count)
