"""Widgets drawn inside nodes: number/integer sliders, toggle, value list, panel.

A node gets one by declaring a :class:`~torsal.engine.widgets.Widget` hint (``widget =
Widget.SLIDER``) and keeping the widget's settings, never by its type id: a plug-in's
slider is drawn as the built-in one.

They are painted by their node item (not QWidgets: hundreds of nodes stay cheap), which
they see as a :class:`~torsal.app.gui.canvas.hosts.WidgetHost`, and get the node's mouse
events that fall in their rectangle. Every change
is an edit through the scene's :class:`~torsal.app.gui.editor.Editor`.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import QPointF, QRectF, QSizeF, Qt
from PySide6.QtGui import QColor, QCursor, QFontMetricsF, QPainter, QPen
from PySide6.QtWidgets import QGraphicsSceneMouseEvent, QInputDialog, QMenu

from torsal.app.gui import theme
from torsal.app.gui.formatting import format_tree
from torsal.engine.node import Node
from torsal.engine.types import INTEGER
from torsal.engine.widgets import Widget

if TYPE_CHECKING:
    from torsal.app.gui.canvas.hosts import WidgetHost
    from torsal.app.gui.editor import Editor

HANDLE_W = 9.0
VALUE_W = 52.0
_OUTLINE_PEN = QPen(theme.NODE_OUTLINE, 1.0)
_TICK_PEN = QPen(QColor("#8a8a8a"), 1.0)
_WHITE = QColor("white")


class InlineWidget:
    """Base: a rectangle inside a node that paints itself and may take mouse events."""

    def __init__(self, item: WidgetHost) -> None:
        self.item = item

    @property
    def settings(self) -> dict[str, Any]:
        return self.item.record.node.settings

    @property
    def editor(self) -> Editor:
        return self.item.canvas().editor

    def size(self) -> QSizeF:
        raise NotImplementedError

    def paint(self, painter: QPainter, rect: QRectF) -> None:
        raise NotImplementedError

    def press(self, pos: QPointF, rect: QRectF, event: QGraphicsSceneMouseEvent) -> bool:
        return False

    def move(self, pos: QPointF, rect: QRectF, event: QGraphicsSceneMouseEvent) -> None:
        """Called while a press this widget took is dragged."""

    def release(self, pos: QPointF, rect: QRectF, event: QGraphicsSceneMouseEvent | None) -> None:
        """Called when a press this widget took ends."""

    def double_click(self, pos: QPointF, rect: QRectF) -> bool:
        return False


class SliderWidget(InlineWidget):
    """A number or integer slider: drag the handle; double-click to edit min/max/step/value."""

    def __init__(self, item: WidgetHost, integer: bool) -> None:
        super().__init__(item)
        self.integer = integer
        self.drag_value: float | None = None
        self._drag_key: object = None

    def size(self) -> QSizeF:
        return QSizeF(170.0, 22.0)

    # -- values ----------------------------------------------------------------------
    def bounds(self) -> tuple[float, float]:
        low, high = _number(self.settings.get("min"), 0.0), _number(self.settings.get("max"), 1.0)
        return (low, high) if high > low else (low, low + 1.0)

    def decimals(self) -> int:
        if self.integer:
            return 0
        decimals = self.settings.get("decimals", 2)
        return int(decimals) if isinstance(decimals, int | float) and not isinstance(decimals, bool) else 2

    def value(self) -> float:
        if self.drag_value is not None:
            return self.drag_value
        return _number(self.settings.get("value"), self.bounds()[0])

    def text(self) -> str:
        value = self.value()
        return str(round(value)) if self.integer else f"{value:.{max(0, min(self.decimals(), 15))}f}"

    def track(self, rect: QRectF) -> QRectF:
        return QRectF(
            rect.left() + HANDLE_W / 2, rect.top(), rect.width() - VALUE_W - HANDLE_W, rect.height()
        )

    def handle_x(self, rect: QRectF) -> float:
        low, high = self.bounds()
        track = self.track(rect)
        fraction = min(1.0, max(0.0, (self.value() - low) / (high - low)))
        return track.left() + fraction * track.width()

    def value_at(self, x: float, rect: QRectF) -> float | int:
        low, high = self.bounds()
        track = self.track(rect)
        fraction = min(1.0, max(0.0, (x - track.left()) / track.width()))
        value = low + fraction * (high - low)
        if self.integer:
            return round(value)
        return round(value, self.decimals())

    # -- painting --------------------------------------------------------------------
    def paint(self, painter: QPainter, rect: QRectF) -> None:
        # painted on every mouse move of a drag: the bounds and track are worked out once
        low, high = self.bounds()
        left, top, width, height = rect.left(), rect.top(), rect.width(), rect.height()
        track_left, track_w = left + HANDLE_W / 2, width - VALUE_W - HANDLE_W
        y = top + height / 2
        painter.setPen(_OUTLINE_PEN)
        painter.setBrush(theme.WIDGET_TRACK)
        painter.drawRoundedRect(QRectF(left, y - 3, track_w + HANDLE_W, 6), 3, 3)
        if self.integer:  # ticks for whole numbers, when they fit
            steps = int(high - low)
            if 0 < steps <= 40:
                painter.setPen(_TICK_PEN)
                for i in range(steps + 1):
                    x = track_left + track_w * i / steps
                    painter.drawLine(QPointF(x, y + 4), QPointF(x, y + 7))
                painter.setPen(_OUTLINE_PEN)
        value = self.value()
        x = track_left + min(1.0, max(0.0, (value - low) / (high - low))) * track_w
        painter.setBrush(theme.WIDGET_HANDLE if self.drag_value is None else theme.WIRE_DRAG)
        painter.drawRoundedRect(QRectF(x - HANDLE_W / 2, top + 2, HANDLE_W, height - 4), 2, 2)
        box_left = left + width - VALUE_W + 4
        painter.setBrush(_WHITE)
        painter.drawRoundedRect(QRectF(box_left, top + 2, VALUE_W - 4, height - 4), 3, 3)
        painter.setPen(theme.NODE_TEXT)
        painter.setFont(self.item.port_font)
        painter.drawText(
            QRectF(box_left + 2, top + 2, VALUE_W - 9, height - 4),
            Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter,
            self.text(),
        )

    # -- mouse -----------------------------------------------------------------------
    def press(self, pos: QPointF, rect: QRectF, event: QGraphicsSceneMouseEvent) -> bool:
        if event.button() != Qt.MouseButton.LeftButton:
            return False
        if abs(pos.x() - self.handle_x(rect)) > HANDLE_W or not self.track(rect).adjusted(
            -6, 0, 6, 0
        ).contains(pos):
            return False
        self._drag_key = self.editor.new_drag()
        self.drag_value = self.value()
        self.item.update()
        return True

    def move(self, pos: QPointF, rect: QRectF, event: QGraphicsSceneMouseEvent) -> None:
        value = self.value_at(pos.x(), rect)
        if value == self.drag_value:
            return
        self.drag_value = value
        self.item.update_widget()
        self.editor.drag_setting(self.item.node_id, "value", value, self._drag_key)

    def release(self, pos: QPointF, rect: QRectF, event: QGraphicsSceneMouseEvent | None) -> None:
        self.editor.end_drag()
        self.drag_value = None
        self.item.update()

    def double_click(self, pos: QPointF, rect: QRectF) -> bool:
        from torsal.app.gui.canvas.slider_dialog import WiredBounds, edit_slider

        scene = self.item.scene()
        bounds = WiredBounds(scene.doc.graph, self.item.node_id) if scene is not None else None
        values = edit_slider(self.item.record.title, dict(self.settings), self.integer, bounds)
        if values:
            self.editor.set_settings(self.item.node_id, values, text="Edit slider")
        return True


class ToggleWidget(InlineWidget):
    """True/False: click to switch."""

    def size(self) -> QSizeF:
        return QSizeF(92.0, 22.0)

    def paint(self, painter: QPainter, rect: QRectF) -> None:
        on = self.settings.get("value") is True
        switch = QRectF(rect.left() + 2, rect.center().y() - 8, 32, 16)
        painter.setPen(QPen(theme.NODE_OUTLINE, 1.0))
        painter.setBrush(QColor("#58a55c") if on else QColor("#e8e8e8"))
        painter.drawRoundedRect(switch, 8, 8)
        painter.setBrush(QColor("white"))
        knob_x = switch.right() - 8 if on else switch.left() + 8
        painter.drawEllipse(QPointF(knob_x, switch.center().y()), 6, 6)
        painter.setPen(theme.NODE_TEXT)
        painter.setFont(self.item.port_font)
        painter.drawText(rect.adjusted(40, 0, 0, 0), Qt.AlignmentFlag.AlignVCenter, "True" if on else "False")

    def press(self, pos: QPointF, rect: QRectF, event: QGraphicsSceneMouseEvent) -> bool:
        if event.button() != Qt.MouseButton.LeftButton:
            return False
        self.editor.set_setting(self.item.node_id, "value", self.settings.get("value") is not True)
        return True


class ValueListWidget(InlineWidget):
    """A drop-down of named values: click to choose."""

    def names(self) -> list[str]:
        items = self.settings.get("items")
        if not isinstance(items, list):
            return []
        return [str(i.get("name", i.get("value", ""))) if isinstance(i, dict) else str(i) for i in items]

    def size(self) -> QSizeF:
        metrics = QFontMetricsF(self.item.port_font)
        widest = max((metrics.horizontalAdvance(n) for n in self.names()), default=40.0)
        return QSizeF(max(100.0, widest + 34.0), 22.0)

    def paint(self, painter: QPainter, rect: QRectF) -> None:
        names = self.names()
        selected = self.settings.get("selected", 0)
        text = names[selected] if isinstance(selected, int) and 0 <= selected < len(names) else "—"
        box = rect.adjusted(1, 1, -1, -1)
        painter.setPen(QPen(theme.NODE_OUTLINE, 1.0))
        painter.setBrush(QColor("white"))
        painter.drawRoundedRect(box, 3, 3)
        painter.setPen(theme.NODE_TEXT)
        painter.setFont(self.item.port_font)
        painter.drawText(box.adjusted(6, 0, -18, 0), Qt.AlignmentFlag.AlignVCenter, text)
        painter.drawText(
            box.adjusted(0, 0, -5, 0), Qt.AlignmentFlag.AlignVCenter | Qt.AlignmentFlag.AlignRight, "▾"
        )

    def press(self, pos: QPointF, rect: QRectF, event: QGraphicsSceneMouseEvent) -> bool:
        if event.button() != Qt.MouseButton.LeftButton:
            return False
        chosen = pick(self.names(), self.settings.get("selected", 0))
        if chosen is not None:
            self.editor.set_setting(self.item.node_id, "selected", chosen)
        return True


def pick(names: list[str], selected: object) -> int | None:
    """A drop-down menu of ``names`` at the cursor; the chosen position, or None."""
    menu = QMenu()
    for index, name in enumerate(names):
        action = menu.addAction(name)
        action.setCheckable(True)
        action.setChecked(index == selected)
        action.setData(index)
    chosen = menu.exec(QCursor.pos())
    return None if chosen is None else int(chosen.data())


class PanelWidget(InlineWidget):
    """A yellow note: shows the data wired into it, or its own text; grows with content."""

    MAX_LINES = 30
    WIDTH = 190.0

    def __init__(self, item: WidgetHost) -> None:
        super().__init__(item)
        self._cache: tuple[object, list[str]] | None = None

    def wired(self) -> bool:
        scene = self.item.scene()
        return scene is not None and bool(scene.doc.graph.wires_into(self.item.node_id))

    def lines(self) -> list[str]:
        if self.wired():
            result = self.item.result
            if result is None:
                return ["…"]
            tree = result.outputs.get("Output")
            lines = format_tree(tree, self.MAX_LINES) if tree is not None else []
            return lines or ["<empty>"]
        text = self.settings.get("text")
        lines = str(text).splitlines() if text else []
        return lines or ["Double-click to type"]

    def visible_lines(self) -> list[str]:
        """The lines drawn (computed once per result or text, not once per paint)."""
        key = (self.wired(), id(self.item.result), self.settings.get("text"))
        if self._cache is not None and self._cache[0] == key:
            return self._cache[1]
        lines = self.lines()
        if len(lines) > self.MAX_LINES:
            lines = [*lines[: self.MAX_LINES - 1], f"… {len(lines) - self.MAX_LINES + 1} more lines"]
        self._cache = (key, lines)
        return lines

    def size(self) -> QSizeF:
        metrics = QFontMetricsF(self.item.mono_font)
        count = max(2, len(self.visible_lines()))
        return QSizeF(self.WIDTH, count * metrics.lineSpacing() + 8)

    def paint(self, painter: QPainter, rect: QRectF) -> None:
        painter.setPen(QPen(QColor("#b8a640"), 1.0))
        painter.setBrush(theme.PANEL_PAPER)
        painter.drawRect(rect)
        painter.setFont(self.item.mono_font)
        metrics = QFontMetricsF(self.item.mono_font)
        y = rect.top() + 4
        for line in self.visible_lines():
            is_path = line.startswith("{")
            painter.setPen(QColor("#6b5d00") if is_path else theme.PANEL_TEXT)
            shown = metrics.elidedText(line, Qt.TextElideMode.ElideRight, rect.width() - 8)
            painter.drawText(
                QRectF(rect.left() + 4, y, rect.width() - 8, metrics.lineSpacing()),
                Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignVCenter,
                shown,
            )
            y += metrics.lineSpacing()

    def double_click(self, pos: QPointF, rect: QRectF) -> bool:
        if self.wired():
            return False
        text, ok = QInputDialog.getMultiLineText(
            None, "Panel", "One item per line:", str(self.settings.get("text") or "")
        )
        if ok:
            self.editor.set_setting(self.item.node_id, "text", text)
        return True


def integer_slider(node: Node) -> bool:
    """Whether a slider node gives whole numbers: its first output is an Integer."""
    outputs = node.output_ports()
    return bool(outputs) and outputs[0].type is INTEGER


def widget_for(item: WidgetHost) -> InlineWidget | None:
    """The inline widget a node asks for by its :class:`~torsal.engine.widgets.Widget` hint, if any."""
    node = item.record.node
    hint = node.widget
    if hint is Widget.SLIDER:
        return SliderWidget(item, integer=integer_slider(node))
    if hint is Widget.TOGGLE:
        return ToggleWidget(item)
    if hint is Widget.VALUE_LIST:
        return ValueListWidget(item)
    if hint is Widget.PANEL:
        return PanelWidget(item)
    return None


def _number(value: Any, fallback: float) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        return fallback
    return float(value)
