"""MeshSurface: a triangle mesh (imported geometry) used as a surface."""

from __future__ import annotations

from typing import Any

import numpy as np

from torsal.engine.node import In, Node, NodeWarning, Out
from torsal.nodes.common.checks import given
from torsal.nodes.common.values import MESH, MESH_SURFACE
from torsal.nodes.geometry import mesh_surface as kernel


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
