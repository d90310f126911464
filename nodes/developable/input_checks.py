"""Input checks for the approximation nodes (RulingDevelopable, SplineApproximation,
SurfaceCoupling).

These nodes cannot do anything sensible with a wrong input, so each check raises
:class:`~engine.node.NodeError` with one sentence naming the input and what to change.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from engine.node import NodeError
from engine.types import describe
from nodes.geometry.curve_base import Curve
from nodes.geometry.mesh_surface import MeshSurface
from nodes.geometry.surface_base import Surface
from nodes.limits import MAX_RULINGS as MAX_SEGMENTS
from nodes.limits import shown

#: Where a curve is sampled to see that it is not a single point.
_SAMPLES = np.linspace(0.0, 1.0, 65)

#: Samples spread less than this share of the curve's distance from the origin are one
#: point (rounding: the curve's length, measured by quadrature, is then noise).
_ROUNDING = 1e-14


def has_no_length(curve: Curve) -> bool:
    """Whether ``curve`` is a single point: its ends and samples all coincide (to
    rounding), or its length is not a positive number. A zero-length line, a spline or
    NURBS curve through one point, an expression curve that does not move."""
    start, end = curve.end_points
    points = curve.point_at(_SAMPLES)
    if not np.isfinite(points).all():
        return not curve.length > 0
    spread = float(np.ptp(points, axis=0).max())
    scale = float(np.abs(points).max())
    # a point has no size to be relative to: rounding is relative to its coordinates
    return not (np.abs(end - start).max() > _ROUNDING * scale or spread > _ROUNDING * scale)


def curve_input(name: str, value: Any) -> Curve:
    """A curve with a length; a zero-length one says so (naming the input), not that it is empty."""
    if value is None:
        raise NodeError(f"{name} is empty: connect a curve")
    if not isinstance(value, Curve):
        raise NodeError(f"{name} {describe(value)} is not a curve")
    if has_no_length(value):
        raise NodeError(f"{name} has zero length, so no rulings can be spaced along it")
    return value


def surface_input(name: str, value: Any) -> Surface:
    """A parameterised surface (not a mesh)."""
    if value is None:
        raise NodeError(f"{name} is empty: connect a surface")
    if isinstance(value, MeshSurface):
        raise NodeError(f"{name} is a mesh surface, which has no (u, v) parameters and no rulings")
    if not isinstance(value, Surface):
        raise NodeError(f"{name} {describe(value)} is not a surface")
    return value


def segments_input(value: Any, limit: int = MAX_SEGMENTS) -> int:
    """Segments, the number of rulings minus one: a whole number from 1 to ``limit``."""
    if value is None:
        raise NodeError("Segments is empty: give the number of rulings minus one")
    n = int(value)
    if n < 1:
        raise NodeError(
            f"Segments is {shown(n)}: give 1 or more (Segments is the number of rulings minus one)"
        )
    if n > limit:
        raise NodeError(f"Segments is {shown(n)}; at most {limit:,} can be made at once")
    return n


def tolerance_input(name: str, value: Any) -> float:
    """An angle tolerance in rad: finite and not negative."""
    if value is None:
        raise NodeError(f"{name} is empty: give an angle in rad, such as 0.01")
    x = float(value)
    if not math.isfinite(x) or x < 0:
        raise NodeError(f"{name} must be an angle of 0 rad or more, such as 0.01, not {x:g}")
    return x


def edge_input(name: str, value: Any) -> int:
    """A surface edge number, 0 to 3 (0: v = 0, 1: u = 1, 2: v = 1, 3: u = 0)."""
    if value is None:
        raise NodeError(f"{name} is empty: give an edge number from 0 to 3")
    n = int(value)
    if not 0 <= n <= 3:
        raise NodeError(f"{name} is {n}: edges are numbered 0 (v = 0), 1 (u = 1), 2 (v = 1) and 3 (u = 0)")
    return n
