"""Node icons: the SVG drawn for each node type, or its nickname on a palette-coloured tile.

Every node of Torsal's catalogue has an SVG in ``torsal/resources/icons`` (one per type id;
the style guide is that folder's README). A plug-in's node without one shows a tile with
its nickname (or the initials of its name), and so does every node while
:func:`set_show_nicknames` is on (the View menu's "Show Nicknames Instead of Icons", as
Grasshopper's "Draw Icons" off).
"""

from __future__ import annotations

import re
from functools import lru_cache
from importlib.resources import files

from PySide6.QtCore import QRectF, Qt
from PySide6.QtGui import QColor, QIcon, QPainter, QPixmap
from PySide6.QtSvg import QSvgRenderer

from torsal.app.gui.theme import PALETTE_COLOURS, ui_font

ICONS = "torsal.resources.icons"
TOOLBOX_LETTERS = {"analysis": "A", "curves": "C", "developable": "D", "patching": "P", "surfaces": "S"}
_show_nicknames = False


def set_show_nicknames(show: bool) -> None:
    """Draw nicknames on tiles instead of the icons (palette, search, nodes)."""
    global _show_nicknames
    _show_nicknames = bool(show)
    letter_icon.cache_clear()
    svg_icon.cache_clear()


def show_nicknames() -> bool:
    return _show_nicknames


def initials(name: str, limit: int = 2) -> str:
    """``NumberSlider`` → ``NS``; ``Point`` → ``Pt``."""
    capitals = re.findall(r"[A-Z0-9]", name)
    if len(capitals) >= 2:
        return "".join(capitals[:limit])
    return (name[:1].upper() + name[1:2].lower()) if name else "?"


def node_letters(cls: type) -> str:
    """The letters of a node type's tile: its ``icon`` letters, else its nickname when
    short, else the toolbox's letter or its initials."""
    explicit = getattr(cls, "icon", "")
    if explicit and len(explicit) <= 3:
        return explicit
    nickname = getattr(cls, "nickname", "")
    if nickname and len(nickname) <= 4:
        return nickname
    palette, _, name = getattr(cls, "type_id", "").partition(".")
    if palette == "developable" and ("Ruled" in name or "Ruling" in name):
        return "R"
    return TOOLBOX_LETTERS.get(palette) or initials(name)


def palette_colour(palette: str) -> QColor:
    return QColor(PALETTE_COLOURS.get(palette, "#6a6a6a"))


@lru_cache(maxsize=1024)
def renderer_for(type_id: str) -> QSvgRenderer | None:
    """The SVG renderer of ``type_id``'s icon, or None when it has none."""
    resource = files(ICONS) / f"{type_id}.svg"
    if not resource.is_file():
        return None
    renderer = QSvgRenderer(resource.read_bytes())
    return renderer if renderer.isValid() else None


def paint_letter_tile(painter: QPainter, rect: QRectF, letters: str, colour: QColor) -> None:
    """Draw a rounded tile with ``letters`` centred in white."""
    painter.save()
    painter.setRenderHint(QPainter.RenderHint.Antialiasing)
    painter.setPen(colour.darker(140))
    painter.setBrush(colour)
    radius = rect.width() * 0.2
    painter.drawRoundedRect(rect, radius, radius)
    share = 0.55 if len(letters) == 1 else 0.42 if len(letters) == 2 else 0.3
    font = ui_font(max(5.0, rect.height() * share), bold=True)
    font.setPixelSize(max(6, int(rect.height() * share)))
    painter.setFont(font)
    painter.setPen(QColor("white"))
    painter.drawText(rect, Qt.AlignmentFlag.AlignCenter, letters)
    painter.restore()


def paint_node_icon(painter: QPainter, rect: QRectF, cls: type, placeholder: bool = False) -> None:
    """Draw ``cls``'s icon into ``rect`` (a node body's icon corner): its SVG, or its tile."""
    type_id = getattr(cls, "type_id", "")
    renderer = None if (placeholder or _show_nicknames) else renderer_for(type_id)
    if renderer is not None:
        renderer.render(painter, rect)
        return
    letters = "?" if placeholder else node_letters(cls)
    paint_letter_tile(painter, rect, letters, palette_colour(type_id.partition(".")[0]))


@lru_cache(maxsize=512)
def letter_icon(letters: str, palette: str, size: int = 32) -> QIcon:
    """A cached :class:`QIcon` of ``letters`` on ``palette``'s colour."""
    pixmap = QPixmap(size, size)
    pixmap.fill(Qt.GlobalColor.transparent)
    painter = QPainter(pixmap)
    paint_letter_tile(painter, QRectF(1, 1, size - 2, size - 2), letters, palette_colour(palette))
    painter.end()
    return QIcon(pixmap)


@lru_cache(maxsize=1024)
def svg_icon(type_id: str, size: int) -> QIcon | None:
    renderer = renderer_for(type_id)
    if renderer is None:
        return None
    icon = QIcon()
    for scale in (1, 2):  # crisp at 100 % and 200 %
        pixmap = QPixmap(size * scale, size * scale)
        pixmap.fill(Qt.GlobalColor.transparent)
        painter = QPainter(pixmap)
        renderer.render(painter, QRectF(0, 0, size * scale, size * scale))
        painter.end()
        pixmap.setDevicePixelRatio(scale)
        icon.addPixmap(pixmap)
    return icon


def node_icon(cls: type, size: int = 32) -> QIcon:
    """A node type's icon for a button or a list row."""
    type_id = getattr(cls, "type_id", "")
    if not _show_nicknames:
        icon = svg_icon(type_id, size)
        if icon is not None:
            return icon
    return letter_icon(node_letters(cls), type_id.partition(".")[0], size)
