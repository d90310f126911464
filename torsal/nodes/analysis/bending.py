"""analysis.BendingCheck: can each strip be bent from the chosen sheet material?

A developable strip is bent, not stretched: at each point it curves only across its
rulings, with the one nonzero principal curvature k (the other is 0). Its *bending
radius* there is 1/|k| — the radius of normal curvature across the ruling: r on a
cylinder of radius r, d·tan α on a cone d from its apex with half-angle α, infinite on
a plane. The strip's smallest bending radius is compared with the material's minimum
bending radius (:data:`MATERIALS`, or a number in mm).

Curvature comes from the surface's exact derivatives at an ``n × n`` grid of (u, v)
(:meth:`~torsal.nodes.geometry.surface_base.Surface.curvature`); the larger of |k1|, |k2| is
taken, so a strip that is not quite developable is judged by its stronger bend.
A curvature below :data:`FLAT` of the strip's inverse size (the extent of a 9 × 9 sample
of it) counts as none: the radius is infinite (a plane passes every material).

The node looks at the cancel token between strips and, within a strip, between blocks
of :data:`CHECK_BLOCK` grid points (through :mod:`torsal.nodes.geometry.watch`), so Esc stops
it within a few tens of milliseconds even at Density 500.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np
import trimesh
from numpy.typing import NDArray

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import BOOLEAN, GENERIC, INTEGER, NUMBER, POINT, TEXT, describe
from torsal.nodes.common.checks import finite, whole
from torsal.nodes.common.convert import points
from torsal.nodes.common.files import FileFailure
from torsal.nodes.common.units import unit_name, unit_scale
from torsal.nodes.common.values import MESH
from torsal.nodes.geometry.array_types import FloatArray
from torsal.nodes.geometry.surface_base import Surface, broadcast_uv, grid_triangles, uv_grid
from torsal.nodes.geometry.watch import watch_check, watch_progress, watched
from torsal.nodes.limits import MAX_DENSITY

#: |k| below this share of 1/size is no curvature at all (rounding on a plane).
FLAT = 1e-9

#: Grid points whose curvature is evaluated between two looks at the cancel token (a
#: ruled strip's exact curvature costs 10-25 µs a point: ≈ 5-13 ms a block).
CHECK_BLOCK = 512

#: Grid points placed (a point costs ~0.3 µs) or failing points made into Point values
#: (~0.6 µs) between two looks at the token.
POINT_BLOCK = 16384


def _blocks(count: int, size: int) -> Iterator[slice]:
    """Slices of ``size`` rows covering ``count``; the enclosing
    :func:`~torsal.nodes.geometry.watch.watched` block's check is called before each."""
    check = watch_check()
    for lo in range(0, count, size):
        if check is not None:
            check()
        yield slice(lo, lo + size)


@dataclass(frozen=True)
class Material:
    """A sheet material and the smallest radius it may be bent to, cold, without damage."""

    name: str
    thickness: float  #: mm
    radius: float  #: minimum bending radius, mm
    source: str


def _elastic(modulus: float, stress: float, thickness: float) -> float:
    """Radius (mm) at which the outer fibre of a sheet ``thickness`` mm thick reaches
    ``stress`` (MPa) for a Young's modulus ``modulus`` (MPa): R = E·t / (2σ)."""
    return modulus * thickness / (2.0 * stress)


#: The Material value list. Figures and where they come from (in the node's help too).
MATERIALS: dict[str, Material] = {m.name: m for m in (
    Material("Paper 80 g/m²", 0.1, 0.0,
             "paper folds without breaking: any radius (a fold is not a bend; see paper-strip.graph)"),
    Material("Card 0.5 mm", 0.5, 0.5 / (2 * 0.015),
             "estimate R = t / (2ε) with ε = 1.5 % stretch at break, a typical machine-direction figure "
             "for folding boxboard: about 17 mm; test the board you use"),
    Material("Birch plywood 4 mm", 4.0, 16.0 * 25.4,
             "FAA Advisory Circular AC 43.13-1B, plywood minimum bend radius table: 0.155 in 3-ply at "
             "10 % moisture on a cold mandrel, 16 in (406 mm) at 90° to the face grain (10 in at 0–45°)"),
    Material("Aluminium 1 mm", 1.0, _elastic(70_000.0, 130.0, 1.0),
             "elastic bend R = E·t / (2 Rp0.2) of EN AW-5754 H22: E = 70 GPa, Rp0.2 ≥ 130 MPa "
             "(EN 485-2): 269 mm (tighter bends yield and stay bent)"),
    Material("Steel 1.5 mm", 1.5, _elastic(210_000.0, 235.0, 1.5),
             "elastic bend R = E·t / (2 ReH) of S235 (EN 10025-2): E = 210 GPa, ReH ≥ 235 MPa: 670 mm"),
    Material("Polycarbonate 6 mm", 6.0, 100.0 * 6.0,
             "cold curving at no less than 100 × the thickness, the sheet suppliers' rule against crazing "
             "(e.g. High Line PC, 'Cold forming polycarbonate sheet'): 600 mm"),
)}


