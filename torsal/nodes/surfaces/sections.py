"""Cutting surfaces and meshes by planes: Contour (parallel planes Distance apart), Section (one plane)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from shapely import LineString
from shapely.ops import linemerge

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import GENERIC, INTEGER, NUMBER, PLANE, POINT, VECTOR
from torsal.engine.values import UNIT_Z, WORLD_XY, Point
from torsal.nodes.common.checks import count, direction, positive, xyz
from torsal.nodes.common.convert import kernel_plane
from torsal.nodes.common.geometry_checks import surface_or_mesh
from torsal.nodes.common.values import CURVE
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curves import Polyline
from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.sections import Chain, Sectioner, grid_triangles
from torsal.nodes.geometry.trimmed_surface import TrimmedSurface
from torsal.nodes.limits import MAX_DENSITY, MAX_DIVISIONS

SHAPE_INPUT = In("Shape", GENERIC, "S", "The surface, mesh or mesh surface to cut.")
DENSITY_INPUT = In("Density", INTEGER, "D", "A surface is cut on a grid of Density × Density points in "
                   "(u, v) (2 or more); a mesh on its own triangles.", default=64)


def _sectioner(value: Any, density: Any) -> tuple[Sectioner, TrimmedSurface | None]:
    """The cutter of the Shape, and the Shape when it is a trimmed surface (to clip by)."""
    shape = surface_or_mesh("Shape", value, "faces to cut")
    if isinstance(shape, MeshSurface):
        return Sectioner(np.asarray(shape.mesh.vertices, dtype=float), np.asarray(shape.mesh.faces)), None
    n = count("Density", density, least=2, limit=MAX_DENSITY)
    u, v = np.meshgrid(np.linspace(0.0, 1.0, n), np.linspace(0.0, 1.0, n), indexing="ij")
    uv = np.stack([u.ravel(), v.ravel()], axis=1)

    def on_surface(at: np.ndarray) -> np.ndarray:
        return shape.point_at(at[:, 0], at[:, 1])

    grid = on_surface(uv)
    if not np.all(np.isfinite(grid)):
        raise NodeWarning("Shape has points that are not finite numbers, so it cannot be cut")
    trim = shape if isinstance(shape, TrimmedSurface) else None
    return Sectioner(grid, grid_triangles(n, n), uv, on_surface), trim


#: Planes × points (grid points or mesh vertices) one Contour may cut: every plane measures
#: every point (6 s at the cap, 4,761 contours of a sphere, on the 2-core machine at load 9).
MAX_CUT_WORK = 20_000_000

#: Chain ends closer than this share of the chain's size meet (a surface's seam, where the
#: grid's first and last columns are the same points to rounding); shorter chains are points.
ROUNDING = 1e-9


def _inside(chain: Chain, trim: TrimmedSurface) -> list[np.ndarray]:
    """The parts of a section of a trimmed surface inside its trim: the (u, v) polyline
    clipped by the trim region (shapely), its pieces put back on the surface. Corners
    inside keep their places; the ends on a trim loop lie on the surface, off the plane by
    at most the grid's chord error."""
    kept = _line_pieces(LineString(chain.uv).intersection(trim.region))
    return [trim.point_at(uv[:, 0], uv[:, 1]) for uv in kept]


def _line_pieces(geometry: Any) -> list[np.ndarray]:
    """The (u, v) coordinates of each line in ``geometry`` (points where a section only
    touches the trim are left out), pieces that meet end to end joined."""
    parts = getattr(geometry, "geoms", [geometry])
    lines = [g for g in parts if isinstance(g, LineString) and not g.is_empty]
    if not lines:
        return []
    merged = linemerge(lines) if len(lines) > 1 else lines[0]
    return [np.asarray(g.coords) for g in getattr(merged, "geoms", [merged])]


