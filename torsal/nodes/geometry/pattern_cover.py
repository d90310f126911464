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

from .polygons import ring_areas

#: The share of the tile's area by which the panels may differ from it and still cover
#: it once (their rounding).
COVER_TOLERANCE = 1e-9


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
