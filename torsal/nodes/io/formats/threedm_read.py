"""Reading ``.3dm`` files: rhino3dm parses in a fenced child, Torsal builds kernel geometry.

:func:`read_3dm` never lets rhino3dm touch the file in this process: the child of
:mod:`.threedm_child` parses it (under a memory and a time limit, :mod:`.fenced`) and
sends back plain arrays, from which the kernel's curves, surfaces and meshes are built and
checked here. A crash of the child becomes a :class:`FileFailure` naming the file ("could
not read FILE: the reader crashed (SIGSEGV)").

What comes in: lines and polylines as such, every other curve as a NURBS curve; surfaces,
extrusions and brep faces as NURBS surfaces — a brep face whose trim loops cut into its
surface as a :class:`~torsal.nodes.geometry.trimmed_surface.TrimmedSurface` (its loops
pulled back from the face's 3D edges onto the surface); meshes as triangles. Lengths are
scaled from the file's units to the model's.
"""

from __future__ import annotations

import fnmatch
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import trimesh

from torsal.nodes.common.files import FileFailure
from torsal.nodes.common.units import unit_name
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curves import Line, NurbsCurve, Polyline
from torsal.nodes.geometry.nurbs_surface import NurbsSurface
from torsal.nodes.geometry.surface_base import Surface
from torsal.nodes.geometry.trimmed_surface import TrimmedSurface

from .fenced import FencedReader, ReaderCrashed, reader

#: The child module that parses .3dm files.
CHILD = "torsal.nodes.io.formats.threedm_child"

#: Torsal's unit names as rhino3dm UnitSystem names, and back.
RHINO_UNITS = {"mm": "Millimeters", "cm": "Centimeters", "m": "Meters", "in": "Inches", "ft": "Feet"}
TORSAL_UNITS = {v: k for k, v in RHINO_UNITS.items()}

#: The largest .3dm file read (bytes): a bigger one is refused before any parsing.
LARGEST_FILE = 512 << 20

#: The time a file may take to read: this many seconds, and a second per SPEED bytes.
SECONDS, SPEED = 20.0, 2 << 20

#: Points along each trim loop edge's span, for pulling it back onto the surface.
TRIM_SAMPLES = 16


@dataclass
class Imported:
    """What :func:`read_3dm` found, in file order, each with its layer path and name."""

    units: str  #: the file's units ("mm" …, "none" for a unitless file)
    scale: float  #: factor applied to the file's lengths
    curves: list[tuple[Curve, str, str]] = field(default_factory=list)
    surfaces: list[tuple[Surface, str, str]] = field(default_factory=list)
    meshes: list[tuple[trimesh.Trimesh, str, str]] = field(default_factory=list)
    skipped: dict[str, int] = field(default_factory=dict)  #: object kinds not imported, counted
    trimmed: int = 0  #: capped extrusions and brep faces whose caps or trims were left out
    trims: int = 0  #: brep faces that came in trimmed (as TrimmedSurface)


def layer_matches(path: str, patterns: Sequence[str]) -> bool:
    """Whether a layer path is picked by any pattern: its full path or its own name, case
    insensitive, ``*`` and ``?`` as wildcards; a parent layer picks its sublayers."""
    if not patterns:
        return True
    full = path.lower()
    name = full.rsplit("::", 1)[-1]
    for pattern in patterns:
        p = pattern.strip().lower()
        if fnmatch.fnmatchcase(full, p) or fnmatch.fnmatchcase(name, p) or full.startswith(p + "::"):
            return True
    return False


