"""Engine values to kernel arrays and back, with the input checks curve and transform nodes share.

Engine values on wires are small tuples (:class:`~engine.values.Point`,
:class:`~engine.values.Plane` ...); the kernel takes numpy arrays and its own
orthonormal :class:`~nodes.geometry.vectors.Plane`. Nodes convert at their boundary
with these helpers. Each check raises :class:`~engine.node.NodeWarning` with one
sentence naming the input, so that call is skipped and the other items still solve.
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from typing import Any

import numpy as np

from engine.node import NodeWarning
from engine.values import Plane, Point, Vector
from nodes.geometry.vectors import Plane as KernelPlane
from nodes.maths.checks import finite

#: Below this length (model units) a direction counts as zero.
ZERO_LENGTH = 1e-12

#: The world YZ plane as an engine value (Mirror's default: reflects x to −x).
WORLD_YZ = Plane(Point(0, 0, 0), Vector(0, 1, 0), Vector(0, 0, 1))


def given(name: str, value: Any) -> Any:
    """``value``, or a warning that the input ``name`` is empty (null)."""
    if value is None:
        raise NodeWarning(f"{name} is empty (null)")
    return value


def xyz(name: str, value: Any) -> np.ndarray:
    """A point or vector as a ``(3,)`` array with finite coordinates."""
    array = np.asarray(given(name, value), dtype=float)
    if not np.all(np.isfinite(array)):
        raise NodeWarning(f"{name} has a coordinate that is not a finite number")
    return array


def direction(name: str, value: Any) -> np.ndarray:
    """A vector that must have a direction: not (almost) zero length."""
    array = xyz(name, value)
    if float(np.linalg.norm(array)) <= ZERO_LENGTH:
        raise NodeWarning(f"{name} has zero length, so it has no direction")
    return array


def point_list(name: str, values: Sequence[Any]) -> np.ndarray:
    """A list of points as an ``(n, 3)`` array; empty (null) or non-finite items are refused."""
    if any(v is None for v in values):
        raise NodeWarning(f"{name} contains empty (null) items: remove them or fix what made them")
    array = np.asarray(values, dtype=float).reshape(-1, 3)
    if not np.all(np.isfinite(array)):
        raise NodeWarning(f"{name} contains a point with a coordinate that is not a finite number")
    return array


number = finite
"""A finite number, or a warning saying it is empty, NaN or infinite (one check for all palettes)."""


def kernel_plane(name: str, plane: Any) -> KernelPlane:
    """An engine :class:`~engine.values.Plane` as the kernel's orthonormal frame.

    The y axis is made perpendicular to x (Gram–Schmidt), as in Rhino; x must have a
    length and y must not be parallel to it.
    """
    given(name, plane)
    origin, x, y = (xyz(name, part) for part in plane)
    if not np.isfinite(np.linalg.norm(np.concatenate([x, y]))):  # an axis near 1e308: its length overflows
        raise NodeWarning(f"{name}'s axes are too long to measure (past 1e154): give axes of ordinary length")
    if float(np.linalg.norm(x)) <= ZERO_LENGTH:
        raise NodeWarning(f"{name}'s X axis has zero length, so the plane has no orientation")
    x = x / np.linalg.norm(x)
    y_perp = y - (y @ x) * x
    if float(np.linalg.norm(y_perp)) <= ZERO_LENGTH * max(1.0, float(np.linalg.norm(y))):
        raise NodeWarning(f"{name}'s X and Y axes are parallel, so they span no plane")
    return KernelPlane.from_axes(origin, x, y_perp)


def engine_plane(plane: KernelPlane) -> Plane:
    """A kernel plane as the engine value on wires (origin, x, y)."""
    return Plane(Point(*plane.origin.tolist()), Vector(*plane.x.tolist()), Vector(*plane.y.tolist()))


def vector(array: Any) -> Vector:
    """A kernel ``(3,)`` array as an engine :class:`~engine.values.Vector`."""
    x, y, z = np.asarray(array, dtype=float).reshape(3).tolist()
    return Vector(x, y, z)


def vectors(array: Any) -> list[Vector]:
    """An ``(n, 3)`` array as a list of :class:`~engine.values.Vector`."""
    return [Vector(x, y, z) for x, y, z in np.asarray(array, dtype=float).reshape(-1, 3).tolist()]


def sentence(exc: BaseException) -> str:
    """A kernel error message in the nodes' style: one sentence, no final full stop."""
    return str(exc).strip().rstrip(".")


@contextmanager
def kernel_errors() -> Iterator[None]:
    """Turn the kernel's ``ValueError`` (already a plain sentence) into a warning for this call."""
    try:
        yield
    except ValueError as exc:
        raise NodeWarning(sentence(exc)) from None
