"""The child process that parses ``.3dm`` files with rhino3dm, fenced off from Torsal.

rhino3dm is C++: one bad byte in a file can crash it (SIGSEGV) or make it allocate without
end. So Torsal never parses a ``.3dm`` in its own process: :mod:`.fenced` starts this module
as ``python -P -m torsal.nodes.io.formats.threedm_child`` with a memory limit (``RLIMIT_AS``,
set here before rhino3dm is imported) and a time limit (the parent's clock), sends it
requests and reads back plain arrays. Nothing here imports the rest of Torsal.

Wire format (stdin and stdout, each message a 4-byte little-endian length and a msgpack
body through msgspec): ``{"ready": true}`` once rhino3dm is imported; then for each
request ``{"path", "units"}`` (units as a rhino3dm UnitSystem name) a reply ``{"ok": true,
"units", "scale", "objects": [...]}`` or ``{"ok": false, "error"}``. Every array goes as
``{"shape": [...], "data": <float64 little-endian bytes>}``. An object is a dict with
``kind`` (``line``, ``polyline``, ``nurbs``, ``surface``, ``mesh`` or ``skip``),
``layer``, ``name`` and the arrays of its kind; a brep face also carries its trim
``loops`` (each ``{"outer": bool, "edges": [nurbs curve, ...]}``, edges in loop order,
already turned to run along the loop).
"""

from __future__ import annotations

import struct
import sys
from typing import Any, BinaryIO

import msgspec
import numpy as np

#: The magic every .3dm file starts with.
MAGIC = b"3D Geometry File Format "


def array(values: Any) -> dict[str, Any]:
    """An array as plain data: its shape and its float64 little-endian bytes."""
    data = np.ascontiguousarray(values, dtype="<f8")
    return {"shape": list(data.shape), "data": data.tobytes()}


def send(stream: BinaryIO, message: dict[str, Any]) -> None:
    body = msgspec.msgpack.encode(message)
    stream.write(struct.pack("<I", len(body)) + body)
    stream.flush()


def receive(stream: BinaryIO) -> dict[str, Any] | None:
    head = stream.read(4)
    if len(head) < 4:
        return None
    (size,) = struct.unpack("<I", head)
    return msgspec.msgpack.decode(stream.read(size))


# ------------------------------------------------------------------ rhino3dm → plain data


def _curve(rh: Any, curve: Any, reverse: bool = False) -> dict[str, Any]:
    if isinstance(curve, rh.LineCurve) and not reverse:
        a, b = curve.PointAtStart, curve.PointAtEnd
        return {"kind": "line", "points": array([[a.X, a.Y, a.Z], [b.X, b.Y, b.Z]])}
    if isinstance(curve, rh.PolylineCurve) and not reverse:
        points = [curve.Point(i) for i in range(curve.PointCount)]
        return {"kind": "polyline", "points": array([[p.X, p.Y, p.Z] for p in points]),
                "closed": bool(curve.IsClosed)}
    nurbs = curve if isinstance(curve, rh.NurbsCurve) and not reverse else curve.ToNurbsCurve()
    if nurbs is None:
        raise ValueError(f"a {type(curve).__name__} has no NURBS form")
    if reverse:
        nurbs.Reverse()
    cells = [nurbs.Points[i] for i in range(len(nurbs.Points))]
    return {"kind": "nurbs", "degree": int(nurbs.Degree), "rational": bool(nurbs.IsRational),
            "points": array([[p.X, p.Y, p.Z, p.W] for p in cells]), "knots": array(nurbs.Knots.ToList())}


def _surface(surface: Any) -> dict[str, Any]:
    nurbs = surface.ToNurbsSurface()
    if nurbs is None:
        raise ValueError(f"a {type(surface).__name__} has no NURBS form")
    nu, nv = nurbs.Points.CountU, nurbs.Points.CountV
    cells = [nurbs.Points.GetControlPoint(i, j) for i in range(nu) for j in range(nv)]
    return {"kind": "surface", "degree": [int(nurbs.OrderU - 1), int(nurbs.OrderV - 1)],
            "rational": bool(nurbs.IsRational),
            "points": array(np.array([[p.X, p.Y, p.Z, p.W] for p in cells]).reshape(nu, nv, 4)),
            "knots": [array(nurbs.KnotsU.ToList()), array(nurbs.KnotsV.ToList())]}


