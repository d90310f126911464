"""Areas of closed plane polygons (rings), many at once: the one home of the shoelace formula.

Each ring is taken relative to its own first vertex, so a panel at site coordinates
(1e6 m from the origin) gets the area and orientation it has at the origin.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike

from .array_types import FloatArray


def signed_ring_areas(rings: Sequence[ArrayLike]) -> FloatArray:
    """The signed area of each closed ring ``(k, 2)`` (or ``(k, 3)``: x and y are used; the
    first vertex not repeated, or repeated: it adds nothing): positive where the ring runs
    counter-clockwise. One pass over all vertices.

    >>> signed_ring_areas([[(0, 0), (2, 0), (2, 1), (0, 1)]]).tolist()
    [2.0]
    """
    if not rings:
        return np.zeros(0)
    points = [np.asarray(r, dtype=float)[:, :2] for r in rings]
    counts = np.array([len(p) for p in points])
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
    flat = np.vstack(points) - np.repeat(np.vstack([p[0] for p in points]), counts, axis=0)
    following = np.arange(len(flat)) + 1
    following[starts + counts - 1] = starts  # each ring's last vertex closes to its first
    cross = flat[:, 0] * flat[following, 1] - flat[following, 0] * flat[:, 1]
    return np.add.reduceat(cross, starts) / 2.0


def ring_areas(rings: Sequence[ArrayLike]) -> FloatArray:
    """The area enclosed by each closed ring, whichever way it runs (see :func:`signed_ring_areas`)."""
    return np.abs(signed_ring_areas(rings))


def signed_ring_area(ring: ArrayLike) -> float:
    """The signed area of one ring: positive when it runs counter-clockwise."""
    return float(signed_ring_areas([ring])[0])
