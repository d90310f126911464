"""MeshSurface: a triangle mesh (imported geometry) used as a surface; SurfaceFromMesh: a
NURBS surface fitted to one, for nodes that need (u, v) parameters."""

from __future__ import annotations

from typing import Any

import numpy as np

from torsal.engine.node import In, Node, NodeWarning, Out
from torsal.engine.types import NUMBER
from torsal.nodes.common.checks import given
from torsal.nodes.common.values import MESH, MESH_SURFACE, SURFACE
from torsal.nodes.geometry import mesh_surface as kernel
from torsal.nodes.geometry.mesh_fit import fit_mesh


class MeshSurface(Node):
    """Use a triangle mesh, such as an imported OBJ or STL, as a surface.

    A mesh has no (u, v) parameters, so a mesh surface cannot be evaluated at a UV
    or cut into isocurves; it measures what a mesh can: Area (with the centroid),
    closest points and a discrete curvature per vertex, and it can be moved like
    any geometry. A surface wired in is meshed on a 33 × 33 grid first.
    """

    type_id = "surfaces.MeshSurface"
    nickname, aliases = "MeshSrf", ("mesh to surface",)
    inputs = (In("Mesh", MESH, "M", "The triangle mesh."),)
    outputs = (Out("Surface", MESH_SURFACE, "S", "The mesh as a surface."),)

    def solve(self, mesh: Any) -> kernel.MeshSurface:
        m = given("Mesh", mesh)
        if len(m.faces) == 0:
            raise NodeWarning("Mesh has no faces, so it has no surface")
        if not np.all(np.isfinite(m.vertices)):
            raise NodeWarning("Mesh has a vertex with a coordinate that is not a finite number")
        if not m.area > 0:
            raise NodeWarning("Mesh has zero area: every triangle is collapsed to a line or a point")
        return kernel.MeshSurface(m)


class SurfaceFromMesh(Node):
    """A NURBS surface fitted to a mesh design (an OBJ, STL or PLY roof, canopy or scan), so
    that nodes that need (u, v) parameters — Rationalise, isocurves — can work on it.

    The mesh must be one height field over its mean plane (every triangle facing the same
    side of it: a roof or a shell, not a wall or a closed shape) and cover most of its
    footprint's bounding rectangle. It is fitted over its plan: the plane onto which its
    outline encloses the most area (a roof drawn over a plan gets that plan, however its
    heights tilt), the rectangle's sides along the outline's smallest bounding rectangle. The
    heights are fitted by least squares (FITPACK's bivariate splines) on a grid of knots
    refined until every vertex, triangle centroid and edge midpoint lies within Tolerance of
    the surface, measured along the plan's normal. Where the mesh's outline does not reach
    the rectangle's edges to within Tolerance (a curved or slanted edge, a hole) the surface
    is trimmed by the outline, so that Rationalise stays on the mesh and covers it to its
    edges. Deviation says how close the fit came: give Rationalise a tolerance smaller by
    that much, and its strips stay within your tolerance of the mesh. See docs/rhino.md.
    """

    type_id = "surfaces.SurfaceFromMesh"
    nickname, aliases = "FitSrf", ("fit surface", "mesh to NURBS", "surface from mesh design")
    inputs = (
        In("Mesh", MESH, "M", "The mesh design (ImportMesh's Mesh)."),
        In("Tolerance", NUMBER, "T", "Largest distance of the mesh from the surface, model units.",
           default=0.002),
    )
    outputs = (
        Out("Surface", SURFACE, "S", "The fitted bicubic NURBS surface, trimmed by the mesh's outline "
            "where that is not its rectangle."),
        Out("Deviation", NUMBER, "E", "Largest distance of the mesh's vertices, centroids and edge "
            "midpoints from the surface, along its plan's normal."),
    )

    def solve(self, mesh: Any, tolerance: Any) -> tuple[Any, float]:
        m = given("Mesh", mesh)
        tol = float(tolerance) if tolerance is not None else float("nan")
        size = float(np.ptp(np.asarray(m.vertices, dtype=float), axis=0).max()) if len(m.vertices) else 0.0
        if not (np.isfinite(tol) and 0.0 < tol < size):
            raise NodeWarning(f"Tolerance must be a distance above 0 and below the mesh's size ({size:g}), "
                              f"not {tol:g}")
        try:
            fitted = fit_mesh(m, tol)
        except ValueError as exc:
            raise NodeWarning(f"Mesh: {exc}") from None
        if fitted.deviation > tol:
            self.warn(f"The closest fit found is {fitted.deviation:.3g} from the mesh, more than Tolerance "
                      f"{tol:g} (with {fitted.knots} knots each way, the closest of the grids tried)")
        return fitted.surface, fitted.deviation
