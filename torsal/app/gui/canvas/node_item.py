"""A node on the canvas: title, named ports, state colour, inline widget, messages.

The item draws one :class:`~torsal.engine.graph.NodeRecord`; it never edits it. Moving an
item is visual until the mouse is released, when the scene turns it into one undo
command.
"""

from __future__ import annotations

import math
import time
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import QPointF, QRectF, Qt, QTimer
from PySide6.QtGui import QColor, QFontMetricsF, QPainter, QPainterPath, QPen
from PySide6.QtWidgets import (
    QGraphicsItem,
    QGraphicsRectItem,
    QGraphicsSceneHoverEvent,
    QGraphicsSceneMouseEvent,
    QStyleOptionGraphicsItem,
    QWidget,
)

from torsal.app.gui import theme
from torsal.app.gui.canvas.inline_widgets import InlineWidget, widget_for
from torsal.app.gui.canvas.layout import TITLE_H, NodeLayout, compute_layout
from torsal.app.gui.canvas.port_item import PortItem
from torsal.app.gui.formatting import MODIFIER_MARKS, format_item
from torsal.app.gui.icons import paint_node_icon
from torsal.engine.cluster import is_cluster
from torsal.engine.graph import Graph, NodeRecord, is_placeholder
from torsal.engine.solver import NodeResult
from torsal.engine.widgets import Widget

if TYPE_CHECKING:
    from torsal.app.gui.canvas.hosts import NodeCanvas

RADIUS = 5.0
#: While a solve runs, a dragged slider is drawn at most this often (ms): 25 times a
#: second, the rate the viewport aims at during a drag (issue "Fluid").
BUSY_WIDGET_INTERVAL_MS = 40


