"""Closed outlines in a plane: rectangles and regular polygons (panel and sheet outlines)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsal.engine.node import In, Node, Out
from torsal.engine.types import INTEGER, NUMBER, PLANE
from torsal.engine.values import WORLD_XY
from torsal.nodes.common.checks import positive, whole
from torsal.nodes.common.convert import kernel_plane
from torsal.nodes.common.values import CURVE
from torsal.nodes.geometry import curves as kernel
from torsal.nodes.limits import MAX_SEGMENTS

PLANE_INPUT = In("Plane", PLANE, "P", "The plane the outline lies in, centred on its origin.",
                 default=WORLD_XY)


class Rectangle(Node):
    """A rectangle Width × Height centred on the Plane's origin, its sides along the
    Plane's X and Y axes; a closed polyline running anticlockwise about the Plane's normal."""

    type_id = "curves.Rectangle"
    nickname, aliases = "Rec", ("Rectangle", "rect", "sheet outline", "panel outline")
    inputs = (
        PLANE_INPUT,
        In("Width", NUMBER, "X", "The side along the Plane's X axis, in model units.", default=1.0),
        In("Height", NUMBER, "Y", "The side along the Plane's Y axis, in model units.", default=1.0),
    )
    outputs = (
        Out("Rectangle", CURVE, "R", "The closed outline."),
        Out("Length", NUMBER, "L", "Its perimeter, 2 × (Width + Height)."),
    )

    def solve(self, plane: Any, width: Any, height: Any) -> tuple[kernel.Polyline, float]:
        frame = kernel_plane("Plane", plane)
        w, h = positive("Width", width) / 2, positive("Height", height) / 2
        corners = frame.point_at(np.array([-w, w, w, -w]), np.array([-h, -h, h, h]))
        return kernel.Polyline(corners, closed=True), 4.0 * (w + h)


class Polygon(Node):
    """A regular polygon of Segments sides, its corners on a circle of Radius around the
    Plane's origin, the first on the Plane's X axis; a closed polyline."""

    type_id = "curves.Polygon"
    nickname, aliases = "Pol", ("Polygon", "regular polygon", "hexagon", "triangle")
    inputs = (
        PLANE_INPUT,
        In("Radius", NUMBER, "R", "From the centre to each corner, in model units.", default=1.0),
        In("Segments", INTEGER, "S", "How many sides (3 or more).", default=6, min=3, max=MAX_SEGMENTS),
    )
    outputs = (
        Out("Polygon", CURVE, "P", "The closed outline."),
        Out("Length", NUMBER, "L", "Its perimeter, 2 n R sin(π / n)."),
    )

    def solve(self, plane: Any, radius: Any, segments: Any) -> tuple[kernel.Polyline, float]:
        frame = kernel_plane("Plane", plane)
        r, n = positive("Radius", radius), whole("Segments", segments)
        angles = 2 * math.pi * np.arange(n) / n
        corners = frame.point_at(r * np.cos(angles), r * np.sin(angles))
        return kernel.Polyline(corners, closed=True), 2 * n * r * math.sin(math.pi / n)
