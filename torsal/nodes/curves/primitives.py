"""Straight and circular curves: Line, Polyline, Circle and Arc."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import BOOLEAN, DOMAIN, NUMBER, PLANE, POINT
from torsal.engine.values import WORLD_XY, Domain
from torsal.nodes.common.checks import number, point_list, xyz
from torsal.nodes.common.convert import kernel_errors, kernel_plane
from torsal.nodes.common.values import CURVE, LINE
from torsal.nodes.geometry import curves as kernel


def _radius(value: Any) -> float:
    radius = number("Radius", value)
    if radius <= 0:
        raise NodeWarning(f"Radius must be a positive length, not {radius:g}")
    return radius


class Line(Node):
    """A straight line from Start to End, the simplest curve.

    Its parameter t runs from 0 at Start to 1 at End in proportion to the distance
    travelled. Start = (0, 0, 0) and End = (3, 4, 0) give a line 5 long. Equal Start
    and End give a zero-length line, with a warning (the nodes it feeds say that their
    curve has zero length).
    """

    type_id = "curves.Line"
    nickname, aliases = "Ln", ("Line SDL", "two point line")
    inputs = (
        In("Start", POINT, "A", "Where the line starts."),
        In("End", POINT, "B", "Where the line ends; must differ from Start."),
    )
    outputs = (Out("Line", LINE, "L", "The line from Start to End."),)

    def solve(self, start: Any, end: Any) -> kernel.Line:
        a, b = xyz("Start", start), xyz("End", end)
        if np.array_equal(a, b):
            # hand on the zero-length line, so the nodes downstream can say what is wrong
            self.warn("Start and End are the same point, so the line has zero length")
        return kernel.Line(a, b)


class Polyline(Node):
    """Straight segments joining the Vertices in order.

    With Closed on, a last segment returns from the last vertex to the first (unless
    the last vertex already repeats the first). The parameter t is the fraction of
    the length travelled, so evaluating at evenly spaced t gives evenly spaced points.
    Vertices that are all one point give a zero-length line there, with a warning.
    """

    type_id = "curves.Polyline"
    nickname, aliases = "PLine", ("PolyLine", "open polygon")
    inputs = (
        In("Vertices", POINT, "V", "The corner points, in order (at least 2).", access=LIST),
        In("Closed", BOOLEAN, "C", "Whether to join the last vertex back to the first.",
           default=False),
    )
    outputs = (Out("Polyline", CURVE, "Pl", "The polyline through the vertices."),)

    def solve(self, vertices: list[Any], closed: bool) -> kernel.Polyline | kernel.Line:
        points = point_list("Vertices", vertices)
        if len(points) < 2:
            raise NodeWarning(f"A polyline needs at least 2 vertices; got {len(points)}")
        if np.all(points == points[0]):
            self.warn("All the vertices are the same point, so the polyline has zero length")
            return kernel.Line(points[0], points[0])
        return kernel.Polyline(points, closed=bool(closed))


class Circle(Node):
    """A circle of Radius centred on the Plane's origin, lying in the Plane.

    It starts on the Plane's X axis and runs counter-clockwise seen from the side the
    Plane's normal points to. It is an exact rational NURBS circle: every point is at
    distance Radius from the centre to rounding error.
    """

    type_id = "curves.Circle"
    nickname, aliases = "Cir", ("Circle CNR",)
    inputs = (
        In("Plane", PLANE, "P", "The circle's plane; its origin is the centre.", default=WORLD_XY),
        In("Radius", NUMBER, "R", "Distance from the centre, in model units (positive).",
           default=1.0),
    )
    outputs = (Out("Circle", CURVE, "C", "The closed circle."),)

    def solve(self, plane: Any, radius: Any) -> kernel.Circle:
        frame = kernel_plane("Plane", plane)
        return kernel.Circle(frame, _radius(radius))


class Arc(Node):
    """A circular arc in a Plane, centred on its origin, over an Angle domain.

    Angles are in radians, measured counter-clockwise from the Plane's X axis about
    its normal: Angle 0 to π/2 is the quarter circle from the X axis to the Y axis.
    A reversed domain (π/2 to 0) gives the same arc run clockwise. The arc is at
    most a full turn; its length is Radius × (the domain's length).
    """

    type_id = "curves.Arc"
    nickname, aliases = "Arc", ("circular arc",)
    inputs = (
        In("Plane", PLANE, "P", "The arc's plane; its origin is the centre.", default=WORLD_XY),
        In("Radius", NUMBER, "R", "Distance from the centre, in model units (positive).",
           default=1.0),
        In("Angle", DOMAIN, "A", "Start and end angle in radians, from the Plane's X axis.",
           default=Domain(0.0, math.pi / 2)),
    )
    outputs = (Out("Arc", CURVE, "A", "The arc from the start angle to the end angle."),)

    def solve(self, plane: Any, radius: Any, angle: Any) -> Any:
        frame = kernel_plane("Plane", plane)
        r = _radius(radius)
        if angle is None:
            raise NodeWarning("Angle is empty (null)")
        a, b = number("Angle start", angle.min), number("Angle end", angle.max)
        sweep = abs(b - a)
        if sweep == 0:
            raise NodeWarning(f"The Angle domain is empty ({a:g} to {b:g}), so the arc would have no length")
        if sweep > 2 * math.pi * (1 + 1e-12):
            raise NodeWarning(
                f"The Angle domain spans {sweep:g} radians, more than a full turn (2π ≈ 6.28319)"
            )
        with kernel_errors():
            if a < b:
                return kernel.Arc(frame, r, a, b)
            return kernel.Arc(frame, r, b, a).reversed()
