"""Clusters on the canvas, driven as a user drives them: a box selection and a Ctrl-click
pick nodes, a right-click opens the node menu, "Cluster" collapses them; double-click
opens the cluster's definition with a breadcrumb back; "Explode" restores; each one undo
step. The saved file solves headless (``torsal run``'s path) exactly as the expanded
graph does."""

from __future__ import annotations

import json
from typing import Any

import pytest
from PySide6.QtCore import QPoint, QPointF, Qt, QTimer
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication, QDialogButtonBox, QLineEdit, QListWidget, QPushButton

from tests.support.fixtures_gui import (
    EXAMPLES,
    double_click,
    drag,
    right_click,
    title_point,
    view_point,
    wait_solved,
)
from torsal.app.gui.cluster_widgets import ClusterPortsDialog
from torsal.app.headless import run_file
from torsal.engine.cluster import is_cluster
from torsal.engine.cluster_edits import definition_of

CTRL = Qt.KeyboardModifier.ControlModifier
INNER = {"edges", "total", "heights"}  # the Series and the two Expressions of first-steps
OUTSIDE = ("width", "count", "wave", "show_heights", "show_total")


def select_inner_nodes(window: Any) -> None:
    """A box round Series and Total, then a Shift-click on Heights' title (Shift adds, as in
    Grasshopper)."""
    scene = window.scene
    top_left = scene.nodes["edges"].sceneBoundingRect().topLeft() - QPointF(8, 8)
    bottom_right = scene.nodes["total"].sceneBoundingRect().bottomRight() + QPointF(8, 8)
    drag(window, view_point(window, top_left), view_point(window, bottom_right))
    assert set(scene.selected_node_ids()) == {"edges", "total"}
    shift = Qt.KeyboardModifier.ShiftModifier
    QTest.mouseClick(window.view.viewport(), Qt.MouseButton.LeftButton, shift, title_point(window, "heights"))
    assert set(scene.selected_node_ids()) == INNER


def cluster_through_the_menu(qtbot: Any, window: Any) -> str:
    select_inner_nodes(window)
    catcher = right_click(window, title_point(window, "heights"), pick="Cluster")
    assert "Cluster" in catcher.entries
    clusters = [n for n, r in window.doc.graph.nodes.items() if is_cluster(r.node)]
    assert len(clusters) == 1
    wait_solved(qtbot, window)
    return clusters[0]


def wiring(graph: Any) -> list[tuple[str, str, str, str]]:
    return sorted((w.source, w.source_port, w.target, w.target_port) for w in graph.wires)


def outputs_of(run: Any, node_ids: tuple[str, ...]) -> dict[str, Any]:
    return {
        node_id: {port: tree.to_dict() for port, tree in run.solver.results[node_id].outputs.items()}
        for node_id in node_ids
    }


def test_a_cluster_made_with_the_mouse_saves_reopens_and_solves_headless_as_the_expanded_graph(
    qtbot, first_steps, tmp_path
):
    window = first_steps
    cluster_id = cluster_through_the_menu(qtbot, window)
    assert INNER.isdisjoint(window.doc.graph.nodes)
    assert window.doc.results[cluster_id].state == "ok"
    path = tmp_path / "clustered.graph"
    assert window.save_as(path)
    assert window.open_file(path, ask=False)
    wait_solved(qtbot, window)
    assert is_cluster(window.doc.graph.nodes[cluster_id].node)
    assert INNER.isdisjoint(window.doc.graph.nodes)
    expanded, clustered = run_file(EXAMPLES / "first-steps.graph"), run_file(path)
    assert clustered.ok and expanded.ok
    assert outputs_of(clustered, OUTSIDE) == outputs_of(expanded, OUTSIDE)
    (definition,) = json.loads(path.read_text(encoding="utf-8"))["clusters"]  # saved inline, once
    assert {n["id"] for n in definition["nodes"]} >= INNER