def _loops(rh: Any, brep: Any, face: Any) -> list[dict[str, Any]]:
    """The face's trim loops as 3D edge curves in loop order (each turned to run along it)."""
    loops = []
    for loop in face.Loops:
        if loop.LoopType not in (rh.BrepLoopType.Outer, rh.BrepLoopType.Inner):
            continue
        trims = loop.Trims
        edges = []
        for k in range(len(trims)):
            trim = trims[k]
            if trim.EdgeIndex < 0:  # a trim along a singular side: no edge
                continue
            edges.append(_curve(rh, brep.Edges[trim.EdgeIndex], reverse=bool(trim.IsReversed)))
        loops.append({"outer": loop.LoopType == rh.BrepLoopType.Outer, "edges": edges})
    return loops


def _mesh(mesh: Any) -> dict[str, Any]:
    vertices = [[p.X, p.Y, p.Z] for p in mesh.Vertices.ToPoint3dArray()]
    faces = [list(mesh.Faces[i]) for i in range(mesh.Faces.Count)]
    return {"kind": "mesh", "points": array(np.reshape(vertices, (-1, 3))),
            "faces": array(np.reshape(faces, (-1, 4)))}


def _objects(rh: Any, geometry: Any) -> list[dict[str, Any]]:
    """One object of the file as records (a brep gives one per face)."""
    if isinstance(geometry, rh.Curve):
        return [_curve(rh, geometry)]
    if isinstance(geometry, rh.Brep):
        out = []
        for i in range(len(geometry.Faces)):
            face = geometry.Faces[i]
            record = _surface(face.UnderlyingSurface())
            record["loops"] = _loops(rh, geometry, face)
            record["reversed"] = bool(face.OrientationIsReversed)
            out.append(record)
        return out
    if isinstance(geometry, rh.Extrusion):
        record = _surface(geometry)
        record["capped"] = bool(geometry.IsCappedAtBottom or geometry.IsCappedAtTop)
        return [record]
    if isinstance(geometry, rh.Surface):
        return [_surface(geometry)]
    if isinstance(geometry, rh.Mesh):
        return [_mesh(geometry)]
    return [{"kind": "skip", "type": type(geometry).__name__}]


def read(rh: Any, path: str, units: str) -> dict[str, Any]:
    """The reply for one request: the file's objects as plain data, or why not."""
    with open(path, "rb") as stream:
        if stream.read(len(MAGIC)) != MAGIC:
            return {"ok": False, "error": "not a Rhino .3dm file (it does not start like one)"}
    model = rh.File3dm.Read(path)
    if model is None:
        return {"ok": False, "error": "damaged or truncated: rhino3dm could not read it"}
    system = model.Settings.ModelUnitSystem
    scale = 1.0
    if system.name not in ("None", "CustomUnits", "Unset"):
        scale = float(rh.UnitSystem.UnitScale(system, getattr(rh.UnitSystem, units)))
    layers = {layer.Index: layer.FullPath for layer in model.Layers}
    objects = []
    for obj in model.Objects:
        geometry, attributes = obj.Geometry, obj.Attributes
        layer, name = layers.get(attributes.LayerIndex, ""), attributes.Name or ""
        try:
            records = _objects(rh, geometry)
        except (ValueError, TypeError, RuntimeError):  # a degenerate object: counted, not fatal
            records = [{"kind": "skip", "type": f"invalid {type(geometry).__name__}"}]
        for record in records:
            record.update(layer=layer, name=name)
        objects.extend(records)
    return {"ok": True, "units": system.name, "scale": scale, "objects": objects}


def limit(memory: int, seconds: int) -> None:
    """Cap this process's address space and CPU time (a crash is better than a swamped machine).
    Where the platform has no such limits (Windows), only the parent's clock fences the child."""
    try:
        import resource
    except ImportError:
        return
    if memory > 0:
        resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
    if seconds > 0:
        resource.setrlimit(resource.RLIMIT_CPU, (seconds, seconds))


def main(argv: list[str]) -> int:
    limit(int(argv[0]) if argv else 0, int(argv[1]) if len(argv) > 1 else 0)
    import rhino3dm as rh  # after the limit: its allocations count against it

    source, sink = sys.stdin.buffer, sys.stdout.buffer
    sys.stdout = sys.stderr  # nothing else may write into the reply channel
    send(sink, {"ready": True})
    while (request := receive(source)) is not None:
        try:
            reply = read(rh, str(request["path"]), str(request["units"]))
        except MemoryError:
            reply = {"ok": False, "error": "it needs more memory than a file reader is allowed"}
        except OSError as exc:
            reply = {"ok": False, "error": f"cannot open it ({exc.strerror or exc})"}
        send(sink, reply)
    return 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
