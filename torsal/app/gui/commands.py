"""Undo commands: one :class:`QUndoCommand` per editing operation.

Every command edits the graph only through :class:`torsal.engine.graph.Graph` methods (the
engine reports each change as an event the canvas redraws from) inside
:meth:`~torsal.app.gui.edited.EditedDocument.editing`, which pauses the solver for edits that change results.
Commands keep the very objects they removed (records, wires, groups), so undo puts
back exactly what was there, in the same order, and a saved file gets the same bytes.
"""

from __future__ import annotations

import copy
from typing import Any

from PySide6.QtGui import QUndoCommand

from torsal.app.gui.edited import EditedDocument
from torsal.app.gui.graph_order import (
    group_by_id,
    restore_group_order,
    restore_node_order,
    restore_wire_order,
)
from torsal.engine.cluster import clone_graph
from torsal.engine.cluster_edits import (
    cluster_instance,
    definition_of,
    explode_cluster,
    make_cluster,
    rename_cluster,
    rename_cluster_port,
    reorder_cluster_ports,
    restore_cluster,
    set_cluster_graph,
)
from torsal.engine.graph import Graph, GraphError, Group, NodeRecord, Wire

SETTING_MERGE_ID = 1001


class GraphCommand(QUndoCommand):
    """Base: ``apply``/``revert`` run inside :meth:`~torsal.app.gui.edited.EditedDocument.editing`."""

    affects_solve = True

    def __init__(self, doc: EditedDocument, text: str) -> None:
        super().__init__(text)
        self.doc = doc

    def redo(self) -> None:
        with self.doc.editing(self.affects_solve) as graph:
            self.apply(graph)

    def undo(self) -> None:
        with self.doc.editing(self.affects_solve) as graph:
            self.revert(graph)

    def apply(self, graph: Graph) -> None:
        raise NotImplementedError

    def revert(self, graph: Graph) -> None:
        raise NotImplementedError


class AddNodes(GraphCommand):
    """Add node records and wires (a new node, a paste, a duplicate)."""

    def __init__(
        self, doc: EditedDocument, records: list[NodeRecord], wires: list[Wire] = (), text: str = "Add node"
    ) -> None:
        super().__init__(doc, text)
        self.records = list(records)
        self.wires = list(wires)

    def apply(self, graph: Graph) -> None:
        graph.add_many(self.records, self.wires)

    def revert(self, graph: Graph) -> None:
        for wire in reversed(self.wires):
            if graph.has_wire(wire):
                graph.disconnect(wire)
        graph.remove_many([record.id for record in reversed(self.records)])


class RemoveNodes(GraphCommand):
    """Delete nodes with their wires; undo restores nodes, wires and group membership in order."""

    def __init__(self, doc: EditedDocument, node_ids: list[str], text: str = "Delete") -> None:
        super().__init__(doc, text)
        graph = doc.graph
        self.node_ids = [n for n in node_ids if n in graph.nodes]
        self.records = [graph.nodes[n] for n in self.node_ids]
        self.node_order: list[str] = []
        self.wire_order: list[Wire] = []
        self.removed_wires: list[Wire] = []
        self.memberships: dict[str, list[str]] = {}

    def apply(self, graph: Graph) -> None:
        doomed = set(self.node_ids)
        self.node_order = list(graph.nodes)
        self.wire_order = list(graph.wires)
        self.removed_wires = [w for w in graph.wires if w.source in doomed or w.target in doomed]
        self.memberships = {g.id: list(g.nodes) for g in graph.groups}
        graph.remove_many(self.node_ids)
        if any(doomed.intersection(members) for members in self.memberships.values()):
            self.doc.groups_changed.emit()

    def revert(self, graph: Graph) -> None:
        graph.add_many(self.records, self.removed_wires)
        restore_wire_order(graph, self.wire_order)
        restore_node_order(graph, self.node_order)
        for group in graph.groups:
            if group.id in self.memberships:
                group.nodes[:] = self.memberships[group.id]
        self.doc.groups_changed.emit()


class ChangeWires(GraphCommand):
    """Connect and/or disconnect wires in one step (replace, add with Shift, remove with Ctrl)."""

    def __init__(
        self, doc: EditedDocument, add: list[Wire] = (), remove: list[Wire] = (), text: str = "Connect"
    ) -> None:
        super().__init__(doc, text)
        self.add = list(add)
        self.remove = list(remove)
        self.wire_order: list[Wire] = []

    def apply(self, graph: Graph) -> None:
        self.wire_order = list(graph.wires)
        for wire in self.remove:
            graph.disconnect(wire)
        for wire in self.add:
            graph.connect_wire(wire)

    def revert(self, graph: Graph) -> None:
        for wire in reversed(self.add):
            graph.disconnect(wire)
        for wire in self.remove:
            graph.connect_wire(wire)
        restore_wire_order(graph, self.wire_order)


