"""The box around geometry, and the volume and volume centroid of a closed mesh."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import trimesh

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import GENERIC, NUMBER, POINT, describe
from torsal.engine.values import Point, Vector
from torsal.nodes.common.convert import point
from torsal.nodes.common.values import MESH
from torsal.nodes.geometry import mesh_surface
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.surface_base import Surface


def _extremes(item: Any) -> np.ndarray:
    """``[[xmin, ymin, zmin], [xmax, ymax, zmax]]`` of one item, or a warning naming its kind."""
    if isinstance(item, Point | Vector):
        corner = np.asarray(item, dtype=float)
        return np.stack([corner, corner])
    if isinstance(item, Curve | Surface | mesh_surface.MeshSurface):
        return np.asarray(item.bounding_box(), dtype=float)
    if isinstance(item, trimesh.Trimesh):
        if len(item.vertices) == 0:
            raise NodeWarning("A mesh of Geometry has no vertices, so it has no box")
        return np.asarray(item.bounds, dtype=float)
    raise NodeWarning(
        f"Geometry holds {describe(item)}: a box is taken of points, curves, surfaces and meshes"
    )


class BoundingBox(Node):
    """The smallest box with sides parallel to the world axes that holds all the Geometry.

    One box for the whole list (Grasshopper's "union box"): graft the input for a box
    per item. Curves and surfaces are boxed by their true extremes (each found by
    optimisation from a dense sample, not by their control points), meshes by their
    vertices. A flat input gives a flat box.
    """

    type_id = "surfaces.BoundingBox"
    nickname, aliases = "BBox", ("Bounding Box", "Box", "extents", "bounds of geometry")
    inputs = (In("Geometry", GENERIC, "G", "Points, curves, surfaces or meshes to hold.", access=LIST),)
    outputs = (
        Out("Box", MESH, "B", "The box, as a closed mesh of 12 triangles."),
        Out("Min", POINT, "Mn", "The corner with the smallest x, y and z."),
        Out("Max", POINT, "Mx", "The corner with the largest x, y and z."),
        Out("Centre", POINT, "C", "The middle of the box.", preview=False),
    )

    def solve(self, geometry: Sequence[Any]) -> tuple[trimesh.Trimesh, Point, Point, Point]:
        items = [g for g in geometry if g is not None]
        if not items:
            raise NodeWarning("Geometry is empty, so there is nothing to box")
        boxes = np.stack([_extremes(item) for item in items])
        low, high = boxes[:, 0].min(axis=0), boxes[:, 1].max(axis=0)
        if not np.all(np.isfinite([low, high])):
            raise NodeWarning("Geometry has a coordinate that is not a finite number")
        centre = 0.5 * (low + high)
        move = trimesh.transformations.translation_matrix(centre)
        box = trimesh.creation.box(extents=high - low, transform=move)
        return box, point(low), point(high), point(centre)


class Volume(Node):
    """The volume a closed mesh encloses, and the centre of that volume.

    Exact for the mesh, by the divergence theorem over its triangles (trimesh's mass
    properties). A surface wired in is meshed first, so a sphere's volume carries the
    meshing's small error. The mesh must be closed (watertight): an open one encloses
    nothing.
    """

    type_id = "surfaces.Volume"
    nickname, aliases = "Vol", ("Volume Centroid", "volume centroid", "mass", "centre of mass")
    inputs = (In("Mesh", MESH, "M", "A closed mesh (or a closed surface, meshed)."),)
    outputs = (
        Out("Volume", NUMBER, "V", "The enclosed volume, in cubic model units."),
        Out("Centroid", POINT, "C", "The centre of the volume (of the solid, not of its skin)."),
    )

    def solve(self, mesh: Any) -> tuple[float, Point]:
        if not isinstance(mesh, trimesh.Trimesh) or len(mesh.faces) == 0:
            raise NodeWarning("Mesh has no faces, so it encloses no volume")
        if not mesh.is_watertight:
            raise NodeWarning("The mesh is open (not watertight), so it encloses no volume")
        # measured about the mesh's own middle: at site coordinates (1e6 m) the triple
        # products about the world origin would cancel away the volume's digits
        middle = np.asarray(mesh.bounds, dtype=float).mean(axis=0)
        local = trimesh.Trimesh(np.asarray(mesh.vertices) - middle, mesh.faces, process=False)
        volume = float(local.volume)
        if not np.isfinite(volume) or volume == 0.0:
            raise NodeWarning("The mesh encloses no volume: it is flat or folds back on itself")
        if volume < 0:
            self.remark("The mesh's faces point inwards; its volume is given as a positive number")
        return abs(volume), point(np.asarray(local.center_mass) + middle)
