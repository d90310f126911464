"""Closed outlines between the patching nodes and the kernel: curves ↔ ``(k, 2)`` rings.

Patterns live in the XY plane; a pattern curve is read as the ring of its vertices
(a polyline) or of a fine tessellation (a circle, a spline), its z dropped.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from torsal.engine.node import NodeWarning
from torsal.engine.types import describe
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curves.line import Polyline

#: Tessellation tolerance of a smooth pattern curve, as a share of its size.
TESSELLATION = 1e-4

#: Relative tolerance for "closed" and "in the XY plane".
FLAT = 1e-9


def ring(name: str, value: Any) -> tuple[np.ndarray, bool]:
    """The closed curve ``value`` as an open ring ``(k, 2)`` and whether it left the XY plane."""
    if value is None:
        raise NodeWarning(f"{name} is empty (null): remove it or fix what made it")
    if not isinstance(value, Curve):
        raise NodeWarning(f"{name} {describe(value)} is not a curve")
    if isinstance(value, Polyline):
        points = np.asarray(value.points, dtype=float)
    else:
        size = float(np.ptp(value.bounding_box(), axis=0).max()) or 1.0
        points = value.point_at(value.tessellate(TESSELLATION * size))
    size = float(np.ptp(points, axis=0).max()) or 1.0
    if not (value.closed or np.abs(points[0] - points[-1]).max() <= FLAT * size):
        raise NodeWarning(f"{name} is open: a panel outline must be a closed curve")
    off_plane = bool(np.ptp(points[:, 2]) > FLAT * size)
    flat = points[:, :2]
    if np.abs(flat[0] - flat[-1]).max() <= FLAT * size:
        flat = flat[:-1]
    if len(flat) < 3:
        raise NodeWarning(f"{name} has fewer than 3 corners, so it encloses no area")
    return flat, off_plane


def closed_polyline(points2d_or_3d: ArrayLike) -> Polyline:
    """A closed polyline through the rows of ``(k, 2)`` (placed at z = 0) or ``(k, 3)``."""
    p = np.asarray(points2d_or_3d, dtype=float)
    if p.shape[1] == 2:
        p = np.column_stack([p, np.zeros(len(p))])
    return Polyline(p, closed=True)


def corners(bounds: ArrayLike) -> np.ndarray:
    """The corners ``(4, 2)`` of the rectangle ``[xmin, ymin, xmax, ymax]``, counter-clockwise."""
    x0, y0, x1, y1 = np.asarray(bounds, dtype=float)
    return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1]])


def rectangle(bounds: ArrayLike) -> Polyline:
    """The closed rectangle ``[xmin, ymin, xmax, ymax]`` in the XY plane, counter-clockwise."""
    return closed_polyline(corners(bounds))
