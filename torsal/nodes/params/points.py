"""Points from coordinates."""

from __future__ import annotations

import numpy as np

from torsal.engine.datatree import Branch
from torsal.engine.node import LIST, In, Node, Out
from torsal.engine.types import NUMBER, POINT
from torsal.engine.values import Point as PointValue
from torsal.nodes.params.coordinates import as_float_columns, each_row, paired_count


class Point(Node):
    """A point from its X, Y and Z coordinates.

    Give lists to make many points at once: X = [0, 1, 2] with Y = 0 and Z = 0 gives
    three points along the X axis (the shorter lists repeat their last value).
    """

    type_id = "params.Point"
    nickname, aliases = "Pt", ("Construct Point", "Point XYZ", "xyz")
    inputs = (
        In("X", NUMBER, "X", "Distance along the X axis, in model units.", default=0.0,
           access=LIST, arrays=True),
        In("Y", NUMBER, "Y", "Distance along the Y axis, in model units.", default=0.0,
           access=LIST, arrays=True),
        In("Z", NUMBER, "Z", "Height along the Z axis, in model units.", default=0.0,
           access=LIST, arrays=True),
    )
    outputs = (Out("Point", POINT, "P", "The point at (X, Y, Z), one for each item of the lists.",
                   access=LIST),)

    def solve(self, x: Branch, y: Branch, z: Branch) -> np.ndarray | list[PointValue | None]:
        columns = {"X": x, "Y": y, "Z": z}
        count = paired_count(self, columns)
        if count == 0:
            return []
        xyz = as_float_columns(columns, count)
        if xyz is not None:
            return xyz  # an (n, 3) array: the tree holds it as Triples of points
        return each_row(self, columns, count, PointValue)
