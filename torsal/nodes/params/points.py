"""Points from coordinates."""

from __future__ import annotations

import numpy as np

from torsal.engine.datatree import Branch
from torsal.engine.node import LIST, Node, Out
from torsal.engine.types import POINT
from torsal.engine.values import Point as PointValue
from torsal.nodes.params.coordinates import xyz_inputs, xyz_rows


class Point(Node):
    """A point from its X, Y and Z coordinates.

    Give lists to make many points at once: X = [0, 1, 2] with Y = 0 and Z = 0 gives
    three points along the X axis (the shorter lists repeat their last value).
    """

    type_id = "params.Point"
    nickname, aliases = "Pt", ("Construct Point", "Point XYZ", "xyz")
    inputs = xyz_inputs(
        "Distance along the X axis, in model units.",
        "Distance along the Y axis, in model units.",
        "Height along the Z axis, in model units.",
    )
    outputs = (Out("Point", POINT, "P", "The point at (X, Y, Z), one for each item of the lists.",
                   access=LIST),)

    def solve(self, x: Branch, y: Branch, z: Branch) -> np.ndarray | list[PointValue | None]:
        return xyz_rows(self, x, y, z, PointValue)
