"""Turn node output values into pyvista datasets, whatever geometry types appear.

What a value draws comes from the preview protocol (:func:`torsal.nodes.common.preview.preview_of`):
plain arrays of points, polylines, rulings, vectors and meshes. The viewport never looks
at a value's class or attributes, so a kernel type added later draws by implementing the
protocol (or having an adapter registered), without changes here. A mesh with scalars
(``mesh.metadata["scalars"]``) or vertex colours is drawn coloured, with a colour bar.

Each node's values are merged into one piece per kind so a node costs a few actors.
Pieces are plain numpy arrays, made on the solver's thread; :func:`dataset` makes the
VTK objects, on the GUI thread. A slider drag prepares the same node's pieces many times
a second with only the points moving, so what does not move is made once: a run of
lines is drawn in one pass (:func:`torsal.nodes.common.preview.preview_of_many`), and the cells
of merged grids and chains are kept by their shapes (the same read-only array each
time, which :func:`same_topology` recognises at once).
"""

from __future__ import annotations

import functools
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pyvista as pv
from vtkmodules.util.numpy_support import vtk_to_numpy

from torsal.nodes.common.preview import (
    PreviewGeometry,
    costly,
    draws_many,
    mesh_scalars,
    preview_of,
    preview_of_many,
)

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
    """A node's geometry sorted by kind, before merging. Chains (``polylines``,
    ``rulings``) are ``(n, 3)`` arrays, or ``(k, n, 3)`` blocks of k chains of n points."""

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
    run: list[Any] = []  # consecutive values of one class drawn together (lines)
    for value in values:
        kind = type(value)
        if kind in PLAIN_TYPES or isinstance(value, bool | int | float | str):
            continue  # not geometry (a node's angles, flags, kinds): nothing to draw or remember
        if run and kind is not type(run[0]):
            _add_run(found, run, memo)
            run = []
        if draws_many(kind):
            run.append(value)
        else:
            _add_value(found, value, memo)
    if run:
        _add_run(found, run, memo)
    return found


#: Classes of values that are never geometry (nothing to draw), found by one set lookup.
PLAIN_TYPES = frozenset({type(None), bool, int, float, str, np.float64, np.int64, np.bool_})


def _add_run(found: Collected, run: list[Any], memo: Memo | None) -> None:
    """Values of one class drawn in one pass; one by one if the pass fails (so that the
    problem names the value)."""
    try:
        geometry = preview_of_many(run)
    except Exception:
        for value in run:
            _add_value(found, value, memo)
        return
    _add_geometry(found, geometry)


def _add_value(found: Collected, value: Any, memo: Memo | None) -> None:
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


def _chains(chains: Any, size: int | None) -> list[np.ndarray]:
    """A geometry's ``polylines`` or ``rulings`` as arrays: one ``(k, n, 3)`` block for an
    array of chains, else one ``(n, 3)`` array per chain (``size`` points each if given)."""
    if isinstance(chains, np.ndarray) and chains.ndim == 3 and chains.shape[2] == 3:
        if size is not None and chains.shape[1] != size:
            raise ValueError(f"cannot reshape chains of {chains.shape[1]} points into ({size}, 3)")
        return [np.asarray(chains, dtype=float)]
    return [np.asarray(c, dtype=float).reshape(-1 if size is None else size, 3) for c in chains]


def _add_geometry(found: Collected, geometry: PreviewGeometry) -> None:
    if len(geometry.points):
        found.points.extend(np.asarray(p, dtype=float).reshape(-1, 3) for p in geometry.points)
    if len(geometry.polylines):
        found.polylines.extend(_chains(geometry.polylines, None))
    if len(geometry.rulings):
        found.rulings.extend(_chains(geometry.rulings, 2))
    if len(geometry.vectors):
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
    """Points and VTK line cells for several polylines: ``(n, 3)`` chains, or ``(k, n, 3)``
    blocks of k chains of n points. The cells are kept by the chains' lengths (read-only)."""
    shapes: list[list[int]] = []  # [chains, points each], runs of one length merged
    for chain in chains:
        count, length = (1, len(chain)) if chain.ndim == 2 else chain.shape[:2]
        if shapes and shapes[-1][1] == length:
            shapes[-1][0] += count
        else:
            shapes.append([count, length])
    points = np.concatenate([c if c.ndim == 2 else c.reshape(-1, 3) for c in chains])
    return points, _cells_for(tuple((count, length) for count, length in shapes))