class SetSetting(GraphCommand):
    """Change one setting; successive changes with the same ``merge_key`` (a slider drag) merge."""

    def __init__(
        self, doc: EditedDocument, node_id: str, name: str, value: Any, merge_key: object = None,
        text: str = "",
    ) -> None:
        # "Set value of Panel width (m)": the undo history names the slider it changed
        super().__init__(doc, text or f"Set {name} of {doc.graph.nodes[node_id].title}")
        self.node_id, self.name, self.value = node_id, name, copy.deepcopy(value)
        self.old = copy.deepcopy(doc.graph.nodes[node_id].node.settings.get(name))
        self.merge_key = merge_key

    def apply(self, graph: Graph) -> None:
        graph.set_setting(self.node_id, self.name, copy.deepcopy(self.value))

    def revert(self, graph: Graph) -> None:
        graph.set_setting(self.node_id, self.name, copy.deepcopy(self.old))

    def id(self) -> int:
        return SETTING_MERGE_ID

    def mergeWith(self, other: QUndoCommand) -> bool:
        if (
            not isinstance(other, SetSetting)
            or self.merge_key is None
            or other.merge_key != self.merge_key
            or (other.node_id, other.name) != (self.node_id, self.name)
        ):
            return False
        self.value = copy.deepcopy(other.value)
        return True


class SetInputValue(GraphCommand):
    """Set (or clear) an input's persistent value."""

    def __init__(
        self, doc: EditedDocument, node_id: str, port: str, value: Any, present: bool = True
    ) -> None:
        super().__init__(doc, f"Set {port}" if present else f"Clear {port}")
        self.node_id, self.port, self.value, self.present = node_id, port, copy.deepcopy(value), present
        state = doc.graph.nodes[node_id].inputs.get(port)
        self.old_present = bool(state and state.has_value)
        self.old_value = copy.deepcopy(state.value) if state else None

    def apply(self, graph: Graph) -> None:
        graph.set_input_value(self.node_id, self.port, copy.deepcopy(self.value), self.present)

    def revert(self, graph: Graph) -> None:
        graph.set_input_value(self.node_id, self.port, copy.deepcopy(self.old_value), self.old_present)


class SetModifiers(GraphCommand):
    """Change an input's graft/flatten/simplify/reverse modifiers."""

    def __init__(self, doc: EditedDocument, node_id: str, port: str, modifiers: list[str]) -> None:
        super().__init__(doc, f"Modify {port}")
        self.node_id, self.port, self.modifiers = node_id, port, list(modifiers)
        state = doc.graph.nodes[node_id].inputs.get(port)
        self.old = list(state.modifiers) if state else []

    def apply(self, graph: Graph) -> None:
        graph.set_modifiers(self.node_id, self.port, self.modifiers)

    def revert(self, graph: Graph) -> None:
        graph.set_modifiers(self.node_id, self.port, self.old)


class _SetFlag(GraphCommand):
    """One on/off setting of several nodes set to ``value``; ``old`` holds each node's value
    before, which undo puts back. A subclass says which setting (:meth:`set`)."""

    def __init__(self, doc: EditedDocument, text: str, value: bool, old: dict[str, bool]) -> None:
        super().__init__(doc, text)
        self.value = value
        self.old = old

    def set(self, graph: Graph, node_id: str, value: bool) -> None:
        raise NotImplementedError

    def apply(self, graph: Graph) -> None:
        for node_id in self.old:
            self.set(graph, node_id, self.value)

    def revert(self, graph: Graph) -> None:
        for node_id, value in self.old.items():
            self.set(graph, node_id, value)


class SetEnabled(_SetFlag):
    def __init__(self, doc: EditedDocument, node_ids: list[str], enabled: bool) -> None:
        old = {n: doc.graph.nodes[n].enabled for n in node_ids}
        super().__init__(doc, "Enable" if enabled else "Disable", enabled, old)

    def set(self, graph: Graph, node_id: str, value: bool) -> None:
        graph.set_enabled(node_id, value)


