"""SurfaceAnalysis's colours: bright pink where a surface is single-curved within the
tolerance, dark purple where it is double-curved, with a sharp step at the tolerance.

The scale runs over min(|k1|, |k2|) from 0 to twice the tolerance (the tolerance in
the middle of the colour bar): within it, pink from bright (flat in one direction)
to deep; above it, purple from medium to dark; beyond twice the tolerance, darkest
purple.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

#: (position on the scale, RGB): position 0 is min|k| = 0, 0.5 the tolerance, 1 twice it.
STOPS: tuple[tuple[float, tuple[int, int, int]], ...] = (
    (0.0, (255, 110, 199)),  # bright pink: single-curved
    (0.5, (224, 33, 138)),  # deep pink: at the tolerance
    (0.5, (106, 27, 122)),  # purple: just above it
    (1.0, (42, 10, 61)),  # dark purple: double-curved
)

#: Entries in the colour bar's lookup table.
TABLE = 256


def colours(ratio: ArrayLike) -> NDArray[np.uint8]:
    """RGBA colours (uint8, ``(n, 4)``) for ``ratio`` = min(|k1|, |k2|) / tolerance."""
    x = np.clip(np.asarray(ratio, dtype=float) / 2.0, 0.0, 1.0)
    x = np.where(np.isfinite(x), x, 1.0)
    below = x <= 0.5
    (p0, c0), (p1, c1), (p2, c2), (p3, c3) = STOPS
    lo = np.asarray(c0) + ((x - p0) / (p1 - p0))[:, None] * (np.asarray(c1) - np.asarray(c0))
    hi = np.asarray(c2) + ((x - p2) / (p3 - p2))[:, None] * (np.asarray(c3) - np.asarray(c2))
    rgb = np.where(below[:, None], lo, hi)
    return np.column_stack([np.round(rgb), np.full(len(x), 255)]).astype(np.uint8)


def colour_table() -> list[str]:
    """The scale as ``TABLE`` ``#rrggbb`` colours, for the viewport's colour bar."""
    ratio = (np.arange(TABLE) + 0.5) / TABLE * 2.0
    return ["#{:02x}{:02x}{:02x}".format(*row[:3]) for row in colours(ratio).tolist()]