def bending_radii(surface: Surface, u: FloatArray, v: FloatArray) -> FloatArray:
    """The bending radius 1/max(|k1|, |k2|) at (u, v) (flattened), model units; inf where
    flat (see :data:`FLAT`), NaN where the surface has no curvature (degenerate).

    Within a :func:`~torsal.nodes.geometry.watch.watched` block it looks at the cancel token
    between blocks of :data:`CHECK_BLOCK` points."""
    uu, vv = broadcast_uv(u, v)
    k = np.empty(len(uu))
    for rows in _blocks(len(uu), CHECK_BLOCK):
        c = surface.curvature(uu[rows], vv[rows])
        k[rows] = np.maximum(np.abs(c.k1), np.abs(c.k2))
    size = _size(surface)
    with np.errstate(divide="ignore"):
        radius = 1.0 / k
    return np.where(k <= FLAT / size, np.inf, radius)


def _size(surface: Surface) -> float:
    """The largest extent of a 9 × 9 sample of the surface (it only scales :data:`FLAT`, so
    the sample's box does: the exact box's L-BFGS polish took ~50 ms a strip)."""
    gu, gv = uv_grid(9, 9)
    size = float(np.ptp(surface.point_at(gu, gv), axis=0).max())
    return size if size > 0 else 1.0


def material_radius(value: Any) -> tuple[float, str]:
    """A Material name or a number (mm): the minimum radius in mm and how to call it."""
    if isinstance(value, int | float) and not isinstance(value, bool):
        radius = float(value)
        if not (math.isfinite(radius) and radius >= 0):
            raise NodeWarning(f"Material must be a name or a radius of 0 mm or more, not {radius:g}")
        return radius, f"{radius:g} mm"
    text = str(value or "").strip()
    for name, material in MATERIALS.items():
        if text.lower() == name.lower():
            return material.radius, name
    try:
        return material_radius(float(text))
    except ValueError:
        pass
    names = "; ".join(MATERIALS)
    raise NodeWarning(f"Material {text!r} is not in the table ({names}) nor a radius in mm")


def _colour(radius_mm: FloatArray, limit: float) -> NDArray[np.uint8]:
    """Red below the material's radius, orange up to twice it, green beyond (and flat)."""
    ratio = np.where(np.isfinite(radius_mm), radius_mm / limit if limit > 0 else np.inf, np.inf)
    rgb = np.where((ratio < 1)[:, None], (220, 40, 40), np.where((ratio < 2)[:, None], (245, 160, 40),
                                                                  (60, 170, 90)))
    rgb = np.where(np.isnan(radius_mm)[:, None], (128, 128, 128), rgb)
    return np.column_stack([rgb, np.full(len(rgb), 255)]).astype(np.uint8)


def _table() -> str:
    return "\n".join(f"    - {m.name}: {m.radius:.0f} mm — {m.source}." for m in MATERIALS.values())


