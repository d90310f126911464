"""Display hints: small values that tell the viewport how to draw things.

Nodes in ``display`` output these; the app's viewport reads them and nothing else
in a solve depends on them, so a headless run simply passes them on.

- :class:`StyledGeometry` — a piece of geometry with the colour and line width to
  draw it in (``display.Preview``'s ``Styled`` output).
- :class:`Tag` — a text drawn at a point (``display.Tag``).

Both are registered as value types (``Styled`` and ``Tag``) so ``torsal run --json``
describes them; a Tag is plain data and can be saved in a graph file.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

import torsal.nodes.common.values  # noqa: F401  (a Styled summary describes its geometry by these types)
from torsal.engine.types import ValueType, summarize_value
from torsal.engine.values import Point


@dataclass(frozen=True)
class StyledGeometry:
    """``geometry`` to be drawn in ``colour`` (``#rrggbb``) with lines ``width`` pixels wide."""

    geometry: Any
    colour: str
    width: float

    @property
    def rgb(self) -> tuple[float, float, float]:
        """The colour as red, green and blue from 0 to 1."""
        return tuple(int(self.colour[i:i + 2], 16) / 255 for i in (1, 3, 5))  # type: ignore[return-value]


@dataclass(frozen=True)
class Tag:
    """``text`` to be drawn at ``location``, facing the camera."""

    text: str
    location: Point


NAMED_COLOURS: dict[str, str] = {
    "black": "#000000", "white": "#ffffff", "red": "#ff0000", "green": "#008000",
    "lime": "#00ff00", "blue": "#0000ff", "yellow": "#ffff00", "cyan": "#00ffff",
    "aqua": "#00ffff", "magenta": "#ff00ff", "fuchsia": "#ff00ff", "orange": "#ffa500",
    "purple": "#800080", "pink": "#ffc0cb", "brown": "#a52a2a", "grey": "#808080",
    "gray": "#808080", "lightgrey": "#d3d3d3", "lightgray": "#d3d3d3", "darkgrey": "#a9a9a9",
    "darkgray": "#a9a9a9", "silver": "#c0c0c0", "maroon": "#800000", "olive": "#808000",
    "navy": "#000080", "teal": "#008080", "gold": "#ffd700", "violet": "#ee82ee",
    "indigo": "#4b0082", "turquoise": "#40e0d0", "crimson": "#dc143c", "coral": "#ff7f50",
    "salmon": "#fa8072", "skyblue": "#87ceeb", "steelblue": "#4682b4", "forestgreen": "#228b22",
}
"""Colour names Preview understands (CSS names), without spaces: ``"sky blue"`` is ``skyblue``."""

_HEX = re.compile(r"#?([0-9a-fA-F]{3}|[0-9a-fA-F]{6})")


def parse_colour(text: str) -> str | None:
    """``#rgb``, ``#rrggbb`` (the ``#`` optional) or a colour name as ``#rrggbb``; None if neither."""
    word = text.strip().lower().replace(" ", "").replace("_", "")
    if word in NAMED_COLOURS:
        return NAMED_COLOURS[word]
    match = _HEX.fullmatch(word)
    if match is None:
        return None
    digits = match.group(1)
    if len(digits) == 3:
        digits = "".join(c * 2 for c in digits)
    return "#" + digits


def _styled_summary(styled: StyledGeometry) -> dict[str, Any]:
    return {
        "type": "Styled",
        "colour": styled.colour,
        "width": styled.width,
        "geometry": summarize_value(styled.geometry),
    }


def _tag_encode(tag: Tag) -> dict[str, Any]:
    return {"type": "Tag", "text": tag.text, "location": list(tag.location)}


def _tag_decode(data: dict[str, Any]) -> Tag:
    x, y, z = data["location"]
    return Tag(str(data["text"]), Point(x, y, z))


STYLED = ValueType(
    "Styled", (StyledGeometry,), "Geometry with the colour and line width to draw it in.",
    summarize=_styled_summary,
)
TAG = ValueType(
    "Tag", (Tag,), "A text shown at a point in the viewport.", encode=_tag_encode, decode=_tag_decode,
)
