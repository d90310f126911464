"""Input checks the surface nodes share, and the MeshSurface value type.

Every surface in Torsal is parameterised on (u, v) in [0, 1]², so a place on a
surface is given as a point whose x is u and y is v (its z is ignored), as in
Grasshopper. Each check raises :class:`~engine.node.NodeWarning` with one sentence
naming the input, so that call is skipped and the other items still solve.

``MESH_SURFACE`` is the wire type of the kernel's mesh-backed
:class:`~nodes.geometry.mesh_surface.MeshSurface` (imported geometry): it casts to
and from Mesh.
"""

from __future__ import annotations

from typing import Any

from engine.node import NodeWarning
from engine.types import ValueType, register_cast, register_type
from nodes.curves.convert import given, number, xyz
from nodes.geometry.mesh_surface import MeshSurface
from nodes.geometry.surface_base import Surface
from nodes.types import MESH

#: How far outside [0, 1] a (u, v) may stray (rounding) before it is refused; it is clamped.
UV_SLACK = 1e-12


def _mesh_surface_summary(surface: MeshSurface) -> dict[str, Any]:
    return {
        "type": "MeshSurface",
        "vertices": len(surface.mesh.vertices),
        "faces": len(surface.mesh.faces),
        "area": surface.area(),
    }


MESH_SURFACE = register_type(ValueType(
    "MeshSurface", (MeshSurface,),
    "A triangle mesh used as a surface: area, closest point and discrete curvature, no (u, v).",
    summarize=_mesh_surface_summary,
))
register_cast(MESH_SURFACE, MESH, lambda surface: surface.to_mesh())
register_cast(MESH, MESH_SURFACE, MeshSurface)


def surface(value: Any, name: str = "Surface") -> Surface:
    """A parameterised surface; the port's type has already refused anything else."""
    return given(name, value)


def uv(value: Any, name: str = "UV") -> tuple[float, float]:
    """The (u, v) a point stands for: its x and y, each from 0 to 1."""
    u, v, _ = xyz(name, value)
    if not (-UV_SLACK <= u <= 1 + UV_SLACK and -UV_SLACK <= v <= 1 + UV_SLACK):
        raise NodeWarning(
            f"{name} must have x (u) and y (v) from 0 to 1, not ({u:g}, {v:g}): every surface "
            "is parameterised on [0, 1]²"
        )
    return min(max(u, 0.0), 1.0), min(max(v, 0.0), 1.0)


def positive(name: str, value: Any) -> float:
    """A length that must be positive (a radius)."""
    length = number(name, value)
    if length <= 0:
        raise NodeWarning(f"{name} must be a positive length, not {length:g}")
    return length


def interval(name: str, value: Any, variable: str) -> tuple[float, float]:
    """A domain's (start, end): finite and not empty; start > end is allowed (reversed)."""
    if value is None:
        raise NodeWarning(f"{name} is empty (null)")
    a, b = number(f"{name} start", value.min), number(f"{name} end", value.max)
    if a == b:
        raise NodeWarning(f"The {name} is empty ({a:g} to {b:g}): {variable} must run over an interval")
    return a, b

