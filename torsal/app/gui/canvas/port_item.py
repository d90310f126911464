"""A port: the small circle on a node's edge that wires start and end at.

Ports are plain C++ ellipse items (no Python ``paint``/``boundingRect``): Qt asks items
for their bounds dozens of times per repaint, and each call into Python would have to
take the GIL from a solving worker thread.
"""

from __future__ import annotations

from PySide6.QtCore import QPointF, QRectF, Qt
from PySide6.QtGui import QBrush, QPen
from PySide6.QtWidgets import QGraphicsEllipseItem, QGraphicsItem

from torsal.app.gui import theme
from torsal.app.gui.canvas.layout import PORT_R

HIT_R = 8.0  # ports are easier to hit than they look (neighbours, ROW_H apart, do not overlap)
# made once: a canvas of 10,000 nodes has 30,000 ports, and Qt copies these cheaply
_HIT_RECT = QRectF(-HIT_R, -HIT_R, HIT_R * 2, HIT_R * 2)
_DOT_RECT = QRectF(-PORT_R, -PORT_R, PORT_R * 2, PORT_R * 2)
_NO_PEN = QPen(Qt.PenStyle.NoPen)
_NO_BRUSH = QBrush(Qt.BrushStyle.NoBrush)
_NO_BUTTON = Qt.MouseButton.NoButton
_DOT_PEN = QPen(theme.NODE_OUTLINE, 1.0)
_FILL, _SET_FILL = QBrush(theme.PORT_FILL), QBrush(theme.PORT_SET_FILL)


class PortItem(QGraphicsEllipseItem):
    """An input or output port of a node (a child of its :class:`NodeItem`).

    The item itself is an invisible disc of radius :data:`HIT_R` (what the mouse hits);
    its child :attr:`dot` is the circle drawn.
    """

    def __init__(self, parent: QGraphicsItem, name: str, is_input: bool, type_name: str) -> None:
        super().__init__(_HIT_RECT, parent)
        self.name = name
        self.is_input = is_input
        self.type_name = type_name
        self.has_value = False
        self.setPen(_NO_PEN)
        self.setBrush(_NO_BRUSH)
        self.setZValue(1)
        self.dot = QGraphicsEllipseItem(_DOT_RECT, self)
        self.dot.setPen(_DOT_PEN)
        self.dot.setAcceptedMouseButtons(_NO_BUTTON)
        self.dot.setBrush(_FILL)

    @property
    def node_id(self) -> str:
        return self.parentItem().node_id

    @property
    def is_output(self) -> bool:
        return not self.is_input

    def set_has_value(self, has_value: bool) -> None:
        """Filled blue when the input keeps a value of its own (used when nothing is wired)."""
        if has_value != self.has_value:
            self.has_value = has_value
            self.dot.setBrush(_SET_FILL if has_value else _FILL)

    def anchor(self) -> QPointF:
        """Where wires attach, in scene coordinates."""
        return self.scenePos()
