"""Engine values to kernel arrays and back, and kernel errors to node warnings.

Engine values on wires are small tuples (:class:`~torsal.engine.values.Point`,
:class:`~torsal.engine.values.Plane` ...); the kernel takes numpy arrays and its own
orthonormal :class:`~torsal.nodes.geometry.vectors.Plane`. Nodes convert at their boundary
with these helpers; a value that cannot be converted is refused as
:mod:`torsal.nodes.common.checks` says (a warning naming the input).
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import numpy as np

from torsal.engine.node import NodeWarning
from torsal.engine.values import Plane, Point, Vector
from torsal.nodes.common.checks import ZERO_LENGTH, given, xyz
from torsal.nodes.geometry.vectors import Plane as KernelPlane

#: The world YZ plane as an engine value (Mirror's default: reflects x to −x).
WORLD_YZ = Plane(Point(0, 0, 0), Vector(0, 1, 0), Vector(0, 0, 1))


def kernel_plane(name: str, plane: Any) -> KernelPlane:
    """An engine :class:`~torsal.engine.values.Plane` as the kernel's orthonormal frame.

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


def _xyz(array: Any) -> list[float]:
    return [float(c) for c in np.asarray(array, dtype=float)[:3]]


def point(array: Any) -> Point:
    """A kernel ``(3,)`` array as an engine :class:`~torsal.engine.values.Point`."""
    x, y, z = _xyz(array)
    return Point(x, y, z)


def points(array: Any) -> list[Point]:
    """An ``(n, 3)`` array as a list of :class:`~torsal.engine.values.Point` (for node outputs)."""
    return [Point(x, y, z) for x, y, z in np.asarray(array, dtype=float).tolist()]


def vector(array: Any) -> Vector:
    """A kernel ``(3,)`` array as an engine :class:`~torsal.engine.values.Vector`."""
    x, y, z = np.asarray(array, dtype=float).reshape(3).tolist()
    return Vector(x, y, z)


def vectors(array: Any) -> list[Vector]:
    """An ``(n, 3)`` array as a list of :class:`~torsal.engine.values.Vector`."""
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