class SetPreview(_SetFlag):
    affects_solve = False

    def __init__(self, doc: EditedDocument, node_ids: list[str], preview: bool) -> None:
        old = {n: doc.graph.nodes[n].preview for n in node_ids}
        super().__init__(doc, "Preview on" if preview else "Preview off", preview, old)

    def set(self, graph: Graph, node_id: str, value: bool) -> None:
        graph.set_preview(node_id, value)


class SetLabel(GraphCommand):
    affects_solve = False

    def __init__(self, doc: EditedDocument, node_id: str, label: str) -> None:
        super().__init__(doc, "Rename")
        self.node_id, self.label = node_id, label
        self.old = doc.graph.nodes[node_id].label

    def apply(self, graph: Graph) -> None:
        graph.set_label(self.node_id, self.label)

    def revert(self, graph: Graph) -> None:
        graph.set_label(self.node_id, self.old)


class MoveNodes(GraphCommand):
    """Move nodes (a drag, an align) — layout only, so a running solve goes on."""

    affects_solve = False

    def __init__(
        self,
        doc: EditedDocument,
        moves: dict[str, tuple[tuple[float, float], tuple[float, float]]],
        text: str = "Move",
    ) -> None:
        super().__init__(doc, text)
        self.moves = dict(moves)

    def apply(self, graph: Graph) -> None:
        for node_id, (_, new) in self.moves.items():
            graph.move_node(node_id, new)

    def revert(self, graph: Graph) -> None:
        for node_id, (old, _) in self.moves.items():
            graph.move_node(node_id, old)


class AddGroup(GraphCommand):
    affects_solve = False

    def __init__(self, doc: EditedDocument, group: Group) -> None:
        super().__init__(doc, "Group")
        self.group = group

    def apply(self, graph: Graph) -> None:
        graph.add_group(self.group)

    def revert(self, graph: Graph) -> None:
        graph.remove_group(self.group.id)


class RemoveGroup(GraphCommand):
    affects_solve = False

    def __init__(self, doc: EditedDocument, group_id: str) -> None:
        super().__init__(doc, "Ungroup")
        self.group = group_by_id(doc.graph, group_id)
        self.order: list[str] = []

    def apply(self, graph: Graph) -> None:
        self.order = [g.id for g in graph.groups]
        graph.remove_group(self.group.id)

    def revert(self, graph: Graph) -> None:
        graph.add_group(self.group)
        restore_group_order(graph, self.order)
        self.doc.groups_changed.emit()


class EditGroup(GraphCommand):
    """Retitle, recolour or change a group's members.

    Engine gap (reported): there is no ``Graph.set_group_*`` method or event, so the
    group object is changed here and :attr:`~torsal.app.gui.edited.EditedDocument.groups_changed` is emitted.
    """

    affects_solve = False

    def __init__(
        self,
        doc: EditedDocument,
        group_id: str,
        *,
        title: str | None = None,
        colour: str | None = None,
        nodes: list[str] | None = None,
    ) -> None:
        super().__init__(doc, "Edit group")
        self.group_id = group_id
        group = group_by_id(doc.graph, group_id)
        self.old = (group.title, group.colour, list(group.nodes))
        self.new = (
            group.title if title is None else title,
            group.colour if colour is None else colour,
            list(group.nodes) if nodes is None else list(nodes),
        )

    def _set(self, graph: Graph, values: tuple[str, str, list[str]]) -> None:
        group = group_by_id(graph, self.group_id)
        group.title, group.colour = values[0], values[1]
        group.nodes[:] = values[2]
        self.doc.groups_changed.emit()

    def apply(self, graph: Graph) -> None:
        self._set(graph, self.new)

    def revert(self, graph: Graph) -> None:
        self._set(graph, self.old)


# -- clusters (see engine.cluster) -------------------------------------------------------
class ClusterCommand(GraphCommand):
    """Base of the cluster edits: an edit the engine refuses (:class:`GraphError`) the
    first time it runs makes the command obsolete (the stack drops it) and its reason
    is kept in :attr:`failure`."""

    def __init__(self, doc: EditedDocument, text: str) -> None:
        super().__init__(doc, text)
        self.failure = ""
        self.done = False

    def redo(self) -> None:
        try:
            super().redo()
        except GraphError as exc:
            if self.done:
                raise
            self.failure = str(exc)
            self.setObsolete(True)
            return
        self.done = True
        self.doc.groups_changed.emit()  # the engine moves nodes in and out of groups unannounced

    def undo(self) -> None:
        super().undo()
        self.doc.groups_changed.emit()


