"""Rhino ``.3dm`` files through rhino3dm: kernel geometry to openNURBS and back.

Writing (:func:`write_3dm`): every curve goes out as a NURBS curve and every surface as
a NURBS surface whose parameterisation is Torsal's own (t in [0, 1] maps linearly onto
the Rhino domain), so evaluating the Rhino object at the same parameter gives the same
point. The forms are exact where the kernel object is a B-spline already — NURBS curves
and surfaces, lines, polylines, circles, arcs, interpolated curves, reversed or moved
copies of them, ruled surfaces between such rails (degree 1 across the rulings) — and
otherwise a cubic interpolation on a grid of Torsal's parameters, refined until it is
within :data:`APPROXIMATION` of the object's size or has 4097 points along a curve,
257 × 257 on a surface (the deviation is reported: ~5e-9 of the size for a sphere).
Files are written in the Rhino 7 format, which Rhino 7 and 8 both open. Developable
strips (ruled surfaces whose rails run on two curves at their rulings' pace) go out face by
face along their rulings instead (:mod:`.threedm_strips`); a curve of no length is left out.

Reading (:func:`read_3dm`) is :mod:`.threedm_read`'s: rhino3dm parses in a fenced child
process, never in Torsal's own.

The kernel's NURBS and meshes become rhino3dm objects in :mod:`.threedm_native`.
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import rhino3dm as rh
import trimesh
from scipy.interpolate import make_interp_spline, make_lsq_spline

from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curves import Line, NurbsCurve, Polyline, ReversedCurve, TransformedCurve
from torsal.nodes.geometry.curves.pieces import PolyCurve
from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.nurbs_surface import NurbsSurface, interpolate_grid
from torsal.nodes.geometry.ruled import RuledSurface, SplineRail
from torsal.nodes.geometry.surface_base import Surface, TransformedSurface
from torsal.nodes.geometry.trimmed_surface import TrimmedSurface
from torsal.nodes.io.common import FileFailure, replacing, unit_name, writable
from torsal.nodes.io.formats.threedm_native import rhino_curve, rhino_mesh, rhino_surface
from torsal.nodes.io.formats.threedm_read import Imported, layer_matches, read_3dm
from torsal.nodes.io.formats.threedm_strips import is_strip, strip_pieces

__all__ = ["Imported", "layer_matches", "read_3dm"]

#: Relative accuracy (of the object's size) an interpolated NURBS form aims for.
APPROXIMATION = 1e-9

#: The file format version written: Rhino 7, which Rhino 7 and 8 both read.
RHINO_VERSION = 7

#: The first bytes of every .3dm file.
MAGIC = b"3D Geometry File Format "

UNIT_SYSTEMS: dict[str, rh.UnitSystem] = {
    "mm": rh.UnitSystem.Millimeters,
    "cm": rh.UnitSystem.Centimeters,
    "m": rh.UnitSystem.Meters,
    "in": rh.UnitSystem.Inches,
    "ft": rh.UnitSystem.Feet,
}


# ------------------------------------------------------------------ kernel → NURBS forms


@dataclass(frozen=True)
class NurbsForm:
    """A NURBS stand-in for a kernel object and how far it strays (0 when exact)."""

    nurbs: NurbsCurve | NurbsSurface
    deviation: float = 0.0


def _size(points: np.ndarray) -> float:
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    return float(np.ptp(points, axis=0).max()) or 1.0


def curve_form(curve: Curve) -> NurbsForm:
    """A NURBS curve with the same parameterisation as ``curve`` (t in [0, 1] onto its domain)."""
    if isinstance(curve, NurbsCurve):
        return NurbsForm(curve)
    if isinstance(curve, Line | Polyline):
        return NurbsForm(curve.to_nurbs())
    if isinstance(curve, ReversedCurve):
        inner = curve_form(curve.curve)
        return NurbsForm(inner.nurbs.reversed(), inner.deviation)  # type: ignore[union-attr]
    if isinstance(curve, TransformedCurve):
        inner = curve_form(curve.curve)
        return NurbsForm(inner.nurbs.transformed(curve.matrix), inner.deviation)  # type: ignore[union-attr]
    if isinstance(curve, SplineRail):
        spline = curve.spline
        count = len(spline.t) - spline.k - 1
        return NurbsForm(NurbsCurve.from_arrays(np.asarray(spline.c)[:count], spline.t, spline.k))
    return _interpolated_curve(curve)


def _interpolated_curve(curve: Curve, start: int = 33, limit: int = 4097) -> NurbsForm:
    """Cubic interpolation of ``curve`` at evenly spaced t, doubled until close enough."""
    count = start
    while True:
        t = np.linspace(0.0, 1.0, count)
        points = curve.point_at(t)
        closed = bool(curve.closed) and count >= 4
        if closed:
            points[-1] = points[0]
        spline = make_interp_spline(t, points, k=3, bc_type="periodic" if closed else None)
        size = _size(points)
        middle = (t[:-1] + t[1:]) / 2
        deviation = float(np.linalg.norm(spline(middle) - curve.point_at(middle), axis=1).max())
        if deviation <= APPROXIMATION * size or count >= limit:
            n = len(spline.t) - spline.k - 1
            nurbs = NurbsCurve.from_arrays(np.asarray(spline.c)[:n], spline.t, spline.k)
            return NurbsForm(nurbs, deviation)
        count = 2 * count - 1


def surface_form(surface: Surface) -> NurbsForm:
    """A NURBS surface with the same (u, v) parameterisation as ``surface``."""
    if isinstance(surface, NurbsSurface):
        return NurbsForm(surface)
    if isinstance(surface, TransformedSurface):
        inner = surface_form(surface.surface)
        nurbs: NurbsSurface = inner.nurbs  # type: ignore[assignment]
        m = surface.matrix
        moved = nurbs.control_points @ m[:3, :3].T + m[:3, 3]
        return NurbsForm(
            NurbsSurface(moved, nurbs.degree_u, nurbs.degree_v, nurbs.knots_u, nurbs.knots_v, nurbs.weights),
            inner.deviation,
        )
    if isinstance(surface, RuledSurface):
        return _ruled_form(surface)
    if isinstance(surface, TrimmedSurface):  # rhino3dm makes no trimmed freeform faces: its surface
        return surface_form(surface.surface)
    return _interpolated_surface(surface, ruled=surface.ruling_direction == "v")


def _ruled_form(surface: RuledSurface) -> NurbsForm:
    """Degree 1 across the rulings: the two rails' control points are the net's two columns."""
    a, b = curve_form(surface.curve_a), curve_form(surface.curve_b)
    rail_a, rail_b = a.nurbs, b.nurbs
    assert isinstance(rail_a, NurbsCurve) and isinstance(rail_b, NurbsCurve)
    compatible = (
        rail_a.degree == rail_b.degree
        and rail_a.knots.shape == rail_b.knots.shape
        and np.allclose(rail_a.knots, rail_b.knots, rtol=0, atol=1e-14)
        and rail_a.domain == (0.0, 1.0) == rail_b.domain
    )
    if not compatible:
        common = _common_rails(rail_a, rail_b)
        if common is None:  # rational rails with different weights: resample both
            return _interpolated_surface(surface, ruled=True)
        rail_a, rail_b = common
    net = np.stack([rail_a.control_points, rail_b.control_points], axis=1)
    weights = None
    if rail_a.is_rational or rail_b.is_rational:
        weights = np.stack([rail_a.weights, rail_b.weights], axis=1)
    nurbs = NurbsSurface(net, rail_a.degree, 1, rail_a.knots, [0.0, 0.0, 1.0, 1.0], weights)
    return NurbsForm(nurbs, max(a.deviation, b.deviation))


def _common_rails(a: NurbsCurve, b: NurbsCurve) -> tuple[NurbsCurve, NurbsCurve] | None:
    """Both polynomial rails in one spline space (the higher degree, every knot of either
    with the multiplicity that keeps its continuity), on t in [0, 1]: exact, by a least
    squares fit in that space (it holds both curves, so the fit reproduces them). None
    for rational rails, or if the fit is not exact to rounding."""
    if a.is_rational or b.is_rational:
        return None
    degree = max(a.degree, b.degree)
    multiplicity: dict[float, int] = {}
    for rail in (a, b):
        lo, hi = rail.domain
        inside = (rail.knots[rail.degree + 1 : len(rail.control_points)] - lo) / (hi - lo)
        values, counts = np.unique(np.round(inside, 14), return_counts=True)
        for value, count in zip(values.tolist(), counts.tolist(), strict=True):
            need = count + degree - rail.degree
            multiplicity[value] = max(multiplicity.get(value, 0), need)
    interior = [k for k, m in sorted(multiplicity.items()) for _ in range(min(m, degree))]
    knots = np.concatenate([np.zeros(degree + 1), interior, np.ones(degree + 1)])
    breaks = np.unique(knots)
    spans = itertools.pairwise(breaks)
    t = np.unique(np.concatenate([np.linspace(lo, hi, 2 * degree + 3) for lo, hi in spans]))
    rails = []
    for rail in (a, b):
        points = rail.point_at(t)
        spline = make_lsq_spline(t, points, knots, degree)
        if np.abs(spline(t) - points).max() > 1e-12 * _size(points):
            return None
        rails.append(NurbsCurve.from_arrays(spline.c, knots, degree))
    return rails[0], rails[1]


def _interpolated_surface(
    surface: Surface, ruled: bool = False, start: int = 17, limit: int = 257
) -> NurbsForm:
    """Cubic interpolation on an evenly spaced (u, v) grid (linear in v when ``ruled``)."""
    count = start
    while True:
        nv = 2 if ruled else count
        u, v = np.linspace(0.0, 1.0, count), np.linspace(0.0, 1.0, nv)
        uu, vv = np.meshgrid(u, v, indexing="ij")
        grid = surface.point_at(uu.ravel(), vv.ravel()).reshape(count, nv, 3)
        # not periodic even when closed: scipy's periodic interpolation solves column by
        # column (~7 s for 257 × 257), and not-a-knot ends converge as fast
        control, knots_u, knots_v, du, dv = interpolate_grid(grid, 3, 1 if ruled else 3, u, v)
        nurbs = NurbsSurface(control, du, dv, knots_u, knots_v)
        mu = (u[:-1] + u[1:]) / 2
        mv = np.linspace(0.0, 1.0, 5) if ruled else (v[:-1] + v[1:]) / 2
        su, sv = np.meshgrid(mu, mv, indexing="ij")
        gap = nurbs.point_at(su.ravel(), sv.ravel()) - surface.point_at(su.ravel(), sv.ravel())
        deviation = float(np.linalg.norm(gap, axis=1).max())
        if deviation <= APPROXIMATION * _size(grid) or count >= limit:
            return NurbsForm(nurbs, deviation)
        count = 2 * count - 1


# ------------------------------------------------------------------ writing


@dataclass(frozen=True)
class Entry:
    """One object to write: kernel geometry, its layer path (``a::b``), name and user strings."""

    geometry: Any
    layer: str
    name: str = ""
    strings: tuple[tuple[str, str], ...] = ()


@dataclass
class Written:
    path: Path
    objects: int
    deviation: float  #: the largest distance of an interpolated NURBS form from its object
    degenerate: int = 0  #: curves of no length left out (a file never holds zero-length curves)


def _layer_index(model: rh.File3dm, cache: dict[str, int], path: str, colour: tuple | None) -> int:
    if path in cache:
        return cache[path]
    parent, _, name = path.rpartition("::")
    layer = rh.Layer()
    layer.Name = name or "Default"
    if parent:
        layer.ParentLayerId = model.Layers.FindIndex(_layer_index(model, cache, parent, None)).Id
    if colour is not None:
        layer.Color = colour
    cache[path] = model.Layers.Add(layer)
    return cache[path]


def _geometry(value: Any) -> tuple[Any, float]:
    """The rhino3dm object for a kernel value, and the deviation of its NURBS form."""
    if isinstance(value, MeshSurface):
        return rhino_mesh(value.mesh), 0.0
    if isinstance(value, trimesh.Trimesh):
        return rhino_mesh(value), 0.0
    if isinstance(value, PolyCurve):  # joined curves stay a polycurve, kinks and all
        joined, worst = rh.PolyCurve(), 0.0
        for piece in value.pieces:
            segment, off = _geometry(piece)
            joined.AppendSegment(segment)
            worst = max(worst, off)
        return joined, worst
    if isinstance(value, Curve):
        form = curve_form(value)
        return rhino_curve(form.nurbs), form.deviation  # type: ignore[arg-type]
    if isinstance(value, Surface):
        form = surface_form(value)
        return rhino_surface(form.nurbs), form.deviation  # type: ignore[arg-type]
    array = np.asarray(value, dtype=float) if isinstance(value, tuple) else None
    if array is not None and array.shape == (3,):
        return rh.Point(rh.Point3d(*array.tolist())), 0.0
    raise FileFailure(f"A {type(value).__name__} cannot be written to a .3dm file")


def _attributes(layer: int, name: str, strings: Iterable[tuple[str, str]]) -> rh.ObjectAttributes:
    attributes = rh.ObjectAttributes()
    attributes.LayerIndex = layer
    if name:
        attributes.Name = name
    for key, value in strings:
        attributes.SetUserString(key, value)
    return attributes


def write_3dm(
    path: Path,
    entries: Iterable[Entry],
    units: str = "m",
    colours: dict[str, tuple[int, int, int, int]] | None = None,
) -> Written:
    """Write ``entries`` to ``path`` in the Rhino 7 format, with the file's units set."""
    model = rh.File3dm()
    model.Settings.ModelUnitSystem = UNIT_SYSTEMS[unit_name(units)]
    model.ApplicationName = "Torsal"
    layers: dict[str, int] = {}
    count, deviation, degenerate = 0, 0.0, 0
    for entry in entries:
        layer = _layer_index(model, layers, entry.layer, (colours or {}).get(entry.layer))
        if is_strip(entry.geometry):  # face by face along its rulings, grouped
            group = rh.Group()
            group.Name = f"{entry.layer.rpartition('::')[2]} {entry.name}".strip()
            model.Groups.Add(group)
            number = model.Groups.FindName(group.Name).Index
            for piece in strip_pieces(entry.geometry):
                deviation = max(deviation, piece.deviation)
                rulings = f"{piece.first + 1}-{piece.last + 1}"
                strings = (*entry.strings, ("TorsalRulings", rulings), ("TorsalFace", piece.kind))
                attributes = _attributes(layer, f"{entry.name} rulings {rulings}", strings)
                attributes.AddToGroup(number)
                model.Objects.Add(piece.brep, attributes)
                count += 1
            continue
        if isinstance(entry.geometry, Curve) and _no_length(entry.geometry):
            degenerate += 1
            continue
        geometry, off = _geometry(entry.geometry)
        deviation = max(deviation, off)
        model.Objects.Add(geometry, _attributes(layer, entry.name, entry.strings))
        count += 1
    writable(path)

    def write(temporary: Path) -> None:
        if not model.Write(str(temporary), RHINO_VERSION):
            raise FileFailure(f"Cannot write {path}: rhino3dm refused (is the folder writable?)")

    replacing(path, write)
    return Written(path, count, deviation, degenerate)


