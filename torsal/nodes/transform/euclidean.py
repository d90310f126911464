"""Transforms of a single piece of geometry: move, rotate, scale, mirror and orient."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsal.engine.node import In, Node, NodeWarning, Out
from torsal.engine.types import GENERIC, NUMBER, PLANE, POINT, VECTOR
from torsal.engine.values import WORLD_XY, Point, Vector
from torsal.nodes.common.checks import number, xyz
from torsal.nodes.common.convert import WORLD_YZ, kernel_plane
from torsal.nodes.geometry import transforms
from torsal.nodes.transform.dispatch import SUPPORTED, transform_value

GEOMETRY = In("Geometry", GENERIC, "G", f"What to transform: {SUPPORTED}.")
MOVED = Out("Geometry", GENERIC, "G", "The transformed copy; the input is left as it was.")


def _factor(name: str, value: Any) -> float:
    factor = number(name, value)
    if factor == 0:
        raise NodeWarning(f"{name} is 0, which would flatten the geometry to nothing")
    return factor


class _Transform(Node):
    """Shared solve: build the matrix from the inputs after Geometry, then apply it."""

    def matrix(self, *args: Any) -> np.ndarray:
        raise NotImplementedError

    def solve(self, geometry: Any, *args: Any) -> Any:
        return transform_value(geometry, self.matrix(*args))


class Move(_Transform):
    """Move geometry by a vector: every point travels Motion's length in Motion's direction.

    Vectors are directions, so moving one leaves it unchanged.
    """

    type_id = "transform.Move"
    nickname, aliases = "Move", ("translate",)
    inputs = (
        GEOMETRY,
        In("Motion", VECTOR, "T", "How far and which way to move, in model units.",
           default=Vector(0.0, 0.0, 10.0)),
    )
    outputs = (MOVED,)

    def matrix(self, motion: Any) -> np.ndarray:
        return transforms.translation(xyz("Motion", motion))


class Rotate(_Transform):
    """Turn geometry by Angle radians about the Plane's normal, through its origin.

    A positive angle turns counter-clockwise seen from the side the normal points
    to (right-handed): Angle π/2 in the XY plane takes the X axis to the Y axis.
    """

    type_id = "transform.Rotate"
    nickname, aliases = "Rot", ("turn",)
    inputs = (
        GEOMETRY,
        In("Angle", NUMBER, "A", "Rotation angle in radians, counter-clockwise about the normal.",
           default=math.pi / 2),
        In("Plane", PLANE, "P", "Rotation axis: the plane's normal through its origin.",
           default=WORLD_XY),
    )
    outputs = (MOVED,)

    def matrix(self, angle: Any, plane: Any) -> np.ndarray:
        frame = kernel_plane("Plane", plane)
        return transforms.rotation(frame.z, number("Angle", angle), frame.origin)


class Scale(_Transform):
    """Scale geometry uniformly by Factor about a Centre point, which stays put.

    Factor 2 doubles every distance from the Centre; 0.5 halves it; a negative
    Factor also turns the geometry through the Centre.
    """

    type_id = "transform.Scale"
    nickname, aliases = "Scale", ("Scale Uniform",)
    inputs = (
        GEOMETRY,
        In("Centre", POINT, "C", "The point that stays where it is.", default=Point(0, 0, 0)),
        In("Factor", NUMBER, "F", "How many times larger to make it (not 0).", default=0.5),
    )
    outputs = (MOVED,)

    def matrix(self, centre: Any, factor: Any) -> np.ndarray:
        return transforms.scaling(_factor("Factor", factor), xyz("Centre", centre))


class ScaleNonUniform(_Transform):
    """Scale geometry by different factors along the Plane's X, Y and Z axes.

    The Plane's origin stays put. X = 2, Y = 1, Z = 1 stretches twice as long along
    the Plane's X axis: a circle becomes an ellipse. Angles are not kept, so curves
    and surfaces are transformed as general affine images.
    """

    type_id = "transform.ScaleNonUniform"
    nickname, aliases = "ScaleNU", ("Scale NU", "Scale Non Uniform")
    inputs = (
        GEOMETRY,
        In("Plane", PLANE, "P", "The axes to scale along; its origin stays put.", default=WORLD_XY),
        In("X", NUMBER, "X", "Factor along the Plane's X axis (not 0).", default=1.0),
        In("Y", NUMBER, "Y", "Factor along the Plane's Y axis (not 0).", default=1.0),
        In("Z", NUMBER, "Z", "Factor along the Plane's normal (not 0).", default=1.0),
    )
    outputs = (MOVED,)

    def matrix(self, plane: Any, x: Any, y: Any, z: Any) -> np.ndarray:
        frame = kernel_plane("Plane", plane)
        factors = (_factor("X", x), _factor("Y", y), _factor("Z", z))
        return transforms.non_uniform_scaling(factors, plane=frame)


class Mirror(_Transform):
    """Reflect geometry in a Plane, as in a mirror standing on it.

    The default, the world YZ plane, swaps left and right: x becomes −x.
    """

    type_id = "transform.Mirror"
    nickname, aliases = "Mirror", ("reflect",)
    inputs = (
        GEOMETRY,
        In("Plane", PLANE, "P", "The mirror plane.", default=WORLD_YZ),
    )
    outputs = (MOVED,)

    def matrix(self, plane: Any) -> np.ndarray:
        return transforms.mirror(kernel_plane("Plane", plane))


class Orient(_Transform):
    """Carry geometry from a Source plane to a Target plane, without changing its shape.

    The Source's origin lands on the Target's origin and its X and Y axes on the
    Target's: geometry drawn on the world XY plane is placed on any other plane.
    """

    type_id = "transform.Orient"
    nickname, aliases = "Orient", ("plane to plane",)
    inputs = (
        GEOMETRY,
        In("Source", PLANE, "A", "The plane the geometry is placed relative to.", default=WORLD_XY),
        In("Target", PLANE, "B", "Where the Source plane goes."),
    )
    outputs = (MOVED,)

    def matrix(self, source: Any, target: Any) -> np.ndarray:
        return transforms.orient(kernel_plane("Source", source), kernel_plane("Target", target))