class NodeItem(QGraphicsRectItem):
    """The drawn form of one node record.

    A rectangle item whose bounds Qt computes itself (only :meth:`paint` is Python, and
    the painting is cached): see :mod:`torsal.app.gui.canvas.port_item` for why.
    """

    title_font = theme.ui_font(8.5, bold=True)
    badge_font = theme.ui_font(7.0, bold=True)
    port_font = theme.ui_font(8.0)
    mono_font = theme.mono_font(8.0)

    def __init__(self, record: NodeRecord, graph: Graph | None = None) -> None:
        super().__init__()
        self.record = record
        self._graph = graph  # a placeholder's ports come from its wires in this graph
        self.node_id = record.id
        self.result: NodeResult | None = None
        self.ports: dict[tuple[bool, str], PortItem] = {}
        self.layout: NodeLayout | None = None
        self.widget: InlineWidget | None = widget_for(self)
        self._widget_grab = False
        self._widget_drawn = 0.0  # when the inline widget was last drawn (perf_counter)
        self._widget_due = False  # a drawing of it waits (see update_widget)
        self.setPen(QPen(Qt.PenStyle.NoPen))
        self.setFlags(
            QGraphicsItem.GraphicsItemFlag.ItemIsMovable
            | QGraphicsItem.GraphicsItemFlag.ItemIsSelectable
            | QGraphicsItem.GraphicsItemFlag.ItemSendsGeometryChanges
            # paint() learns the part to draw (option.exposedRect): see update_widget
            | QGraphicsItem.GraphicsItemFlag.ItemUsesExtendedStyleOption
        )
        self.setAcceptHoverEvents(True)
        # Painted once into a pixmap and reused: repaints (scrolling, a wire moving over it)
        # cost no Python, which keeps the GUI quick while the solver holds the GIL.
        self.setCacheMode(QGraphicsItem.CacheMode.DeviceCoordinateCache)
        self.setPos(QPointF(*record.position))
        self.rebuild()

    def canvas(self) -> NodeCanvas:
        return self.scene()

    # -- structure -------------------------------------------------------------------
    @property
    def state(self) -> str:
        if not self.record.enabled:
            return "disabled"
        return self.result.state if self.result is not None else "pending"

    def port_names(self) -> tuple[list[tuple[str, str, str]], list[tuple[str, str]]]:
        """``(name, label, type)`` of inputs and ``(name, type)`` of outputs.

        A placeholder (node type not installed) shows the ports its wires and stored
        inputs name, so its wires still have somewhere to end.
        """
        node = self.record.node
        if is_placeholder(node):
            scene = self.scene()
            graph = scene.doc.graph if scene is not None else self._graph
            into = graph.wires_into(self.node_id) if graph is not None else []
            out = graph.wires_from(self.node_id) if graph is not None else []
            ins = list(dict.fromkeys([*self.record.inputs, *(w.target_port for w in into)]))
            outs = list(dict.fromkeys(w.source_port for w in out))
            return [(n, n, "?") for n in ins], [(n, "?") for n in outs]
        if self.is_panel:  # a note: ports without labels, as in Grasshopper
            return [(p.name, "", p.type.name) for p in node.input_ports()], [
                (p.name, p.type.name) for p in node.output_ports()
            ]
        inputs = []
        for port in node.input_ports():
            state = self.record.inputs.get(port.name)
            marks = "".join(
                MODIFIER_MARKS[m] for m in (state.modifiers if state else []) if m in MODIFIER_MARKS
            )
            inputs.append((port.name, f"{port.name} {marks}".strip(), port.type.name))
        return inputs, [(p.name, p.type.name) for p in node.output_ports()]

    @property
    def is_panel(self) -> bool:
        """A note (the node asks for Widget.PANEL): ports without labels, resized to its text."""
        return self.record.node.widget is Widget.PANEL

    def rebuild(self) -> bool:
        """Recompute the layout and ports (after a change to settings, modifiers, label).
        True if the node's outline or any of its ports moved (its wires must follow)."""
        before = self._geometry()
        self.prepareGeometryChange()
        inputs, outputs = self.port_names()
        widget_size = self.widget.size() if self.widget is not None else None
        self.layout = compute_layout(
            self.record.title,
            [(name, label) for name, label, _ in inputs],
            [(name, "" if self.is_panel else name) for name, _ in outputs],
            _title_metrics(),
            _port_metrics(),
            widget_size,
        )
        wanted = {(True, name): type_name for name, _, type_name in inputs}
        wanted.update({(False, name): type_name for name, type_name in outputs})
        for key in [k for k in self.ports if k not in wanted]:
            port = self.ports.pop(key)
            port.setParentItem(None)
            if port.scene() is not None:
                port.scene().removeItem(port)
        for key, type_name in wanted.items():
            if key not in self.ports:
                self.ports[key] = PortItem(self, key[1], key[0], type_name)
        for slot in self.layout.inputs:
            self.ports[(True, slot.name)].setPos(slot.centre)
        for slot in self.layout.outputs:
            self.ports[(False, slot.name)].setPos(slot.centre)
        for (is_input, name), port in self.ports.items():
            state = self.record.inputs.get(name) if is_input else None
            port.set_has_value(bool(state and state.has_value))
        self.setRect(self.layout.rect)
        self.update()
        return self._geometry() != before

    def _geometry(self) -> tuple[object, ...]:
        """The node's rectangle and where each of its ports is (what its wires attach to)."""
        rect = self.rect()
        ports = tuple((key, id(port), port.pos().x(), port.pos().y()) for key, port in self.ports.items())
        return (rect.x(), rect.y(), rect.width(), rect.height(), ports)

    def update_widget(self) -> None:
        """Draw the inline widget again, and only it: a slider drag moves the handle on
        every mouse move, and the rest of the node stays as it is in the item's cache.

        While a solve is running the widget is drawn at most every
        :data:`BUSY_WIDGET_INTERVAL_MS` (the last move's value, once that time is up): each
        drawing is GUI work beside the solve, taken from its share of a busy processor
        (a Kaohsiung drag at load 10: the GUI thread's CPU during a solve 7-12 ms with a
        drawing per mouse move, 5 ms without)."""
        scene = self.scene()
        if scene is not None and scene.doc.solves.in_flight():
            wait = BUSY_WIDGET_INTERVAL_MS - (time.perf_counter() - self._widget_drawn) * 1000
            if wait > 0:
                if not self._widget_due:
                    self._widget_due = True
                    QTimer.singleShot(math.ceil(wait), scene, self._draw_widget_due)
                return
        self._draw_widget()

    def _draw_widget_due(self) -> None:
        if self._widget_due and self.scene() is not None:
            self._draw_widget()

    def _draw_widget(self) -> None:
        self._widget_due = False
        self._widget_drawn = time.perf_counter()
        if self.layout is not None and self.layout.widget_rect is not None:
            self.update(self.layout.widget_rect)
        else:
            self.update()

    def drawn_from_wires(self) -> bool:
        """Whether the wires into this node change how it is drawn: a placeholder's ports
        come from its wires, and an inline widget may show what is wired in."""
        return self.widget is not None or is_placeholder(self.record.node)

    def input_port(self, name: str) -> PortItem | None:
        return self.ports.get((True, name))

    def output_port(self, name: str) -> PortItem | None:
        return self.ports.get((False, name))

    def set_result(self, result: NodeResult | None) -> None:
        """Show ``result``: repainted only if it changes what is drawn (a slider drag gives
        every node downstream a new result each solve, mostly in the same state)."""
        resize = self.widget is not None and self.is_panel
        before = self.drawn_state()
        self.result = result
        if resize:
            self.rebuild()
        elif self.drawn_state() != before:
            self.update()

    def drawn_state(self) -> tuple[str, str]:
        """What of the result the node draws: its state (the body colour) and the worst
        level and the count of its messages (the balloon)."""
        messages = self.result.messages if self.result is not None else ()
        worst = max(m.level for m in messages).name if messages else ""
        return self.state, f"{worst}{len(messages)}" if messages else ""

    def size(self) -> tuple[float, float]:
        return (self.layout.width, self.layout.height)

    # -- tooltips --------------------------------------------------------------------
    def tooltip(self) -> str:
        """Title, type, id, state and time, every message (the message balloon), preview."""
        record = self.record
        lines = [f"<b>{_escape(record.title)}</b> &nbsp;<i>{record.type_id}</i> &nbsp;[{record.id}]"]
        if self.result is not None:
            lines.append(f"{self.result.state}, {self.result.seconds * 1000:.1f} ms")
            for message in self.result.messages:
                level = message.level.name.lower()
                colour = theme.MESSAGE_COLOURS.get(level, QColor("black")).name()
                lines.append(f"<span style='color:{colour}'>{level}: {_escape(message.text)}</span>")
        if not record.preview:
            lines.append("<i>preview off</i>")
        return "<br>".join(lines)

    def port_tooltip(self, name: str, is_input: bool) -> str:
        """A port's tooltip: type, access, description, value, modifiers, data (made when
        asked for: see :meth:`CanvasScene.helpEvent`)."""
        node = self.record.node
        port = node.input_port(name) if is_input else node.output_port(name)
        if port is None:
            return name
        text = f"<b>{port.name}</b> ({port.nickname}) — {port.type.name}, {port.access.value} access"
        if port.description:
            text += f"<br>{_escape(port.description)}"
        state = self.record.inputs.get(name) if is_input else None
        if state is not None and state.has_value:
            text += f"<br>value: {_escape(str(state.value))}"
        if state is not None and state.modifiers:
            text += f"<br>modifiers: {', '.join(state.modifiers)}"
        if not is_input and self.result is not None and name in self.result.outputs:
            tree = self.result.outputs[name]
            text += f"<br>{tree.item_count} items in {tree.branch_count} branches"
            first = tree.first()
            if first is not None:
                text += f"; first: {_escape(format_item(first))}"
        return text

    # -- painting --------------------------------------------------------------------
    def body_colour(self) -> QColor:
        if self.isSelected():
            return theme.SELECTED_BODY
        colour = theme.STATE_BODY.get(self.state, theme.NODE_BODY)
        if not self.record.preview and self.state not in ("disabled",):
            colour = colour.darker(118)
        return colour

    def paint(
        self, painter: QPainter, option: QStyleOptionGraphicsItem, widget: QWidget | None = None
    ) -> None:
        layout = self.layout
        rect = layout.rect
        painter.setRenderHint(QPainter.RenderHint.Antialiasing)
        if self.state == "disabled":
            painter.setOpacity(0.55)
        body = self.body_colour()
        around = layout.widget_rect.adjusted(-2, -2, 2, 2) if layout.widget_rect is not None else None
        if self.widget is not None and around is not None and around.contains(option.exposedRect):
            # only the inline widget is to be drawn again (a slider's handle moved, see
            # update_widget): in and just around its rectangle the node is its body colour
            # (the port labels and the title bar are further away) and the widget. The next
            # busy drawing waits from now, not from when this one was asked for: a paint
            # that came late would otherwise be followed early
            self._widget_drawn = time.perf_counter()
            painter.fillRect(around, body)
            self.widget.paint(painter, layout.widget_rect)
            return
        outline = QPen(
            theme.SELECTED_OUTLINE if self.isSelected() else theme.NODE_OUTLINE,
            2.0 if self.isSelected() else 1.0,
        )
        if self.state == "missing":
            outline.setStyle(Qt.PenStyle.DashLine)
        painter.setPen(outline)
        painter.setBrush(body)
        inset = outline.widthF() / 2  # the outline stays inside the item's bounds
        painter.drawRoundedRect(rect.adjusted(inset, inset, -inset, -inset), RADIUS, RADIUS)
        # title bar
        clip = QPainterPath()
        clip.addRoundedRect(rect, RADIUS, RADIUS)
        painter.save()
        painter.setClipPath(clip)
        painter.setPen(Qt.PenStyle.NoPen)
        painter.setBrush(body.darker(118))
        painter.drawRect(QRectF(0, 0, rect.width(), TITLE_H))
        painter.restore()
        painter.setPen(QPen(body.darker(150), 1.0))
        painter.drawLine(QPointF(0.5, TITLE_H), QPointF(rect.width() - 0.5, TITLE_H))
        painter.setFont(self.title_font)
        painter.setPen(theme.NODE_TEXT)
        title_rect = layout.title_rect.adjusted(6, 0, -16, 0)
        title = QFontMetricsF(self.title_font).elidedText(
            self.record.title, Qt.TextElideMode.ElideRight, title_rect.width()
        )
        painter.drawText(title_rect, Qt.AlignmentFlag.AlignCenter, title)
        # ports
        painter.setFont(self.port_font)
        for slot in layout.inputs:
            painter.drawText(
                slot.label_rect, Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignVCenter, slot.text
            )
        for slot in layout.outputs:
            painter.drawText(
                slot.label_rect, Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter, slot.text
            )
        if layout.icon_rect is not None:
            node = self.record.node
            paint_node_icon(painter, layout.icon_rect, type(node), is_placeholder(node))
        if self.widget is not None and layout.widget_rect is not None:
            self.widget.paint(painter, layout.widget_rect)
        self._paint_badge(painter)

    def _paint_badge(self, painter: QPainter) -> None:
        """A balloon at the top-right corner when the node has something to say: coloured by
        its worst level, holding how many messages there are (hover the node to read them)."""
        if self.result is None or not self.result.messages:
            return
        count = len(self.result.messages)
        worst = max(m.level for m in self.result.messages).name.lower()
        colour = theme.MESSAGE_COLOURS.get(worst, QColor("#606060"))
        centre = QPointF(self.layout.width - 10, TITLE_H / 2)
        painter.setOpacity(1.0)
        painter.setPen(QPen(colour.darker(140), 1.0))
        painter.setBrush(colour)
        painter.drawEllipse(centre, 7, 7)
        painter.setPen(QColor("white"))
        painter.setFont(self.title_font if count < 10 else self.badge_font)
        painter.drawText(
            QRectF(centre.x() - 7, centre.y() - 7, 14, 14),
            Qt.AlignmentFlag.AlignCenter,
            str(count) if count < 10 else "9+",
        )

    # -- events ----------------------------------------------------------------------
    def itemChange(self, change: QGraphicsItem.GraphicsItemChange, value: Any) -> Any:
        if change == QGraphicsItem.GraphicsItemChange.ItemPositionHasChanged and self.scene() is not None:
            self.canvas().node_item_moved(self)
        elif change == QGraphicsItem.GraphicsItemChange.ItemSelectedHasChanged:
            self.update()
        return super().itemChange(change, value)

    def _in_widget(self, pos: QPointF) -> bool:
        return (
            self.widget is not None
            and self.layout.widget_rect is not None
            and self.layout.widget_rect.contains(pos)
        )

    def mousePressEvent(self, event: QGraphicsSceneMouseEvent) -> None:
        if self._in_widget(event.pos()) and self.widget.press(event.pos(), self.layout.widget_rect, event):
            self._widget_grab = True
            event.accept()
            return
        super().mousePressEvent(event)

    def mouseMoveEvent(self, event: QGraphicsSceneMouseEvent) -> None:
        if self._widget_grab:
            self.widget.move(event.pos(), self.layout.widget_rect, event)
            return
        super().mouseMoveEvent(event)

    def mouseReleaseEvent(self, event: QGraphicsSceneMouseEvent) -> None:
        if self._widget_grab:
            self._widget_grab = False
            self.widget.release(event.pos(), self.layout.widget_rect, event)
            return
        super().mouseReleaseEvent(event)

    def end_widget_press(self) -> None:
        """End a press the node's widget took (a slider drag), as its release would."""
        if self._widget_grab:
            self._widget_grab = False
            self.widget.release(QPointF(), self.layout.widget_rect, None)

    def mouseDoubleClickEvent(self, event: QGraphicsSceneMouseEvent) -> None:
        if self._in_widget(event.pos()) and self.widget.double_click(event.pos(), self.layout.widget_rect):
            return
        if is_cluster(self.record.node):  # as in Grasshopper: open it for editing
            self.canvas().open_cluster(self.node_id)
            return
        if event.pos().y() <= TITLE_H:
            self.canvas().rename_node(self.node_id)
            return
        super().mouseDoubleClickEvent(event)

    def hoverEnterEvent(self, event: QGraphicsSceneHoverEvent) -> None:
        self.setToolTip(self.tooltip())
        super().hoverEnterEvent(event)


class _Widths:
    """Text widths in one font, measured once per text (titles and port names repeat)."""

    def __init__(self, font: Any) -> None:
        self.metrics = QFontMetricsF(font)
        self.widths: dict[str, float] = {}

    def horizontalAdvance(self, text: str) -> float:
        width = self.widths.get(text)
        if width is None:
            if len(self.widths) > 4096:
                self.widths.clear()
            width = self.widths[text] = self.metrics.horizontalAdvance(text)
        return width


_widths: dict[str, _Widths] = {}


def _title_metrics() -> Any:
    if "title" not in _widths:
        _widths["title"] = _Widths(NodeItem.title_font)
    return _widths["title"]


def _port_metrics() -> Any:
    if "port" not in _widths:
        _widths["port"] = _Widths(NodeItem.port_font)
    return _widths["port"]


def _escape(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
