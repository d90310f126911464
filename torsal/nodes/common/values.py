"""The geometry value types: what the kernel's objects are called on wires and in results.

Declared by the library (``VALUE_TYPES`` in ``nodes/__init__.py``), so casts such as
Line → Curve, Surface → Mesh and Mesh ↔ MeshSurface work on every wire, and ``torsal run
--json`` describes geometry by its key figures (lengths, areas, bounding boxes). Import
a type from here to declare a port of it.

- ``CURVE``, ``LINE``, ``SURFACE``, ``MESH``: the kernel's curves, lines, parameterised
  surfaces and trimesh meshes;
- ``MESH_SURFACE``: the kernel's mesh-backed
  :class:`~torsal.nodes.geometry.mesh_surface.MeshSurface` (imported geometry): area, closest
  point and discrete curvature, no (u, v);
- ``DEVELOPMENT``: IsoMapping's ``Map`` output, the kernel's
  :class:`~torsal.nodes.geometry.unroll.Development` — the flat and 3D rulings, the accuracy
  figures and the map that carries points and polylines between the development and the
  3D strip (SurfacePatching draws panels on the development and maps them onto the
  surface with it).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from torsal.engine.types import ValueType, register_cast
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curves.line import Line
from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.surface_base import Surface
from torsal.nodes.geometry.trimesh_type import TriangleMesh
from torsal.nodes.geometry.unroll import Development

if TYPE_CHECKING:
    import trimesh


def _xyz(array: Any) -> list[float]:
    return [float(c) for c in np.asarray(array, dtype=float)[:3]]


def _line_summary(line: Line) -> dict[str, Any]:
    return {"type": "Line", "from": _xyz(line.start), "to": _xyz(line.end), "length": float(line.length)}


def _line_decode(data: dict[str, Any]) -> Line:
    return Line(np.asarray(data["from"], dtype=float), np.asarray(data["to"], dtype=float))


def _curve_summary(curve: Curve) -> dict[str, Any]:
    return {
        "type": "Curve",
        "kind": type(curve).__name__,
        "length": float(curve.length),
        "closed": bool(curve.closed),
        "start": _xyz(curve.start),
        "end": _xyz(curve.end),
    }


def _surface_summary(surface: Surface) -> dict[str, Any]:
    box = np.asarray(surface.bounding_box(), dtype=float)
    return {
        "type": "Surface",
        "kind": type(surface).__name__,
        "area": float(surface.area()),
        "bbox": [box[0].tolist(), box[1].tolist()],
    }


def _mesh_summary(mesh: trimesh.Trimesh) -> dict[str, Any]:
    return {
        "type": "Mesh",
        "vertices": len(mesh.vertices),
        "faces": len(mesh.faces),
        "area": float(mesh.area),
    }


def _mesh_surface_summary(surface: MeshSurface) -> dict[str, Any]:
    return {
        "type": "MeshSurface",
        "vertices": len(surface.mesh.vertices),
        "faces": len(surface.mesh.faces),
        "area": surface.area(),
    }


def _development_summary(development: Development) -> dict[str, Any]:
    bounds = np.asarray(development.bounds, dtype=float)
    return {
        "type": "Development",
        "rulings": len(development.requested_rulings),
        "area_3d": float(development.area_3d),
        "area_2d": float(development.area_2d),
        "area_error": float(development.area_error),
        "max_edge_length_error": float(development.max_edge_length_error),
        "bounds": [bounds[:2].tolist(), bounds[2:].tolist()],
    }


CURVE = ValueType("Curve", (Curve,), "A curve, parameterised on [0, 1].", summarize=_curve_summary)
LINE = ValueType(
    "Line", (Line,), "A straight segment.",
    encode=lambda line: {"type": "Line", "from": _xyz(line.start), "to": _xyz(line.end)},
    decode=_line_decode,
    summarize=_line_summary,
)
SURFACE = ValueType("Surface", (Surface,), "A surface, parameterised on [0, 1]².", summarize=_surface_summary)
MESH = ValueType("Mesh", (TriangleMesh,), "A triangle mesh.", summarize=_mesh_summary)
MESH_SURFACE = ValueType(
    "MeshSurface", (MeshSurface,),
    "A triangle mesh used as a surface: area, closest point and discrete curvature, no (u, v).",
    summarize=_mesh_surface_summary,
)
DEVELOPMENT = ValueType(
    "Development", (Development,),
    "A ruled surface unrolled into the XY plane, with the map between the plane and the surface.",
    summarize=_development_summary,
)

register_cast(SURFACE, MESH, lambda surface: surface.to_mesh())
register_cast(MESH_SURFACE, MESH, lambda surface: surface.to_mesh())
register_cast(MESH, MESH_SURFACE, MeshSurface)
