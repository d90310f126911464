"""Turn node output values into pyvista datasets, whatever geometry types appear.

Values are recognised by type where the engine knows them (Point, Vector) and by what
they can do otherwise, so kernel types added later draw without changes here:

- ``trimesh.Trimesh`` → a shaded mesh; with per-vertex or per-face scalars in
  ``mesh.metadata["scalars"]`` (name in ``"scalar_name"``, optional ``"clim"`` and
  ``"cmap"``) or explicit vertex colours it is drawn coloured, with a colour bar;
- anything with ``to_mesh(nu, nv)`` and ``derivatives`` (a surface) → its mesh, plus
  its rulings as lines when the surface is ruled (developables);
- anything with ``to_mesh()`` returning a trimesh (a mesh-backed surface) → that mesh;
- a Line (``start`` and ``end``) → one segment;
- anything with ``point_at`` (a curve) → a polyline through evenly spaced points;
- Point → a dot, Vector → an arrow from the origin.

Each node's values are merged into one dataset per kind so a node costs a few actors.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pyvista as pv

from engine.values import Plane, Point, Vector

SURFACE_GRID = 33
RULINGS_SHOWN = 17
CURVE_SAMPLES = 97

KINDS = ("surfaces", "rulings", "curves", "points", "vectors", "scalars")


@dataclass
class Piece:
    """One dataset to draw for a node: its kind and, for coloured meshes, its scalars."""

    kind: str
    dataset: pv.DataSet
    scalars: str | None = None
    rgb: bool = False
    clim: tuple[float, float] | None = None
    cmap: str | None = None


@dataclass
class Collected:
    """A node's geometry sorted by kind, before merging."""

    points: list[np.ndarray] = field(default_factory=list)
    polylines: list[np.ndarray] = field(default_factory=list)
    rulings: list[np.ndarray] = field(default_factory=list)
    vectors: list[np.ndarray] = field(default_factory=list)
    meshes: list[tuple[np.ndarray, np.ndarray]] = field(default_factory=list)
    coloured: list[Piece] = field(default_factory=list)
    problems: list[str] = field(default_factory=list)


def collect(values: Iterable[Any]) -> Collected:
    """Sort ``values`` into drawable geometry; values that are not geometry are skipped."""
    found = Collected()
    for value in values:
        try:
            _add(found, value)
        except Exception as exc:
            found.problems.append(f"{type(value).__name__}: {exc}")
    return found


def _add(found: Collected, value: Any) -> None:
    if value is None or isinstance(value, bool | int | float | str):
        return
    if isinstance(value, Vector):
        found.vectors.append(np.asarray(value, dtype=float))
    elif isinstance(value, Point):
        found.points.append(np.asarray(value, dtype=float))
    elif isinstance(value, Plane):
        found.points.append(np.asarray(value.origin, dtype=float))
    elif _is_trimesh(value):
        _add_trimesh(found, value)
    elif hasattr(value, "to_mesh") and hasattr(value, "derivatives"):
        direction = ruling_direction(value)
        # along a straight ruling two rows of vertices are exact: 16 times fewer triangles
        nu, nv = {"v": (SURFACE_GRID, 2), "u": (2, SURFACE_GRID)}.get(direction, (SURFACE_GRID, SURFACE_GRID))
        _add_trimesh(found, value.to_mesh(nu, nv))
        rulings = surface_rulings(value) if direction else None
        if rulings is not None:
            found.rulings.extend(rulings)
    elif hasattr(value, "to_mesh"):
        _add_trimesh(found, value.to_mesh())
    elif hasattr(value, "start") and hasattr(value, "end") and type(value).__name__ == "Line":
        found.polylines.append(np.array([value.start, value.end], dtype=float).reshape(2, 3))
    elif hasattr(value, "point_at"):
        found.polylines.append(curve_points(value))
    elif isinstance(value, np.ndarray) and value.shape[-1:] == (3,):
        found.points.extend(np.asarray(value, dtype=float).reshape(-1, 3))


def _is_trimesh(value: Any) -> bool:
    return type(value).__name__ == "Trimesh" and hasattr(value, "faces") and hasattr(value, "vertices")


def _add_trimesh(found: Collected, mesh: Any) -> None:
    vertices = np.asarray(mesh.vertices, dtype=float)
    faces = np.asarray(mesh.faces, dtype=np.int64)
    if len(vertices) == 0 or len(faces) == 0:
        return
    coloured = mesh_scalars(mesh)
    if coloured is None:
        found.meshes.append((vertices, faces))
        return
    name, data, rgb, clim, cmap = coloured
    poly = pv.PolyData(vertices, _vtk_faces(faces))
    if len(data) == len(vertices):
        poly.point_data[name] = data
    else:
        poly.cell_data[name] = data
    found.coloured.append(Piece("scalars", poly, name, rgb, clim, cmap))


