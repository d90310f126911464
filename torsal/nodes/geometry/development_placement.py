"""Where a flat development is laid in model space: a rigid motion of its XY frame.

A development is computed in its own XY frame (the first ruling from the origin up
the Y axis). To show it where it reads — beside the 3D model rather than through
it — its frame is carried onto a :class:`~torsal.nodes.geometry.vectors.Plane`: the point
``(x, y)`` of the development goes to ``plane.origin + x·plane.x + y·plane.y``. The
plane's axes are orthonormal, so the motion is rigid: every length, angle and area of
the development is kept, only positions move.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .array_types import FloatArray
from .vec_ops import bounds
from .vectors import Plane

#: The gap between the model and a development laid beside it, as a share of the
#: model's size (its bounding box's longest side).
BESIDE_GAP = 0.2

#: The development's own frame: the world XY plane (no motion).
WORLD_XY = Plane(np.zeros(3), np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]), np.array([0.0, 0.0, 1.0]))


def beside_model(model_points: ArrayLike, flat_bounds: ArrayLike, gap: float = BESIDE_GAP) -> Plane:
    """The frame that lays a development flat beside a 3D model, in +X.

    ``model_points`` ``(n, 3)`` are points of the model (their bounding box is the
    model's); ``flat_bounds`` is the development's ``[xmin, ymin, xmax, ymax]`` in its
    own frame. The development stays parallel to the world XY plane, at the height of
    the model's lowest point; its least x lies ``gap`` × the model's size past the
    model's greatest x, and its least y level with the model's least y. A translation
    only, so the development keeps its orientation.
    """
    points = np.asarray(model_points, dtype=float).reshape(-1, 3)
    low, high = bounds(points)
    xmin, ymin = np.asarray(flat_bounds, dtype=float)[:2]
    size = float(np.max(high - low))
    origin = np.array([high[0] + gap * size - xmin, low[1] - ymin, low[2]])
    return Plane(origin, WORLD_XY.x, WORLD_XY.y, WORLD_XY.z)


def place(frame: Plane, points2d: ArrayLike) -> FloatArray:
    """The development points ``(n, 2)`` (or ``(n, 3)`` with z = 0) carried onto ``frame``: ``(n, 3)``."""
    p = np.asarray(points2d, dtype=float)
    return frame.point_at(p[..., 0], p[..., 1])
