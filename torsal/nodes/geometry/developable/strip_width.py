"""How wide a strip is across: the distance between its two boundary curves.

A strip's rulings need not run across it: where they run nearly along its boundaries (as
next to a line along an asymptotic direction) they are long while the strip is narrow, so
a ruling's length says nothing about whether a sheet that narrow can be made. The width
here is measured across: from points evenly spaced along each rail, the distance to the
other rail (a dense polyline of it, whose chords sag far below any MinWidth), and the
median of those — a strip that tapers to a point at one end is as wide as most of it is.
"""

from __future__ import annotations

import numpy as np

from ..array_types import FloatArray
from ..curve_base import Curve

#: Points along each rail measured, and the polyline's vertices on the other.
SAMPLES = 129


def width_across(curve_a: Curve, curve_b: Curve, count: int = SAMPLES) -> float:
    """The median distance from points evenly spaced along each of ``curve_a`` and
    ``curve_b`` (parameters 0 … 1) to the other curve."""
    u = np.linspace(0.0, 1.0, count)
    a, b = curve_a.point_at(u), curve_b.point_at(u)
    return float(np.median(np.concatenate([to_polyline(a, b), to_polyline(b, a)])))


def to_polyline(points: FloatArray, polyline: FloatArray) -> FloatArray:
    """Each point's distance to the polyline through ``polyline``'s vertices in order."""
    start, edge = polyline[:-1], np.diff(polyline, axis=0)
    length2 = np.einsum("ij,ij->i", edge, edge)
    offset = points[:, None, :] - start[None, :, :]
    along = np.einsum("pij,ij->pi", offset, edge) / np.where(length2 > 0, length2, 1.0)
    nearest = start[None] + np.clip(along, 0.0, 1.0)[..., None] * edge[None]
    return np.linalg.norm(points[:, None, :] - nearest, axis=2).min(axis=1)
