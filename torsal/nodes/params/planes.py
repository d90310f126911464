"""Planes: the world planes, a plane from axes, a normal or three points, and its parts.

A plane on a wire is an origin with an X and a Y axis (its Z axis is X × Y), as in
Grasshopper. The planes these nodes make are orthonormal: the Y axis is made
perpendicular to X (Gram–Schmidt), as Rhino does.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from torsal.engine.node import In, Node, NodeWarning, Out
from torsal.engine.types import PLANE, POINT, VECTOR
from torsal.engine.values import UNIT_X, UNIT_Y, UNIT_Z, WORLD_XY, Plane, Point, Vector
from torsal.nodes.common.checks import direction, xyz
from torsal.nodes.common.convert import engine_plane, kernel_plane, point, vector
from torsal.nodes.geometry.vectors import Plane as KernelPlane

ORIGIN = Point(0.0, 0.0, 0.0)


def _origin_input() -> In:
    return In("Origin", POINT, "O", "Where the plane's origin is.", default=ORIGIN)


def _world(origin: Any, x: Vector, y: Vector) -> Plane:
    return Plane(point(xyz("Origin", origin)), x, y)


class XYPlane(Node):
    """The world XY plane (the ground), moved to Origin: X along x, Y along y, normal +z."""

    type_id = "params.XYPlane"
    nickname, aliases = "XY", ("Plane", "ground plane", "World XY", "top plane")
    inputs = (_origin_input(),)
    outputs = (Out("Plane", PLANE, "P", "The plane parallel to world XY through Origin."),)

    def solve(self, origin: Any) -> Plane:
        return _world(origin, UNIT_X, UNIT_Y)


class XZPlane(Node):
    """The world XZ plane (a front elevation), moved to Origin: X along x, Y along z, normal −y."""

    type_id = "params.XZPlane"
    nickname, aliases = "XZ", ("front plane", "World XZ", "elevation plane")
    inputs = (_origin_input(),)
    outputs = (Out("Plane", PLANE, "P", "The plane parallel to world XZ through Origin."),)

    def solve(self, origin: Any) -> Plane:
        return _world(origin, UNIT_X, UNIT_Z)


class YZPlane(Node):
    """The world YZ plane (a side elevation), moved to Origin: X along y, Y along z, normal +x."""

    type_id = "params.YZPlane"
    nickname, aliases = "YZ", ("side plane", "World YZ", "right plane")
    inputs = (_origin_input(),)
    outputs = (Out("Plane", PLANE, "P", "The plane parallel to world YZ through Origin."),)

    def solve(self, origin: Any) -> Plane:
        return _world(origin, UNIT_Y, UNIT_Z)


class ConstructPlane(Node):
    """A plane from its origin and two axes.

    The X axis keeps its direction; Y is turned in the plane of the two axes until it
    is perpendicular to X. The axes must not be parallel.
    """

    type_id = "params.ConstructPlane"
    nickname, aliases = "Pl", ("Construct Plane", "plane from axes")
    inputs = (
        _origin_input(),
        In("XAxis", VECTOR, "X", "Direction of the plane's X axis.", default=UNIT_X),
        In("YAxis", VECTOR, "Y", "A direction on the plane's Y side, not parallel to X.", default=UNIT_Y),
    )
    outputs = (Out("Plane", PLANE, "P", "The plane, with unit, perpendicular axes."),)

    def solve(self, origin: Any, x_axis: Any, y_axis: Any) -> Plane:
        return engine_plane(kernel_plane("Plane", Plane(origin, x_axis, y_axis)))


class DeconstructPlane(Node):
    """The origin and the three unit axes of a plane."""

    type_id = "params.DeconstructPlane"
    nickname, aliases = "DePlane", ("Deconstruct Plane", "plane origin", "plane axes")
    inputs = (In("Plane", PLANE, "P", "The plane to take apart.", default=WORLD_XY),)
    outputs = (
        Out("Origin", POINT, "O", "The plane's origin."),
        Out("XAxis", VECTOR, "X", "The unit X axis.", preview=False),
        Out("YAxis", VECTOR, "Y", "The unit Y axis, perpendicular to X.", preview=False),
        Out("ZAxis", VECTOR, "Z", "The unit normal, X × Y.", preview=False),
    )

    def solve(self, plane: Any) -> tuple[Point, Vector, Vector, Vector]:
        frame = kernel_plane("Plane", plane)
        return point(frame.origin), vector(frame.x), vector(frame.y), vector(frame.z)


class PlaneNormal(Node):
    """A plane through Origin square to a Normal, as a sheet lies on a table.

    Its X axis is the world x axis laid into the plane (the world y axis when the normal
    is almost along x), so a normal of +z gives the world XY plane.
    """

    type_id = "params.PlaneNormal"
    nickname, aliases = "PlN", ("Plane Normal", "plane from normal", "plane origin normal")
    inputs = (
        _origin_input(),
        In("Normal", VECTOR, "Z", "The plane's normal (its Z axis).", default=UNIT_Z),
    )
    outputs = (Out("Plane", PLANE, "P", "The plane through Origin with that normal."),)

    def solve(self, origin: Any, normal: Any) -> Plane:
        return engine_plane(KernelPlane.from_normal(xyz("Origin", origin), direction("Normal", normal)))


class PlaneThreePoints(Node):
    """The plane through three points: origin at A, X axis towards B, C on its +Y side."""

    type_id = "params.PlaneThreePoints"
    nickname, aliases = "Pl3Pt", ("Plane 3Pt", "plane from points", "plane through points")
    inputs = (
        In("A", POINT, "A", "The origin."),
        In("B", POINT, "B", "A point along the X axis."),
        In("C", POINT, "C", "A point on the plane's +Y side."),
    )
    outputs = (Out("Plane", PLANE, "P", "The plane through A, B and C."),)

    def solve(self, a: Any, b: Any, c: Any) -> Plane:
        pa, pb, pc = xyz("A", a), xyz("B", b), xyz("C", c)
        x, y = pb - pa, pc - pa
        size = max(float(abs(x).max()), float(abs(y).max()))
        cross = float(np.abs(np.cross(x, y)).max())
        if size == 0 or cross <= 1e-12 * size * size:
            raise NodeWarning("A, B and C lie on one line (or coincide), so they span no plane")
        return engine_plane(KernelPlane.from_axes(pa, x, y))
