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

    ``points`` are ``(n, 3)``; ``faces`` ``(m, 3)`` triangles with unit vertex ``normals``
    (so shading is smooth without a normals filter), or ``lines`` VTK line cells
    (``[count, i0, i1, …]`` repeated); for ``vectors`` the points are the vectors
    themselves (drawn as arrows from the origin). Coloured meshes carry ``scalars``.
    :func:`dataset` turns a piece into a pyvista dataset — on the GUI thread only.
    """

    kind: str
    points: np.ndarray
    faces: np.ndarray | None = None
    lines: np.ndarray | None = None
    normals: np.ndarray | None = None
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
    meshes: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = field(default_factory=list)
    coloured: list[Piece] = field(default_factory=list)
    problems: list[str] = field(default_factory=list)


#: Tessellations already made in one preparing pass, by value identity: a curve that
#: several nodes pass on (List Item, Move by zero …) is sampled once.
Memo = dict[int, tuple[Any, Collected]]


def collect(values: Iterable[Any], memo: Memo | None = None) -> Collected:
    """Sort ``values`` into drawable geometry; values that are not geometry are skipped.

    ``memo`` (shared by the nodes of one pass, while their values are alive) reuses the
    tessellation of a curve or surface met before.
    """
    found = Collected()
    for value in values:
        try:
            if memo is not None and _tessellated(value):
                key = id(value)
                if key not in memo or memo[key][0] is not value:
                    memo[key] = (value, collect([value]))
                _merge(found, memo[key][1])
            else:
                _add(found, value)
        except Exception as exc:
            found.problems.append(f"{type(value).__name__}: {exc}")
    return found


def _tessellated(value: Any) -> bool:
    """Values whose drawing costs an evaluation (curves, surfaces), worth remembering."""
    return hasattr(value, "point_at") or hasattr(value, "to_mesh")


def _merge(found: Collected, part: Collected) -> None:
    for name in ("points", "polylines", "rulings", "vectors", "meshes", "coloured", "problems"):
        getattr(found, name).extend(getattr(part, name))


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
        # the kernel's meshes carry exact normals; trimesh averages face normals otherwise
        normals = np.asarray(mesh.vertex_normals, dtype=float)
        found.meshes.append((vertices, faces, normals))
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


ARROW_SIDES = 8
ARROW_HEAD = 0.25  # head length, as a fraction of the arrow's length
ARROW_RADIUS = 0.08  # head radius, as a fraction of the arrow's length


def arrows(vectors: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Arrows from the origin to each of ``vectors`` ``(n, 3)``: a line for the shaft and
    a cone of :data:`ARROW_SIDES` triangles (capped) for the head.

    Returns points, triangles and VTK line cells. Per arrow the points are the origin,
    the centre of the head's base, the tip and the base's rim.
    """
    n = len(vectors)
    length = np.linalg.norm(vectors, axis=1, keepdims=True)
    axis = vectors / length
    # any unit vector across the axis: x, unless the axis is nearly along x
    helper = np.where(np.abs(axis[:, :1]) < 0.9, [[1.0, 0.0, 0.0]], [[0.0, 1.0, 0.0]])
    across = np.cross(axis, helper)
    across /= np.linalg.norm(across, axis=1, keepdims=True)
    other = np.cross(axis, across)
    base = vectors - ARROW_HEAD * length * axis
    angle = np.linspace(0.0, 2.0 * np.pi, ARROW_SIDES, endpoint=False)
    rim = base[:, None, :] + ARROW_RADIUS * length[:, None, :] * (
        np.cos(angle)[None, :, None] * across[:, None, :] + np.sin(angle)[None, :, None] * other[:, None, :]
    )
    stride = 3 + ARROW_SIDES
    origin = np.zeros((n, 1, 3))
    points = np.concatenate([origin, base[:, None], vectors[:, None], rim], axis=1).reshape(-1, 3)
    first = stride * np.arange(n)[:, None]
    side = 3 + np.arange(ARROW_SIDES)[None, :]
    following = 3 + (np.arange(ARROW_SIDES)[None, :] + 1) % ARROW_SIDES
    cone = np.stack([first + side, first + following, first + 2 + 0 * side], axis=-1)
    cap = np.stack([first + 1 + 0 * side, first + following, first + side], axis=-1)
    faces = np.concatenate([cone, cap], axis=1).reshape(-1, 3)
    lines = np.column_stack([np.full(n, 2), stride * np.arange(n), stride * np.arange(n) + 1]).ravel()
    return points, faces.astype(np.int64), lines.astype(np.int64)


def pieces(found: Collected) -> list[Piece]:
    """Merge collected geometry into one piece per kind (coloured meshes stay apart)."""
    out: list[Piece] = []
    if found.meshes:
        vertices, faces, normals = zip(*found.meshes, strict=True)
        offsets = np.cumsum([0] + [len(v) for v in vertices[:-1]])
        faces = np.concatenate([f + o for f, o in zip(faces, offsets, strict=True)])
        out.append(
            Piece("surfaces", np.concatenate(vertices), faces=faces, normals=np.concatenate(normals))
        )
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
            points, faces, lines = arrows(vectors)
            out.append(Piece("vectors", points, faces=faces, lines=lines))
    out.extend(found.coloured)
    return out


def face_cells(faces: np.ndarray) -> np.ndarray:
    """VTK's flat cell array ``[3, a, b, c, 3, …]`` for triangles."""
    return np.hstack([np.full((len(faces), 1), 3, dtype=np.int64), faces]).ravel()


def dataset(piece: Piece) -> pv.PolyData:
    """The pyvista dataset of a piece. GUI thread only: VTK objects made on the solver's
    thread can deadlock against a render (VTK's locks and the GIL taken in opposite order)."""
    if piece.faces is not None:
        poly = pv.PolyData(piece.points, face_cells(piece.faces), lines=piece.lines)
        if piece.normals is not None:
            poly.point_data.active_normals = piece.normals
    elif piece.lines is not None:
        poly = pv.PolyData(piece.points, lines=piece.lines)
    else:
        poly = pv.PolyData(piece.points)
    if piece.scalars is not None:
        target = poly.point_data if len(piece.scalars) == poly.n_points else poly.cell_data
        target[piece.scalar_name or "value"] = piece.scalars
    return poly


def same_topology(piece: Piece, other: Piece) -> bool:
    """Whether ``other`` has ``piece``'s kind, point count and cells (only points moved)."""
    if piece.kind != other.kind or len(piece.points) != len(other.points):
        return False
    for mine, theirs in ((piece.faces, other.faces), (piece.lines, other.lines)):
        if (mine is None) != (theirs is None) or (mine is not None and not np.array_equal(mine, theirs)):
            return False
    return (piece.normals is None) == (other.normals is None)


def move_points(poly: pv.PolyData, piece: Piece) -> None:
    """Give ``poly`` (made from a piece of the same topology) the points of ``piece``."""
    poly.points = np.asarray(piece.points, dtype=float)
    if piece.normals is not None:
        poly.point_data.active_normals = piece.normals
