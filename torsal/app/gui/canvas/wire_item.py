"""Wires: bezier curves from an output port to an input port.

Drawn the way Grasshopper users read them: a thin line carries one item, a thick line
a list, a dashed line a tree of several branches.
"""

from __future__ import annotations

from PySide6.QtCore import QPointF, Qt
from PySide6.QtGui import QPainterPath, QPen
from PySide6.QtWidgets import QGraphicsPathItem

from torsal.app.gui import theme
from torsal.app.gui.canvas.layout import PORT_R
from torsal.app.gui.canvas.wire_routing import NodeGrid, plain_path, route
from torsal.engine.graph import Wire

WIDTHS = {"item": 1.3, "list": 3.0, "tree": 2.2}


def wire_path(start: QPointF, end: QPointF) -> QPainterPath:
    """A horizontal-tangent cubic from ``start`` to ``end``."""
    return plain_path(start, end)


WIRE_Z = 0.5  # above group boxes (-10) and nodes (0): a wire never hides behind a node it passes


class WireItem(QGraphicsPathItem):
    """One engine wire between two port items. It bends around the nodes it does not
    connect to (:mod:`~torsal.app.gui.canvas.wire_routing`, with the scene's ``grid`` of node
    rectangles) and is drawn above the nodes, so even where no detour is found it never
    runs hidden behind one; it starts and ends at its ports' rims, so the port dots stay
    whole."""

    def __init__(
        self, wire: Wire, source_port: object, target_port: object, grid: NodeGrid | None = None
    ) -> None:
        super().__init__()
        self.wire = wire
        self.grid = grid
        self.source_port = source_port
        self.target_port = target_port
        self.kind = "item"
        self.highlighted = False
        self.setZValue(WIRE_Z)
        self.setAcceptedMouseButtons(Qt.MouseButton.NoButton)  # clicks go to the nodes under it
        self.update_path()
        self.update_pen()

    def update_path(self) -> None:
        rim = QPointF(PORT_R, 0.0)
        start, end = self.source_port.anchor() + rim, self.target_port.anchor() - rim
        self.setPath(route(start, end, self.grid, (self.wire.source, self.wire.target)))

    def set_kind(self, kind: str) -> None:
        if kind != self.kind:
            self.kind = kind
            self.update_pen()

    def set_highlighted(self, on: bool) -> None:
        if on != self.highlighted:
            self.highlighted = on
            self.update_pen()

    def update_pen(self) -> None:
        colour = theme.WIRE_SELECTED if self.highlighted else theme.WIRE
        pen = QPen(colour, WIDTHS[self.kind])
        pen.setCapStyle(Qt.PenCapStyle.RoundCap)
        if self.kind == "tree":
            pen.setStyle(Qt.PenStyle.DashLine)
        self.setPen(pen)


class DragWire(QGraphicsPathItem):
    """The wire that follows the mouse while a connection is being dragged."""

    def __init__(self, port: object) -> None:
        super().__init__()
        self.port = port
        pen = QPen(theme.WIRE_DRAG, 2.0)
        pen.setStyle(Qt.PenStyle.DashLine)
        self.setPen(pen)
        self.setZValue(10)

    def follow(self, scene_pos: QPointF) -> None:
        anchor = self.port.anchor()
        if self.port.is_input:
            self.setPath(wire_path(scene_pos, anchor))
        else:
            self.setPath(wire_path(anchor, scene_pos))
