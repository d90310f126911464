"""How a panel pattern covers the tile it repeats by: the panels' area against the tile's.

Repeated by its tile, a pattern covers the plane once exactly when its panels add up to
the tile's area (and do not overlap one another): less leaves gaps between the copies
(a running bond read with its bounding rectangle as the tile), more makes copies
overlap. The areas are the rings' own (the shoelace formula, each ring taken relative
to its first vertex, so a pattern far from the origin measures as at it).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from .array_types import FloatArray

#: The share of the tile's area by which the panels may differ from it and still cover
#: it once (their rounding).
COVER_TOLERANCE = 1e-9


def ring_areas(rings: Sequence[ArrayLike]) -> FloatArray:
    """The area enclosed by each closed ring ``(k, 2)`` (first vertex not repeated, or
    repeated: it adds nothing), whichever way it runs; one pass over all vertices."""
    if not rings:
        return np.zeros(0)
    points = [np.asarray(r, dtype=float)[:, :2] for r in rings]
    counts = np.array([len(p) for p in points])
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
    flat = np.vstack(points) - np.repeat(np.vstack([p[0] for p in points]), counts, axis=0)
    following = np.arange(len(flat)) + 1
    following[starts + counts - 1] = starts  # each ring's last vertex closes to its first
    cross = flat[:, 0] * flat[following, 1] - flat[following, 0] * flat[:, 1]
    return np.abs(np.add.reduceat(cross, starts)) / 2.0


@dataclass(frozen=True)
class Cover:
    """The panels' total area as a share of the tile's (1 when they cover it once)."""

    share: float

    @property
    def gaps(self) -> bool:
        """The panels fall short of the tile: the tiling leaves gaps."""
        return self.share < 1.0 - COVER_TOLERANCE

    @property
    def overlaps(self) -> bool:
        """The panels exceed the tile: repeated, they overlap."""
        return self.share > 1.0 + COVER_TOLERANCE


def pattern_cover(rings: Sequence[ArrayLike], period: ArrayLike) -> Cover:
    """How the panel ``rings`` cover the tile ``period`` = ``[xmin, ymin, xmax, ymax]``
    (which must have an area)."""
    x0, y0, x1, y1 = np.asarray(period, dtype=float)
    tile = (x1 - x0) * (y1 - y0)
    if not tile > 0:
        raise ValueError("the tile has no area")
    return Cover(float(ring_areas(rings).sum() / tile))
