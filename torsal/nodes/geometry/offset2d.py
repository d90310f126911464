"""Planar polygon offsets with mitred corners (shapely), for kerf compensation.

A laser or router removes a kerf of width k centred on its path; moving the path
outwards by k/2 leaves the part at its drawn size. Corners stay sharp (mitre joins)
up to ``mitre_limit`` times the offset, beyond which a spike is bevelled, as CAM
software does.

>>> square = [[0, 0], [10, 0], [10, 10], [0, 10]]
>>> offset_polygon(square, 0.5).tolist()[:2]
[[-0.5, -0.5], [10.5, -0.5]]
"""

from __future__ import annotations

import numpy as np
import shapely
from numpy.typing import ArrayLike, NDArray


def offset_polygon(points: ArrayLike, distance: float, mitre_limit: float = 5.0) -> NDArray[np.float64]:
    """The outline moved outwards by ``distance`` (inwards when negative), counter-clockwise,
    without the repeated closing point, starting from its lowest-left vertex.

    Raises ValueError when an inward offset swallows the polygon or splits it in pieces.
    """
    polygon = shapely.Polygon(np.asarray(points, dtype=float)[:, :2])
    if distance == 0:
        grown = polygon
    else:
        grown = polygon.buffer(distance, join_style="mitre", mitre_limit=mitre_limit)
    if grown.is_empty or grown.geom_type != "Polygon":
        raise ValueError(f"An offset of {distance:g} does not leave one piece of this outline.")
    ring = np.asarray(shapely.geometry.polygon.orient(grown, 1.0).exterior.coords)[:-1]
    start = int(np.lexsort((ring[:, 0], ring[:, 1]))[0])
    return np.roll(ring, -start, axis=0)
