"""Geometry value types: what the kernel's objects are called on wires and in results.

Registered with the engine's type registry when ``nodes`` is imported, so casts such as
Line → Curve and Surface → Mesh work on every wire, and ``torsal run --json`` describes
geometry by its key figures (lengths, areas, bounding boxes).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import trimesh

from engine.types import ValueType, register_cast, register_type
from engine.values import Point
from nodes.geometry.curve_base import Curve
from nodes.geometry.curves.line import Line
from nodes.geometry.surface_base import Surface


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


CURVE = register_type(ValueType("Curve", (Curve,), "A curve, parameterised on [0, 1].",
                                summarize=_curve_summary))
LINE = register_type(ValueType(
    "Line", (Line,), "A straight segment.",
    encode=lambda line: {"type": "Line", "from": _xyz(line.start), "to": _xyz(line.end)},
    decode=_line_decode,
    summarize=_line_summary,
))
SURFACE = register_type(ValueType("Surface", (Surface,), "A surface, parameterised on [0, 1]².",
                                  summarize=_surface_summary))
MESH = register_type(ValueType("Mesh", (trimesh.Trimesh,), "A triangle mesh.", summarize=_mesh_summary))

register_cast(SURFACE, MESH, lambda surface: surface.to_mesh())


def point(array: Any) -> Point:
    """A kernel ``(3,)`` array as an engine :class:`Point`."""
    x, y, z = _xyz(array)
    return Point(x, y, z)


def points(array: Any) -> list[Point]:
    """An ``(n, 3)`` array as a list of :class:`Point` (for node outputs)."""
    return [Point(x, y, z) for x, y, z in np.asarray(array, dtype=float).tolist()]
