"""The input checks of curves and surfaces, under the rule in :mod:`torsal.nodes.common.checks`.

Each refuses a value with a :class:`~torsal.engine.node.NodeWarning` naming the input: that call
is skipped and the node's other items still solve.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import numpy as np

from torsal.engine.node import NodeWarning
from torsal.engine.types import describe
from torsal.nodes.common.checks import given
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.surface_base import Surface
from torsal.nodes.geometry.trimesh_type import TriangleMesh

#: Where a curve is sampled to see that it is not a single point.
_SAMPLES = np.linspace(0.0, 1.0, 65)

#: Samples spread less than this share of the curve's distance from the origin are one
#: point (rounding: the curve's length, measured by quadrature, is then noise).
_ROUNDING = 1e-14

NOT_RULED = (
    "surface has no straight rulings: {node} works on ruled surfaces (a loft between two curves, "
    "or the output of the developable nodes); analyse a double-curved surface with SurfaceAnalysis"
)


def has_no_length(curve: Curve) -> bool:
    """Whether ``curve`` is a single point: its ends and samples all coincide (to
    rounding), or its length is not a positive number. A zero-length line, a spline or
    NURBS curve through one point, an expression curve that does not move."""
    ends = curve.end_points
    start, end = ends
    # (a NaN in the ends makes the gap NaN, which is never above: on to the samples)
    if np.abs(end - start).max() > _ROUNDING * np.abs(ends).max():
        return False  # ends apart: not a point (only a closed curve or a point needs samples)
    points = curve.point_at(_SAMPLES)
    if not np.isfinite(points).all():
        return not curve.length > 0
    spread = float(np.ptp(points, axis=0).max())
    scale = float(np.abs(points).max())
    # a point has no size to be relative to: rounding is relative to its coordinates
    return not (np.abs(end - start).max() > _ROUNDING * scale or spread > _ROUNDING * scale)


def curves_with_length(values: Iterable[Any]) -> set[int]:
    """The ids of the curves among ``values`` whose ends lie apart (to rounding), found for
    all of them at once: :func:`has_no_length` is False for each without looking further
    (the others, and what is not a curve, are left to it)."""
    curves = list({id(value): value for value in values if isinstance(value, Curve)}.values())
    if not curves:
        return set()
    ends = np.array([curve.end_points for curve in curves])  # (curves, 2, 3)
    apart = np.abs(ends[:, 1] - ends[:, 0]).max(axis=1) > _ROUNDING * np.abs(ends).max(axis=(1, 2))
    return {id(curve) for curve, ok in zip(curves, apart.tolist(), strict=True) if ok}


def curve(name: str, value: Any) -> Curve:
    """A curve with a length; a zero-length one says so (naming the input), not that it is empty."""
    if value is None:
        raise NodeWarning(f"{name} is empty: connect a curve")
    if not isinstance(value, Curve):
        raise NodeWarning(f"{name} {describe(value)} is not a curve")
    if has_no_length(value):
        raise NodeWarning(f"{name} has zero length, so no rulings can be spaced along it")
    return value


def surface(name: str, value: Any) -> Surface:
    """A surface; the port's type has already refused anything else."""
    return given(name, value)


def parametric_surface(name: str, value: Any) -> Surface:
    """A parameterised surface (not a mesh)."""
    if value is None:
        raise NodeWarning(f"{name} is empty: connect a surface")
    if isinstance(value, MeshSurface):
        raise NodeWarning(f"{name} is a mesh surface, which has no (u, v) parameters and no rulings")
    if not isinstance(value, Surface):
        raise NodeWarning(f"{name} {describe(value)} is not a surface")
    return value


def surface_or_mesh(name: str, value: Any, lacking: str) -> Surface | MeshSurface:
    """A surface or a mesh surface, or a mesh taken as a mesh surface; a mesh with no faces
    is refused as having no ``lacking`` ("curvature to count", "surface to analyse")."""
    g = given(name, value)
    if isinstance(g, Surface | MeshSurface):
        return g
    if isinstance(g, TriangleMesh):
        if len(g.faces) == 0:
            raise NodeWarning(f"The mesh has no faces, so it has no {lacking}")
        return MeshSurface(g)
    raise NodeWarning(f"{name} {describe(g)} is not a surface: give a surface, a mesh or a mesh surface")


def ruled_surface(value: Any, node: str) -> Surface:
    """A parameterised surface with straight rulings, or a warning saying it has none."""
    s = surface("Surface", value)
    if not s.is_ruled:
        raise NodeWarning(NOT_RULED.format(node=node))
    return s