@functools.lru_cache(maxsize=64)
def _cells_for(shapes: tuple[tuple[int, int], ...]) -> np.ndarray:
    """VTK line cells for blocks of ``k`` chains of ``n`` points, ``(k, n)`` each."""
    counts, lengths = np.array(shapes, dtype=np.int64).reshape(-1, 2).T
    lengths = np.repeat(lengths, counts)
    # each chain's cell is its count then its point indices: the indices run on from one
    # chain to the next, and the counts sit just before each chain's first index
    heads = np.cumsum(lengths + 1) - (lengths + 1)
    cells = np.empty(int(lengths.sum()) + len(lengths), dtype=np.int64)
    cells[heads] = lengths
    body = np.ones(len(cells), dtype=bool)
    body[heads] = False
    cells[body] = np.arange(len(cells) - len(lengths), dtype=np.int64)
    cells.flags.writeable = False
    return cells


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
        out.append(
            Piece("surfaces", np.concatenate(vertices), faces=_merged_faces(vertices, faces),
                  normals=np.concatenate(normals))
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


def _merged_faces(vertices: tuple[np.ndarray, ...], faces: tuple[np.ndarray, ...]) -> np.ndarray:
    """The triangles of meshes put one after the other (each mesh's indices moved on by
    the vertices before it). Meshes that all share one read-only triangle array (grids of
    one size) get the same read-only merged array for as long as they come."""
    template, count = faces[0], len(vertices[0])
    if not template.flags.writeable and all(
        f is template and len(v) == count for f, v in zip(faces, vertices, strict=True)
    ):
        key = (id(template), count, len(faces))
        kept = _MERGED.get(key)
        if kept is None or kept[0] is not template:
            if len(_MERGED) >= 64:
                _MERGED.clear()
            offsets = count * np.arange(len(faces), dtype=np.int64)
            merged = (template[None] + offsets[:, None, None]).reshape(-1, 3)
            merged.flags.writeable = False
            kept = _MERGED[key] = (template, merged)
        return kept[1]
    offsets = np.cumsum([0] + [len(v) for v in vertices[:-1]])
    return np.concatenate([f + o for f, o in zip(faces, offsets, strict=True)])


#: Merged triangles of grids, by (their triangles' identity, vertices per grid, grids).
_MERGED: dict[tuple[int, int, int], tuple[np.ndarray, np.ndarray]] = {}


def face_cells(faces: np.ndarray) -> np.ndarray:
    """VTK's flat cell array ``[3, a, b, c, 3, …]`` for triangles."""
    return np.hstack([np.full((len(faces), 1), 3, dtype=np.int64), faces]).ravel()


def dataset(piece: Piece) -> pv.PolyData:
    """The pyvista dataset of a piece. GUI thread only: VTK objects made on the solver's
    thread can deadlock against a render (VTK's locks and the GIL taken in opposite order).
    Its points and normals are its own copies (:func:`move_points` writes into them)."""
    points = np.array(piece.points, dtype=float)
    lines = None if piece.lines is None else np.array(piece.lines, dtype=np.int64)  # (cells may be shared)
    if piece.faces is not None:
        poly = pv.PolyData(points, face_cells(piece.faces), lines=lines)
        if piece.normals is not None:
            poly.point_data.active_normals = np.array(piece.normals, dtype=float)
    elif lines is not None:
        poly = pv.PolyData(points, lines=lines)
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
        if mine is theirs:  # (cells kept by their shapes: the same array again)
            continue
        if mine is None or theirs is None or not np.array_equal(mine, theirs):
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


def reshape(poly: pv.PolyData, piece: Piece) -> None:
    """Give ``poly`` the points and cells of ``piece`` (of its kind, with other cells): the
    dataset an actor draws stays that actor's, only its arrays are replaced (a drag that
    adds rulings to a strip makes no new actor)."""
    poly.shallow_copy(dataset(piece))


def _overwrite(array: Any, values: np.ndarray) -> bool:
    """Copy ``values`` into the VTK ``array`` of the same shape; False if the shapes differ."""
    target = vtk_to_numpy(array)
    values = np.asarray(values)
    if target.shape != values.shape:
        return False
    target[...] = values
    array.Modified()
    return True
