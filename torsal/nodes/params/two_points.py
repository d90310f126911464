"""What two points make: the vector from one to the other, and the distance between them."""

from __future__ import annotations

from typing import Any

import numpy as np

from torsal.engine.node import In, Node, Out
from torsal.engine.types import BOOLEAN, NUMBER, POINT, VECTOR
from torsal.engine.values import Vector
from torsal.nodes.common.checks import direction, xyz
from torsal.nodes.common.convert import vector


class VectorTwoPoints(Node):
    """The vector from point A to point B (B − A), made unit length when Unit is true."""

    type_id = "params.VectorTwoPoints"
    nickname, aliases = "Vec2Pt", ("Vector 2Pt", "vector between points", "direction from points")
    inputs = (
        In("A", POINT, "A", "Where the vector starts."),
        In("B", POINT, "B", "Where the vector ends."),
        In("Unit", BOOLEAN, "U", "Make the vector one unit long (its direction only).", default=False),
    )
    outputs = (
        Out("Vector", VECTOR, "V", "B − A (or its direction, Unit long)."),
        Out("Length", NUMBER, "L", "The distance from A to B."),
    )

    def solve(self, a: Any, b: Any, unit: Any) -> tuple[Vector, float]:
        start, end = xyz("A", a), xyz("B", b)
        span = end - start
        length = float(np.linalg.norm(span))
        if unit:
            span = direction("B − A", span) / length
        return vector(span), length


class Distance(Node):
    """The straight distance between two points."""

    type_id = "params.Distance"
    nickname, aliases = "Dist", ("Distance", "point distance", "length between points")
    inputs = (In("A", POINT, "A", "The first point."), In("B", POINT, "B", "The second point."))
    outputs = (Out("Distance", NUMBER, "D", "|B − A|, in model units."),)

    def solve(self, a: Any, b: Any) -> float:
        return float(np.linalg.norm(xyz("B", b) - xyz("A", a)))
