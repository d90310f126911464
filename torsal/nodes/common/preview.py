"""The preview protocol: geometry as plain arrays, for a viewport to draw.

A viewport asks :func:`preview_of` for every value a node outputs and draws what comes
back: points, polylines, rulings, vectors and triangle meshes, each a numpy array, in
one :class:`PreviewGeometry`. It never looks at a value's class or attributes itself,
so a new kind of geometry draws by offering its arrays in one of two ways:

- a kernel or plug-in class implements the protocol — a method
  ``preview_geometry(self) -> PreviewGeometry`` (:class:`Previewable`);
- or an adapter is registered for the class with :func:`register_preview`, as done here
  for the kernel's curves, lines, polylines, surfaces and meshes and the engine's
  points, vectors and planes (so kernel files need not know about drawing). Adapters are
  found through the class's bases: a new curve class draws as a sampled curve (an adapter
  for an abstract class that recognises classes not derived from it, as
  :class:`~torsal.nodes.geometry.trimesh_type.TriangleMesh` does trimesh's meshes, is
  found by ``isinstance``).

A class whose values come by the hundred (a strip's rulings) may also register an adapter
for many values at once, :func:`register_preview_many`: :func:`preview_of_many` then
draws a run of them in one pass, exactly as :func:`preview_of` would one by one. A
geometry's ``polylines`` or ``rulings`` may be one ``(k, n, 3)`` array (k chains of n
points each): that too is a sequence of ``(n, 3)`` chains.

Example::

    class Helix:
        def preview_geometry(self) -> PreviewGeometry:
            t = np.linspace(0, 6 * np.pi, 200)
            return PreviewGeometry(polylines=[np.column_stack([np.cos(t), np.sin(t), t / 10])])
"""

from __future__ import annotations

from abc import ABCMeta
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any, Protocol, runtime_checkable

import numpy as np

from torsal.engine.values import Plane, Point, Triple, Vector
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curves.interpolated import InterpolatedCurve
from torsal.nodes.geometry.curves.line import Line, Polyline
from torsal.nodes.geometry.curves.nurbs import NurbsCurve
from torsal.nodes.geometry.curves.shared_knots import derivative_each
from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.geometry.ruled_meshes import ruled_mesh_arrays
from torsal.nodes.geometry.surface_base import Surface
from torsal.nodes.geometry.trimesh_type import TriangleMesh

#: Grid points per direction of a surface's preview mesh (two along a straight ruling).
SURFACE_GRID = 33
#: Rulings drawn over a ruled surface.
RULINGS_SHOWN = 17
#: Points a curve is drawn through (evenly spaced parameters).
CURVE_SAMPLES = 97


@dataclass(slots=True)
class PreviewMesh:
    """A triangle mesh as arrays: ``vertices`` ``(n, 3)``, ``faces`` ``(m, 3)`` and unit vertex
    ``normals`` ``(n, 3)``; a coloured mesh carries ``scalars`` (one per vertex or face,
    named ``scalar_name``, shown over ``clim`` with colour map ``cmap``) or, with ``rgb``,
    ``(n, 3)`` colours 0–255."""

    vertices: np.ndarray
    faces: np.ndarray
    normals: np.ndarray | None = None
    scalars: np.ndarray | None = None
    scalar_name: str | None = None
    rgb: bool = False
    clim: tuple[float, float] | None = None
    cmap: str | None = None


@dataclass(slots=True)
class PreviewGeometry:
    """What one value draws, as plain arrays: ``points`` ``(n, 3)`` each, ``polylines``
    ``(k, 3)`` each (curves), ``rulings`` ``(2, 3)`` each (the straight lines over a ruled
    surface), ``vectors`` ``(3,)`` each (arrows from the origin) and ``meshes``. Each is a
    sequence (a tuple, a list, or for chains of one length an ``(m, k, 3)`` array); empty
    by default."""

    points: Sequence[np.ndarray] = ()
    polylines: Sequence[np.ndarray] = ()
    rulings: Sequence[np.ndarray] = ()
    vectors: Sequence[np.ndarray] = ()
    meshes: Sequence[PreviewMesh] = ()


@runtime_checkable
class Previewable(Protocol):
    """Geometry that says itself how it is drawn."""

    def preview_geometry(self) -> PreviewGeometry:
        ...


Adapter = Callable[[Any], PreviewGeometry]
ManyAdapter = Callable[[Sequence[Any]], PreviewGeometry]
_ADAPTERS: dict[type, Adapter] = {}
_MANY: dict[type, ManyAdapter] = {}


def register_preview(cls: type) -> Callable[[Adapter], Adapter]:
    """Decorator: ``fn(value) -> PreviewGeometry`` draws values of ``cls`` (and its subclasses)."""
    def decorate(fn: Adapter) -> Adapter:
        _ADAPTERS[cls] = fn
        return fn
    return decorate


