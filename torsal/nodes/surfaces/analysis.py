"""Reading surfaces: evaluate, curvature, isocurves, edges, and the area of anything flat or curved."""

from __future__ import annotations

from typing import Any

import numpy as np
import trimesh

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import GENERIC, NUMBER, PLANE, POINT, VECTOR, describe
from torsal.engine.values import Plane, Point, Vector
from torsal.nodes.common.checks import given, uv
from torsal.nodes.common.convert import point, vector
from torsal.nodes.common.geometry_checks import surface
from torsal.nodes.common.values import CURVE, SURFACE
from torsal.nodes.geometry import mesh_surface
from torsal.nodes.geometry.area import watched
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.surface_base import IsoCurve, Surface
from torsal.nodes.surfaces.measure import enclosed

MIDDLE = Point(0.5, 0.5, 0.0)
"""UV default: the middle of the parameter square."""

SURFACE_INPUT = In("Surface", SURFACE, "S", "The surface to read.")
UV_INPUT = In("UV", POINT, "uv", "Where: x is u and y is v, each from 0 to 1 (z is ignored).",
              default=MIDDLE)


def _regular(values: np.ndarray, u: float, v: float) -> np.ndarray:
    if not np.all(np.isfinite(values)):
        raise NodeWarning(
            f"The surface has no normal at ({u:g}, {v:g}): its u and v directions are parallel "
            "or zero all around there"
        )
    return values


class EvaluateSurface(Node):
    """The point, unit normal and tangent frame of a surface at a (u, v).

    Every surface is parameterised on [0, 1]², so UV (0.5, 0.5) is its middle and
    (0, 0) a corner. The normal is Su × Sv made unit length (it flips with the
    direction of u or v); at a pole or apex, where it has no direction of its own,
    it is the limit from inside the surface. The Frame's X axis is the u direction,
    its normal the Normal, its Y axis Normal × X.
    """

    type_id = "surfaces.EvaluateSurface"
    nickname, aliases = "EvalSrf", ("point on surface", "surface frame", "Surface Frames")
    inputs = (SURFACE_INPUT, UV_INPUT)
    outputs = (
        Out("Point", POINT, "P", "The point at (u, v)."),
        Out("Normal", VECTOR, "N", "The unit normal there.", preview=False),
        Out("Frame", PLANE, "F", "The tangent plane: X along u, Z along the normal."),
    )

    def solve(self, value: Any, place: Any) -> tuple[Point, Vector, Plane]:
        s = surface("Surface", value)
        u, v = uv("UV", place)
        origin, x, y, z = (row[0] for row in s.frame_at(u, v))
        _regular(np.concatenate([x, z]), u, v)
        return point(origin), vector(z), Plane(point(origin), vector(x), vector(y))


class SurfaceCurvature(Node):
    """Principal, Gaussian and mean curvature of a surface at a (u, v).

    K1 ≥ K2 are the largest and smallest bending of the surface through the point,
    along the perpendicular unit tangents Direction1 and Direction2. A curvature is
    positive where the surface bends towards its Normal, so an outward-facing
    sphere of radius r has K1 = K2 = −1/r. Gaussian = K1·K2 (positive on a dome,
    negative on a saddle, 0 on a developable surface, whichever way the normal
    faces) and Mean = (K1 + K2)/2. All are exact to rounding for primitives and
    NURBS, and to ~1e-10 for parametric surfaces.
    """

    type_id = "surfaces.SurfaceCurvature"
    nickname, aliases = "SrfCrv", ("principal curvature", "gaussian curvature", "mean curvature")
    inputs = (SURFACE_INPUT, UV_INPUT)
    outputs = (
        Out("Point", POINT, "P", "The point at (u, v)."),
        Out("Normal", VECTOR, "N", "The unit normal that gives the curvatures their sign.", preview=False),
        Out("K1", NUMBER, "K1", "The larger principal curvature."),
        Out("K2", NUMBER, "K2", "The smaller principal curvature."),
        Out("Direction1", VECTOR, "D1", "Unit tangent along which the surface bends by K1."),
        Out("Direction2", VECTOR, "D2", "Unit tangent along which the surface bends by K2."),
        Out("Gaussian", NUMBER, "G", "Gaussian curvature K1·K2."),
        Out("Mean", NUMBER, "M", "Mean curvature (K1 + K2)/2."),
    )

    def solve(self, value: Any, place: Any) -> tuple[Any, ...]:
        s = surface("Surface", value)
        u, v = uv("UV", place)
        c = s.curvature(u, v)
        _regular(np.concatenate([c.normal[0], c.direction1[0], [c.k1[0], c.k2[0]]]), u, v)
        return (
            point(s.point_at(u, v)),
            vector(c.normal[0]),
            float(c.k1[0]),
            float(c.k2[0]),
            vector(c.direction1[0]),
            vector(c.direction2[0]),
            float(c.gaussian[0]),
            float(c.mean[0]),
        )


