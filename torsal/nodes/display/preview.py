"""Preview and Tag: display hints for the viewport."""

from __future__ import annotations

import math
from typing import Any

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import GENERIC, NUMBER, POINT, TEXT
from torsal.engine.values import Point
from torsal.nodes.common.checks import given, xyz
from torsal.nodes.display.hints import STYLED, TAG, StyledGeometry, parse_colour
from torsal.nodes.display.hints import Tag as TagValue


def _colour(text: Any) -> str:
    if text is None:
        raise NodeWarning("Colour is empty (null)")
    colour = parse_colour(str(text))
    if colour is None:
        raise NodeWarning(
            f"Colour {str(text)!r} is not a colour: write #rrggbb (like #ff8800) or a name such as red"
        )
    return colour


def _width(value: Any) -> float:
    if value is None:
        raise NodeWarning("Width is empty (null)")
    width = float(value)
    if not (math.isfinite(width) and width > 0):
        raise NodeWarning(f"Width must be a positive number of pixels, not {width:g}")
    return width


class Preview(Node):
    """Draw geometry in a colour and line width of your choice, and pass it on.

    Colour is ``#rrggbb`` (``#ff8800``), the short ``#rgb``, or a name such as
    ``red``, ``orange``, ``steel blue``. Give one Colour and Width for the whole
    list, or one per item (a shorter list reuses its last value). The viewport draws
    the Styled output, each item a StyledGeometry(geometry, colour, width); the
    Geometry output is the input, unchanged, for wiring on.
    """

    type_id = "display.Preview"
    nickname, aliases = "Prev", ("Custom Preview", "colour", "color")
    inputs = (
        In("Geometry", GENERIC, "G", "What to draw: any geometry.", access=LIST),
        In("Colour", TEXT, "C", "Colour as #rrggbb or a name, one or one per item.", access=LIST,
           default="#ff8800"),
        In("Width", NUMBER, "W", "Line width in pixels, one or one per item.", access=LIST,
           default=2.0),
    )
    outputs = (
        Out("Geometry", GENERIC, "G", "The geometry, passed on unchanged.", access=LIST),
        Out("Styled", STYLED, "S", "Each item with its colour and width, for the viewport.",
            access=LIST),
    )

    def solve(
        self, geometry: list[Any], colours: list[Any], widths: list[Any]
    ) -> tuple[list[Any], list[StyledGeometry | None]]:
        if not colours:
            raise NodeWarning("Colour is empty: give a colour such as #ff8800")
        if not widths:
            raise NodeWarning("Width is empty: give a line width such as 2")
        for name, values in (("Colour", colours), ("Width", widths)):
            if 1 < len(values) < len(geometry):
                self.remark(
                    f"Geometry has {len(geometry)} items, {name} has {len(values)}: "
                    f"{name}'s last value is reused"
                )
        parsed_colours = [_colour(c) for c in colours]
        parsed_widths = [_width(w) for w in widths]
        styled = [
            None if item is None else StyledGeometry(
                item,
                parsed_colours[min(i, len(parsed_colours) - 1)],
                parsed_widths[min(i, len(parsed_widths) - 1)],
            )
            for i, item in enumerate(geometry)
        ]
        return list(geometry), styled


class Tag(Node):
    """Show a text at a point in the viewport, such as a panel's number or a label.

    The tag is a display hint: it is drawn facing the camera and does not change
    the geometry. Give lists of texts and locations to tag many points at once.
    """

    type_id = "display.Tag"
    nickname, aliases = "Tag", ("Text Tag", "Text Tag 3D", "label", "dot")
    inputs = (
        In("Text", TEXT, "T", "What to write."),
        In("Location", POINT, "L", "Where to write it.", default=Point(0.0, 0.0, 0.0)),
    )
    outputs = (Out("Tag", TAG, "T", "The text at its location, for the viewport."),)

    def solve(self, text: Any, location: Any) -> TagValue:
        words = str(given("Text", text))
        return TagValue(words, Point(*xyz("Location", location).tolist()))