def register_preview_many(cls: type) -> Callable[[ManyAdapter], ManyAdapter]:
    """Decorator: ``fn(values) -> PreviewGeometry`` draws a run of values of exactly ``cls``
    in one pass (what :func:`preview_of` draws for each, in order, merged)."""
    def decorate(fn: ManyAdapter) -> ManyAdapter:
        _MANY[cls] = fn
        return fn
    return decorate


def draws_many(cls: type) -> bool:
    """Whether values of exactly ``cls`` are drawn by the run (see :func:`preview_of_many`)."""
    return cls in _MANY


def preview_of_many(values: Sequence[Any]) -> PreviewGeometry:
    """The arrays that draw ``values``, all of one class for which :func:`draws_many`."""
    return _MANY[type(values[0])](values)


def preview_of(value: Any) -> PreviewGeometry | None:
    """The arrays that draw ``value``, or None when it is not geometry (a number, a text)."""
    if value is None or isinstance(value, bool | int | float | str):
        return None
    own = getattr(type(value), "preview_geometry", None)  # the Previewable protocol (a class lookup:
    if own is not None:  # isinstance with a runtime-checkable Protocol costs 15 µs a value)
        return own(value)
    for cls in type(value).__mro__:
        adapter = _ADAPTERS.get(cls)
        if adapter is not None:
            return adapter(value)
    for cls, adapter in _ADAPTERS.items():  # an abstract class recognising classes not derived
        if isinstance(cls, ABCMeta) and isinstance(value, cls):  # from it (TriangleMesh)
            return adapter(value)
    return None


def costly(value: Any) -> bool:
    """Whether drawing ``value`` costs an evaluation (a curve, a surface): worth remembering
    when several nodes pass the same object on."""
    return not isinstance(value, Triple | Plane | np.ndarray | TriangleMesh) and value is not None


# -- adapters for the engine's values ----------------------------------------------------------


@register_preview(Point)
def _point(value: Point) -> PreviewGeometry:
    return PreviewGeometry(points=[np.asarray(value, dtype=float).reshape(1, 3)])


@register_preview(Vector)
def _vector(value: Vector) -> PreviewGeometry:
    return PreviewGeometry(vectors=[np.asarray(value, dtype=float)])


@register_preview(Plane)
def _plane(value: Plane) -> PreviewGeometry:
    return PreviewGeometry(points=[np.asarray(value.origin, dtype=float).reshape(1, 3)])


@register_preview(np.ndarray)
def _array(value: np.ndarray) -> PreviewGeometry:
    if value.shape[-1:] != (3,):
        return PreviewGeometry()
    return PreviewGeometry(points=[np.asarray(value, dtype=float).reshape(-1, 3)])


# -- adapters for the kernel's geometry -------------------------------------------------------

def mesh_scalars(mesh: Any) -> tuple[str, np.ndarray, bool, tuple[float, float] | None, str | None] | None:
    """``(name, values, rgb, clim, cmap)`` when a mesh carries colours, else None: per-vertex
    or per-face scalars in ``mesh.metadata["scalars"]`` (name in ``"scalar_name"``, optional
    ``"clim"`` and ``"cmap"``), or explicit vertex or face colours."""
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


@register_preview(TriangleMesh)
def _trimesh(mesh: Any) -> PreviewGeometry:
    vertices = np.asarray(mesh.vertices, dtype=float)
    faces = np.asarray(mesh.faces, dtype=np.int64)
    if len(vertices) == 0 or len(faces) == 0:
        return PreviewGeometry()
    coloured = mesh_scalars(mesh)
    if coloured is None:
        # the kernel's meshes carry exact normals; trimesh averages face normals otherwise
        normals = np.asarray(mesh.vertex_normals, dtype=float)
        return PreviewGeometry(meshes=[PreviewMesh(vertices, faces, normals)])
    name, data, rgb, clim, cmap = coloured
    return PreviewGeometry(meshes=[PreviewMesh(vertices, faces, None, data, name, rgb, clim, cmap)])


def ruling_direction(surface: Surface) -> str | None:
    """``"v"`` or ``"u"``, the parameter along which the surface is straight, or None."""
    if getattr(surface, "ruling_lines", None) is not None:
        return "v"  # a loft of given rulings (RuledSurface.from_rulings)
    try:
        direction = getattr(surface, "ruling_direction", None)
        direction = direction() if callable(direction) else direction
    except (ValueError, ArithmeticError, TypeError):
        return None
    return direction if direction in ("u", "v") else None


