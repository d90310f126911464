"""Frames on curves (the Frenet plane at a parameter, planes square to a curve along it)
and the point of a curve closest to a given point.

A curve's Frenet frame at t is its unit tangent T, its unit principal normal N (towards
the centre of curvature) and the binormal B = T × N. Where the curve is straight N has
no direction of its own; it is then a fixed unit vector square to T, so every frame is
valid (see ``Curve.frames_at`` in the kernel).
"""

from __future__ import annotations

from typing import Any

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import INTEGER, NUMBER, PLANE, POINT
from torsal.engine.values import Plane, Point, Vector
from torsal.nodes.common.checks import given, number, whole, xyz
from torsal.nodes.common.values import CURVE
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.limits import MAX_DIVISIONS


def _curve(value: Any) -> Curve:
    return given("Curve", value)


def _plane(origin: Any, x: Any, y: Any) -> Plane:
    return Plane(Point(*map(float, origin)), Vector(*map(float, x)), Vector(*map(float, y)))


class CurveFrame(Node):
    """The Frenet plane of a curve at a parameter t from 0 to 1.

    Its X axis is the unit tangent, its Y axis the principal normal (towards the centre
    of curvature) and its normal the binormal: on a circle in the XY plane run
    anticlockwise, every frame's Y axis points at the centre and its normal is +z.
    """

    type_id = "curves.CurveFrame"
    nickname, aliases = "CFrame", ("Curve Frame", "Frenet frame", "frame on curve")
    inputs = (
        In("Curve", CURVE, "C", "The curve to read."),
        In("Parameter", NUMBER, "t", "Where on the curve, from 0 (start) to 1 (end).", default=0.0),
    )
    outputs = (Out("Frame", PLANE, "F", "The plane at t: X the tangent, Y the principal normal."),)

    def solve(self, curve: Any, parameter: Any) -> Plane:
        c = _curve(curve)
        t = number("Parameter", parameter)
        if not -1e-12 <= t <= 1 + 1e-12:
            raise NodeWarning(f"Parameter must be from 0 to 1 (the curve's domain), not {t:g}")
        frames = c.frames_at([min(max(t, 0.0), 1.0)])
        return _plane(frames.origins[0], frames.tangents[0], frames.normals[0])


class PerpFrames(Node):
    """Planes square to a curve at Count + 1 points equally spaced along it: cutting planes.

    Each plane's normal is the curve's tangent there, its X axis the principal normal
    and its Y axis the binormal, so sections cut with them follow the curve the way
    the ribs of a hull follow its keel. A closed curve gives Count planes.
    """

    type_id = "curves.PerpFrames"
    nickname, aliases = "PFrames", ("Perp Frames", "Perp Frame", "Curve Frames", "section planes")
    inputs = (
        In("Curve", CURVE, "C", "The curve to follow."),
        In("Count", INTEGER, "N", "How many equal segments to space the planes by (1 or more).",
           default=10, min=1, max=MAX_DIVISIONS),
    )
    outputs = (
        Out("Frames", PLANE, "F", "The planes, from the start; each normal is the tangent.", access=LIST),
        Out("Parameters", NUMBER, "t", "The curve parameter t of each plane, 0 to 1.", access=LIST),
    )

    def solve(self, curve: Any, count: Any) -> tuple[list[Plane], list[float]]:
        c = _curve(curve)
        n = whole("Count", count)
        if c.length == 0:
            raise NodeWarning("The curve has zero length, so it has no tangent to be square to")
        t = c.divide_by_count(n)
        f = c.frames_at(t)
        planes = [_plane(o, x, y) for o, x, y in zip(f.origins, f.normals, f.binormals, strict=True)]
        return planes, t.tolist()


class CurveClosestPoint(Node):
    """The point of a curve closest to a given point, its parameter t and the distance.

    The global closest point, not merely a local one: the curve is sampled finely enough
    to find every stretch that could hold it, then refined by Newton's method to
    rounding. On a closed curve with two equally close points, either may be given.
    """

    type_id = "curves.CurveClosestPoint"
    nickname, aliases = "CrvCP", ("Curve Closest Point", "closest point", "pull point", "project point")
    inputs = (
        In("Point", POINT, "P", "The point to look from."),
        In("Curve", CURVE, "C", "The curve to find the closest point on."),
    )
    outputs = (
        Out("Point", POINT, "P", "The closest point on the curve."),
        Out("Parameter", NUMBER, "t", "Its curve parameter, 0 to 1."),
        Out("Distance", NUMBER, "D", "How far it is from Point."),
    )

    def solve(self, place: Any, curve: Any) -> tuple[Point, float, float]:
        c = _curve(curve)
        found = c.closest_point(xyz("Point", place))
        origin = found.points[0]
        return Point(*map(float, origin)), float(found.parameters[0]), float(found.distances[0])
