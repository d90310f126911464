"""The canvas scene: items kept in step with the engine graph's change events.

The scene owns no data. It creates, updates and removes node, wire and group items
when the :class:`~torsal.app.gui.document.Document` reports a change, and recolours them
when solve results arrive.

An edit costs what it touches: the wire items of each node are indexed, and the work
that concerns the whole scene (its rectangle, the one ``selectionChanged`` for the
selected items an edit removed) is done once when the edit's undo command has run
(or on the next event-loop turn for an edit made outside the undo stack).
"""

from __future__ import annotations

import gc

from PySide6.QtCore import QObject, QPointF, QRectF, QTimer, Signal
from PySide6.QtWidgets import QGraphicsScene, QGraphicsSceneHelpEvent, QInputDialog

from torsal.app.gui.canvas.group_item import GroupItem
from torsal.app.gui.canvas.node_item import NodeItem
from torsal.app.gui.canvas.port_item import PortItem
from torsal.app.gui.canvas.wire_item import WireItem
from torsal.app.gui.canvas.wire_routing import NodeGrid
from torsal.app.gui.cluster_widgets import ClusterPortsDialog
from torsal.app.gui.commands import AddNodes
from torsal.app.gui.document import Document
from torsal.app.gui.editor import Editor
from torsal.app.gui.graph_order import fresh_id
from torsal.app.gui.qt_compat import defer
from torsal.app.gui.solve_controller import SolveOutcome
from torsal.engine.cluster import INPUT_TYPE, OUTPUT_TYPE, ClusterInput, ClusterOutput, is_cluster
from torsal.engine.cluster_edits import definition_of
from torsal.engine.events import (
    NODE_REDRAWN,
    GroupEvent,
    NodeAdded,
    NodeMoved,
    NodeRemoved,
    WireAdded,
    WireRemoved,
)
from torsal.engine.graph import GraphEvent, NodeRecord, Wire
from torsal.engine.node import LIST, TREE

#: Events that change how a node is drawn (its ports, labels, widget).
REDRAW_EVENTS = NODE_REDRAWN