def test_clustering_is_one_undo_step_and_redo_makes_it_again(qtbot, first_steps):
    window = first_steps
    before_nodes, before_wires = list(window.doc.graph.nodes), wiring(window.doc.graph)
    stack = window.doc.undo_stack
    count = stack.count()
    cluster_id = cluster_through_the_menu(qtbot, window)
    assert stack.count() == count + 1
    after_wires = wiring(window.doc.graph)
    window.actions_by_name["undo"].trigger()
    assert sorted(window.doc.graph.nodes) == sorted(before_nodes)
    assert wiring(window.doc.graph) == before_wires
    assert set(window.scene.nodes) == set(before_nodes)
    window.actions_by_name["redo"].trigger()
    assert cluster_id in window.doc.graph.nodes and INNER.isdisjoint(window.doc.graph.nodes)
    assert wiring(window.doc.graph) == after_wires
    assert cluster_id in window.scene.nodes


def test_explode_from_the_cluster_menu_restores_the_nodes_in_one_undo_step(qtbot, first_steps):
    window = first_steps
    expanded_wires = wiring(window.doc.graph)
    heights_before = window.doc.results["heights"].output("Result").to_dict()
    cluster_id = cluster_through_the_menu(qtbot, window)
    clustered_wires = wiring(window.doc.graph)
    count = window.doc.undo_stack.count()
    right_click(window, title_point(window, cluster_id), pick="Explode")
    assert set(window.doc.graph.nodes) >= INNER and cluster_id not in window.doc.graph.nodes
    assert wiring(window.doc.graph) == expanded_wires
    assert window.doc.undo_stack.count() == count + 1
    wait_solved(qtbot, window)
    assert window.doc.results["heights"].output("Result").to_dict() == heights_before
    window.actions_by_name["undo"].trigger()
    assert cluster_id in window.doc.graph.nodes and wiring(window.doc.graph) == clustered_wires
    window.actions_by_name["redo"].trigger()
    assert wiring(window.doc.graph) == expanded_wires


def test_ctrl_alt_g_clusters_the_selection(qtbot, first_steps):
    window = first_steps
    select_inner_nodes(window)
    QTest.keyClick(window.view.viewport(), Qt.Key.Key_G, CTRL | Qt.KeyboardModifier.AltModifier)
    assert INNER.isdisjoint(window.doc.graph.nodes)
    assert any(is_cluster(r.node) for r in window.doc.graph.nodes.values())


def test_double_click_opens_the_definition_with_a_breadcrumb_and_edits_inside_update_the_instance(
    qtbot, first_steps
):
    window = first_steps
    cluster_id = cluster_through_the_menu(qtbot, window)
    double_click(window, title_point(window, cluster_id))
    qtbot.waitUntil(lambda: len(window.doc.frames) == 1, timeout=3000)
    assert set(window.scene.nodes) >= INNER
    assert window.breadcrumb.isVisible()
    assert [b.text() for b in window.breadcrumb.crumbs] == ["Document", "Cluster"]
    wait_solved(qtbot, window)
    # the inner nodes see the instance's data: Heights inside gives what it gave outside
    heights = window.doc.results["heights"].output("Result")
    assert heights.item_count > 0
    # an edit inside: Total's formula (x) doubled, then back through the breadcrumb
    window.editor.set_settings("total", {"expression": "2*w*n"}, text="Edit expression")
    QTest.mouseClick(window.breadcrumb.crumbs[0], Qt.MouseButton.LeftButton)
    assert not window.doc.frames and not window.breadcrumb.isVisible()
    assert cluster_id in window.scene.nodes
    wait_solved(qtbot, window)
    width = window.doc.graph.nodes["width"].node.settings["value"]
    count = window.doc.graph.nodes["count"].node.settings["value"]
    assert total_out_of(window, cluster_id) == pytest.approx(2 * width * count)
    # the whole edit inside is one undo step outside
    window.actions_by_name["undo"].trigger()
    wait_solved(qtbot, window)
    assert total_out_of(window, cluster_id) == pytest.approx(width * count)


def total_out_of(window: Any, cluster_id: str) -> float:
    """What the cluster's output wired to the Total panel gives."""
    (wire,) = window.doc.graph.wires_into("show_total")
    assert wire.source == cluster_id
    return window.doc.results[cluster_id].outputs[wire.source_port].first()


