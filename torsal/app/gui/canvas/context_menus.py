"""Right-click menus: on an input (modifiers, set value), an output (export), a node, a group,
the canvas."""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any

from PySide6.QtCore import QPointF
from PySide6.QtGui import QColor
from PySide6.QtWidgets import QColorDialog, QInputDialog, QMenu

from torsal.app.gui.canvas.node_item import NodeItem
from torsal.app.gui.canvas.port_item import PortItem
from torsal.app.gui.graph_order import group_by_id
from torsal.engine.cluster import is_cluster
from torsal.engine.graph import Wire
from torsal.engine.node import Node
from torsal.engine.types import CastError, decode_value
from torsal.engine.widgets import Widget

if TYPE_CHECKING:
    from torsal.app.gui.canvas.hosts import MenuView
    from torsal.app.gui.canvas.scene import CanvasScene

MODIFIER_LABELS = {"graft": "Graft", "flatten": "Flatten", "simplify": "Simplify", "reverse": "Reverse"}


def parse_value(text: str) -> Any:
    """What the user typed as an input value: JSON where it parses (``4.5``, ``[1, 2]``,
    ``{"type": "Point", "xyz": [0, 0, 1]}``), otherwise the text itself."""
    try:
        value = json.loads(text)
    except ValueError:
        return text
    decode_value(value)  # raises CastError for an unknown {"type": ...}
    return value


def add_modifier_actions(menu: QMenu, scene: CanvasScene, node_id: str, name: str) -> None:
    """Graft, Flatten, Simplify, Reverse of input ``name`` (checkable, each one undo step)."""
    editor = scene.editor
    state = scene.doc.graph.nodes[node_id].inputs.get(name)
    current = state.modifiers if state else []
    for modifier, label in MODIFIER_LABELS.items():
        action = menu.addAction(label)
        action.setCheckable(True)
        action.setChecked(modifier in current)
        action.triggered.connect(lambda _=False, m=modifier: editor.toggle_modifier(node_id, name, m))


def port_menu(scene: CanvasScene, port: PortItem) -> QMenu:
    menu = QMenu()
    editor = scene.editor
    graph = scene.doc.graph
    node_id, name = port.node_id, port.name
    if port.is_input:
        state = graph.nodes[node_id].inputs.get(name)
        add_modifier_actions(menu, scene, node_id, name)
        menu.addSeparator()
        menu.addAction("Set value…", lambda: ask_input_value(scene, node_id, name))
        clear = menu.addAction("Clear value", lambda: editor.clear_input_value(node_id, name))
        clear.setEnabled(bool(state and state.has_value))
        wires = graph.wires_into(node_id, name)
        disconnect = menu.addAction(
            f"Disconnect ({len(wires)})", lambda: editor.disconnect_input(node_id, name)
        )
        disconnect.setEnabled(bool(wires))
    else:
        wires = [w for w in graph.wires_from(node_id) if w.source_port == name]
        disconnect = menu.addAction(
            f"Disconnect ({len(wires)})", lambda: editor.disconnect_output(node_id, name)
        )
        disconnect.setEnabled(bool(wires))
        menu.addSeparator()
        menu.addAction("Export…", lambda: scene.export_requested.emit(node_id, name))
    return menu


def wire_menu(scene: CanvasScene, wire: Wire) -> QMenu:
    """A wire's menu: the modifiers of the input it feeds, and Delete wire."""
    menu = QMenu()
    add_modifier_actions(menu, scene, wire.target, wire.target_port)
    menu.addSeparator()
    menu.addAction(
        "Delete wire",
        lambda: scene.editor.connect(wire.source, wire.source_port, wire.target, wire.target_port, "remove"),
    )
    return menu


def ask_input_value(scene: CanvasScene, node_id: str, port: str) -> None:
    state = scene.doc.graph.nodes[node_id].inputs.get(port)
    current = json.dumps(state.value) if state and state.has_value else ""
    text, ok = QInputDialog.getText(
        None, "Set value", f"Value of {port} (a number, text, or JSON):", text=current
    )
    if not ok:
        return
    try:
        value = parse_value(text)
    except CastError as exc:
        scene.editor.refused.emit(f"{port}: {exc}")
        return
    scene.editor.set_input_value(node_id, port, value)


