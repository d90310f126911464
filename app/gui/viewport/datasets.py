"""Turn node output values into pyvista datasets, whatever geometry types appear.

What a value draws comes from the preview protocol (:func:`nodes.common.preview.preview_of`):
plain arrays of points, polylines, rulings, vectors and meshes. The viewport never looks
at a value's class or attributes, so a kernel type added later draws by implementing the
protocol (or having an adapter registered), without changes here. A mesh with scalars
(``mesh.metadata["scalars"]``) or vertex colours is drawn coloured, with a colour bar.

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
from vtkmodules.util.numpy_support import vtk_to_numpy

from nodes.common.preview import PreviewGeometry, costly, mesh_scalars, preview_of

__all__ = ["mesh_scalars"]  # also read by the GUI tests: the colours a mesh carries

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
Memo = dict[int, tuple[Any, PreviewGeometry | None]]


def collect(values: Iterable[Any], memo: Memo | None = None) -> Collected:
    """Sort ``values`` into drawable geometry; values that are not geometry are skipped.

    ``memo`` (shared by the nodes of one pass, while their values are alive) reuses the
    tessellation of a curve or surface met before.
    """
    found = Collected()
    for value in values:
        if value is None or isinstance(value, bool | int | float | str):
            continue  # not geometry (a node's angles, flags, kinds): nothing to draw or remember
        try:
            if memo is not None and costly(value):
                entry = memo.get(id(value))
                if entry is None or entry[0] is not value:
                    entry = memo[id(value)] = (value, preview_of(value))
                geometry = entry[1]
            else:
                geometry = preview_of(value)
            if geometry is not None:
                _add_geometry(found, geometry)
        except Exception as exc:
            found.problems.append(f"{type(value).__name__}: {exc}")
    return found


def _add_geometry(found: Collected, geometry: PreviewGeometry) -> None:
    if geometry.points:
        found.points.extend(np.asarray(p, dtype=float).reshape(-1, 3) for p in geometry.points)
    if geometry.polylines:
        found.polylines.extend(np.asarray(c, dtype=float).reshape(-1, 3) for c in geometry.polylines)
    if geometry.rulings:
        found.rulings.extend(np.asarray(r, dtype=float).reshape(2, 3) for r in geometry.rulings)
    if geometry.vectors:
        found.vectors.extend(np.asarray(v, dtype=float).reshape(3) for v in geometry.vectors)
    for mesh in geometry.meshes:
        vertices = np.asarray(mesh.vertices, dtype=float)
        faces = np.asarray(mesh.faces, dtype=np.int64)
        if len(vertices) == 0 or len(faces) == 0:
            continue
        if mesh.scalars is None:
            found.meshes.append((vertices, faces, _normals(vertices, faces, mesh.normals)))
        else:
            found.coloured.append(Piece(
                "scalars", vertices, faces=faces, scalars=np.asarray(mesh.scalars),
                scalar_name=mesh.scalar_name, rgb=mesh.rgb, clim=mesh.clim, cmap=mesh.cmap,
            ))


def _normals(vertices: np.ndarray, faces: np.ndarray, normals: np.ndarray | None) -> np.ndarray:
    """The mesh's unit vertex normals, or the area-weighted average of its face normals."""
    if normals is not None:
        return np.asarray(normals, dtype=float)
    corners = vertices[faces]
    face_normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    summed = np.zeros_like(vertices)
    for k in range(3):
        np.add.at(summed, faces[:, k], face_normals)
    length = np.linalg.norm(summed, axis=1, keepdims=True)
    return np.divide(summed, length, out=np.zeros_like(summed), where=length > 0)


def _line_cells(chains: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Points and VTK line cells for several polylines."""
    points = np.concatenate(chains)
    lengths = np.fromiter((len(c) for c in chains), dtype=np.int64, count=len(chains))
    # each chain's cell is its count then its point indices: the indices run on from one
    # chain to the next, and the counts sit just before each chain's first index
    heads = np.cumsum(lengths + 1) - (lengths + 1)
    cells = np.empty(len(points) + len(chains), dtype=np.int64)
    cells[heads] = lengths
    body = np.ones(len(cells), dtype=bool)
    body[heads] = False
    cells[body] = np.arange(len(points), dtype=np.int64)
    return points, cells


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
    thread can deadlock against a render (VTK's locks and the GIL taken in opposite order).
    Its points and normals are its own copies (:func:`move_points` writes into them)."""
    points = np.array(piece.points, dtype=float)
    if piece.faces is not None:
        poly = pv.PolyData(points, face_cells(piece.faces), lines=piece.lines)
        if piece.normals is not None:
            poly.point_data.active_normals = np.array(piece.normals, dtype=float)
    elif piece.lines is not None:
        poly = pv.PolyData(points, lines=piece.lines)
    else:
        poly = pv.PolyData(points)
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
    """Give ``poly`` (made from a piece of the same topology) the points of ``piece``:
    copied into its point (and normal) arrays in place, which makes no new VTK objects
    (a slider drag moves every strip's points on every solve)."""
    points = poly.GetPoints()
    if points is None or not _overwrite(points.GetData(), piece.points):
        poly.points = np.asarray(piece.points, dtype=float)
    else:
        points.Modified()
    if piece.normals is not None:
        normals = poly.GetPointData().GetNormals()
        if normals is None or not _overwrite(normals, piece.normals):
            poly.point_data.active_normals = piece.normals
    poly.Modified()


def _overwrite(array: Any, values: np.ndarray) -> bool:
    """Copy ``values`` into the VTK ``array`` of the same shape; False if the shapes differ."""
    target = vtk_to_numpy(array)
    values = np.asarray(values)
    if target.shape != values.shape:
        return False
    target[...] = values
    array.Modified()
    return True