def answer_ports_dialog(actions: list[Any]) -> list[BaseException]:
    """When the ports dialog opens: run ``actions`` on it (each takes the dialog), then OK
    (Cancel if one failed: the dialog never stays open). What failed is in the list returned."""
    failures: list[BaseException] = []

    def poll() -> None:
        dialog = QApplication.activeModalWidget()
        if not isinstance(dialog, ClusterPortsDialog):
            QTimer.singleShot(20, poll)
            return
        button = QDialogButtonBox.StandardButton.Ok
        try:
            for action in actions:
                action(dialog)
        except BaseException as exc:  # reported by the test, once the dialog has closed
            failures.append(exc)
            button = QDialogButtonBox.StandardButton.Cancel
        finally:
            QTest.mouseClick(dialog.findChild(QDialogButtonBox).button(button), Qt.MouseButton.LeftButton)

    QTimer.singleShot(20, poll)
    return failures


def test_the_ports_dialog_renames_and_reorders_the_cluster_inputs_in_one_undo_step(qtbot, first_steps):
    window = first_steps
    cluster_id = cluster_through_the_menu(qtbot, window)
    definition = definition_of(window.doc.graph, cluster_id)
    before = definition.input_names()
    assert len(before) >= 2

    def rename_first(dialog: ClusterPortsDialog) -> None:  # double-click the name, type, Enter
        box = dialog.findChild(QListWidget, "inputs")
        centre = box.visualItemRect(box.item(0)).center()
        QTest.mouseClick(box.viewport(), Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, centre)
        QTest.mouseDClick(box.viewport(), Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, centre)
        editor = box.findChild(QLineEdit)  # the in-place editor the double-click opened
        assert editor is not None and editor.isVisible()
        editor.selectAll()
        QTest.keyClicks(editor, "Bay width")
        QTest.keyClick(editor, Qt.Key.Key_Return)
        QApplication.processEvents()  # the item view commits the edit on the next turn
        assert box.item(0).text() == "Bay width"

    def move_first_down(dialog: ClusterPortsDialog) -> None:
        box = dialog.findChild(QListWidget, "inputs")
        box.setCurrentRow(0)
        QTest.mouseClick(dialog.findChild(QPushButton, "input_down"), Qt.MouseButton.LeftButton)

    failures = answer_ports_dialog([rename_first, move_first_down])
    count = window.doc.undo_stack.count()
    right_click(window, title_point(window, cluster_id), pick="Cluster ports…")
    assert not failures, failures
    names = definition_of(window.doc.graph, cluster_id).input_names()
    assert names[:2] == [before[1], "Bay width"]
    assert window.doc.undo_stack.count() == count + 1
    wired = {w.target_port for w in window.doc.graph.wires if w.target == cluster_id}
    assert "Bay width" in wired and before[0] not in wired
    window.actions_by_name["undo"].trigger()
    assert definition_of(window.doc.graph, cluster_id).input_names() == before


def empty_spot(window: Any) -> QPoint:
    rect = window.view.viewport().rect()
    for x in range(rect.width() - 30, 30, -40):
        for y in range(rect.height() - 30, 30, -40):
            if window.view.itemAt(QPoint(x, y)) is None:
                return QPoint(x, y)
    raise AssertionError("no empty spot on the canvas")


def test_an_input_added_inside_the_cluster_becomes_a_port_of_the_instance(qtbot, first_steps):
    window = first_steps
    cluster_id = cluster_through_the_menu(qtbot, window)
    ports_before = len(definition_of(window.doc.graph, cluster_id).input_names())
    double_click(window, title_point(window, cluster_id))
    qtbot.waitUntil(lambda: len(window.doc.frames) == 1, timeout=3000)
    qtbot.wait(50)
    right_click(window, empty_spot(window), pick="Add cluster input")
    QTest.mouseClick(window.breadcrumb.crumbs[0], Qt.MouseButton.LeftButton)
    assert not window.doc.frames
    assert len(definition_of(window.doc.graph, cluster_id).input_names()) == ports_before + 1
    item = window.scene.nodes[cluster_id]
    assert len([key for key in item.ports if key[0]]) == ports_before + 1


def test_the_cluster_takes_the_place_of_its_nodes_in_their_group_box(qtbot, first_steps):
    window = first_steps
    cluster_id = cluster_through_the_menu(qtbot, window)
    box = window.scene.groups["layout"].sceneBoundingRect()
    assert box.contains(window.scene.nodes[cluster_id].sceneBoundingRect())