class CanvasScene(QGraphicsScene):
    """Node, wire and group items for the document's graph."""

    help_requested = Signal(str)
    export_requested = Signal(str, str)  # node id, output port: "Export…"
    bake_requested = Signal(object)  # node ids: a node's own "Bake…"

    def __init__(self, doc: Document, editor: Editor, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.doc = doc
        self.editor = editor
        self.nodes: dict[str, NodeItem] = {}
        self.wires: dict[Wire, WireItem] = {}
        self.groups: dict[str, GroupItem] = {}
        self._wires_of: dict[str, dict[Wire, None]] = {}  # node id → its wire items' wires
        self.grid = NodeGrid()  # node rectangles, for wires to bend around
        self._moved_boxes: dict[str, QRectF] = {}  # where moved nodes were and went: wires near re-route
        self._removed_boxes: list[QRectF] = []  # where removed nodes were: detours near re-route
        self._added_boxes: list[QRectF] = []  # where nodes were added (pasted...): wires there re-route
        self._routed_since_added: set[Wire] = set()  # wires made after the last node added: routed
        self._highlighted: set[Wire] = set()
        self._syncing_move = False
        self._rect_due = False  # the scene rectangle waits for the end of the edit
        self._selection_due = False  # selected items were removed: selectionChanged is owed
        self._finish_timer = QTimer(self)
        self._finish_timer.setSingleShot(True)
        self._finish_timer.setInterval(0)
        self._finish_timer.timeout.connect(self.finish_edit)
        self.setItemIndexMethod(QGraphicsScene.ItemIndexMethod.NoIndex)
        doc.graph_replaced.connect(self.rebuild)
        doc.graph_changed.connect(self.on_graph_event)
        doc.undo_group.indexChanged.connect(lambda _index: self.finish_edit())
        doc.groups_changed.connect(self.refresh_groups)
        doc.results_changed.connect(self.apply_results)
        self.selectionChanged.connect(self._highlight_wires)
        self.rebuild()

    # -- building --------------------------------------------------------------------
    def rebuild(self) -> None:
        """Items for the whole graph (a file opened). The garbage collector waits meanwhile:
        every object made here stays alive, and each full collection it would run on the
        way scans the window's whole heap (half a second each with 10,000 nodes)."""
        paused = gc.isenabled()
        gc.disable()
        try:
            self._rebuild()
        finally:
            if paused:
                gc.enable()

    def _rebuild(self) -> None:
        self.clear()
        self.nodes.clear()
        self.wires.clear()
        self.groups.clear()
        self._wires_of.clear()
        self._highlighted.clear()
        self.grid.clear()
        self._moved_boxes.clear()
        self._removed_boxes.clear()
        self._added_boxes.clear()
        self._routed_since_added.clear()
        graph = self.doc.graph
        for record in graph.nodes.values():
            self._add_node(record.id)
        for wire in graph.wires:
            self._add_wire(wire)
        self.refresh_groups()
        self.update_scene_rect()

    def _add_node(self, node_id: str) -> NodeItem:
        item = NodeItem(self.doc.graph.nodes[node_id], self.doc.graph)  # laid out once, here
        self.addItem(item)
        self.grid.set(node_id, item.sceneBoundingRect())
        result = self.doc.result(node_id)
        if result is not None:
            item.set_result(result)
        self.nodes[node_id] = item
        return item

    def _add_wire(self, wire: Wire) -> WireItem | None:
        source, target = self.nodes.get(wire.source), self.nodes.get(wire.target)
        if source is None or target is None:
            return None
        if source.output_port(wire.source_port) is None or target.input_port(wire.target_port) is None:
            source.rebuild()  # a placeholder learns its ports from its wires
            target.rebuild()
        out_port, in_port = source.output_port(wire.source_port), target.input_port(wire.target_port)
        if out_port is None or in_port is None:
            return None
        item = WireItem(wire, out_port, in_port, self.grid)
        item.set_kind(self._wire_kind(wire))
        self.addItem(item)
        self.wires[wire] = item
        self._wires_of.setdefault(wire.source, {})[wire] = None
        self._wires_of.setdefault(wire.target, {})[wire] = None
        return item

    def _remove_wire(self, wire: Wire) -> None:
        item = self.wires.pop(wire, None)
        if item is not None:
            self.removeItem(item)
            self._highlighted.discard(wire)
            for node_id in (wire.source, wire.target):
                self._wires_of.get(node_id, {}).pop(wire, None)

    def wire_items_of(self, node_id: str) -> list[WireItem]:
        """The wire items into and out of ``node_id``."""
        return [self.wires[w] for w in self._wires_of.get(node_id, ())]

    # -- engine events ---------------------------------------------------------------
    def on_graph_event(self, event: GraphEvent) -> None:
        node_id = event.node_id
        if isinstance(event, NodeAdded):
            self._added_boxes.append(self._add_node(node_id).sceneBoundingRect())
            self._routed_since_added.clear()
        elif isinstance(event, NodeRemoved):
            item = self.nodes.pop(node_id, None)
            self._wires_of.pop(node_id, None)
            box = self.grid.boxes.get(node_id)
            self.grid.remove(node_id)
            if box is not None:  # wires that went round it may go straight now
                self._removed_boxes.append(QRectF(box[0], box[1], box[2] - box[0], box[3] - box[1]))
            if item is not None:
                self._remove_node_item(item)
        elif isinstance(event, WireAdded):
            self._add_wire(event.wire)
            if self._added_boxes:
                self._routed_since_added.add(event.wire)
            self._rewired(event.wire.target)
        elif isinstance(event, WireRemoved):
            self._remove_wire(event.wire)
            self._rewired(event.wire.target)
        elif isinstance(event, NodeMoved):
            item = self.nodes.get(node_id)
            if item is not None and (item.pos().x(), item.pos().y()) != tuple(event.new):
                self._syncing_move = True
                item.setPos(QPointF(*event.new))
                self._syncing_move = False
                self.node_item_moved(item)
        elif isinstance(event, REDRAW_EVENTS):
            self._refresh_node(node_id)
        elif isinstance(event, GroupEvent):
            self.refresh_groups()
        self._rect_due = True
        self._finish_timer.start()

    def _remove_node_item(self, item: NodeItem) -> None:
        """Remove a node's item; a selected one owes one ``selectionChanged`` for the edit."""
        if not item.isSelected():
            self.removeItem(item)
            return
        blocked = self.blockSignals(True)
        try:
            self.removeItem(item)
        finally:
            self.blockSignals(blocked)
        self._selection_due = True
        self._finish_timer.start()

    def finish_edit(self) -> None:
        """What waits for the end of an edit: the scene rectangle, one ``selectionChanged``."""
        self._finish_timer.stop()
        if self._rect_due:
            self._rect_due = False
            self.update_scene_rect()
        if self._selection_due:
            self._selection_due = False
            self.selectionChanged.emit()
        if self._moved_boxes:
            boxes, self._moved_boxes = list(self._moved_boxes.values()), {}
            self.reroute_near(boxes)
        if self._added_boxes:  # a node pasted or placed on a wire: the wire goes round it
            boxes, self._added_boxes = self._added_boxes, []
            routed, self._routed_since_added = self._routed_since_added, set()
            self.reroute_near(boxes, skip=routed)  # a paste's own wires were routed with its nodes there
        if self._removed_boxes:
            boxes, self._removed_boxes = self._removed_boxes, []
            self.reroute_near(boxes, detours_only=True)

    def reroute_near(self, boxes: list[QRectF], detours_only: bool = False,
                     skip: set[Wire] | frozenset[Wire] = frozenset()) -> None:
        """Route again the wires whose course comes near ``boxes``: the places nodes moved
        from and to or were added at, which wires not their own may have to bend around or
        may now pass straight by (a node's own wires follow it as it moves). With ``detours_only`` (the
        places of removed nodes, which no wire has to bend around now) only the wires that
        make a detour are looked at: deleting a thousand nodes costs no re-routing of the
        rest. Wires in ``skip`` are left as they are."""
        if len(boxes) > 64:  # a bulk edit: one box round them all
            union = QRectF(boxes[0])
            for box in boxes[1:]:
                union = union.united(box)
            boxes = [union]
        for wire, wire_item in self.wires.items():
            if wire in skip:
                continue
            path = wire_item.path()
            if detours_only and path.elementCount() <= 4:  # a plain curve: nothing to undo
                continue
            reach = path.boundingRect()
            if any(reach.intersects(box) for box in boxes):
                wire_item.update_path()

    def _rewired(self, node_id: str) -> None:
        """A wire into ``node_id`` came or went: only a node drawn from its wires (a
        placeholder's ports, a panel showing its input) is laid out again."""
        item = self.nodes.get(node_id)
        if item is not None and item.drawn_from_wires():
            self._refresh_node(node_id)

    def _refresh_node(self, node_id: str | None) -> None:
        item = self.nodes.get(node_id) if node_id else None
        if item is None:
            return
        if item.rebuild():  # a slider's new value moves nothing: its wires stay as routed
            self.node_item_moved(item)

    def node_item_moved(self, item: NodeItem) -> None:
        """Keep wires and group boxes attached while an item moves; the wires of other
        nodes near where it was and went are routed again when the edit ends."""
        old = self.grid.boxes.get(item.node_id)
        rect = item.sceneBoundingRect()
        self.grid.set(item.node_id, rect)
        if old is not None:
            swept = self._moved_boxes.get(item.node_id)
            if swept is None:
                swept = QRectF(old[0], old[1], old[2] - old[0], old[3] - old[1])
            self._moved_boxes[item.node_id] = swept.united(rect)
        for wire_item in self.wire_items_of(item.node_id):
            wire_item.update_path()
        for group in self.doc.graph.groups:
            if item.node_id in group.nodes:
                self._fit_group(group.id)

    def refresh_groups(self) -> None:
        present = {g.id for g in self.doc.graph.groups}
        for group_id in [g for g in self.groups if g not in present]:
            self.removeItem(self.groups.pop(group_id))
        for group in self.doc.graph.groups:
            if group.id not in self.groups:
                item = GroupItem(group.id)
                self.addItem(item)
                self.groups[group.id] = item
            self._fit_group(group.id)

    def _fit_group(self, group_id: str) -> None:
        group = next((g for g in self.doc.graph.groups if g.id == group_id), None)
        item = self.groups.get(group_id)
        if group is None or item is None:
            return
        rects = [self.nodes[n].sceneBoundingRect() for n in group.nodes if n in self.nodes]
        item.set_content(group.title, group.colour, rects)

    # -- results ---------------------------------------------------------------------
    def apply_results(self, outcome: SolveOutcome) -> None:
        """Recolour the nodes whose result changed (only those are repainted)."""
        resized = False
        changed = []
        for node_id, item in self.nodes.items():
            result = self.doc.result(node_id)
            if result is not item.result:
                changed.append(node_id)
                before = item.size()
                item.set_result(result)
                resized = resized or item.size() != before
        for node_id in changed:  # a wire's kind follows the data its source gave
            for wire in self._wires_of.get(node_id, ()):
                if wire.source == node_id:
                    self.wires[wire].set_kind(self._wire_kind(wire))
        if resized:  # a panel grew or shrank: the wires and groups follow
            for node_id, item in self.nodes.items():
                self.grid.set(node_id, item.sceneBoundingRect())
            for wire_item in self.wires.values():
                wire_item.update_path()
            self.refresh_groups()
            self.update_scene_rect()

    def _wire_kind(self, wire: Wire) -> str:
        """``item``, ``list`` or ``tree``, from the data the wire carried last."""
        result = self.doc.result(wire.source)
        tree = result.outputs.get(wire.source_port) if result is not None else None
        if tree is not None and not tree.is_empty():
            if tree.branch_count > 1:
                return "tree"
            return "list" if tree.item_count > 1 else "item"
        record = self.doc.graph.nodes.get(wire.source)
        port = record.node.output_port(wire.source_port) if record else None
        if port is not None and port.access is TREE:
            return "tree"
        if port is not None and port.access is LIST:
            return "list"
        return "item"

    def helpEvent(self, event: QGraphicsSceneHelpEvent) -> None:  # Qt's name
        """A port's tooltip is written when it is asked for: it shows the data the port
        carries, which changes with every solve, and most ports are never hovered."""
        for item in self.items(event.scenePos()):
            port = item if isinstance(item, PortItem) else item.parentItem()
            if isinstance(port, PortItem) and isinstance(port.parentItem(), NodeItem):
                port.setToolTip(port.parentItem().port_tooltip(port.name, port.is_input))
                break
        super().helpEvent(event)

    # -- selection and moves -----------------------------------------------------------
    def selected_node_ids(self) -> list[str]:
        return [i.node_id for i in self.selectedItems() if isinstance(i, NodeItem)]

    def select_nodes(self, node_ids: list[str]) -> None:
        """Select exactly ``node_ids``: one ``selectionChanged``, however many they are."""
        before = set(self.selectedItems())
        blocked = self.blockSignals(True)
        try:
            self.clearSelection()
            for node_id in node_ids:
                if node_id in self.nodes:
                    self.nodes[node_id].setSelected(True)
        finally:
            self.blockSignals(blocked)
        if set(self.selectedItems()) != before and not blocked:
            self.selectionChanged.emit()

    def _highlight_wires(self) -> None:
        """Highlight the wires of the selected nodes (only the wires that change are touched)."""
        wanted = {w for n in self.selected_node_ids() for w in self._wires_of.get(n, ())}
        for wire in self._highlighted - wanted:
            if wire in self.wires:
                self.wires[wire].set_highlighted(False)
        for wire in wanted - self._highlighted:
            self.wires[wire].set_highlighted(True)
        self._highlighted = wanted

    def commit_moves(self) -> None:
        """Turn items dragged to new places into one Move command."""
        moved = {}
        for node_id, item in self.nodes.items():
            record = self.doc.graph.nodes.get(node_id)
            if record is not None and (item.pos().x(), item.pos().y()) != tuple(record.position):
                moved[node_id] = (item.pos().x(), item.pos().y())
        if moved:
            self.editor.move(moved)
            for node_id in moved:  # positions are rounded to whole units
                item = self.nodes[node_id]
                item.setPos(QPointF(*self.doc.graph.nodes[node_id].position))

    def sizes(self, node_ids: list[str]) -> dict[str, tuple[float, float]]:
        return {n: self.nodes[n].size() for n in node_ids if n in self.nodes}

    def rename_node(self, node_id: str) -> None:
        record = self.doc.graph.nodes[node_id]
        label, ok = QInputDialog.getText(
            None,
            "Rename",
            f"Label of {record.node.name()} [{node_id}]:",
            text=record.label or record.node.name(),
        )
        if ok:
            self.editor.rename(node_id, "" if label == record.node.name() else label)

    # -- clusters --------------------------------------------------------------------
    def cluster_selection(self) -> str | None:
        """Collapse the selected nodes into one cluster node (selected afterwards)."""
        cluster_id = self.editor.cluster(self.selected_node_ids())
        if cluster_id is not None:
            self.select_nodes([cluster_id])
        return cluster_id

    def explode_cluster(self, node_id: str) -> list[str]:
        """Put a cluster's nodes in its place (selected afterwards)."""
        ids = self.editor.explode(node_id)
        self.select_nodes(ids)
        return ids

    def open_cluster(self, node_id: str) -> None:
        """Edit cluster ``node_id``'s definition on this canvas (on the next event-loop
        turn: the scene is rebuilt, and the item asking may be in the middle of an event)."""
        if node_id in self.doc.graph.nodes and is_cluster(self.doc.graph.nodes[node_id].node):
            defer(self, lambda: self.doc.enter_cluster(node_id))

    def add_cluster_port(self, kind: str, position: tuple[float, float]) -> str:
        """Inside a cluster: a new Input or Output node (a new port of the cluster once the
        edit is committed); its id."""
        node = ClusterInput() if kind == "input" else ClusterOutput()
        type_id = INPUT_TYPE if kind == "input" else OUTPUT_TYPE
        label = "Input" if kind == "input" else "Output"
        node_id = fresh_id(label, set(self.doc.graph.nodes))
        place = (float(round(position[0])), float(round(position[1])))
        record = NodeRecord(node_id, node, type_id, label, place)
        self.doc.push(AddNodes(self.doc, [record], text=f"Add cluster {kind}"))
        self.select_nodes([node_id])
        return node_id

    def edit_cluster_ports(self, node_id: str) -> None:
        """The cluster's name and ports: rename, reorder (one undo step)."""
        definition = definition_of(self.doc.graph, node_id)
        dialog = ClusterPortsDialog(definition.name, definition.input_names(), definition.output_names())
        if dialog.exec() == ClusterPortsDialog.DialogCode.Accepted:
            self.editor.edit_cluster(
                definition.id, dialog.name.text().strip(), dialog.ports("input"), dialog.ports("output")
            )

    def rename_group(self, group_id: str) -> None:
        """Ask for a group's new title (a double-click on its title bar)."""
        group = next((g for g in self.doc.graph.groups if g.id == group_id), None)
        if group is None:
            return
        title, ok = QInputDialog.getText(None, "Group", "Title:", text=group.title)
        if ok and title != group.title:
            self.editor.edit_group(group_id, title=title)

    def items_rect(self) -> QRectF:
        rect = QRectF()
        for item in [*self.nodes.values(), *self.groups.values()]:
            rect = rect.united(item.sceneBoundingRect())
        return rect

    def update_scene_rect(self) -> None:
        """A generous scene rectangle so the canvas can always be panned past the nodes."""
        rect = self.items_rect()
        if rect.isNull():
            rect = QRectF(0, 0, 800, 600)
        self.setSceneRect(rect.adjusted(-4000, -4000, 4000, 4000))
