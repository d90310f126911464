"""Vectors from components, and the unit vectors along the axes."""

from __future__ import annotations

from engine.node import In, Node, Out
from engine.types import NUMBER, VECTOR
from engine.values import Vector as VectorValue
from nodes.common.checks import finite


class Vector(Node):
    """A vector from its X, Y and Z components: a direction with a length.

    A zero-length vector (0, 0, 0) is allowed but has no direction; the node
    remarks on it because nodes that need a direction cannot use it.
    """

    type_id = "params.Vector"
    inputs = (
        In("X", NUMBER, "X", "Component along the X axis, in model units.", default=0.0),
        In("Y", NUMBER, "Y", "Component along the Y axis, in model units.", default=0.0),
        In("Z", NUMBER, "Z", "Component along the Z axis, in model units.", default=0.0),
    )
    outputs = (Out("Vector", VECTOR, "V", "The vector (X, Y, Z)."),)

    def solve(self, x: float, y: float, z: float) -> VectorValue:
        vector = VectorValue(finite("X", x), finite("Y", y), finite("Z", z))
        if vector.length == 0.0:
            self.remark("The vector has zero length, so it has no direction")
        return vector


class _Unit(Node):
    """Shared solve of UnitX, UnitY and UnitZ: the axis direction scaled by Factor."""

    axis = 0  # index of the component Factor goes into

    def solve(self, factor: float) -> VectorValue:
        components = [0.0, 0.0, 0.0]
        components[self.axis] = finite("Factor", factor)
        return VectorValue(*components)


def _factor(axis: str) -> In:
    return In("Factor", NUMBER, "F",
              f"Length of the vector along {axis}, in model units; negative points backwards.",
              default=1.0)


class UnitX(_Unit):
    """A vector along the X axis, Factor long: (Factor, 0, 0)."""

    type_id = "params.UnitX"
    axis = 0
    inputs = (_factor("X"),)
    outputs = (Out("Vector", VECTOR, "V", "The vector (Factor, 0, 0)."),)


class UnitY(_Unit):
    """A vector along the Y axis, Factor long: (0, Factor, 0)."""

    type_id = "params.UnitY"
    axis = 1
    inputs = (_factor("Y"),)
    outputs = (Out("Vector", VECTOR, "V", "The vector (0, Factor, 0)."),)


class UnitZ(_Unit):
    """A vector along the Z axis, Factor long: (0, 0, Factor)."""

    type_id = "params.UnitZ"
    axis = 2
    inputs = (_factor("Z"),)
    outputs = (Out("Vector", VECTOR, "V", "The vector (0, 0, Factor)."),)
