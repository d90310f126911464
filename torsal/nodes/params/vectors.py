"""Vectors from components, and the unit vectors along the axes."""

from __future__ import annotations

import numpy as np

from torsal.engine.datatree import Branch
from torsal.engine.node import LIST, In, Node, Out
from torsal.engine.types import NUMBER, VECTOR
from torsal.engine.values import Vector as VectorValue
from torsal.nodes.params.coordinates import as_float_columns, each_row, paired_count, xyz_inputs, xyz_rows

_ZERO = "The vector has zero length, so it has no direction"


class Vector(Node):
    """A vector from its X, Y and Z components: a direction with a length.

    A zero-length vector (0, 0, 0) is allowed but has no direction; the node
    remarks on it because nodes that need a direction cannot use it.
    """

    type_id = "params.Vector"
    nickname, aliases = "Vec", ("Vector XYZ", "Construct Vector")
    inputs = xyz_inputs(
        "Component along the X axis, in model units.",
        "Component along the Y axis, in model units.",
        "Component along the Z axis, in model units.",
    )
    outputs = (Out("Vector", VECTOR, "V", "The vector (X, Y, Z), one for each item of the lists.",
                   access=LIST),)

    def solve(self, x: Branch, y: Branch, z: Branch) -> np.ndarray | list[VectorValue | None]:
        made = xyz_rows(self, x, y, z, VectorValue)
        if isinstance(made, np.ndarray):
            zero = bool((made == 0.0).all(axis=1).any())
        else:
            zero = any(v is not None and v.length == 0.0 for v in made)
        if zero:
            self.remark(_ZERO)
        return made


class _Unit(Node):
    """Shared solve of UnitX, UnitY and UnitZ: the axis direction scaled by Factor."""

    axis = 0  # index of the component Factor goes into

    def solve(self, factor: Branch) -> np.ndarray | list[VectorValue | None]:
        columns = {"Factor": factor}
        count = paired_count(self, columns)
        if count == 0:
            return []
        factors = as_float_columns(columns, count)
        if factors is None:
            return each_row(self, columns, count, self._vector)
        xyz = np.zeros((count, 3))
        xyz[:, self.axis] = factors[:, 0]
        return xyz  # an (n, 3) array: the tree holds it as Triples of vectors

    def _vector(self, factor: float) -> VectorValue:
        components = [0.0, 0.0, 0.0]
        components[self.axis] = factor
        return VectorValue(*components)


def _factor(axis: str) -> In:
    return In("Factor", NUMBER, "F",
              f"Length of the vector along {axis}, in model units; negative points backwards.",
              default=1.0, access=LIST, arrays=True)


class UnitX(_Unit):
    """A vector along the X axis, Factor long: (Factor, 0, 0)."""

    type_id = "params.UnitX"
    nickname, aliases = "X", ("X axis",)
    axis = 0
    inputs = (_factor("X"),)
    outputs = (Out("Vector", VECTOR, "V", "The vector (Factor, 0, 0), one for each Factor.", access=LIST),)


class UnitY(_Unit):
    """A vector along the Y axis, Factor long: (0, Factor, 0)."""

    type_id = "params.UnitY"
    nickname, aliases = "Y", ("Y axis",)
    axis = 1
    inputs = (_factor("Y"),)
    outputs = (Out("Vector", VECTOR, "V", "The vector (0, Factor, 0), one for each Factor.", access=LIST),)


class UnitZ(_Unit):
    """A vector along the Z axis, Factor long: (0, 0, Factor)."""

    type_id = "params.UnitZ"
    nickname, aliases = "Z", ("Z axis", "up")
    axis = 2
    inputs = (_factor("Z"),)
    outputs = (Out("Vector", VECTOR, "V", "The vector (0, 0, Factor), one for each Factor.", access=LIST),)
