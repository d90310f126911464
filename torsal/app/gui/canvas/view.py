"""The canvas view: zoom about the cursor, pan, box select, drag wires, search, drop nodes.

Mouse, as in Grasshopper: drag from a port to wire it (Shift adds to what feeds the
input, Ctrl removes the wire); drop a wire on empty canvas to search for a node that
takes it; double-click empty canvas to search; wheel zooms about the cursor; middle or
right drag pans (a right-click without a drag opens the menu of what is under the cursor:
a port, a node, a group, the canvas); left drag on empty canvas selects with a box;
Alt-drag duplicates.

Selection, as in Grasshopper, for a click on a node and for a box alike: a plain click or
box replaces the selection, Shift adds to it, Ctrl removes from it, Ctrl+Shift toggles.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager

from PySide6.QtCore import QMimeData, QPoint, QPointF, QRectF, Qt, Signal
from PySide6.QtGui import (
    QContextMenuEvent,
    QCursor,
    QDragEnterEvent,
    QDragMoveEvent,
    QDropEvent,
    QKeyEvent,
    QMouseEvent,
    QPainter,
    QPainterPathStroker,
    QPen,
    QWheelEvent,
)
from PySide6.QtWidgets import QGraphicsItem, QGraphicsView, QMenu, QWidget

from torsal.app.gui import theme
from torsal.app.gui.canvas import context_menus
from torsal.app.gui.canvas.group_item import GroupItem
from torsal.app.gui.canvas.node_item import NodeItem
from torsal.app.gui.canvas.opening_focus import focus_regions
from torsal.app.gui.canvas.port_item import PortItem
from torsal.app.gui.canvas.scene import CanvasScene
from torsal.app.gui.canvas.wire_item import DragWire, WireItem
from torsal.app.gui.fuzzy import Entry
from torsal.app.gui.search_popup import SearchPopup
from torsal.app.gui.theme import palette_order
from torsal.app.gui.wire_ranking import rank_for_wire
from torsal.engine.types import can_cast, get_type

NODE_MIME = "application/x-torsal-node-type"
ZOOM_STEP = 1.15
ZOOM_RANGE = (0.15, 4.0)
READABLE_ZOOM = 0.75  # below this the 8-point labels cannot be read
OPENING_ZOOM = 0.6  # an opened file is shown whole only when it can be read at this zoom
PAN_THRESHOLD = 4
WIRE_REACH = 4.0  # view pixels either side of a wire that a right-click still finds it


def selection_operation(modifiers: Qt.KeyboardModifier) -> str:
    """What a click or box with ``modifiers`` does to the selection: "replace", "add",
    "remove" or "toggle" (Grasshopper's Shift, Ctrl and Ctrl+Shift)."""
    shift = bool(modifiers & Qt.KeyboardModifier.ShiftModifier)
    ctrl = bool(modifiers & Qt.KeyboardModifier.ControlModifier)
    if shift and ctrl:
        return "toggle"
    if shift:
        return "add"
    if ctrl:
        return "remove"
    return "replace"


def _combine(operation: str, before: set[QGraphicsItem], touched: set[QGraphicsItem]) -> set[QGraphicsItem]:
    if operation == "add":
        return before | touched
    if operation == "remove":
        return before - touched
    if operation == "toggle":
        return before ^ touched
    return set(touched)


def _without_modifiers(event: QMouseEvent) -> QMouseEvent:
    """The same mouse event with no keyboard modifiers (Qt's own Ctrl-toggles rule must not
    run: the view applies Grasshopper's)."""
    return QMouseEvent(
        event.type(),
        event.position(),
        event.scenePosition(),
        event.globalPosition(),
        event.button(),
        event.buttons(),
        Qt.KeyboardModifier.NoModifier,
    )


class CanvasView(QGraphicsView):
    """Shows a :class:`CanvasScene` and turns mouse gestures into edits."""

    node_placed = Signal(str)
    escape_pressed = Signal()

    def __init__(self, scene: CanvasScene, popup: SearchPopup, parent: QWidget | None = None) -> None:
        super().__init__(scene, parent)
        self.canvas = scene
        self.popup = popup
        self.setRenderHints(QPainter.RenderHint.Antialiasing | QPainter.RenderHint.TextAntialiasing)
        self.setViewportUpdateMode(QGraphicsView.ViewportUpdateMode.SmartViewportUpdate)
        self.setCacheMode(QGraphicsView.CacheModeFlag.CacheBackground)  # the grid is drawn once
        self.setTransformationAnchor(QGraphicsView.ViewportAnchor.AnchorUnderMouse)
        # a dock growing (the Messages dock after a solve) keeps the top-left in place: a graph
        # reads from its inputs, top-left
        self.setResizeAnchor(QGraphicsView.ViewportAnchor.NoAnchor)
        self.setDragMode(QGraphicsView.DragMode.RubberBandDrag)
        self.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        self.setVerticalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        self.setAcceptDrops(True)
        self.setFocusPolicy(Qt.FocusPolicy.StrongFocus)
        self._drag_wire: DragWire | None = None
        self._pan_start: QPoint | None = None
        self._panned = False
        self._alt_drag: tuple[QPointF, dict[NodeItem, QPointF]] | None = None
        self._pending_wire: PortItem | None = None
        self._place_at = QPointF()
        self._last_mouse: QPoint | None = None
        self._menu_on_release = False
        # a Shift/Ctrl click or box in progress: the operation, the selection before it, and
        # (for a click) the selection it made, restored after Qt's own release handling
        self._selecting: tuple[str, set[QGraphicsItem]] | None = None
        self._click_selection: set[QGraphicsItem] | None = None
        self.viewport().setMouseTracking(True)  # the Menu key opens the menu under the mouse
        popup.chosen.connect(self._place_chosen)
        popup.dismissed.connect(self._forget_pending_wire)

    # -- helpers ---------------------------------------------------------------------
    def zoom(self) -> float:
        return self.transform().m11()

    def zoom_by(self, factor: float, anchor: QPoint | None = None) -> None:
        """Zoom by ``factor`` keeping the scene point under ``anchor`` (view coordinates) still."""
        target = min(ZOOM_RANGE[1], max(ZOOM_RANGE[0], self.zoom() * factor))
        factor = target / self.zoom()
        anchor = anchor if anchor is not None else self.viewport().rect().center()
        before = self.mapToScene(anchor)
        mode = self.transformationAnchor()
        self.setTransformationAnchor(QGraphicsView.ViewportAnchor.NoAnchor)
        self.scale(factor, factor)
        self.setTransformationAnchor(mode)
        drift = self.mapToScene(anchor) - before
        self.pan_by(QPointF(drift.x() * self.zoom(), drift.y() * self.zoom()))

    def pan_by(self, delta: QPointF) -> None:
        """Move the view's content by ``delta`` view pixels (the scroll bars are hidden, not gone)."""
        horizontal, vertical = self.horizontalScrollBar(), self.verticalScrollBar()
        horizontal.setValue(round(horizontal.value() - delta.x()))
        vertical.setValue(round(vertical.value() - delta.y()))

    def zoom_to_fit(self, readable: bool = False) -> None:
        """Show every node. With ``readable`` (a file just opened) the zoom stays at least
        :data:`READABLE_ZOOM`, so the labels can be read, and the view starts at the graph's
        top-left (its inputs, by convention) when it does not all fit."""
        rect = self.canvas.items_rect()
        if rect.isNull():
            return
        margin = rect.adjusted(-30, -30, 30, 30)
        self.fitInView(margin, Qt.AspectRatioMode.KeepAspectRatio)
        zoom = self.zoom()
        target = min(zoom, 1.25)
        if readable:
            target = max(target, READABLE_ZOOM)
        if target != zoom:
            self.resetTransform()
            self.scale(target, target)
        if target > zoom + 1e-9:  # it does not all fit: begin at the top-left corner
            view = self.viewport().rect()
            self.centerOn(
                margin.left() + view.width() / (2 * target), margin.top() + view.height() / (2 * target)
            )
        else:
            self.centerOn(rect.center())

    def frame_opened(self) -> None:
        """Frame a file just opened: the whole graph when it can be read at
        :data:`OPENING_ZOOM` or more, otherwise the widest region around its last (most
        downstream) previewed nodes that can (:func:`~.opening_focus.focus_regions`), and
        at worst the last node itself at that zoom."""
        rect = self.canvas.items_rect()
        if rect.isNull():
            return
        zoom, margin = self._fit(rect)
        if zoom >= OPENING_ZOOM:
            self._show(margin, min(zoom, 1.25))
            return
        x_of = {n: item.pos().x() for n, item in self.canvas.nodes.items()}
        regions = focus_regions(self.canvas.doc.graph, x_of)
        boxes = [self._nodes_rect(region) for region in regions]
        boxes = [box for box in boxes if not box.isNull()]
        for box in boxes:
            zoom, margin = self._fit(box)
            if zoom >= OPENING_ZOOM:
                self._show(margin, min(zoom, 1.0))
                return
        self._show(boxes[-1] if boxes else rect, OPENING_ZOOM)

    def _nodes_rect(self, node_ids: set[str]) -> QRectF:
        rect = QRectF()
        for node_id in node_ids:
            item = self.canvas.nodes.get(node_id)
            if item is not None:
                rect = rect.united(item.sceneBoundingRect())
        return rect

    def _fit(self, rect: QRectF) -> tuple[float, QRectF]:
        """The zoom that shows ``rect`` with a margin, and that margin rectangle."""
        margin = rect.adjusted(-30, -30, 30, 30)
        view = self.viewport().rect()
        zoom = min(view.width() / max(margin.width(), 1.0), view.height() / max(margin.height(), 1.0))
        return zoom, margin

    def _show(self, rect: QRectF, zoom: float) -> None:
        self.resetTransform()
        self.scale(zoom, zoom)
        self.centerOn(rect.center())

    def _port_at(self, view_pos: QPoint) -> PortItem | None:
        for item in self.items(view_pos):
            if isinstance(item, PortItem):
                return item
        return None

    def itemAt(self, *pos: object) -> QGraphicsItem | None:
        """The topmost item under the point that is not a wire (wires draw above the nodes,
        and the area a curved wire encloses would otherwise hide what is under it)."""
        for item in self.items(*pos):
            if not isinstance(item, WireItem | DragWire):
                return item
        return None

    def _node_at(self, view_pos: QPoint) -> NodeItem | None:
        item = self.itemAt(view_pos)
        while item is not None and not isinstance(item, NodeItem):
            item = item.parentItem()
        return item

    # -- painting --------------------------------------------------------------------
    def drawBackground(self, painter: QPainter, rect: QRectF) -> None:
        painter.fillRect(rect, theme.CANVAS_BACKGROUND)
        if self.zoom() < 0.35:
            return
        step = 20.0
        left = int(rect.left() // step) * step
        top = int(rect.top() // step) * step
        for colour, spacing in ((theme.GRID_MINOR, step), (theme.GRID_MAJOR, step * 5)):
            painter.setPen(QPen(colour, 0))
            x = left - left % spacing
            while x < rect.right():
                painter.drawLine(QPointF(x, rect.top()), QPointF(x, rect.bottom()))
                x += spacing
            y = top - top % spacing
            while y < rect.bottom():
                painter.drawLine(QPointF(rect.left(), y), QPointF(rect.right(), y))
                y += spacing

    # -- mouse -----------------------------------------------------------------------
    def wheelEvent(self, event: QWheelEvent) -> None:
        steps = event.angleDelta().y() / 120.0
        if steps:
            self.zoom_by(ZOOM_STEP**steps, event.position().toPoint())
        event.accept()

    def mousePressEvent(self, event: QMouseEvent) -> None:
        pos = event.position().toPoint()
        self._last_mouse = pos
        if event.button() in (Qt.MouseButton.MiddleButton, Qt.MouseButton.RightButton):
            # Right: a drag pans, a click (released without a drag) opens the menu of what
            # is under the cursor, wherever the press lands (node, port, wire, group, canvas).
            self._pan_start = pos
            self._panned = False
            self._menu_on_release = False
            event.accept()
            return
        if event.button() == Qt.MouseButton.LeftButton:
            port = self._port_at(pos)
            if port is not None:
                self._drag_wire = DragWire(port)
                self.canvas.addItem(self._drag_wire)
                self._drag_wire.follow(self.mapToScene(pos))
                event.accept()
                return
            node = self._node_at(pos)
            if node is not None and event.modifiers() & Qt.KeyboardModifier.AltModifier:
                self._start_alt_drag(node, self.mapToScene(pos))
                event.accept()
                return
            operation = selection_operation(event.modifiers())
            if operation != "replace":
                self._modified_press(event, node, operation)
                return
        super().mousePressEvent(event)

    def _modified_press(self, event: QMouseEvent, node: NodeItem | None, operation: str) -> None:
        """A Shift/Ctrl press: on a node it changes that node's selection (and a drag then
        moves what is selected); on empty canvas it begins a box with that operation."""
        before = set(self.canvas.selectedItems())
        if node is None:
            self._selecting = (operation, before)
            with self._quiet_selection():  # Qt starts its box, clearing the selection
                super().mousePressEvent(_without_modifiers(event))
            self._apply_selection(before, announce=True)
            return
        wanted = _combine(operation, before, {node})
        self._apply_selection(wanted)
        self._click_selection = wanted
        if node in wanted:  # a drag from here moves the selection
            super().mousePressEvent(_without_modifiers(event))
        event.accept()

    @contextmanager
    def _quiet_selection(self) -> Iterator[None]:
        """Qt's own selection changes inside are not announced (the view announces its own)."""
        blocked = self.canvas.blockSignals(True)
        try:
            yield
        finally:
            self.canvas.blockSignals(blocked)

    def _apply_selection(self, items: set[QGraphicsItem], announce: bool = False) -> None:
        """Select exactly ``items`` with one ``selectionChanged`` (none when nothing changes,
        unless ``announce``: Qt changed it quietly just before)."""
        if set(self.canvas.selectedItems()) == items and not announce:
            return
        blocked = self.canvas.blockSignals(True)
        try:
            for item in self.canvas.selectedItems():
                if item not in items:
                    item.setSelected(False)
            for item in items:
                if item.scene() is self.canvas:
                    item.setSelected(True)
        finally:
            self.canvas.blockSignals(blocked)
        self.canvas.selectionChanged.emit()

    def _band_selection(self, announce: bool = False) -> None:
        """While a Shift/Ctrl box is dragged: what it touches combined with what was selected."""
        if self._selecting is None:
            return
        operation, before = self._selecting
        band = self.rubberBandRect()
        touched: set[QGraphicsItem] = set()
        if not band.isNull():
            area = self.mapToScene(band)
            mode = self.rubberBandSelectionMode()
            touched = {
                item
                for item in self.canvas.items(area, mode)
                if item.flags() & QGraphicsItem.GraphicsItemFlag.ItemIsSelectable
            }
        self._apply_selection(_combine(operation, before, touched), announce)

    def mouseMoveEvent(self, event: QMouseEvent) -> None:
        pos = event.position().toPoint()
        self._last_mouse = pos
        if self.canvas.editor.dragging and not event.buttons() & Qt.MouseButton.LeftButton:
            # the button went up where the canvas never saw it (over a popup that took the
            # mouse): the slider's press ends as its release would have ended it
            for item in self.canvas.nodes.values():
                item.end_widget_press()
        if self._pan_start is not None:
            delta = pos - self._pan_start
            if self._panned or delta.manhattanLength() > PAN_THRESHOLD:
                self._panned = True
                self._pan_start = pos
                self.pan_by(QPointF(delta))
            event.accept()
            return
        if self._drag_wire is not None:
            self._drag_wire.follow(self.mapToScene(pos))
            event.accept()
            return
        if self._alt_drag is not None:
            start, items = self._alt_drag
            delta = self.mapToScene(pos) - start
            for item, origin in items.items():
                item.setPos(origin + delta)
            event.accept()
            return
        if self._selecting is not None:
            with self._quiet_selection():  # Qt's box replaces the selection: ours follows
                super().mouseMoveEvent(_without_modifiers(event))
            self._band_selection(announce=True)
            return
        if self._click_selection is not None:
            super().mouseMoveEvent(_without_modifiers(event))
            return
        super().mouseMoveEvent(event)

    def mouseReleaseEvent(self, event: QMouseEvent) -> None:
        pos = event.position().toPoint()
        if self._pan_start is not None and event.button() in (
            Qt.MouseButton.MiddleButton,
            Qt.MouseButton.RightButton,
        ):
            panned = self._panned
            self._pan_start = None
            if not panned and event.button() == Qt.MouseButton.RightButton:
                self._menu_on_release = True  # a platform context-menu event after this is spent
                self._context_menu(pos, event.globalPosition().toPoint())
            event.accept()
            return
        if self._drag_wire is not None and event.button() == Qt.MouseButton.LeftButton:
            self._finish_wire(pos, event.modifiers(), event.globalPosition().toPoint())
            event.accept()
            return
        if self._alt_drag is not None and event.button() == Qt.MouseButton.LeftButton:
            self._alt_drag = None
            self.canvas.commit_moves()
            self.canvas.doc.undo_stack.endMacro()
            event.accept()
            return
        if event.button() == Qt.MouseButton.LeftButton and (
            self._selecting is not None or self._click_selection is not None
        ):
            self._band_selection()
            wanted = self._click_selection if self._click_selection is not None else None
            if wanted is None and self._selecting is not None:
                wanted = set(self.canvas.selectedItems())
            self._selecting = None
            self._click_selection = None
            with self._quiet_selection():  # Qt's release of a still click selects only it
                super().mouseReleaseEvent(_without_modifiers(event))
            if wanted is not None:
                self._apply_selection(wanted, announce=True)
            self.canvas.commit_moves()
            return
        super().mouseReleaseEvent(event)
        if event.button() == Qt.MouseButton.LeftButton:
            self.canvas.commit_moves()

    def mouseDoubleClickEvent(self, event: QMouseEvent) -> None:
        pos = event.position().toPoint()
        item = self.itemAt(pos)
        if isinstance(item, GroupItem) and item.title_rect().contains(self.mapToScene(pos)):
            self.canvas.rename_group(item.group_id)
            event.accept()
            return
        if (item is None or isinstance(item, GroupItem)) and event.button() == Qt.MouseButton.LeftButton:
            self.open_search(self.mapToScene(pos), event.globalPosition().toPoint())
            event.accept()
            return
        super().mouseDoubleClickEvent(event)

    def contextMenuEvent(self, event: QContextMenuEvent) -> None:
        """The platform's context-menu event. A right press in progress opens its menu on
        release (so a right drag can pan: X11 sends this event on the press); a menu the
        release already opened is not opened twice (Windows sends it after the release); any
        other mouse-made event (a touch-and-hold, a pen) opens the menu where it points. The
        keyboard's event opens the menu of the item under the mouse."""
        if event.reason() == QContextMenuEvent.Reason.Mouse:
            if self._pan_start is not None:
                pass
            elif self._menu_on_release:
                self._menu_on_release = False
            else:
                self._context_menu(event.pos(), event.globalPos())
        else:
            self._menu_under_mouse()
        event.accept()

    def _menu_under_mouse(self) -> None:
        """The Menu key: the menu of the item under the mouse (the view's centre when the
        mouse is elsewhere)."""
        viewport = self.viewport()
        pos = viewport.mapFromGlobal(QCursor.pos())
        if self._last_mouse is not None and (viewport.underMouse() or not viewport.rect().contains(pos)):
            pos = self._last_mouse
        if not viewport.rect().contains(pos):
            pos = viewport.rect().center()
        self._context_menu(pos, viewport.mapToGlobal(pos))

    def _wire_at(self, view_pos: QPoint) -> WireItem | None:
        """The wire passing within a few pixels of ``view_pos`` (its stroke, not the area its
        curve encloses)."""
        scene_pos = self.mapToScene(view_pos)
        reach = WIRE_REACH / max(self.zoom(), 1e-6)
        near = QRectF(scene_pos.x() - reach, scene_pos.y() - reach, 2 * reach, 2 * reach)
        stroker = QPainterPathStroker()
        stroker.setWidth(2 * reach)
        for item in self.canvas.items(near):
            if isinstance(item, WireItem) and stroker.createStroke(item.path()).contains(scene_pos):
                return item
        return None

    def _context_menu(self, pos: QPoint, global_pos: QPoint) -> None:
        port = self._port_at(pos)
        if port is not None:
            menu = context_menus.port_menu(self.canvas, port)
        else:
            node = self._node_at(pos)
            under = self.itemAt(pos)
            if node is not None:
                if not node.isSelected():
                    self.canvas.select_nodes([node.node_id])
                menu = context_menus.node_menu(self.canvas, node)
            elif (wire := self._wire_at(pos)) is not None:
                menu = context_menus.wire_menu(self.canvas, wire.wire)
            elif isinstance(under, GroupItem):
                menu = context_menus.group_menu(self.canvas, under.group_id)
            else:
                menu = context_menus.canvas_menu(self, self.mapToScene(pos))
        if menu is not None:
            self.show_menu(menu, global_pos)

    def show_menu(self, menu: QMenu, global_pos: QPoint) -> None:
        """Open a right-click menu at ``global_pos`` (tests replace this to pick an entry)."""
        menu.exec(global_pos)

    def keyPressEvent(self, event: QKeyEvent) -> None:
        if event.key() == Qt.Key.Key_Menu:
            self._menu_under_mouse()
            event.accept()  # accepted: the platform sends no second, keyboard context-menu event
            return
        if event.key() == Qt.Key.Key_Escape:
            if self._drag_wire is not None:  # Esc first drops a wire being dragged
                self.canvas.removeItem(self._drag_wire)
                self._drag_wire = None
            else:
                self.escape_pressed.emit()
            event.accept()
            return
        super().keyPressEvent(event)

    # -- wires -----------------------------------------------------------------------
    def _finish_wire(self, pos: QPoint, modifiers: Qt.KeyboardModifier, global_pos: QPoint) -> None:
        drag, self._drag_wire = self._drag_wire, None
        self.canvas.removeItem(drag)
        start = drag.port
        end = self._port_at(pos)
        if end is None:
            if self.itemAt(pos) is None or isinstance(self.itemAt(pos), GroupItem):
                self._pending_wire = start
                accept, note, rank = self._type_filter(start)
                self.open_search(self.mapToScene(pos), global_pos, accept, note, rank)
            return
        if end.is_input == start.is_input or end.node_id == start.node_id:
            return
        out_port, in_port = (start, end) if start.is_output else (end, start)
        mode = "replace"
        if modifiers & Qt.KeyboardModifier.ShiftModifier:
            mode = "add"
        elif modifiers & Qt.KeyboardModifier.ControlModifier:
            mode = "remove"
        self.canvas.editor.connect(out_port.node_id, out_port.name, in_port.node_id, in_port.name, mode)

    def _type_filter(self, port: PortItem) -> tuple[object, str, object]:
        """Which nodes a wire dropped from ``port`` may meet, the popup's note, and their
        ranking (the likeliest first: :mod:`torsal.app.gui.wire_ranking`)."""
        try:
            value_type = get_type(port.type_name)
        except KeyError:
            return None, "", None
        rank = rank_for_wire(value_type, port.is_output, self.popup.registry, palette_order)
        if port.is_output:

            def accept(entry: Entry) -> bool:
                return any(can_cast(value_type, p.type) for p in entry.cls.inputs)

            return accept, f"Nodes that take {value_type.name}", rank

        def accept_source(entry: Entry) -> bool:
            return any(can_cast(p.type, value_type) for p in entry.cls.outputs)

        return accept_source, f"Nodes that give {value_type.name}", rank

    def _forget_pending_wire(self) -> None:
        self._pending_wire = None

    # -- search and placing ------------------------------------------------------------
    def open_search(
        self,
        scene_pos: QPointF,
        global_pos: QPoint,
        accept: object = None,
        note: str = "",
        rank: object = None,
    ) -> None:
        self._place_at = scene_pos
        self.popup.open_at(global_pos, accept, note, rank)

    def _place_chosen(self, type_id: str, settings: dict | None = None) -> None:
        pending, self._pending_wire = self._pending_wire, None
        editor = self.canvas.editor
        doc = self.canvas.doc
        position = (self._place_at.x(), self._place_at.y())
        if pending is None:
            node_id = editor.add_node(type_id, position, settings)
        else:
            doc.undo_stack.beginMacro("Add and connect")
            if pending.is_output:
                node_id = editor.add_node(type_id, position, settings)
            else:  # the new node feeds the input: put it to the left of the drop point
                node_id = editor.add_node(type_id, (position[0] - 160, position[1]), settings)
            if node_id is not None:
                self._connect_new(pending, node_id)
            doc.undo_stack.endMacro()
        if node_id is not None:
            self.canvas.select_nodes([node_id])
            self.node_placed.emit(node_id)

    def _connect_new(self, port: PortItem, node_id: str) -> None:
        """Wire a just-placed node to the port a wire was dragged from."""
        graph = self.canvas.doc.graph
        node = graph.nodes[node_id].node
        other = graph.nodes[port.node_id].node
        if port.is_output:
            source = other.output_port(port.name)
            candidates = [p for p in node.input_ports() if can_cast(source.type, p.type)]
            candidates.sort(key=lambda p: p.type is not source.type)
            if candidates:
                self.canvas.editor.connect(port.node_id, port.name, node_id, candidates[0].name)
        else:
            target = other.input_port(port.name)
            candidates = [p for p in node.output_ports() if can_cast(p.type, target.type)]
            candidates.sort(key=lambda p: p.type is not target.type)
            if candidates:
                self.canvas.editor.connect(node_id, candidates[0].name, port.node_id, port.name)

    # -- Alt-drag duplicates ---------------------------------------------------------
    def _start_alt_drag(self, node: NodeItem, scene_pos: QPointF) -> None:
        if not node.isSelected():
            self.canvas.select_nodes([node.node_id])
        ids = self.canvas.selected_node_ids()
        self.canvas.doc.undo_stack.beginMacro("Duplicate")
        new_ids = self.canvas.editor.duplicate(ids, offset=(0.0, 0.0))
        self.canvas.select_nodes(new_ids)
        items = {self.canvas.nodes[n]: self.canvas.nodes[n].pos() for n in new_ids}
        self._alt_drag = (scene_pos, items)

    # -- drops from the palette ------------------------------------------------------
    def dragEnterEvent(self, event: QDragEnterEvent) -> None:
        if event.mimeData().hasFormat(NODE_MIME):
            event.acceptProposedAction()
        else:
            event.ignore()

    def dragMoveEvent(self, event: QDragMoveEvent) -> None:
        if event.mimeData().hasFormat(NODE_MIME):
            event.acceptProposedAction()
        else:
            event.ignore()

    def dropEvent(self, event: QDropEvent) -> None:
        mime: QMimeData = event.mimeData()
        if not mime.hasFormat(NODE_MIME):
            event.ignore()
            return
        type_id = bytes(mime.data(NODE_MIME)).decode("utf-8")
        scene_pos = self.mapToScene(event.position().toPoint())
        node_id = self.canvas.editor.add_node(type_id, (scene_pos.x(), scene_pos.y()))
        if node_id:
            self.canvas.select_nodes([node_id])
        event.acceptProposedAction()

    def place_in_view(self, type_id: str) -> str | None:
        """Add a node near the middle of what the view shows (a palette click)."""
        centre = self.mapToScene(self.viewport().rect().center())
        offset = 12 * (len(self.canvas.nodes) % 6)
        node_id = self.canvas.editor.add_node(type_id, (centre.x() - 60 + offset, centre.y() - 30 + offset))
        if node_id:
            self.canvas.select_nodes([node_id])
        return node_id