def mesh_scalars(mesh: Any) -> tuple[str, np.ndarray, bool, tuple[float, float] | None, str | None] | None:
    """``(name, values, rgb, clim, cmap)`` when a mesh carries colours, else None."""
    metadata = getattr(mesh, "metadata", None) or {}
    n_vertices, n_faces = len(mesh.vertices), len(mesh.faces)
    scalars = metadata.get("scalars")
    if scalars is not None:
        data = np.asarray(scalars, dtype=float)
        if data.ndim == 1 and len(data) in (n_vertices, n_faces):
            name = str(metadata.get("scalar_name") or metadata.get("scalars_name") or "value")
            clim = metadata.get("clim") or metadata.get("range")
            clim = (float(clim[0]), float(clim[1])) if clim is not None and len(clim) == 2 else None
            return name, data, False, clim, metadata.get("cmap")
    visual = getattr(mesh, "visual", None)
    if visual is not None and getattr(visual, "kind", None) in ("vertex", "face"):
        colours = np.asarray(
            visual.vertex_colors if visual.kind == "vertex" else visual.face_colors, dtype=np.uint8
        )[:, :3]
        return "colour", colours, True, None, None
    return None


def ruling_direction(surface: Any) -> str | None:
    """``"v"`` or ``"u"``, the parameter along which the surface is straight, or None."""
    if getattr(surface, "ruling_lines", None) is not None:
        return "v"  # a loft of given rulings (RuledSurface.from_rulings)
    try:
        direction = getattr(surface, "ruling_direction", None)
        direction = direction() if callable(direction) else direction
    except (ValueError, ArithmeticError, TypeError):
        return None
    return direction if direction in ("u", "v") else None


def surface_rulings(surface: Any) -> list[np.ndarray] | None:
    """The surface's rulings as ``(2, 3)`` segments when it is ruled, else None."""
    lines = getattr(surface, "ruling_lines", None)
    if lines is not None:
        lines = np.asarray(lines, dtype=float)
        if lines.ndim == 3 and lines.shape[1:] == (2, 3):
            step = max(1, len(lines) // RULINGS_SHOWN)
            return list(lines[::step])
    try:
        return list(np.asarray(surface.rulings(RULINGS_SHOWN), dtype=float))
    except (ValueError, AttributeError, TypeError):
        return None


def curve_points(curve: Any) -> np.ndarray:
    """Points along a curve for drawing: a polyline's own vertices, else
    :data:`CURVE_SAMPLES` evenly spaced parameters in one vectorised evaluation (an
    adaptive tessellation looks no better at preview size and costs 30 times more)."""
    vertices = getattr(curve, "points", None)
    if type(curve).__name__ == "Polyline" and vertices is not None:
        return np.asarray(vertices, dtype=float).reshape(-1, 3)
    return np.asarray(curve.point_at(np.linspace(0.0, 1.0, CURVE_SAMPLES)), dtype=float).reshape(-1, 3)


def _vtk_faces(faces: np.ndarray) -> np.ndarray:
    return np.hstack([np.full((len(faces), 1), 3, dtype=np.int64), faces]).ravel()


def _polylines(chains: list[np.ndarray]) -> pv.PolyData:
    points = np.concatenate(chains)
    cells, start = [], 0
    for chain in chains:
        cells.append(np.concatenate([[len(chain)], np.arange(start, start + len(chain))]))
        start += len(chain)
    return pv.PolyData(points, lines=np.concatenate(cells).astype(np.int64))


def pieces(found: Collected) -> list[Piece]:
    """Merge collected geometry into one dataset per kind (coloured meshes stay apart)."""
    out: list[Piece] = []
    if found.meshes:
        offset, verts, faces = 0, [], []
        for v, f in found.meshes:
            verts.append(v)
            faces.append(f + offset)
            offset += len(v)
        out.append(Piece("surfaces", pv.PolyData(np.concatenate(verts), _vtk_faces(np.concatenate(faces)))))
    if found.rulings:
        out.append(Piece("rulings", _polylines(found.rulings)))
    if found.polylines:
        out.append(Piece("curves", _polylines(found.polylines)))
    if found.points:
        out.append(Piece("points", pv.PolyData(np.vstack(found.points))))
    if found.vectors:
        vectors = np.vstack(found.vectors)
        lengths = np.linalg.norm(vectors, axis=1)
        keep = lengths > 0
        if keep.any():
            origins = pv.PolyData(np.zeros((int(keep.sum()), 3)))
            origins["vectors"] = vectors[keep]
            origins["length"] = lengths[keep]
            arrows = origins.glyph(orient="vectors", scale="length", factor=1.0, geom=pv.Arrow())
            out.append(Piece("vectors", arrows))
    out.extend(found.coloured)
    return out
