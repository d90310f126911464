"""Points from coordinates."""

from __future__ import annotations

from engine.node import In, Node, Out
from engine.types import NUMBER, POINT
from engine.values import Point as PointValue
from nodes.common.checks import finite


class Point(Node):
    """A point from its X, Y and Z coordinates.

    Give lists to make many points at once: X = [0, 1, 2] with Y = 0 and Z = 0 gives
    three points along the X axis (the shorter lists repeat their last value).
    """

    type_id = "params.Point"
    inputs = (
        In("X", NUMBER, "X", "Distance along the X axis, in model units.", default=0.0),
        In("Y", NUMBER, "Y", "Distance along the Y axis, in model units.", default=0.0),
        In("Z", NUMBER, "Z", "Height along the Z axis, in model units.", default=0.0),
    )
    outputs = (Out("Point", POINT, "P", "The point at (X, Y, Z)."),)

    def solve(self, x: float, y: float, z: float) -> PointValue:
        return PointValue(finite("X", x), finite("Y", y), finite("Z", z))
