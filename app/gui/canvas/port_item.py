"""A port: the small circle on a node's edge that wires start and end at."""

from __future__ import annotations

from PySide6.QtCore import QPointF, QRectF
from PySide6.QtGui import QPainter, QPainterPath, QPen
from PySide6.QtWidgets import QGraphicsItem, QGraphicsSceneHoverEvent, QStyleOptionGraphicsItem, QWidget

from app.gui import theme
from app.gui.canvas.layout import PORT_R

HIT_R = 9.0  # ports are easier to hit than they look


class PortItem(QGraphicsItem):
    """An input or output port of a node (a child of its :class:`NodeItem`)."""

    def __init__(self, parent: QGraphicsItem, name: str, is_input: bool, type_name: str) -> None:
        super().__init__(parent)
        self.name = name
        self.is_input = is_input
        self.type_name = type_name
        self.has_value = False
        self.setAcceptHoverEvents(True)
        self.setZValue(1)

    @property
    def node_id(self) -> str:
        return self.parentItem().node_id

    @property
    def is_output(self) -> bool:
        return not self.is_input

    def hoverEnterEvent(self, event: QGraphicsSceneHoverEvent) -> None:
        self.setToolTip(self.parentItem().port_tooltip(self.name, self.is_input))
        super().hoverEnterEvent(event)

    def anchor(self) -> QPointF:
        """Where wires attach, in scene coordinates."""
        return self.scenePos()

    def boundingRect(self) -> QRectF:
        return QRectF(-HIT_R, -HIT_R, HIT_R * 2, HIT_R * 2)

    def shape(self) -> QPainterPath:
        path = QPainterPath()
        path.addEllipse(self.boundingRect())
        return path

    def paint(
        self, painter: QPainter, option: QStyleOptionGraphicsItem, widget: QWidget | None = None
    ) -> None:
        painter.setRenderHint(QPainter.RenderHint.Antialiasing)
        painter.setPen(QPen(theme.NODE_OUTLINE, 1.0))
        painter.setBrush(theme.PORT_SET_FILL if self.has_value else theme.PORT_FILL)
        painter.drawEllipse(QPointF(0, 0), PORT_R, PORT_R)