class Isocurve(Node):
    """The two curves of constant parameter through a (u, v) on a surface.

    U is the curve along u (v held at the UV's y): t ↦ S(t, v). V is the curve
    along v (u held at the UV's x): t ↦ S(u, t). Both run from 0 to 1 like every
    curve and carry the surface's exact derivatives. On a ruled surface made by
    RuledSurface the V curves are its straight rulings.
    """

    type_id = "surfaces.Isocurve"
    nickname, aliases = "Iso", ("Iso Curve", "isoparametric curve", "Extract Isocurve")
    inputs = (SURFACE_INPUT, UV_INPUT)
    outputs = (
        Out("U", CURVE, "U", "The curve along u through the point."),
        Out("V", CURVE, "V", "The curve along v through the point."),
    )

    def solve(self, value: Any, place: Any) -> tuple[IsoCurve, IsoCurve]:
        s = surface("Surface", value)
        u, v = uv("UV", place)
        return s.isocurve("u", v), s.isocurve("v", u)


class SurfaceEdges(Node):
    """The four boundary curves of a surface, numbered and running counter-clockwise.

    Seen in the parameter square (u to the right, v up), each edge starts where the
    previous one ends::

        0: v = 0, from u = 0 to 1       (bottom)
        1: u = 1, from v = 0 to 1       (right)
        2: v = 1, from u = 1 back to 0  (top)
        3: u = 0, from v = 1 back to 0  (left)

    So edge 0 starts at S(0, 0) and edge 3 ends there. A closed surface lists its
    seam twice (edges 1 and 3 of a sphere or cylinder coincide, run opposite ways),
    and an edge collapsed to a pole or apex is a curve of zero length: the node
    remarks which.
    """

    type_id = "surfaces.SurfaceEdges"
    nickname, aliases = "Edges", ("Brep Edges", "boundary", "naked edges")
    inputs = (SURFACE_INPUT,)
    outputs = (Out("Edges", CURVE, "E", "Edges 0 to 3, in the order above.", access=LIST),)

    def solve(self, value: Any) -> list[IsoCurve]:
        s = surface("Surface", value)
        edges = s.edges()
        samples = [edge.point_at(np.linspace(0.0, 1.0, 9)) for edge in edges]
        size = float(np.ptp(np.vstack(samples), axis=0).max())
        collapsed = [str(i) for i, p in enumerate(samples) if np.ptp(p, axis=0).max() <= 1e-12 * size]
        if len(collapsed) == 1:
            self.remark(f"Edge {collapsed[0]} is collapsed to a point (zero length)")
        elif collapsed:
            names = f"{', '.join(collapsed[:-1])} and {collapsed[-1]}"
            self.remark(f"Edges {names} are collapsed to points (zero length)")
        return edges


class Area(Node):
    """The area of a surface, a mesh or a closed planar curve, and its area centroid.

    Surfaces are measured by Gauss–Legendre cubature of |Su × Sv| to about 1e-11
    relative (adaptive, or patch by patch between a NURBS surface's knots); meshes
    and mesh surfaces exactly, triangle by triangle. A closed
    curve must lie in one plane: its area is the region it bounds (Green's theorem);
    a curve that crosses itself counts each loop with the sense it is run in. The
    Centroid is the centre of the area itself (of a sphere's skin, not of the ball).
    """

    type_id = "surfaces.Area"
    nickname, aliases = "Area", ("Area Centroid", "centroid")
    inputs = (In("Geometry", GENERIC, "G", "A surface, a mesh or a closed planar curve."),)
    outputs = (
        Out("Area", NUMBER, "A", "The area, in square model units."),
        Out("Centroid", POINT, "C", "The centre of the area."),
    )

    def solve(self, geometry: Any) -> tuple[float, Point]:
        g = given("Geometry", geometry)
        if isinstance(g, Surface | mesh_surface.MeshSurface):
            with watched(self.check_cancelled, self.progress):
                area, centroid = g.area_and_centroid()
        elif isinstance(g, trimesh.Trimesh):
            if len(g.faces) == 0:
                raise NodeWarning("The mesh has no faces, so it has no area")
            area, centroid = mesh_surface.MeshSurface(g).area_and_centroid()
        elif isinstance(g, Curve):
            area, centroid = enclosed(g)
        else:
            raise NodeWarning(
                f"Geometry {describe(g)} has no area: give a surface, a mesh or a closed planar curve"
            )
        if not area > 0:
            raise NodeWarning("The geometry has zero area, so it has no centroid")
        return float(area), point(centroid)