def _no_length(curve: Curve) -> bool:
    """Whether a curve is a point: every sample of it at one place (to 1e-15 of its distance
    from the origin, or exactly there)."""
    points = curve.point_at(np.linspace(0.0, 1.0, 17))
    reach = float(np.abs(points).max()) if np.isfinite(points).all() else 0.0
    return bool(np.ptp(points, axis=0).max() <= 1e-15 * reach)


def tree_entries(
    tree: Any, layer: str, kind: str, names: Sequence[str] | None = None, name_key: str = ""
) -> list[Entry]:
    """The items of a data tree as entries on ``layer``, named ``kind 1``, ``kind 2`` … (or by
    ``names``, also stored as the user string ``name_key``), each with its tree path and
    index as the user strings ``TorsalPath`` and ``TorsalIndex``. Empty items are skipped."""
    from torsal.engine.datatree import format_path

    entries = []
    number = 0
    for path, items in tree.items():
        for index, item in enumerate(items):
            if item is None:
                continue
            strings = [("TorsalPath", format_path(path)), ("TorsalIndex", str(index))]
            name = f"{kind} {number + 1}"
            if names is not None and number < len(names) and names[number] is not None:
                name = str(names[number])
                if name_key:
                    strings.append((name_key, name))
            entries.append(Entry(item, layer, name, tuple(strings)))
            number += 1
    return entries
