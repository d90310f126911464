"""Points and vectors taken apart into their coordinates."""

from __future__ import annotations

from typing import Any

import numpy as np

from torsal.engine.node import In, Node, Out
from torsal.engine.types import NUMBER, POINT, VECTOR
from torsal.nodes.common.checks import xyz


class DeconstructPoint(Node):
    """The X, Y and Z coordinates of a point."""

    type_id = "params.DeconstructPoint"
    nickname, aliases = "pDecon", ("Deconstruct Point", "Deconstruct", "point coordinates", "xyz of point")
    inputs = (In("Point", POINT, "P", "The point to take apart."),)
    outputs = (
        Out("X", NUMBER, "X", "Its x coordinate."),
        Out("Y", NUMBER, "Y", "Its y coordinate."),
        Out("Z", NUMBER, "Z", "Its z coordinate."),
    )

    def solve(self, value: Any) -> tuple[float, float, float]:
        x, y, z = (float(c) for c in xyz("Point", value))
        return x, y, z


class DeconstructVector(Node):
    """The X, Y and Z components of a vector, and its length."""

    type_id = "params.DeconstructVector"
    nickname, aliases = "DeVec", ("Deconstruct Vector", "vector components", "Vector Length", "Amplitude")
    inputs = (In("Vector", VECTOR, "V", "The vector to take apart."),)
    outputs = (
        Out("X", NUMBER, "X", "Its x component."),
        Out("Y", NUMBER, "Y", "Its y component."),
        Out("Z", NUMBER, "Z", "Its z component."),
        Out("Length", NUMBER, "L", "Its length, sqrt(X² + Y² + Z²)."),
    )

    def solve(self, value: Any) -> tuple[float, float, float, float]:
        array = xyz("Vector", value)
        x, y, z = (float(c) for c in array)
        return x, y, z, float(np.linalg.norm(array))