class MakeCluster(ClusterCommand):
    """Collapse nodes into one cluster node (undo explodes it back to the same ids)."""

    def __init__(self, doc: EditedDocument, node_ids: list[str], name: str = "Cluster") -> None:
        super().__init__(doc, f"Cluster {len(node_ids)} node{'s' * (len(node_ids) != 1)}")
        self.node_ids, self.name = list(node_ids), name
        self.cluster_id: str | None = None
        self.definition_id: str | None = None

    def apply(self, graph: Graph) -> None:
        if self.cluster_id is None:
            self.cluster_id = make_cluster(graph, self.node_ids, self.name)
            self.definition_id = definition_of(graph, self.cluster_id).id
        else:
            make_cluster(graph,
                self.node_ids, self.name, node_id=self.cluster_id, definition_id=self.definition_id
            )

    def revert(self, graph: Graph) -> None:
        explode_cluster(graph, self.cluster_id)


class ExplodeCluster(ClusterCommand):
    """Put a cluster's inner nodes in its place (undo puts the cluster back)."""

    def __init__(self, doc: EditedDocument, cluster_id: str) -> None:
        super().__init__(doc, "Explode cluster")
        self.cluster_id = cluster_id
        self.info: Any = None
        self.restored: list[str] = []

    def apply(self, graph: Graph) -> None:
        info = cluster_instance(graph, self.cluster_id)
        self.restored = explode_cluster(graph, self.cluster_id)
        self.info = info

    def revert(self, graph: Graph) -> None:
        restore_cluster(graph, self.info, self.restored)


class EditClusterDefinition(ClusterCommand):
    """Commit a cluster definition edited on the canvas: every instance updates."""

    def __init__(
        self, doc: EditedDocument, definition_id: str, edited: Graph, text: str = "Edit cluster"
    ) -> None:
        super().__init__(doc, text)
        self.definition_id = definition_id
        self.edited = edited
        self.change: Any = None

    def apply(self, graph: Graph) -> None:
        self.change = set_cluster_graph(graph, self.definition_id, clone_graph(self.edited))

    def revert(self, graph: Graph) -> None:
        change = self.change
        set_cluster_graph(graph,
            self.definition_id, change.previous, change.previous_inputs, change.previous_outputs
        )
        for wire in change.dropped:
            if not graph.has_wire(wire):
                graph.connect_wire(wire)


class RenameClusterPort(ClusterCommand):
    """Rename an input or output of a cluster definition (outer wires follow)."""

    def __init__(self, doc: EditedDocument, definition_id: str, kind: str, old: str, new: str) -> None:
        super().__init__(doc, f"Rename {kind} {old}")
        self.definition_id, self.kind, self.old, self.new = definition_id, kind, old, new
        self.given = new  # the name the definition gave (a repeat gets " 2")

    def _names(self, graph: Graph) -> list[str]:
        definition = definition_of(graph, self.definition_id)
        return definition.input_names() if self.kind == "input" else definition.output_names()

    def apply(self, graph: Graph) -> None:
        index = self._names(graph).index(self.old)
        rename_cluster_port(graph, self.definition_id, self.kind, self.old, self.new)
        self.given = self._names(graph)[index]

    def revert(self, graph: Graph) -> None:
        rename_cluster_port(graph, self.definition_id, self.kind, self.given, self.old)


class ReorderClusterPorts(ClusterCommand):
    """Put a cluster definition's inputs or outputs in a new order."""

    def __init__(self, doc: EditedDocument, definition_id: str, kind: str, names: list[str]) -> None:
        super().__init__(doc, f"Reorder {kind}s")
        self.definition_id, self.kind, self.names = definition_id, kind, list(names)
        self.old: list[str] = []

    def apply(self, graph: Graph) -> None:
        self.old = list(reorder_cluster_ports(graph, self.definition_id, self.kind, self.names))

    def revert(self, graph: Graph) -> None:
        reorder_cluster_ports(graph, self.definition_id, self.kind, self.old)


class RenameCluster(ClusterCommand):
    """Rename a cluster definition (every instance shows the new name)."""

    def __init__(self, doc: EditedDocument, definition_id: str, name: str) -> None:
        super().__init__(doc, "Rename cluster")
        self.definition_id, self.name = definition_id, name
        self.old = ""

    def apply(self, graph: Graph) -> None:
        self.old = rename_cluster(graph, self.definition_id, self.name)

    def revert(self, graph: Graph) -> None:
        rename_cluster(graph, self.definition_id, self.old)
