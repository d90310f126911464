"""Colours, sizes and fonts shared by the canvas, the palette and the viewport."""

from __future__ import annotations

from PySide6.QtGui import QColor, QFont

from torsal.app import palette_colours

CANVAS_BACKGROUND = QColor("#d2d4d6")
GRID_MINOR = QColor("#c8cacc")
GRID_MAJOR = QColor("#b9bcbf")

NODE_BODY = QColor("#c9c9c9")
NODE_TITLE = QColor("#a9acae")
NODE_OUTLINE = QColor("#3c3c3c")
NODE_TEXT = QColor("#141414")
NODE_PENDING = QColor("#d6d6d6")

#: Body colour per solver state (grey ok, orange warning, red error, dim disabled).
STATE_BODY: dict[str, QColor] = {
    "ok": NODE_BODY,
    "warning": QColor("#f3a83b"),
    "error": QColor("#e0584f"),
    "disabled": QColor("#e2e2e2"),
    "missing": QColor("#b79ad6"),
    "pending": NODE_PENDING,
}
SELECTED_BODY = QColor("#7cc67a")
SELECTED_OUTLINE = QColor("#1f6f1d")

WIRE = QColor("#3a3a3a")
WIRE_SELECTED = QColor("#1f6f1d")
WIRE_DRAG = QColor("#2563a8")
PORT_FILL = QColor("#f4f4f4")
PORT_SET_FILL = QColor("#2563a8")

WIDGET_TRACK = QColor("#f2f2f2")
WIDGET_HANDLE = QColor("#2f2f2f")
PANEL_PAPER = QColor("#fff6b8")
PANEL_TEXT = QColor("#202020")

MESSAGE_COLOURS = {"remark": QColor("#606060"), "warning": QColor("#c77700"), "error": QColor("#c0281f")}

#: Letter-icon colours per palette (Grasshopper-like tabs).
#: The palette tabs a Grasshopper user expects, in order; other palettes (io, plug-ins) follow.
PALETTE_TABS = (
    "params", "maths", "lists", "curves", "surfaces", "transform", "analysis", "developable",
    "patching", "display",
)


def palette_order(palette: str) -> int:
    """A palette's place in the palette bar (plug-ins' palettes after Torsal's)."""
    return PALETTE_TABS.index(palette) if palette in PALETTE_TABS else len(PALETTE_TABS)


PALETTE_COLOURS = palette_colours.COLOURS  # each palette's colour: tiles, icons, node bars

# viewport colours (RGB hex strings, as pyvista takes them)
PREVIEW_SURFACE = "#9fb8d3"
PREVIEW_CURVE = "#1d1d1d"
PREVIEW_POINT = "#8b1a1a"
PREVIEW_VECTOR = "#2a5fa0"
PREVIEW_RULING = "#4a5a6a"
PREVIEW_SELECTED = "#30b030"
PREVIEW_PICKED = "#e07020"  #: a cut-sheet part picked in the viewport, and its strip
VIEWPORT_BACKGROUND = "#f4f5f7"
VIEWPORT_BACKGROUND_TOP = "#dfe4ea"
VIEWPORT_GRID = "#c4c9d0"


def ui_font(point_size: float = 8.5, bold: bool = False) -> QFont:
    """The canvas font: DejaVu Sans (always present on Debian), a little small like Grasshopper's."""
    font = QFont("DejaVu Sans")
    font.setPointSizeF(point_size)
    font.setBold(bold)
    return font


def mono_font(point_size: float = 8.0) -> QFont:
    font = QFont("DejaVu Sans Mono")
    font.setPointSizeF(point_size)
    return font