def parse(path: Path, units: str = "m", fence: FencedReader | None = None) -> dict[str, Any]:
    """The child's reply for ``path`` (``ok`` true), or a FileFailure naming the file.
    ``fence``: the reader to ask (default: this process's shared one)."""
    from torsal.nodes.io.common import readable

    if path.exists() and not (path.is_file() or path.is_dir()):
        raise FileFailure(f"{path.name} is not a regular file (a device or a pipe?), so not a .3dm")
    readable(path, "Rhino .3dm")
    size = path.stat().st_size
    if size > LARGEST_FILE:
        raise FileFailure(f"{path.name} is {size / 2**20:.0f} MB, more than the {LARGEST_FILE >> 20} MB "
                          "a .3dm may have here")
    try:
        request = {"path": str(path), "units": RHINO_UNITS[unit_name(units)]}
        reply = (fence or reader(CHILD)).request(request, SECONDS + size / SPEED)
    except ReaderCrashed as exc:
        raise FileFailure(f"could not read {path.name}: {exc}") from None
    if not reply.get("ok"):
        raise FileFailure(f"{path.name} is {reply.get('error') or 'unreadable'}")
    return reply


def read_3dm(path: Path, units: str = "m", layers: Sequence[str] = (),
             fence: FencedReader | None = None) -> Imported:
    """Curves, surfaces and meshes of a .3dm file, scaled into ``units``.

    ``layers`` filters by layer (see :func:`layer_matches`); empty means all layers.
    """
    reply = parse(path, units, fence)
    found = str(reply.get("units", ""))
    if found in ("CustomUnits", "Unset"):
        raise FileFailure(
            f"The file's units are {found}, which Torsal cannot convert: "
            "set standard units in Rhino (File ▸ Properties ▸ Units) and save again"
        )
    scale = float(reply.get("scale", 1.0))
    if not (np.isfinite(scale) and scale > 0):
        raise FileFailure(f"{path.name} has units Torsal cannot convert ({found})")
    result = Imported("none" if found == "None" else TORSAL_UNITS.get(found, found), scale)
    for record in reply.get("objects", []):
        if not isinstance(record, dict):
            continue
        layer, name = str(record.get("layer", "")), str(record.get("name", ""))
        if not layer_matches(layer, layers):
            continue
        try:
            _take(result, record, layer, name, scale)
        except (ValueError, TypeError, KeyError, FloatingPointError, IndexError) as exc:
            kind = f"invalid {record.get('kind', 'object')}"
            result.skipped[kind] = result.skipped.get(kind, 0) + 1
            del exc
    return result


def _array(data: Any, ndim: int, last: int | None = None) -> np.ndarray:
    """A plain array from the child, checked: shape, size and finiteness."""
    shape = [int(x) for x in data["shape"]]
    raw = data["data"]
    if len(shape) != ndim or any(x < 0 for x in shape) or (last is not None and shape[-1] != last):
        raise ValueError("an array of the wrong shape")
    if len(raw) != 8 * int(np.prod(shape)):
        raise ValueError("an array of the wrong size")
    values = np.frombuffer(raw, dtype="<f8").reshape(shape).astype(float)
    if not np.isfinite(values).all():
        raise ValueError("a coordinate that is not a finite number")
    return values


def _full(knots: np.ndarray) -> np.ndarray:
    """openNURBS' knots (n + p − 1 of them) as a full vector (its first and last repeated)."""
    return np.concatenate([knots[:1], knots, knots[-1:]])


def kernel_curve(record: dict[str, Any], scale: float = 1.0) -> Curve:
    kind = record["kind"]
    if kind == "line":
        a, b = _array(record["points"], 2, 3) * scale
        return Line(a, b)
    if kind == "polyline":
        return Polyline(_array(record["points"], 2, 3) * scale, closed=bool(record.get("closed")))
    homogeneous = _array(record["points"], 2, 4)
    weights = homogeneous[:, 3]
    if not np.all(weights > 0):
        raise ValueError("a weight that is not positive")
    points = homogeneous[:, :3] / weights[:, None] * scale
    return NurbsCurve(points, int(record["degree"]), _full(_array(record["knots"], 1)),
                      weights if record.get("rational") else None)