def open_cluster_by_double_click(qtbot: Any, window: Any, cluster_id: str) -> None:
    double_click(window, title_point(window, cluster_id))
    qtbot.waitUntil(lambda: len(window.doc.frames) == 1, timeout=3000)
    wait_solved(qtbot, window)


def test_saving_inside_a_cluster_goes_back_out_and_saves_the_edits_made_inside(qtbot, first_steps, tmp_path):
    window = first_steps
    cluster_id = cluster_through_the_menu(qtbot, window)
    open_cluster_by_double_click(qtbot, window, cluster_id)
    window.editor.set_settings("total", {"expression": "3*w*n"}, text="Edit expression")
    path = tmp_path / "edited.graph"
    assert window.save_as(path)
    assert not window.doc.frames and not window.doc.dirty
    (definition,) = json.loads(path.read_text(encoding="utf-8"))["clusters"]
    total = next(n for n in definition["nodes"] if n["id"] == "total")
    assert total["settings"]["expression"] == "3*w*n"


def test_going_back_out_of_a_cluster_shows_the_canvas_where_it_was(qtbot, first_steps):
    window = first_steps
    cluster_id = cluster_through_the_menu(qtbot, window)
    window.view.zoom_by(1.6)
    zoom, centre = window.view.zoom(), window.view.mapToScene(window.view.viewport().rect().center())
    open_cluster_by_double_click(qtbot, window, cluster_id)
    qtbot.wait(50)
    QTest.mouseClick(window.breadcrumb.crumbs[0], Qt.MouseButton.LeftButton)
    qtbot.wait(50)
    assert window.view.zoom() == pytest.approx(zoom)
    back = window.view.mapToScene(window.view.viewport().rect().center())
    assert abs(back.x() - centre.x()) < 2 and abs(back.y() - centre.y()) < 2


def test_copy_and_paste_of_a_cluster_shares_its_definition(qtbot, first_steps):
    window = first_steps
    cluster_id = cluster_through_the_menu(qtbot, window)
    definitions = set(window.doc.graph.clusters)
    window.view.setFocus()
    QTest.keyClick(window.view.viewport(), Qt.Key.Key_C, CTRL)
    QTest.keyClick(window.view.viewport(), Qt.Key.Key_V, CTRL)
    clusters = [n for n, r in window.doc.graph.nodes.items() if is_cluster(r.node)]
    assert len(clusters) == 2
    pasted = next(n for n in clusters if n != cluster_id)
    same = definition_of(window.doc.graph, pasted) is definition_of(window.doc.graph, cluster_id)
    assert same and set(window.doc.graph.clusters) == definitions
    original, copy = window.scene.nodes[cluster_id], window.scene.nodes[pasted]
    assert set(copy.ports) == set(original.ports)


def test_a_cluster_made_inside_a_cluster_nests_and_the_outer_result_stays(qtbot, first_steps):
    window = first_steps
    cluster_id = cluster_through_the_menu(qtbot, window)
    expected = total_out_of(window, cluster_id)
    open_cluster_by_double_click(qtbot, window, cluster_id)
    window.scene.select_nodes(["total"])
    QTest.keyClick(window.view.viewport(), Qt.Key.Key_G, CTRL | Qt.KeyboardModifier.AltModifier)
    inner = [n for n, r in window.doc.graph.nodes.items() if is_cluster(r.node)]
    assert len(inner) == 1
    double_click(window, title_point(window, inner[0]))
    qtbot.waitUntil(lambda: len(window.doc.frames) == 2, timeout=3000)
    assert [b.text() for b in window.breadcrumb.crumbs] == ["Document", "Cluster", "Cluster"]
    QTest.mouseClick(window.breadcrumb.crumbs[0], Qt.MouseButton.LeftButton)
    assert not window.doc.frames
    wait_solved(qtbot, window)
    assert total_out_of(window, cluster_id) == pytest.approx(expected)
    definition = definition_of(window.doc.graph, cluster_id)
    assert any(is_cluster(r.node) for r in definition.graph.nodes.values())