def surface_rulings(surface: Surface) -> np.ndarray | None:
    """The surface's rulings as ``(k, 2, 3)`` segments when it is ruled, else None."""
    lines = getattr(surface, "ruling_lines", None)
    if lines is not None:
        lines = np.asarray(lines, dtype=float)
        if lines.ndim == 3 and lines.shape[1:] == (2, 3):
            step = max(1, len(lines) // RULINGS_SHOWN)
            return lines[::step]
    try:
        lines = np.asarray(surface.rulings(RULINGS_SHOWN), dtype=float)
    except (ValueError, AttributeError, TypeError):
        return None
    return lines.reshape(-1, 2, 3)


@register_preview(Surface)
def _surface(surface: Surface) -> PreviewGeometry:
    direction = ruling_direction(surface)
    # along a straight ruling two rows of vertices are exact: 16 times fewer triangles
    nu, nv = {"v": (SURFACE_GRID, 2), "u": (2, SURFACE_GRID)}.get(direction, (SURFACE_GRID, SURFACE_GRID))
    if type(surface).to_mesh is Surface.to_mesh:  # its mesh's arrays, without making the mesh
        vertices, faces, normals = surface.mesh_arrays(nu, nv)
        meshes = [PreviewMesh(vertices, faces, normals)]
    else:  # a surface meshing itself its own way
        meshes = _trimesh(surface.to_mesh(nu, nv)).meshes
    rulings = surface_rulings(surface) if direction else None
    return PreviewGeometry(meshes=meshes, rulings=() if rulings is None else rulings)


@register_preview_many(RuledSurface)
def _ruled_surfaces(surfaces: Sequence[RuledSurface]) -> PreviewGeometry:
    """A run of ruled surfaces (a strip's pieces): what :func:`_surface` draws for each, in
    order, with the meshes of those between curve rails made in one pass."""
    direction = [ruling_direction(surface) for surface in surfaces]
    grids = {"v": (SURFACE_GRID, 2), "u": (2, SURFACE_GRID)}
    plain = [
        k for k, surface in enumerate(surfaces)
        if direction[k] == "v" and type(surface).to_mesh is Surface.to_mesh
    ]
    meshes = dict(zip(plain, ruled_mesh_arrays([surfaces[k] for k in plain], *grids["v"]), strict=True))
    out = PreviewGeometry(meshes=[], rulings=[])
    for k, surface in enumerate(surfaces):
        if k in meshes:
            rulings = surface_rulings(surface)
            rulings = () if rulings is None else rulings
            drawn = PreviewGeometry(meshes=[PreviewMesh(*meshes[k])], rulings=rulings)
        else:
            drawn = _surface(surface)
        out.meshes.extend(drawn.meshes)
        if drawn.rulings is not None and len(drawn.rulings):
            out.rulings.append(np.asarray(drawn.rulings, dtype=float).reshape(-1, 2, 3))
    out.rulings = np.concatenate(out.rulings) if out.rulings else ()
    return out


@register_preview(MeshSurface)
def _mesh_surface(surface: MeshSurface) -> PreviewGeometry:
    return _trimesh(surface.to_mesh())


@register_preview(Line)
def _line(line: Line) -> PreviewGeometry:
    return PreviewGeometry(polylines=[np.array([line.start, line.end], dtype=float).reshape(2, 3)])


@register_preview_many(Line)
def _lines(lines: Sequence[Line]) -> PreviewGeometry:
    """A run of lines as one ``(k, 2, 3)`` array of chains (a strip's hundreds of rulings)."""
    ends = np.empty((len(lines), 2, 3))
    ends[:, 0] = [line.start for line in lines]
    ends[:, 1] = [line.end for line in lines]
    return PreviewGeometry(polylines=ends)


@register_preview(Polyline)
def _polyline(polyline: Polyline) -> PreviewGeometry:
    return PreviewGeometry(polylines=[np.asarray(polyline.points, dtype=float).reshape(-1, 3)])


def curve_points(curve: Curve) -> np.ndarray:
    """:data:`CURVE_SAMPLES` points at evenly spaced parameters, in one vectorised
    evaluation (an adaptive tessellation looks no better at preview size and costs 30
    times more)."""
    return np.asarray(curve.point_at(_CURVE_PARAMETERS.copy()), dtype=float).reshape(-1, 3)


_CURVE_PARAMETERS = np.linspace(0.0, 1.0, CURVE_SAMPLES)  # (copied for each curve: a copy costs less)


@register_preview(Curve)
def _curve(curve: Curve) -> PreviewGeometry:
    return PreviewGeometry(polylines=[curve_points(curve)])


@register_preview_many(NurbsCurve)
@register_preview_many(InterpolatedCurve)
def _nurbs_curves(curves: Sequence[NurbsCurve]) -> PreviewGeometry:
    """A run of NURBS curves (a roof's edges) as one ``(k, n, 3)`` array of chains: what
    :func:`_curve` draws for each, those that share their knots evaluated together
    (:func:`~torsal.nodes.geometry.curves.shared_knots.derivative_each`, bit for bit)."""
    points = derivative_each(curves, [_RUN_PARAMETERS] * len(curves), 0)
    return PreviewGeometry(polylines=np.array(points).reshape(len(curves), -1, 3))


#: :data:`_CURVE_PARAMETERS` for a run of curves (one array for all: read-only).
_RUN_PARAMETERS = _CURVE_PARAMETERS.copy()
_RUN_PARAMETERS.setflags(write=False)
