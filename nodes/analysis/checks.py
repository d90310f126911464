"""Input checks the analysis nodes share; each failure is one sentence saying what to change."""

from __future__ import annotations

import math
from typing import Any

from engine.node import NodeError, NodeWarning
from nodes.geometry.surface_base import Surface
from nodes.limits import MAX_ANALYSIS_SEGMENTS as MAX_SEGMENTS
from nodes.maths.checks import count, finite
from nodes.surfaces.convert import surface

NOT_RULED = (
    "surface has no straight rulings: {node} works on ruled surfaces (a loft between two curves, "
    "or the output of the developable nodes); analyse a double-curved surface with SurfaceAnalysis"
)


def ruled_surface(value: Any, node: str) -> Surface:
    """A parameterised surface with straight rulings, or an error saying it has none."""
    s = surface(value)
    if not s.is_ruled:
        raise NodeError(NOT_RULED.format(node=node))
    return s


def segments(value: Any, name: str = "Segments") -> int:
    """The number of strips between rulings: a whole number from 1 to MAX_SEGMENTS."""
    return count(name, value, least=1, limit=MAX_SEGMENTS)


def angle(name: str, value: Any, example: str, largest: float = math.pi / 2) -> float:
    """A positive tolerance angle in radians, at most ``largest``."""
    x = finite(name, value)
    if x <= 0:
        raise NodeWarning(f"{name} must be a positive angle in radians (e.g. {example}), not {x:g}")
    if x > largest:
        raise NodeWarning(f"{name} is {x:g} rad; it is an angle in radians, at most {largest:.4g} (π/2)")
    return x
