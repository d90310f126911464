"""Every node has its own SVG icon: the file exists, it renders, no two nodes of one
palette look the same (rendered pixels compared), and palette buttons and node bodies
show it; the View menu's setting shows nicknames instead."""

from __future__ import annotations

from collections import defaultdict
from importlib.resources import files

from PySide6.QtCore import QPointF, QRectF, Qt
from PySide6.QtGui import QColor, QImage, QPainter
from PySide6.QtSvg import QSvgRenderer

from tests.support.fixtures_gui import view_point
from torsal.nodes.catalogue import default_registry

CATALOGUE = list(default_registry(plugins=False))
ACCENT = QColor("#ffd166")  # the Point glyph's accent dot, in the middle of its icon


def rendered(type_id: str, size: int = 24) -> QImage:
    renderer = QSvgRenderer(files("torsal.resources.icons").joinpath(f"{type_id}.svg").read_bytes())
    assert renderer.isValid(), type_id
    image = QImage(size, size, QImage.Format.Format_ARGB32)
    image.fill(Qt.GlobalColor.transparent)
    painter = QPainter(image)
    renderer.render(painter, QRectF(0, 0, size, size))
    painter.end()
    return image


def test_every_node_in_the_catalogue_has_an_icon_file():
    folder = files("torsal.resources.icons")
    missing = [cls.type_id for cls in CATALOGUE if not folder.joinpath(f"{cls.type_id}.svg").is_file()]
    assert missing == []


def test_no_two_nodes_of_a_palette_share_an_icon_at_100_or_200_percent(qapp):
    for size in (24, 48):
        seen: dict[tuple[str, bytes], str] = {}
        clashes = defaultdict(list)
        for cls in CATALOGUE:
            key = (cls.type_id.partition(".")[0], bytes(rendered(cls.type_id, size).constBits()))
            if key in seen:
                clashes[seen[key]].append(cls.type_id)
            seen.setdefault(key, cls.type_id)
        assert not clashes, (size, dict(clashes))


def near_accent(image: QImage, x: int, y: int) -> bool:
    return any(
        abs(QColor(image.pixel(x + dx, y + dy)).red() - ACCENT.red()) < 30
        and abs(QColor(image.pixel(x + dx, y + dy)).blue() - ACCENT.blue()) < 40
        for dx in range(-2, 3) for dy in range(-2, 3)
    )


def test_palette_buttons_and_node_bodies_show_the_icon_and_the_setting_shows_nicknames(qtbot, window):
    button = window.palette.findChild(object, "palette:params.Point")
    size = button.iconSize().width()
    shown = button.icon().pixmap(size, size).toImage().convertToFormat(QImage.Format.Format_ARGB32)
    assert shown == rendered("params.Point", size)
    node_id = window.editor.add_node("params.Point", (0.0, 0.0))
    item = window.scene.nodes[node_id]
    window.view.centerOn(item)
    qtbot.wait(50)
    icon = item.mapToScene(item.layout.icon_rect).boundingRect()
    centre = view_point(window, QPointF(icon.center().x(), icon.center().y()))
    assert near_accent(window.view.viewport().grab().toImage(), centre.x(), centre.y())
    window.actions_by_name["show_nicknames"].setChecked(True)
    qtbot.wait(50)
    assert not near_accent(window.view.viewport().grab().toImage(), centre.x(), centre.y())
    tile = window.palette.findChild(object, "palette:params.Point").icon().pixmap(size, size).toImage()
    assert tile.convertToFormat(QImage.Format.Format_ARGB32) != shown
    window.actions_by_name["show_nicknames"].setChecked(False)
