"""Small immutable value classes the engine knows natively: points, vectors, domains, planes.

They are tuples underneath, so ``numpy.asarray(point)`` gives ``[x, y, z]`` without the
engine importing numpy.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import NamedTuple, Self


class Triple(tuple):
    """Three floats with ``x``, ``y``, ``z`` accessors: the base of points and vectors."""

    __slots__ = ()

    def __new__(cls, x: float = 0.0, y: float = 0.0, z: float = 0.0) -> Triple:
        return tuple.__new__(cls, (float(x), float(y), float(z)))

    @classmethod
    def many(cls, rows: Iterable[list[float]]) -> list[Self]:
        """``[cls(*row) for row in rows]`` for rows of three Python floats (a float array's
        ``tolist()``), taking the floats as they are rather than converting each again:
        1.25× faster on EvaluateCurve's batched calls and 1.6× on VectorAnalysis' 10⁵
        vectors (the speed trick docs/contributing.md keeps; a test holds it to the
        constructor's values)."""
        make = tuple.__new__
        return [make(cls, row) for row in rows]

    x = property(lambda self: self[0])
    y = property(lambda self: self[1])
    z = property(lambda self: self[2])

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self[0]:g}, {self[1]:g}, {self[2]:g})"


class Point(Triple):
    """A location in model space."""

    __slots__ = ()


class Vector(Triple):
    """A direction and magnitude."""

    __slots__ = ()

    @property
    def length(self) -> float:
        return math.hypot(self[0], self[1], self[2])  # ** 2 raises OverflowError from 1e155


class Domain(NamedTuple):
    """A numeric interval from ``min`` to ``max`` (``min`` may exceed ``max``: a reversed domain)."""

    min: float
    max: float

    @property
    def length(self) -> float:
        return self.max - self.min

    def __repr__(self) -> str:
        return f"Domain({self.min:g} to {self.max:g})"


class Plane(NamedTuple):
    """An origin with two in-plane axes (``x``, ``y``); ``z`` is their cross product."""

    origin: Point
    x: Vector
    y: Vector

    @property
    def z(self) -> Vector:
        (ax, ay, az), (bx, by, bz) = self.x, self.y
        return Vector(ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx)


WORLD_XY = Plane(Point(0, 0, 0), Vector(1, 0, 0), Vector(0, 1, 0))
UNIT_X = Vector(1, 0, 0)
UNIT_Y = Vector(0, 1, 0)
UNIT_Z = Vector(0, 0, 1)
