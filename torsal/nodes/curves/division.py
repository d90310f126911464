"""Dividing a curve by a length: points every L along it, as a tape measure would mark them."""

from __future__ import annotations

import math
from typing import Any

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import NUMBER, POINT, VECTOR
from torsal.engine.values import Point, Vector
from torsal.nodes.common.checks import given, positive
from torsal.nodes.common.convert import points, vectors
from torsal.nodes.common.values import CURVE
from torsal.nodes.limits import MAX_DIVISIONS


class DivideLength(Node):
    """Points every Length along a curve, measured along it from its start.

    The start is always a point; the end only when the curve's length is a whole number
    of Lengths (what is left over is shorter than Length). On a closed curve the start
    is not repeated. For a given number of equal pieces use Divide Curve.
    """

    type_id = "curves.DivideLength"
    nickname, aliases = "DivLength", ("Divide Length", "measure along", "points every", "Divide Distance")
    inputs = (
        In("Curve", CURVE, "C", "The curve to mark."),
        In("Length", NUMBER, "L", "The distance between neighbouring points, along the curve.", default=1.0),
    )
    outputs = (
        Out("Points", POINT, "P", "The points, from the start.", access=LIST),
        Out("Tangents", VECTOR, "T", "The unit tangent at each point.", access=LIST, preview=False),
        Out("Parameters", NUMBER, "t", "The curve parameter t of each point, 0 to 1.", access=LIST),
    )

    def solve(self, curve: Any, length: Any) -> tuple[list[Point], list[Vector], list[float]]:
        c = given("Curve", curve)
        step = positive("Length", length)
        total = c.length
        if total == 0:
            raise NodeWarning("The curve has zero length, so it cannot be divided")
        count = math.floor(total / step * (1 + 1e-9))
        if count > MAX_DIVISIONS:
            raise NodeWarning(
                f"Length {step:g} would divide this {total:g} long curve into {count:,} pieces; "
                f"at most {MAX_DIVISIONS:,}: give a longer Length"
            )
        t = c.divide_by_length(step)
        return points(c.point_at(t)), vectors(c.tangent_at(t)), t.tolist()
