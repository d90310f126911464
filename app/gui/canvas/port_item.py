"""A port: the small circle on a node's edge that wires start and end at.

Ports are plain C++ ellipse items (no Python ``paint``/``boundingRect``): Qt asks items
for their bounds dozens of times per repaint, and each call into Python would have to
take the GIL from a solving worker thread.
"""

from __future__ import annotations

from PySide6.QtCore import QPointF, QRectF, Qt
from PySide6.QtGui import QBrush, QPen
from PySide6.QtWidgets import QGraphicsEllipseItem, QGraphicsItem

from app.gui import theme
from app.gui.canvas.layout import PORT_R

HIT_R = 9.0  # ports are easier to hit than they look


class PortItem(QGraphicsEllipseItem):
    """An input or output port of a node (a child of its :class:`NodeItem`).

    The item itself is an invisible disc of radius :data:`HIT_R` (what the mouse hits);
    its child :attr:`dot` is the circle drawn.
    """

    def __init__(self, parent: QGraphicsItem, name: str, is_input: bool, type_name: str) -> None:
        super().__init__(QRectF(-HIT_R, -HIT_R, HIT_R * 2, HIT_R * 2), parent)
        self.name = name
        self.is_input = is_input
        self.type_name = type_name
        self.has_value = False
        self.setPen(QPen(Qt.PenStyle.NoPen))
        self.setBrush(QBrush(Qt.BrushStyle.NoBrush))
        self.setZValue(1)
        self.dot = QGraphicsEllipseItem(QRectF(-PORT_R, -PORT_R, PORT_R * 2, PORT_R * 2), self)
        self.dot.setPen(QPen(theme.NODE_OUTLINE, 1.0))
        self.dot.setAcceptedMouseButtons(Qt.MouseButton.NoButton)
        self.set_has_value(False)

    @property
    def node_id(self) -> str:
        return self.parentItem().node_id

    @property
    def is_output(self) -> bool:
        return not self.is_input

    def set_has_value(self, has_value: bool) -> None:
        """Filled blue when the input keeps a value of its own (used when nothing is wired)."""
        self.has_value = has_value
        self.dot.setBrush(theme.PORT_SET_FILL if has_value else theme.PORT_FILL)

    def anchor(self) -> QPointF:
        """Where wires attach, in scene coordinates."""
        return self.scenePos()
