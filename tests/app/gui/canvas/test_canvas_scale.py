"""The canvas at scale: each node item is built once when a file opens, and bulk edits
tell the rest of the window once (the timed bars are in tests/benchmarks/bench_gui_edits.py)."""

from __future__ import annotations

from collections import Counter

import pytest
from hypothesis import given
from hypothesis import strategies as st
from PySide6.QtCore import QEvent
from PySide6.QtWidgets import QGraphicsSceneHelpEvent

from tests.support.fixtures_gui import EXAMPLES, wait_solved
from torsal.app.gui.canvas.node_item import NodeItem
from torsal.app.gui.fragments import fresh_ids
from torsal.app.gui.graph_order import fresh_id
from torsal.engine.graph import Graph, NodeRecord, PlaceholderNode
from torsal.engine.graphfile import write_graph

NODES = 5_000


def big_graph(registry) -> Graph:
    """A slider feeding a chain of Expressions, with a few nodes of a type not installed."""
    graph = Graph()
    graph.add_node(registry.create("params.NumberSlider"), "slider")
    previous = "slider"
    for i in range(1, NODES):
        node_id = f"e{i}"
        if i % 1000 == 500:  # a placeholder: its ports come from its wires
            graph.add_record(NodeRecord(node_id, PlaceholderNode("gone.Node"), "gone.Node"))
        else:
            position = (200.0 * (i % 50), 90.0 * (i // 50))
            graph.add_node(registry.create("maths.Expression"), node_id, position=position)
        graph.connect(previous, "Value" if previous == "slider" else "Result", node_id, "x")
        previous = node_id
    return graph


@pytest.fixture
def builds(monkeypatch) -> Counter:
    """How many times each node's item has been laid out."""
    counts: Counter = Counter()
    rebuild = NodeItem.rebuild

    def counted(item: NodeItem) -> None:
        counts[item.node_id] += 1
        rebuild(item)

    monkeypatch.setattr(NodeItem, "rebuild", counted)
    return counts


def test_opening_a_5000_node_graph_builds_each_node_item_once(qtbot, window, registry, tmp_path, builds):
    path = tmp_path / "big.graph"
    write_graph(big_graph(registry), path)
    assert window.open_file(path, ask=False)
    wait_solved(qtbot, window, timeout=120_000)
    assert len(window.scene.nodes) == NODES and len(window.scene.wires) == NODES - 1
    assert len(builds) == NODES
    assert set(builds.values()) == {1}


def test_selecting_many_nodes_tells_the_window_once(first_window):
    window, signals = first_window
    window.scene.select_nodes(list(window.scene.nodes))
    assert signals == [len(window.scene.nodes)]


def test_deleting_selected_nodes_tells_the_window_once_and_unhighlights_nothing_left(first_window):
    window, signals = first_window
    doomed = list(window.scene.nodes)[:3]
    window.scene.select_nodes(doomed)
    signals.clear()
    window.editor.delete(doomed)
    assert signals == [0]
    assert not any(item.highlighted for item in window.scene.wires.values())
    assert set(window.scene.wires) == set(window.doc.graph.wires)


def test_selecting_a_node_highlights_exactly_its_wires(first_window):
    window, _ = first_window
    node_id = next(n for n in window.scene.nodes if window.doc.graph.wires_from(n))
    window.scene.select_nodes([node_id])
    lit = {w for w, item in window.scene.wires.items() if item.highlighted}
    assert lit == {w for w in window.doc.graph.wires if node_id in (w.source, w.target)}
    window.scene.select_nodes([])
    assert not any(item.highlighted for item in window.scene.wires.values())


@pytest.fixture
def first_window(qtbot, window):
    assert window.open_file(EXAMPLES / "first-steps.graph", ask=False)
    wait_solved(qtbot, window)
    signals: list[int] = []
    window.scene.selectionChanged.connect(lambda: signals.append(len(window.scene.selected_node_ids())))
    return window, signals


@given(
    st.lists(st.sampled_from(["e", "e2", "e3", "slider", "slider7", "x1", "E4", "a-b"]), max_size=12),
    st.lists(st.sampled_from(["e", "e2", "e4", "slider", "slider2", "x", "x1", "x2"]), max_size=8),
)
def test_fresh_ids_are_the_ids_fresh_id_gives_one_by_one(pasted, present):
    ids = list(dict.fromkeys(pasted))
    taken = set(present)
    expected = {}
    for node_id in ids:
        new_id = fresh_id(node_id, taken) if node_id in taken else node_id
        taken.add(new_id)
        expected[node_id] = new_id
    assert fresh_ids(ids, set(present)) == expected


def test_a_ports_tooltip_is_written_when_asked_for_and_names_its_data(qtbot, first_window):
    window, _ = first_window
    node_id = next(n for n in window.scene.nodes if window.doc.graph.wires_from(n))
    port = window.scene.nodes[node_id].output_port(window.doc.graph.wires_from(node_id)[0].source_port)
    assert port.toolTip() == ""  # nothing is written until someone hovers
    event = QGraphicsSceneHelpEvent(QEvent.Type.GraphicsSceneHelp)
    event.setScenePos(port.scenePos())
    event.setScreenPos(window.view.mapToGlobal(window.view.mapFromScene(port.scenePos())))
    window.scene.helpEvent(event)
    assert f"<b>{port.name}</b>" in port.toolTip() and "items in" in port.toolTip()
