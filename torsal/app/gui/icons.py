"""Letter icons for node types: the toolbox's letters on a palette-coloured tile.

Analysis nodes carry A, curve nodes C, developables D (ruled ones R) and patching P,
as in the TU Delft toolbox; other nodes show the initials of their name. A node class
may choose its own letters with its ``icon`` class attribute.
"""

from __future__ import annotations

import re
from functools import lru_cache

from PySide6.QtCore import QRectF, Qt
from PySide6.QtGui import QColor, QIcon, QPainter, QPixmap

from torsal.app.gui.theme import PALETTE_COLOURS, ui_font

TOOLBOX_LETTERS = {"analysis": "A", "curves": "C", "developable": "D", "patching": "P", "surfaces": "S"}


def initials(name: str, limit: int = 2) -> str:
    """``NumberSlider`` → ``NS``; ``Point`` → ``Pt``."""
    capitals = re.findall(r"[A-Z0-9]", name)
    if len(capitals) >= 2:
        return "".join(capitals[:limit])
    return (name[:1].upper() + name[1:2].lower()) if name else "?"


def node_letters(cls: type) -> str:
    """The letters drawn on a node type's icon."""
    explicit = getattr(cls, "icon", "")
    if explicit and len(explicit) <= 3:
        return explicit
    palette, _, name = getattr(cls, "type_id", "").partition(".")
    if palette == "developable" and ("Ruled" in name or "Ruling" in name):
        return "R"
    return TOOLBOX_LETTERS.get(palette) or initials(name)


def palette_colour(palette: str) -> QColor:
    return QColor(PALETTE_COLOURS.get(palette, "#6a6a6a"))


def paint_letter_tile(painter: QPainter, rect: QRectF, letters: str, colour: QColor) -> None:
    """Draw a rounded tile with ``letters`` centred in white."""
    painter.save()
    painter.setRenderHint(QPainter.RenderHint.Antialiasing)
    painter.setPen(colour.darker(140))
    painter.setBrush(colour)
    radius = rect.width() * 0.2
    painter.drawRoundedRect(rect, radius, radius)
    font = ui_font(max(5.0, rect.height() * (0.42 if len(letters) > 1 else 0.55)), bold=True)
    font.setPixelSize(max(6, int(rect.height() * (0.42 if len(letters) > 1 else 0.56))))
    painter.setFont(font)
    painter.setPen(QColor("white"))
    painter.drawText(rect, Qt.AlignmentFlag.AlignCenter, letters)
    painter.restore()


@lru_cache(maxsize=512)
def letter_icon(letters: str, palette: str, size: int = 32) -> QIcon:
    """A cached :class:`QIcon` of ``letters`` on ``palette``'s colour."""
    pixmap = QPixmap(size, size)
    pixmap.fill(Qt.GlobalColor.transparent)
    painter = QPainter(pixmap)
    paint_letter_tile(painter, QRectF(1, 1, size - 2, size - 2), letters, palette_colour(palette))
    painter.end()
    return QIcon(pixmap)


def node_icon(cls: type, size: int = 32) -> QIcon:
    palette = getattr(cls, "type_id", "").partition(".")[0]
    return letter_icon(node_letters(cls), palette, size)
