"""Where a curve crosses a plane: section points, as Grasshopper's Curve | Plane."""

from __future__ import annotations

from typing import Any

import numpy as np

from torsal.engine.node import LIST, In, Node, Out
from torsal.engine.types import NUMBER, PLANE, POINT
from torsal.engine.values import WORLD_XY, Point
from torsal.nodes.common.checks import given
from torsal.nodes.common.convert import kernel_plane, points
from torsal.nodes.common.values import CURVE
from torsal.nodes.geometry.intersections import curve_plane_intersections


class CurvePlane(Node):
    """Every point where a curve crosses or touches a plane, in order along the curve.

    Crossings are found on a fine sampling of the curve and refined to rounding;
    touching points count when the curve comes within 1e-10 of its size of the plane. A
    stretch lying in the plane gives its sampled points; two crossings closer together
    than the sampling can be missed.
    """

    type_id = "curves.CurvePlane"
    nickname, aliases = "PCX", ("Curve | Plane", "Curve Plane", "section points", "intersect plane")
    inputs = (
        In("Curve", CURVE, "C", "The curve to cut."),
        In("Plane", PLANE, "P", "The cutting plane.", default=WORLD_XY),
    )
    outputs = (
        Out("Points", POINT, "P", "The points where the curve meets the plane.", access=LIST),
        Out("Parameters", NUMBER, "t", "Their curve parameters, 0 to 1.", access=LIST),
    )

    def solve(self, curve: Any, plane: Any) -> tuple[list[Point], list[float]]:
        c = given("Curve", curve)
        frame = kernel_plane("Plane", plane)
        box = np.asarray(c.bounding_box(), dtype=float)
        size = float(np.linalg.norm(box[1] - box[0])) or 1.0
        hits = curve_plane_intersections(c, frame, tolerance=1e-10 * size)
        return points(hits.points), [float(t) for t in hits.parameters]