def kernel_surface(record: dict[str, Any], scale: float = 1.0) -> NurbsSurface:
    homogeneous = _array(record["points"], 3, 4)
    weights = homogeneous[..., 3]
    if not np.all(weights > 0):
        raise ValueError("a weight that is not positive")
    points = homogeneous[..., :3] / weights[..., None] * scale
    degree_u, degree_v = (int(d) for d in record["degree"])
    knots_u, knots_v = (_full(_array(k, 1)) for k in record["knots"])
    return NurbsSurface(points, degree_u, degree_v, knots_u, knots_v,
                        weights if record.get("rational") else None)


def kernel_mesh(record: dict[str, Any], scale: float = 1.0) -> trimesh.Trimesh:
    vertices = _array(record["points"], 2, 3) * scale
    faces = _array(record["faces"], 2, 4).astype(np.int64)
    if len(faces) and (faces.min() < 0 or faces.max() >= len(vertices)):
        raise ValueError("a face with a vertex the mesh does not have")
    quads = faces[:, 2] != faces[:, 3]
    triangles = np.concatenate([faces[:, :3], faces[quads][:, [0, 2, 3]]])
    if not len(triangles):
        raise ValueError("a mesh without faces")
    return trimesh.Trimesh(vertices, triangles, process=False)


def trimmed_face(surface: NurbsSurface, loops: list[dict[str, Any]], scale: float) -> Surface:
    """The face as a TrimmedSurface when its loops cut into the surface, else the surface."""
    rings: list[tuple[bool, np.ndarray]] = []
    for loop in loops:
        points = []
        for edge in loop["edges"]:
            curve = kernel_curve(edge, scale)
            t = np.linspace(0.0, 1.0, TRIM_SAMPLES * max(1, _spans(curve)) + 1)
            points.append(curve.point_at(t)[:-1])
        if points:
            rings.append((bool(loop["outer"]), np.concatenate(points)))
    if not rings:
        return surface
    size = float(np.ptp(surface.control_points.reshape(-1, 3), axis=0).max()) or 1.0
    uv_rings = []
    for outer, ring in rings:
        found = surface.closest_point(ring)
        if float(found.distances.max()) > 1e-3 * size:  # Rhino keeps edges within its tolerance
            raise ValueError("a trim loop that does not lie on its surface")
        uv_rings.append((outer, found.parameters))
    outers = [uv for outer, uv in uv_rings if outer]
    holes = [uv for outer, uv in uv_rings if not outer]
    if len(outers) != 1:
        raise ValueError("a brep face without exactly one outer loop")
    (outer,) = outers
    on_edge = np.minimum(np.minimum(outer[:, 0], 1 - outer[:, 0]), np.minimum(outer[:, 1], 1 - outer[:, 1]))
    if not holes and float(on_edge.max()) <= 1e-9:  # the loop runs round the surface's own edges
        return surface
    return TrimmedSurface(surface, outer, holes)


def _spans(curve: Curve) -> int:
    knots = getattr(curve, "knots", None)
    return 1 if knots is None else max(1, len(np.unique(np.asarray(knots))) - 1)


def _take(result: Imported, record: dict[str, Any], layer: str, name: str, scale: float) -> None:
    """Convert one record and file it under curves, surfaces or meshes (or skipped)."""
    kind = record.get("kind")
    if kind in ("line", "polyline", "nurbs"):
        result.curves.append((kernel_curve(record, scale), layer, name))
    elif kind == "surface":
        surface: Surface = kernel_surface(record, scale)
        if "loops" in record:
            try:
                surface = trimmed_face(surface, record["loops"], scale)  # type: ignore[arg-type]
                result.trims += isinstance(surface, TrimmedSurface)
            except (ValueError, KeyError, TypeError, FloatingPointError):  # loops across a seam …
                result.trimmed += 1  # comes in untrimmed, and the node says so
        result.trimmed += bool(record.get("capped"))
        result.surfaces.append((surface, layer, name))
    elif kind == "mesh":
        result.meshes.append((kernel_mesh(record, scale), layer, name))
    else:
        what = str(record.get("type", "object"))
        result.skipped[what] = result.skipped.get(what, 0) + 1
