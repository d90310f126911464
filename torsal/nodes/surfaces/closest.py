"""The point of a surface closest to a given point: how far a design lies from its strips."""

from __future__ import annotations

from typing import Any

from torsal.engine.node import In, Node, Out
from torsal.engine.types import NUMBER, POINT
from torsal.engine.values import Point
from torsal.nodes.common.checks import xyz
from torsal.nodes.common.convert import point
from torsal.nodes.common.geometry_checks import surface
from torsal.nodes.common.values import SURFACE


class SurfaceClosestPoint(Node):
    """The point of a surface closest to a given point, its (u, v) and the distance.

    Searched from the nearest points of a fine grid over the surface, then refined by
    Newton's method to rounding (a point on an edge when the closest lies there). Use it
    to measure how far a point of the design lies from a developable strip.
    """

    type_id = "surfaces.SurfaceClosestPoint"
    nickname, aliases = "SrfCP", ("Surface Closest Point", "Brep Closest Point", "pull to surface",
                                  "project to surface")
    inputs = (
        In("Point", POINT, "P", "The point to look from."),
        In("Surface", SURFACE, "S", "The surface to find the closest point on."),
    )
    outputs = (
        Out("Point", POINT, "P", "The closest point on the surface."),
        Out("UV", POINT, "uv", "Its parameters: x is u, y is v, each 0 to 1.", preview=False),
        Out("Distance", NUMBER, "D", "How far it is from Point."),
    )

    def solve(self, place: Any, value: Any) -> tuple[Point, Point, float]:
        s = surface("Surface", value)
        found = s.closest_point(xyz("Point", place))
        u, v = (float(x) for x in found.parameters[0])
        return point(found.points[0]), Point(u, v, 0.0), float(found.distances[0])
