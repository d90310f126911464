"""Arrays: many copies of a piece of geometry, in a row or around an axis."""

from __future__ import annotations

import math
from typing import Any

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import GENERIC, INTEGER, NUMBER, PLANE, VECTOR
from torsal.engine.values import WORLD_XY, Vector
from torsal.nodes.common.checks import direction, number, whole
from torsal.nodes.common.convert import kernel_plane
from torsal.nodes.geometry import transforms
from torsal.nodes.limits import MAX_COPIES
from torsal.nodes.transform.dispatch import SUPPORTED, transform_value


class Array(Node):
    """Copies of geometry in a row: copy k is moved k times by Direction.

    Count includes the original (copy 0, unmoved): Count 4 with Direction (2, 0, 0)
    gives copies at x offsets 0, 2, 4 and 6. Each piece of geometry gets its own
    list of copies.
    """

    type_id = "transform.Array"
    nickname, aliases = "ArrLin", ("Linear Array", "copy")
    inputs = (
        In("Geometry", GENERIC, "G", f"What to copy: {SUPPORTED}."),
        In("Direction", VECTOR, "D", "The step between neighbouring copies.",
           default=Vector(10.0, 0.0, 0.0)),
        In("Count", INTEGER, "N", "How many copies, the original included (1 or more).", default=10,
           min=1, max=MAX_COPIES),
    )
    outputs = (Out("Geometry", GENERIC, "G", "The copies, the unmoved one first.", access=LIST),)

    def solve(self, geometry: Any, step: Any, count: Any) -> list[Any]:
        d = direction("Direction", step)
        n = whole("Count", count)  # 1 to MAX_COPIES: the port's bounds
        return [transform_value(geometry, transforms.translation(k * d)) for k in range(n)]


class PolarArray(Node):
    """Copies of geometry around an axis: copy k is turned by k × Angle / Count.

    The axis is the Plane's normal through its origin, and turns are
    counter-clockwise about it. With the default Angle of a full turn (2π), Count
    copies are spaced evenly all the way round; with Angle π and Count 4 they are
    at 0, 45°, 90° and 135°. Count includes the original.
    """

    type_id = "transform.PolarArray"
    nickname, aliases = "ArrPolar", ("radial array",)
    inputs = (
        In("Geometry", GENERIC, "G", f"What to copy: {SUPPORTED}."),
        In("Plane", PLANE, "P", "The axis: the plane's normal through its origin.", default=WORLD_XY),
        In("Count", INTEGER, "N", "How many copies, the original included (1 or more).", default=6,
           min=1, max=MAX_COPIES),
        In("Angle", NUMBER, "A", "The angle Count steps add up to, in radians.", default=2 * math.pi),
    )
    outputs = (Out("Geometry", GENERIC, "G", "The copies, the unturned one first.", access=LIST),)

    def solve(self, geometry: Any, plane: Any, count: Any, angle: Any) -> list[Any]:
        frame = kernel_plane("Plane", plane)
        n = whole("Count", count)  # 1 to MAX_COPIES: the port's bounds
        sweep = number("Angle", angle)
        if sweep == 0:
            raise NodeWarning("Angle is 0, so every copy would sit on the original")
        return [
            transform_value(geometry, transforms.rotation(frame.z, k * sweep / n, frame.origin))
            for k in range(n)
        ]