def _curves(chains: list[Chain], trim: TrimmedSurface | None = None) -> list[Curve]:
    """Polylines from the chains (clipped by ``trim``): consecutive repeats (a cut through a
    vertex) dropped, a chain whose ends meet across a seam closed, a chain with no length
    (a plane touching a pole) left out."""
    curves: list[Curve] = []
    pieces = [c.points for c in chains] if trim is None else [p for c in chains for p in _inside(c, trim)]
    for chain in pieces:
        keep = np.concatenate([[True], np.any(np.diff(chain, axis=0) != 0, axis=1)])
        chain = chain[keep]
        size = float(np.linalg.norm(np.ptp(chain, axis=0)))
        if len(chain) < 2 or not size > ROUNDING * float(np.abs(chain).max(initial=0.0)):
            continue
        if np.linalg.norm(chain[-1] - chain[0]) <= ROUNDING * size:
            chain[-1] = chain[0]  # closed exactly
        curves.append(Polyline(chain))
    return curves


class Contour(Node):
    """Cut a surface or mesh by parallel planes Distance apart: contour lines, or the
    cutting pattern of a stack of ribs.

    The planes are square to Direction and pass through Point + k·Distance·Direction for
    every whole k that meets the shape. A surface is cut on a (u, v) grid of Density ×
    Density points: each corner of a contour lies on the surface and on its plane to
    rounding, the straight pieces between them stray by the grid's chord error (raise
    Density for a closer fit). A trimmed surface (a face from Rhino) is cut only inside
    its trim. A mesh is cut exactly on its triangles. Each contour is a
    polyline (closed when it closes); Levels gives each one's distance from Point along
    Direction.
    """

    type_id = "surfaces.Contour"
    nickname, aliases = "Contour", ("Contour", "contours", "ribs", "slice", "Mesh Contour", "waterfall")
    inputs = (
        SHAPE_INPUT,
        In("Point", POINT, "P", "A point the first plane passes through.", default=Point(0.0, 0.0, 0.0)),
        In("Direction", VECTOR, "N", "The planes' normal: the direction the contours are stacked in.",
           default=UNIT_Z),
        In("Distance", NUMBER, "D", "The distance between neighbouring planes, in model units.", default=1.0),
        DENSITY_INPUT,
    )
    outputs = (
        Out("Curves", CURVE, "C", "The contours, from the lowest plane up.", access=LIST),
        Out("Levels", NUMBER, "L", "Each contour's distance from Point along Direction.", access=LIST),
    )

    def solve(self, shape: Any, point: Any, normal: Any, distance: Any, density: Any
              ) -> tuple[list[Curve], list[float]]:
        origin = xyz("Point", point)
        n = direction("Direction", normal)
        n = n / np.linalg.norm(n)
        step = positive("Distance", distance)
        cutter, trim = _sectioner(shape, density)
        height = (cutter.points - origin) @ n
        low, high = math.ceil(height.min() / step), math.floor(height.max() / step)
        planes = high - low + 1
        most = min(MAX_DIVISIONS, MAX_CUT_WORK // len(cutter.points))
        if planes > most:
            raise NodeWarning(f"Distance {step:g} would cut {planes:,} contours; at most {most:,} on this "
                              "shape: give a longer Distance")
        curves: list[Curve] = []
        levels: list[float] = []
        heights = np.arange(low, high + 1) * step
        for level, chains in zip(heights.tolist(), cutter.sections(origin, n, heights), strict=True):
            made = _curves(chains, trim)
            curves += made
            levels += [level] * len(made)
        return curves, levels


class Section(Node):
    """Cut a surface or mesh by one plane: the section curves where they meet.

    As Contour, for a single Plane: a surface is cut on a (u, v) grid of Density ×
    Density points (every corner on the surface and on the plane; a trimmed surface only
    inside its trim), a mesh on its triangles. A shape the plane misses gives no curves.
    """

    type_id = "surfaces.Section"
    nickname, aliases = "Sec", ("Brep | Plane", "Mesh | Plane", "section", "cut by plane", "Section")
    inputs = (SHAPE_INPUT, In("Plane", PLANE, "P", "The cutting plane.", default=WORLD_XY), DENSITY_INPUT)
    outputs = (Out("Curves", CURVE, "C", "The section curves.", access=LIST),)

    def solve(self, shape: Any, plane: Any, density: Any) -> list[Curve]:
        frame = kernel_plane("Plane", plane)
        cutter, trim = _sectioner(shape, density)
        return _curves(cutter.section(frame.origin, frame.z), trim)
