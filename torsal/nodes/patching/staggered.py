"""patching.StaggeredPattern: one tile of a running-bond panel layout."""

from __future__ import annotations

import math
from typing import Any

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import NUMBER
from torsal.nodes.common.checks import number
from torsal.nodes.common.values import CURVE
from torsal.nodes.geometry.curves.line import Polyline
from torsal.nodes.geometry.patching import staggered_pattern
from torsal.nodes.patching.outlines import closed_polyline, rectangle


class StaggeredPattern(Node):
    """One tile of a running bond: rows of Width × Height panels, every other row shifted.

    The tile holds two panels in the XY plane: [0, Width] × [0, Height], and the one
    above it shifted along X by Offset, [Offset, Offset + Width] × [Height, 2·Height]
    (Offset is taken modulo Width). Repeated by Tile — the Width × 2·Height
    rectangle — the panels cover the plane without gaps or overlaps, each one
    whole, the way sheet panels run on the Guggenheim Bilbao. Offset = Width / 2
    gives the classic half bond; Offset = 0 a plain grid.

    Wire Pattern and Tile into SurfacePatching: the shifted panel overhangs the
    tile, so the tile, not the pattern's bounding rectangle, is the repeat.
    """

    type_id = "patching.StaggeredPattern"
    nickname, aliases = "Stagger", ("panel pattern", "brick", "running bond")
    inputs = (
        In("Width", NUMBER, "W", "Panel width along X, model units.", default=2.0),
        In("Height", NUMBER, "H", "Panel height along Y (one row), model units.", default=1.0),
        In("Offset", NUMBER, "O", "Shift of every other row along X, model units (modulo Width).",
           default=1.0),
    )
    outputs = (
        Out("Pattern", CURVE, "P", "The two panel outlines of one tile, closed polylines in XY.",
            access=LIST),
        Out("Tile", CURVE, "T", "The rectangle the pattern repeats by: Width × 2·Height."),
    )

    def solve(self, width: Any, height: Any, offset: Any) -> tuple[list[Polyline], Polyline]:
        w, h, o = number("Width", width), number("Height", height), number("Offset", offset)
        for name, value in (("Width", w), ("Height", h)):
            if value <= 0:
                raise NodeWarning(f"{name} must be a positive length, not {value:g}")
            if not math.isfinite(2.0 * value):  # the tile is 2 × Height tall, the bond 2 × Width wide
                raise NodeWarning(f"{name} is {value:g}: twice that is larger than any number can hold; "
                                  "give a panel size in model units")
        pattern = staggered_pattern(w, h, o)
        return [closed_polyline(p) for p in pattern.polygons], rectangle(pattern.period)
