"""Editing operations the GUI offers: each one undo command (or one macro of them).

The canvas, menus, inspector and tests all edit through :class:`Editor`, so an edit
made with the mouse and the same edit made by a test take the same path. Edits that
cannot be made (a wire between types that do not cast) are refused with a message on
:attr:`Editor.refused` instead of an exception.
"""

from __future__ import annotations

import copy
from collections.abc import Callable, Iterable
from typing import Any

from PySide6.QtCore import QObject, QTimer, Signal

from torsal.app.gui import commands as cmd
from torsal.app.gui.document import Document
from torsal.app.gui.fragments import copy_fragment, paste_fragment
from torsal.app.gui.graph_order import fresh_id, group_by_id
from torsal.engine.cluster_edits import definition_of
from torsal.engine.datatree import MODIFIERS
from torsal.engine.graph import Graph, GraphError, Group, NodeRecord, Wire
from torsal.engine.types import can_cast

#: How long a slider drag's next value waits for the viewport to draw the last result
#: (ms) before it is solved anyway (a viewport that never paints: a minimised window).
FRAME_WAIT_MS = 250

GROUP_COLOURS = ("#d8e4f0", "#e8e0f4", "#dceee2", "#f4ecd8", "#f2dede", "#e0f0f0")
Size = tuple[float, float]


