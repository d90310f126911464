"""Undo/redo: every edit is one command; undoing all restores the file's exact bytes."""

from __future__ import annotations

import random

from tests.support.fixtures_gui import EXAMPLES, copy_fixture, wait_solved
from torsal.app.gui.main_window import MainWindow
from torsal.engine.graph import Wire

NEW_TYPES = [
    "params.NumberSlider",
    "params.IntegerSlider",
    "maths.Series",
    "maths.Expression",
    "params.Point",
    "params.Panel",
    "params.Toggle",
    "lists.ListItem",
]


def random_edit(window: MainWindow, rng: random.Random) -> None:
    """Try one random edit through the editor (it may be refused: the caller checks)."""
    editor, graph = window.editor, window.doc.graph
    ids = list(graph.nodes)
    node_id = rng.choice(ids) if ids else None
    record = graph.nodes[node_id] if node_id else None
    kind = rng.choice(
        [
            "add",
            "add",
            "delete",
            "connect",
            "connect",
            "disconnect",
            "setting",
            "drag",
            "move",
            "value",
            "modifier",
            "enable",
            "preview",
            "label",
            "group",
            "ungroup",
            "duplicate",
            "variables",
            "align",
        ]
    )
    if kind == "add" or record is None:
        editor.add_node(rng.choice(NEW_TYPES), (rng.uniform(-200, 900), rng.uniform(-200, 600)))
    elif kind == "delete" and len(ids) > 3:
        editor.delete(rng.sample(ids, rng.choice([1, 1, 2])))
    elif kind == "connect":
        source = graph.nodes[rng.choice(ids)]
        outs = source.node.output_ports()
        ins = record.node.input_ports()
        if outs and ins:
            mode = rng.choice(["replace", "add"])
            editor.connect(source.id, rng.choice(outs).name, node_id, rng.choice(ins).name, mode)
    elif kind == "disconnect" and graph.wires:
        wire: Wire = rng.choice(graph.wires)
        editor.connect(wire.source, wire.source_port, wire.target, wire.target_port, "remove")
    elif (
        kind in ("setting", "drag") and "value" in record.node.settings and record.type_id.endswith("Slider")
    ):
        if kind == "setting":
            editor.set_setting(node_id, "value", round(rng.uniform(0, 1), 2))
        else:  # a drag: many values, one merged command
            key = editor.new_drag()
            for _ in range(5):
                editor.drag_setting(node_id, "value", round(rng.uniform(0, 1), 2), key)
            editor.end_drag()
    elif kind == "move":
        x, y = record.position
        editor.move({node_id: (x + rng.randint(-80, 80), y + rng.randint(-80, 80))})
    elif kind == "value" and record.node.input_ports():
        port = rng.choice(record.node.input_ports()).name
        if rng.random() < 0.3:
            editor.clear_input_value(node_id, port)
        else:
            editor.set_input_value(node_id, port, rng.choice([1, 2.5, [1, 2, 3], "text"]))
    elif kind == "modifier" and record.node.input_ports():
        port = rng.choice(record.node.input_ports()).name
        editor.toggle_modifier(node_id, port, rng.choice(["graft", "flatten", "simplify", "reverse"]))
    elif kind == "enable":
        editor.set_enabled([node_id], not record.enabled)
    elif kind == "preview":
        editor.set_preview([node_id], not record.preview)
    elif kind == "label":
        editor.rename(node_id, rng.choice(["A", "Beam", "", "Façade panel"]))
    elif kind == "group":
        group_id = editor.group(rng.sample(ids, min(len(ids), 2)), "New group")
        if group_id and rng.random() < 0.5:
            editor.edit_group(group_id, title="Renamed", colour="#f2dede")
    elif kind == "ungroup" and graph.groups:
        editor.ungroup(rng.choice(graph.groups).id)
    elif kind == "duplicate":
        editor.duplicate(rng.sample(ids, min(len(ids), 2)))
    elif kind == "variables" and record.type_id == "maths.Expression":
        editor.set_settings(node_id, {"variables": rng.choice([["x"], ["x", "y", "z"], ["s", "a"]])})
    elif kind == "align" and len(ids) > 1:
        chosen = rng.sample(ids, 3 if len(ids) > 2 else 2)
        editor.align(window.scene.sizes(chosen), rng.choice(["left", "right", "top", "bottom", "hcentre"]))


def assert_canvas_matches_graph(window: MainWindow) -> None:
    graph = window.doc.graph
    assert set(window.scene.nodes) == set(graph.nodes)
    assert set(window.scene.wires) == set(graph.wires)
    assert set(window.scene.groups) == {g.id for g in graph.groups}
    for node_id, item in window.scene.nodes.items():
        assert (item.pos().x(), item.pos().y()) == graph.nodes[node_id].position


def test_fifty_random_edits_undo_to_the_same_bytes_and_redo_to_the_final_bytes(qtbot, window, tmp_path):
    path = copy_fixture(EXAMPLES / "first-steps.graph", tmp_path)
    original = path.read_bytes()
    assert window.open_file(path)
    wait_solved(qtbot, window)
    stack = window.doc.undo_stack
    rng = random.Random(20240605)
    attempts = 0
    while stack.count() < 50:
        attempts += 1
        assert attempts < 2000, "random edits kept being refused"
        random_edit(window, rng)
    assert stack.index() == 50
    assert_canvas_matches_graph(window)
    assert window.save()
    final = path.read_bytes()
    assert final != original

    for _ in range(50):
        stack.undo()
    assert window.doc.dirty  # the saved state was the final one
    assert_canvas_matches_graph(window)
    assert window.save()
    assert path.read_bytes() == original

    for _ in range(50):
        stack.redo()
    assert_canvas_matches_graph(window)
    assert window.save()
    assert path.read_bytes() == final
    wait_solved(qtbot, window)
