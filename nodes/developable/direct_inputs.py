"""Input checks the direct-modelling developable nodes share.

Each check raises :class:`~engine.node.NodeWarning` with one sentence naming the
input and what to change, so that call is skipped and the other items still solve.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from engine.node import NodeWarning
from engine.types import describe
from nodes.curves.convert import given, number
from nodes.developable.input_checks import has_no_length
from nodes.geometry.curve_base import Curve
from nodes.limits import MAX_RULINGS as MAX_SEGMENTS
from nodes.limits import shown

#: Below this share of a shape's size a distance counts as zero.
COINCIDENT = 1e-12


def curve(value: Any, name: str = "Curve") -> Curve:
    """A curve with a length, or a warning naming what arrived instead (a zero-length
    curve is named as one, not as empty)."""
    given(name, value)
    if not isinstance(value, Curve):
        raise NodeWarning(f"{name} {describe(value)} is not a curve")
    if has_no_length(value):
        raise NodeWarning(f"{name} has zero length, so no rulings can be spaced along it")
    return value


def segments(value: Any) -> int:
    """Segments, the number of rulings minus one: a whole number from 1 to MAX_SEGMENTS."""
    given("Segments", value)
    n = int(value)
    if n < 1:
        raise NodeWarning(
            f"Segments is {shown(n)}: give 1 or more (Segments is the number of rulings minus one)"
        )
    if n > MAX_SEGMENTS:
        raise NodeWarning(f"Segments is {shown(n)}; at most {MAX_SEGMENTS:,} can be made at once")
    return n


def length(name: str, value: Any) -> float:
    """A finite, non-zero ruling length in model units (negative reverses the rulings)."""
    x = number(name, value)
    if x == 0:
        raise NodeWarning(f"{name} is 0, so the rulings would have no length: give a length")
    return x


def positive(name: str, value: Any) -> float:
    """A finite, positive length in model units."""
    x = number(name, value)
    if x <= 0:
        raise NodeWarning(f"{name} must be a positive length, not {x:g}")
    return x


def first_where(mask: np.ndarray, parameters: np.ndarray) -> str:
    """'k of n stations (first at t = …)' for a boolean mask over stations."""
    k = int(np.count_nonzero(mask))
    return f"{k} of {mask.size} stations (first at t = {float(parameters[np.argmax(mask)]):.4g})"


def along_tangent(directions: np.ndarray, tangents: np.ndarray, tolerance: float = 1e-9) -> np.ndarray:
    """Where a ruling direction is parallel to the curve's tangent: the strip has no width there."""
    d = directions / np.maximum(np.linalg.norm(directions, axis=1), 1e-300)[:, None]
    t = tangents / np.maximum(np.linalg.norm(tangents, axis=1), 1e-300)[:, None]
    moving = np.linalg.norm(tangents, axis=1) > 0
    return moving & (np.linalg.norm(np.cross(d, t), axis=1) <= tolerance)
