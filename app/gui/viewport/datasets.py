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

Each node's values are merged into one piece per kind so a node costs a few actors.
Pieces are plain numpy arrays, made on the solver's thread; :func:`dataset` makes the
VTK objects, on the GUI thread.
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


@dataclass
class Piece:
    """One thing to draw for a node, as plain arrays (made on any thread).

    ``points`` are ``(n, 3)``; ``faces`` ``(m, 3)`` triangles, or ``lines`` VTK line cells
    (``[count, i0, i1, …]`` repeated); for ``vectors`` the points are the vectors
    themselves (drawn as arrows from the origin). Coloured meshes carry ``scalars``.
    :func:`dataset` turns a piece into a pyvista dataset — on the GUI thread only.
    """

    kind: str
    points: np.ndarray
    faces: np.ndarray | None = None
    lines: np.ndarray | None = None
    scalars: np.ndarray | None = None
    scalar_name: str | None = None
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
    found.coloured.append(
        Piece("scalars", vertices, faces=faces, scalars=data, scalar_name=name, rgb=rgb, clim=clim, cmap=cmap)
    )


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


def _line_cells(chains: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Points and VTK line cells for several polylines."""
    points = np.concatenate(chains)
    lengths = np.array([len(c) for c in chains])
    starts = np.concatenate([[0], np.cumsum(lengths)[:-1]])
    cells = np.concatenate(
        [np.concatenate([[n], np.arange(s, s + n)]) for s, n in zip(starts, lengths, strict=True)]
    )
    return points, cells.astype(np.int64)


def pieces(found: Collected) -> list[Piece]:
    """Merge collected geometry into one piece per kind (coloured meshes stay apart)."""
    out: list[Piece] = []
    if found.meshes:
        offsets = np.cumsum([0] + [len(v) for v, _ in found.meshes[:-1]])
        faces = np.concatenate([f + o for (_, f), o in zip(found.meshes, offsets, strict=True)])
        out.append(Piece("surfaces", np.concatenate([v for v, _ in found.meshes]), faces=faces))
    for kind, chains in (("rulings", found.rulings), ("curves", found.polylines)):
        if chains:
            points, cells = _line_cells(chains)
            out.append(Piece(kind, points, lines=cells))
    if found.points:
        out.append(Piece("points", np.vstack(found.points)))
    if found.vectors:
        vectors = np.vstack(found.vectors)
        vectors = vectors[np.linalg.norm(vectors, axis=1) > 0]
        if len(vectors):
            out.append(Piece("vectors", vectors))
    out.extend(found.coloured)
    return out


def dataset(piece: Piece) -> pv.PolyData:
    """The pyvista dataset of a piece. GUI thread only: VTK objects made on the solver's
    thread can deadlock against a render (VTK's locks and the GIL taken in opposite order)."""
    if piece.kind == "vectors":
        origins = pv.PolyData(np.zeros_like(piece.points))
        origins["vectors"] = piece.points
        origins["length"] = np.linalg.norm(piece.points, axis=1)
        return origins.glyph(orient="vectors", scale="length", factor=1.0, geom=pv.Arrow())
    if piece.faces is not None:
        cells = np.hstack([np.full((len(piece.faces), 1), 3, dtype=np.int64), piece.faces]).ravel()
        poly = pv.PolyData(piece.points, cells)
    elif piece.lines is not None:
        poly = pv.PolyData(piece.points, lines=piece.lines)
    else:
        poly = pv.PolyData(piece.points)
    if piece.scalars is not None:
        target = poly.point_data if len(piece.scalars) == poly.n_points else poly.cell_data
        target[piece.scalar_name or "value"] = piece.scalars
    return poly