class Editor(QObject):
    """High-level edits of a :class:`Document`'s graph."""

    refused = Signal(str)  # why an edit was not made
    drag_started = Signal()  # a slider is being dragged (see :meth:`new_drag`)
    drag_ended = Signal()  # a slider drag (see :meth:`new_drag`) was let go

    def __init__(self, doc: Document, parent: QObject | None = None) -> None:
        super().__init__(parent)
        self.doc = doc
        self._pending_drag: tuple[str, str, Any, object] | None = None
        self._drag_counter = 0
        #: a slider is being dragged (from :meth:`new_drag` to :meth:`end_drag`)
        self.dragging = False
        #: Whether the last result is still on its way to the screen (the window sets the
        #: viewport's :meth:`~torsal.app.gui.viewport.panel.ViewportPanel.frame_due`): a
        #: drag's next value is solved once it is drawn (see :meth:`drag_setting`).
        self.frame_due: Callable[[], bool] = lambda: False
        self._next_value = QTimer(self)
        self._next_value.setSingleShot(True)
        self._next_value.timeout.connect(self._flush_when_drawn)
        # checked on the next event-loop turn: by then every view has taken the result in
        # (and the viewport has asked for its frame)
        doc.results_changed.connect(lambda _outcome: self._check_next_value(0))

    @property
    def graph(self) -> Graph:
        return self.doc.graph

    # -- nodes -----------------------------------------------------------------------
    def add_node(
        self,
        type_id: str,
        position: tuple[float, float],
        settings: dict[str, Any] | None = None,
        label: str = "",
    ) -> str | None:
        """Place a new node of ``type_id`` with its top-left at ``position``; returns its id."""
        try:
            node = self.doc.registry.create(type_id, settings)
        except (KeyError, TypeError, ValueError) as exc:
            self.refused.emit(str(exc))
            return None
        node_id = fresh_id(node.name(), set(self.graph.nodes))
        record = NodeRecord(
            node_id, node, type_id, label, (float(round(position[0])), float(round(position[1])))
        )
        self.doc.push(cmd.AddNodes(self.doc, [record], text=f"Add {node.name()}"))
        return node_id

    def delete(self, node_ids: Iterable[str]) -> None:
        ids = [n for n in node_ids if n in self.graph.nodes]
        if ids:
            self.doc.push(
                cmd.RemoveNodes(self.doc, ids, text=f"Delete {len(ids)} node{'s' * (len(ids) > 1)}")
            )

    def rename(self, node_id: str, label: str) -> None:
        if self.graph.nodes[node_id].label != label:
            self.doc.push(cmd.SetLabel(self.doc, node_id, label))

    def set_enabled(self, node_ids: Iterable[str], enabled: bool) -> None:
        ids = [n for n in node_ids if self.graph.nodes[n].enabled != enabled]
        if ids:
            self.doc.push(cmd.SetEnabled(self.doc, ids, enabled))

    def set_preview(self, node_ids: Iterable[str], preview: bool) -> None:
        ids = [n for n in node_ids if self.graph.nodes[n].preview != preview]
        if ids:
            self.doc.push(cmd.SetPreview(self.doc, ids, preview))

    def move(self, positions: dict[str, tuple[float, float]], text: str = "Move") -> None:
        """Move nodes to new top-left ``positions`` (rounded to whole units)."""
        moves = {}
        for node_id, (x, y) in positions.items():
            new = (float(round(x)), float(round(y)))
            old = self.graph.nodes[node_id].position
            if tuple(old) != new:
                moves[node_id] = (old, new)
        if moves:
            self.doc.push(cmd.MoveNodes(self.doc, moves, text))

    # -- settings ----------------------------------------------------------------------
    def set_setting(self, node_id: str, name: str, value: Any, merge_key: object = None) -> None:
        self.set_settings(node_id, {name: value}, merge_key=merge_key)

    def set_settings(
        self, node_id: str, values: dict[str, Any], text: str = "", merge_key: object = None
    ) -> None:
        """Change settings; wires into inputs or out of outputs the new settings remove are
        disconnected first (one undo step with the change)."""
        record = self.graph.nodes[node_id]
        changed = {k: v for k, v in values.items() if record.node.settings.get(k) != v}
        if not changed:
            return
        lost = self._wires_lost_by(record, changed)
        several = len(changed) > 1 or lost
        if several:
            self.doc.undo_stack.beginMacro(text or "Edit settings")
        if lost:
            self.doc.push(cmd.ChangeWires(self.doc, remove=lost, text="Disconnect"))
        for name, value in changed.items():
            self.doc.push(cmd.SetSetting(self.doc, node_id, name, value, merge_key=merge_key, text=text))
        if several:
            self.doc.undo_stack.endMacro()

    def _wires_lost_by(self, record: NodeRecord, changed: dict[str, Any]) -> list[Wire]:
        settings = copy.deepcopy(record.node.settings)
        settings.update(changed)
        try:
            future = type(record.node)(settings)
            inputs = {p.name for p in future.input_ports()}
            outputs = {p.name for p in future.output_ports()}
        except Exception:
            return []
        return [w for w in self.graph.wires_into(record.id) if w.target_port not in inputs] + [
            w for w in self.graph.wires_from(record.id) if w.source_port not in outputs
        ]

    def new_drag(self) -> object:
        """A key that merges the setting changes of one slider drag into one undo step."""
        self._drag_counter += 1
        if not self.dragging:
            self.dragging = True
            self.drag_started.emit()
        return ("drag", self._drag_counter)

    def drag_setting(self, node_id: str, name: str, value: Any, drag_key: object) -> None:
        """A value from a slider being dragged, latest wins: applied now if the solver is
        idle, else as soon as the running solve's result is drawn. A drag never cancels a
        solve, so every solve finishes and reaches the viewport while dragging.

        The next solve waits for the frame of the last one (at most :data:`FRAME_WAIT_MS`):
        solving while the viewport renders, the canvas repaints and the views take the
        result in made every drag's solve share the processor with them (1.3-1.8× the
        same re-solve headless), and gained no frames on a machine whose cores are busy.
        """
        self._pending_drag = (node_id, name, value, drag_key)
        self._flush_when_drawn()

    def frame_shown(self) -> None:
        """The viewport has drawn the latest result: the drag's next value is solved now.

        Called as the render ends, inside the viewport's paint, and not on a later turn of
        the event loop: Qt still composes the window after the render (8-30 ms a frame with
        software OpenGL, measured), and the next solve runs alongside that instead of after
        it. Applying a setting there only edits the graph and schedules repaints."""
        if self._pending_drag is not None:
            self._flush_when_drawn()

    def _check_next_value(self, delay_ms: int) -> None:
        self._next_value.start(delay_ms)

    def _flush_when_drawn(self) -> None:
        # not busy() but in flight: a solve that has just finished has a result on its way
        # to the viewport, and starting another now would throw that result away
        if self._pending_drag is None or self.doc.solves.in_flight():
            return
        if self.frame_due():
            self._check_next_value(FRAME_WAIT_MS)  # or sooner, by frame_shown
            return
        self._next_value.stop()
        self._flush_drag()

    def end_drag(self) -> None:
        """The drag is over: its last value is applied now (cancelling an older solve)."""
        self._next_value.stop()
        self._flush_drag()
        if self.dragging:
            self.dragging = False
            self.drag_ended.emit()

    def _flush_drag(self) -> None:
        if self._pending_drag is None:
            return
        node_id, name, value, key = self._pending_drag
        self._pending_drag = None
        if node_id in self.graph.nodes:
            self.set_setting(node_id, name, value, merge_key=key)
            # start now, not on the next event-loop turn: the worker solves while the GUI
            # is still drawing the previous result
            self.doc.solves.solve_now()

    # -- inputs ------------------------------------------------------------------------
    def set_input_value(self, node_id: str, port: str, value: Any) -> None:
        self.doc.push(cmd.SetInputValue(self.doc, node_id, port, value, True))

    def clear_input_value(self, node_id: str, port: str) -> None:
        state = self.graph.nodes[node_id].inputs.get(port)
        if state is not None and state.has_value:
            self.doc.push(cmd.SetInputValue(self.doc, node_id, port, None, False))

    def toggle_modifier(self, node_id: str, port: str, modifier: str) -> None:
        if modifier not in MODIFIERS:
            raise ValueError(modifier)
        state = self.graph.nodes[node_id].inputs.get(port)
        current = list(state.modifiers) if state else []
        new = [m for m in current if m != modifier] if modifier in current else [*current, modifier]
        self.doc.push(cmd.SetModifiers(self.doc, node_id, port, new))

    # -- wires -------------------------------------------------------------------------
    def connect(
        self, source: str, source_port: str, target: str, target_port: str, mode: str = "replace"
    ) -> bool:
        """Wire an output to an input.

        ``mode``: ``"replace"`` (a plain drag: the new wire replaces what fed the input),
        ``"add"`` (Shift: keep the others when the input takes several), ``"remove"``
        (Ctrl: take this wire away).
        """
        graph = self.graph
        wire = Wire(source, source_port, target, target_port)
        if mode == "remove":
            if graph.has_wire(wire):
                self.doc.push(cmd.ChangeWires(self.doc, remove=[wire], text="Disconnect"))
                return True
            return False
        if graph.has_wire(wire):
            return False
        in_port = graph.nodes[target].node.input_port(target_port)
        existing = graph.wires_into(target, target_port)
        keep = mode == "add" and in_port is not None and in_port.accepts_several_wires
        remove = [] if keep else existing
        problem = self.wire_problem(wire, ignore_existing=bool(remove))
        if problem:
            self.refused.emit(problem)
            return False
        self.doc.push(cmd.ChangeWires(self.doc, add=[wire], remove=remove, text="Connect"))
        return True

    def wire_problem(self, wire: Wire, ignore_existing: bool = False) -> str:
        """Why ``wire`` cannot be added ("" when it can).

        With ``ignore_existing`` the wires already feeding the input are taken as
        replaced. Engine gap (reported): ``Graph.check_wire`` cannot be told that, so the
        type and loop checks are repeated here for that case.
        """
        graph = self.graph
        if not ignore_existing:
            try:
                graph.check_wire(wire)
            except GraphError as exc:
                return str(exc)
            return ""
        src, dst = graph.nodes[wire.source], graph.nodes[wire.target]
        out_port = src.node.output_port(wire.source_port)
        in_port = dst.node.input_port(wire.target_port)
        if out_port is None or in_port is None:
            return f"{wire} joins ports that do not exist"
        if not can_cast(out_port.type, in_port.type):
            return (
                f"{src.title}.{out_port.name} gives {out_port.type.name}, "
                f"which {dst.title}.{in_port.name} ({in_port.type.name}) cannot take"
            )
        if graph.reaches(wire.target, wire.source):
            return f"{wire} would make a loop: {dst.title} already feeds {src.title}"
        return ""

    def disconnect_input(self, node_id: str, port: str) -> None:
        wires = self.graph.wires_into(node_id, port)
        if wires:
            self.doc.push(cmd.ChangeWires(self.doc, remove=wires, text="Disconnect"))

    def disconnect_output(self, node_id: str, port: str) -> None:
        wires = [w for w in self.graph.wires_from(node_id) if w.source_port == port]
        if wires:
            self.doc.push(cmd.ChangeWires(self.doc, remove=wires, text="Disconnect"))

    # -- clipboard ---------------------------------------------------------------------
    def copy(self, node_ids: Iterable[str]) -> str:
        return copy_fragment(self.graph, list(node_ids))

    def paste(
        self,
        text: str,
        anchor: tuple[float, float] | None = None,
        offset: tuple[float, float] = (30.0, 30.0),
        label: str = "Paste",
    ) -> list[str]:
        """Add the nodes of a fragment; returns their ids. Raises GraphFileError for bad text."""
        records, wires = paste_fragment(text, self.graph, self.doc.registry, offset, anchor)
        if records:
            self.doc.push(cmd.AddNodes(self.doc, records, wires, text=label))
        return [r.id for r in records]

    def duplicate(self, node_ids: Iterable[str], offset: tuple[float, float] = (30.0, 30.0)) -> list[str]:
        ids = list(node_ids)
        if not ids:
            return []
        return self.paste(self.copy(ids), offset=offset, label="Duplicate")

    # -- layout ------------------------------------------------------------------------
    def align(self, sizes: dict[str, Size], how: str) -> None:
        """Line nodes up: ``left``, ``right``, ``top``, ``bottom``, ``hcentre``, ``vcentre``.

        ``sizes`` gives each node's drawn width and height (the canvas knows them).
        """
        if len(sizes) < 2:
            return
        pos = {n: self.graph.nodes[n].position for n in sizes}
        lefts = [pos[n][0] for n in sizes]
        tops = [pos[n][1] for n in sizes]
        rights = [pos[n][0] + sizes[n][0] for n in sizes]
        bottoms = [pos[n][1] + sizes[n][1] for n in sizes]
        target: dict[str, tuple[float, float]] = {}
        for n, (w, h) in sizes.items():
            x, y = pos[n]
            if how == "left":
                x = min(lefts)
            elif how == "right":
                x = max(rights) - w
            elif how == "top":
                y = min(tops)
            elif how == "bottom":
                y = max(bottoms) - h
            elif how == "hcentre":
                x = (min(lefts) + max(rights)) / 2 - w / 2
            elif how == "vcentre":
                y = (min(tops) + max(bottoms)) / 2 - h / 2
            else:
                raise ValueError(f"unknown alignment {how!r}")
            target[n] = (x, y)
        self.move(target, text=f"Align {how}")

    def group(self, node_ids: Iterable[str], title: str = "Group") -> str | None:
        wanted = set(node_ids)
        ids = [n for n in self.graph.nodes if n in wanted]
        if not ids:
            return None
        group_id = fresh_id("group", {g.id for g in self.graph.groups})
        colour = GROUP_COLOURS[len(self.graph.groups) % len(GROUP_COLOURS)]
        self.doc.push(cmd.AddGroup(self.doc, Group(group_id, title, colour, ids)))
        return group_id

    def ungroup(self, group_id: str) -> None:
        if group_by_id(self.graph, group_id) is not None:
            self.doc.push(cmd.RemoveGroup(self.doc, group_id))

    def edit_group(self, group_id: str, **changes: Any) -> None:
        self.doc.push(cmd.EditGroup(self.doc, group_id, **changes))

    # -- clusters ----------------------------------------------------------------------
    def cluster(self, node_ids: Iterable[str], name: str = "Cluster") -> str | None:
        """Collapse ``node_ids`` into one cluster node (one undo step); its id, or None
        (with the reason on :attr:`refused`) when the engine refuses."""
        ids = [n for n in node_ids if n in self.graph.nodes]
        if not ids:
            self.refused.emit("Cluster: select the nodes to put in the cluster")
            return None
        command = cmd.MakeCluster(self.doc, ids, name)
        self.doc.push(command)
        if command.failure:
            self.refused.emit(f"Cluster: {command.failure}")
            return None
        return command.cluster_id

    def explode(self, cluster_id: str) -> list[str]:
        """Put the cluster's nodes back in its place (one undo step); their ids."""
        command = cmd.ExplodeCluster(self.doc, cluster_id)
        self.doc.push(command)
        if command.failure:
            self.refused.emit(f"Explode: {command.failure}")
            return []
        return command.restored

    def edit_cluster(
        self,
        definition_id: str,
        name: str,
        inputs: list[tuple[str, str]],
        outputs: list[tuple[str, str]],
    ) -> None:
        """Rename a cluster and rename and reorder its ports, as one undo step.

        ``inputs`` and ``outputs`` are ``(current name, new name)`` pairs in the new order.
        """
        definition = definition_of(self.graph, definition_id)
        commands: list[cmd.ClusterCommand] = []
        if name and name != definition.name:
            commands.append(cmd.RenameCluster(self.doc, definition_id, name))
        for kind, pairs, current in (
            ("input", inputs, definition.input_names()),
            ("output", outputs, definition.output_names()),
        ):
            renames = [(old, new) for old, new in pairs if new and new != old]
            taken = set(current)
            later = []
            for old, new in renames:
                if new in taken:  # a name a port has now (a swap): first to a name no port has
                    step = f"{old}\u2060"
                    commands.append(cmd.RenameClusterPort(self.doc, definition_id, kind, old, step))
                    later.append(cmd.RenameClusterPort(self.doc, definition_id, kind, step, new))
                else:
                    commands.append(cmd.RenameClusterPort(self.doc, definition_id, kind, old, new))
            commands += later
            final = [new if new and new != old else old for old, new in pairs]
            if [old for old, _ in pairs] != current and sorted(current) == sorted(o for o, _ in pairs):
                commands.append(cmd.ReorderClusterPorts(self.doc, definition_id, kind, final))
        if not commands:
            return
        self.doc.undo_stack.beginMacro("Edit cluster ports")
        try:
            for command in commands:
                self.doc.push(command)
                if command.failure:
                    self.refused.emit(f"Cluster ports: {command.failure}")
                    break
        finally:
            self.doc.undo_stack.endMacro()