class BendingCheck(Node):
    """Check that each strip can be bent from a sheet material.

    Strips are developable surfaces (in model Units); at a grid of Density × Density
    points each one's bending radius is measured — the radius of normal curvature
    across the rulings, 1/|k| of its one nonzero principal curvature (a cylinder of
    radius r gives r, a cone at distance d from its apex with half-angle α gives
    d·tan α, a plane is infinite). With ModelScale n (a 1:n model) the cut part bends
    n times tighter than the surface in the model's units, so radii are divided by n
    before the check. Ok is true where the smallest radius is at least the material's
    minimum bending radius. Material is a name from the table below or a number in mm.

    Materials (minimum bending radius, cold, and the source of the figure):

{table}
    """

    type_id = "analysis.BendingCheck"
    nickname, aliases = "Bend", ("bending radius", "minimum radius", "material check")
    inputs = (
        In("Strips", GENERIC, "S", "The developable strips (surfaces), in model units.", access=LIST),
        In("Material", GENERIC, "M", "A material from the table (see help) or its minimum bending radius "
           "in mm.", default="Birch plywood 4 mm"),
        In("Units", TEXT, "U", "The model's units (mm, cm, m, in, ft).", default="m"),
        In("ModelScale", NUMBER, "n", "1:n — the model is n times smaller than the built strips' drawing "
           "(1 at full size).", default=1.0),
        In("Density", INTEGER, "D", "Grid points per direction on each strip (2 or more).", default=24,
           min=2, max=MAX_DENSITY),
    )
    outputs = (
        Out("MinRadius", NUMBER, "R", "Each strip's smallest bending radius, mm as cut (inf: flat).",
            access=LIST),
        Out("Ok", BOOLEAN, "Ok", "Per strip: true when it can be bent from the material.", access=LIST),
        Out("Failing", POINT, "F", "Points where a strip bends tighter than the material allows.",
            access=LIST),
        Out("ColouredMesh", MESH, "Cm", "The strips coloured by radius: red below the material's, "
            "orange up to twice it, green beyond.", access=LIST),
        Out("MaterialRadius", NUMBER, "Mr", "The material's minimum bending radius, mm."),
    )

    def solve(self, strips: list[Any], material: Any, units: Any, model_scale: Any,
              density: Any) -> tuple[Any, ...]:
        limit, called = material_radius(material)
        try:
            to_mm = unit_scale(unit_name(units), "mm")
        except FileFailure as exc:  # "Units 'furlong' is not a length unit ...": one refused value
            raise NodeWarning(str(exc)) from None
        scale = finite("ModelScale", model_scale)
        if not scale > 0:
            raise NodeWarning(f"ModelScale must be positive (1 for full size, 50 for 1:50), not {scale:g}")
        n = whole("Density", density)  # 2 to MAX_DENSITY: the port's bounds
        if not strips:
            raise NodeWarning("There are no strips: wire surfaces into Strips")
        u, v = uv_grid(n, n)
        with watched(self.check_cancelled, self.progress):
            return self._check(strips, u, v, n, limit, called, (to_mm, scale))

    def _check(self, strips: list[Any], u: FloatArray, v: FloatArray, n: int, limit: float, called: str,
               scales: tuple[float, float]) -> tuple[Any, ...]:
        """Each strip's radii (mm as cut: model units × to_mm / scale), Ok, failing points and
        coloured mesh; the remark."""
        to_mm, scale = scales
        progress = watch_progress()
        radii, oks, failing, meshes = [], [], [], []
        for index, surface in enumerate(strips):
            if not isinstance(surface, Surface):  # one refused strip: null outputs for it, the rest checked
                what = "empty (null)" if surface is None else f"{describe(surface)}, not a surface"
                self.warn(f"Strip {index + 1} of Strips is {what}: it is not checked and its outputs "
                          "are null")
                radii.append(None)
                oks.append(None)
                meshes.append(None)
                continue
            self.check_cancelled()
            radius = bending_radii(surface, u, v) * to_mm / scale
            known = radius[~np.isnan(radius)]
            smallest = float(known.min()) if len(known) else math.nan
            if not len(known):
                self.warn(f"Strip {index + 1} has no curvature anywhere (degenerate): its radius is NaN")
            radii.append(smallest)
            oks.append(bool(smallest >= limit))
            xyz = np.empty((len(u), 3))
            for rows in _blocks(len(u), POINT_BLOCK):
                xyz[rows] = surface.point_at(u[rows], v[rows])
            tight = xyz[radius < limit]
            for rows in _blocks(len(tight), POINT_BLOCK):
                failing += points(tight[rows])
            mesh = trimesh.Trimesh(xyz, grid_triangles(n, n), process=False)
            mesh.visual = trimesh.visual.ColorVisuals(mesh, vertex_colors=_colour(radius, limit))
            mesh.metadata.update({"scalars": np.where(np.isfinite(radius), radius, np.nan),
                                  "scalar_name": "bending radius, mm"})
            meshes.append(mesh)
            if progress is not None:
                progress((index + 1) / len(strips))
        bad = [i + 1 for i, ok in enumerate(oks) if ok is False]
        checked = sum(ok is not None for ok in oks)
        if bad:
            listed = ", ".join(map(str, bad[:20])) + (" …" if len(bad) > 20 else "")
            self.remark(f"{len(bad)} of {checked} strips bend tighter than {called} allows "
                        f"({limit:.0f} mm): strips {listed}")
        elif checked:
            which = "Every strip checked" if checked < len(oks) else "Every strip"
            self.remark(f"{which} can be bent from {called} ({limit:.0f} mm)")
        return radii, oks, failing, meshes, limit


BendingCheck.__doc__ = (BendingCheck.__doc__ or "").replace("{table}", _table())