def node_menu(scene: CanvasScene, node: NodeItem) -> QMenu:
    menu = QMenu()
    editor = scene.editor
    selected = scene.selected_node_ids() or [node.node_id]
    record = node.record
    preview = menu.addAction("Preview")
    preview.setCheckable(True)
    preview.setChecked(record.preview)
    preview.triggered.connect(lambda on: editor.set_preview(selected, on))
    enabled = menu.addAction("Enabled")
    enabled.setCheckable(True)
    enabled.setChecked(record.enabled)
    enabled.triggered.connect(lambda on: editor.set_enabled(selected, on))
    menu.addSeparator()
    menu.addAction("Rename…", lambda: scene.rename_node(node.node_id))
    if record.node.widget is Widget.EXPRESSION:
        menu.addAction("Edit expression…", lambda: ask_expression(scene, node.node_id))
    if type(record.node).match_outputs is not Node.match_outputs:
        menu.addAction("Match outputs", lambda: match_outputs(scene, node.node_id))
    menu.addAction("Help", lambda: scene.help_requested.emit(node.node_id))
    menu.addAction("Bake…", lambda: scene.bake_requested.emit(list(selected)))
    outputs = [port.name for port in node.record.node.output_ports()]
    if outputs:
        export = menu.addMenu("Export output")
        for port in outputs:
            export.addAction(
                f"{port}…", lambda _=False, p=port: scene.export_requested.emit(node.node_id, p)
            )
    menu.addSeparator()
    if is_cluster(record.node):
        menu.addAction("Edit cluster", lambda: scene.open_cluster(node.node_id))
        menu.addAction("Cluster ports…", lambda: scene.edit_cluster_ports(node.node_id))
        menu.addAction("Explode", lambda: scene.explode_cluster(node.node_id))
    menu.addAction("Cluster", scene.cluster_selection)
    menu.addSeparator()
    menu.addAction("Delete", lambda: editor.delete(selected))
    return menu


def ask_expression(scene: CanvasScene, node_id: str) -> None:
    settings = scene.doc.graph.nodes[node_id].node.settings
    text, ok = QInputDialog.getText(None, "Expression", "Formula:", text=str(settings.get("expression", "")))
    if not ok:
        return
    variables, ok = QInputDialog.getText(
        None, "Expression", "Variables (comma separated):", text=", ".join(settings.get("variables", []))
    )
    if ok:
        names = [v.strip() for v in variables.split(",") if v.strip()]
        scene.editor.set_settings(node_id, {"expression": text, "variables": names}, text="Edit expression")


def match_outputs(scene: CanvasScene, node_id: str) -> None:
    """Fit the node's outputs to the trees it last received (Explode Tree: one per branch)."""
    node = scene.doc.graph.nodes[node_id].node
    settings = node.match_outputs(scene.doc.solver.inputs_of(node_id))
    if settings:
        scene.editor.set_settings(node_id, settings, text="Match outputs")


def group_menu(scene: CanvasScene, group_id: str) -> QMenu:
    """Rename…, Colour… and Ungroup, each one undo step."""
    menu = QMenu()
    menu.addAction("Rename…", lambda: scene.rename_group(group_id))
    menu.addAction("Colour…", lambda: ask_group_colour(scene, group_id))
    menu.addSeparator()
    menu.addAction("Ungroup", lambda: scene.editor.ungroup(group_id))
    return menu


def ask_group_colour(scene: CanvasScene, group_id: str) -> None:
    group = group_by_id(scene.doc.graph, group_id)
    if group is None:
        return
    colour = QColorDialog.getColor(QColor(group.colour), None, f"Colour of {group.title or 'the group'}")
    if colour.isValid() and colour.name() != group.colour.lower():
        scene.editor.edit_group(group_id, colour=colour.name())


def canvas_menu(view: MenuView, scene_pos: QPointF) -> QMenu:
    menu = QMenu()
    menu.addAction(
        "Add node…", lambda: view.open_search(scene_pos, view.mapToGlobal(view.mapFromScene(scene_pos)))
    )
    if view.canvas.doc.frames:  # inside a cluster: its ports are Input and Output nodes
        position = (scene_pos.x(), scene_pos.y())
        menu.addAction("Add cluster input", lambda: view.canvas.add_cluster_port("input", position))
        menu.addAction("Add cluster output", lambda: view.canvas.add_cluster_port("output", position))
        menu.addSeparator()
    for action in view.actions():
        menu.addAction(action)
    return menu
