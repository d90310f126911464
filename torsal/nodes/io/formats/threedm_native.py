"""Kernel geometry as rhino3dm objects: NURBS curves and surfaces, triangle meshes.

rhino3dm's control points are homogeneous ``(w·x, w·y, w·z, w)`` and its knot vectors
have the ``n + p − 1`` knots of the openNURBS convention (the kernel's full vectors
without their first and last knot). :mod:`.threedm` (whole files) and
:mod:`.threedm_strips` (strips face by face) both write through these.
"""

from __future__ import annotations

import numpy as np
import rhino3dm as rh
import trimesh

from torsal.nodes.geometry.curves import NurbsCurve
from torsal.nodes.geometry.nurbs_surface import NurbsSurface


def rhino_curve(curve: NurbsCurve) -> rh.NurbsCurve:
    """The rhino3dm NURBS curve with ``curve``'s control points, weights and knots."""
    points = curve.control_points
    weights = curve.weights
    out = rh.NurbsCurve(3, bool(curve.is_rational), curve.degree + 1, len(points))
    homogeneous = np.column_stack([points * weights[:, None], weights]).tolist()
    for i, (x, y, z, w) in enumerate(homogeneous):
        out.Points[i] = rh.Point4d(x, y, z, w)
    for i, knot in enumerate(np.asarray(curve.knots, dtype=float)[1:-1].tolist()):
        out.Knots[i] = knot
    return out


def rhino_surface(surface: NurbsSurface) -> rh.NurbsSurface:
    """The rhino3dm NURBS surface with ``surface``'s net, weights and (normalised) knots."""
    return rhino_net(surface.control_points, surface.weights, surface.knots_u, surface.knots_v,
                     (surface.degree_u, surface.degree_v), bool(surface.is_rational))


def rhino_net(points: np.ndarray, weights: np.ndarray, knots_u: np.ndarray, knots_v: np.ndarray,
              degrees: tuple[int, int], rational: bool) -> rh.NurbsSurface:
    """The rhino3dm NURBS surface of a control net ``points`` (nu, nv, 3), its ``weights``
    (nu, nv) and full knot vectors, straight from the arrays (no kernel surface made)."""
    nu, nv = points.shape[:2]
    out = rh.NurbsSurface.Create(3, rational, degrees[0] + 1, degrees[1] + 1, nu, nv)
    homogeneous = np.concatenate([points * weights[..., None], weights[..., None]], axis=2)
    for i, row in enumerate(homogeneous.tolist()):
        for j, (x, y, z, w) in enumerate(row):
            out.Points[(i, j)] = rh.Point4d(x, y, z, w)
    for i, knot in enumerate(np.asarray(knots_u, dtype=float)[1:-1].tolist()):
        out.KnotsU[i] = knot
    for i, knot in enumerate(np.asarray(knots_v, dtype=float)[1:-1].tolist()):
        out.KnotsV[i] = knot
    return out


def rhino_mesh(mesh: trimesh.Trimesh) -> rh.Mesh:
    """The rhino3dm mesh with ``mesh``'s vertices (double precision) and triangles."""
    out = rh.Mesh()
    out.Vertices.UseDoublePrecisionVertices = True
    for x, y, z in np.asarray(mesh.vertices, dtype=float).tolist():
        out.Vertices.Add(x, y, z)
    for a, b, c in np.asarray(mesh.faces, dtype=int).tolist():
        out.Faces.AddFace(a, b, c)
    return out
