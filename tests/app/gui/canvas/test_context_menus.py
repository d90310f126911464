"""Right-click menus, driven as a user drives them: real mouse and key events on the canvas
viewport open the menu, the test reads the open QMenu and picks an entry with the mouse."""

from __future__ import annotations

from typing import Any

from PySide6.QtCore import QPoint, QPointF, Qt
from PySide6.QtGui import QContextMenuEvent
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication, QInputDialog

from tests.support.fixtures_gui import (
    MenuCatcher,
    port_point,
    right_click,
    title_point,
    view_point,
    wait_solved,
)
from torsal.app.gui.canvas.wire_item import WireItem

RIGHT = Qt.MouseButton.RightButton
NONE = Qt.KeyboardModifier.NoModifier


def wire_point(window: Any, source: str, target: str, target_port: str) -> QPoint:
    item = next(
        w
        for w in window.scene.wires.values()
        if (w.wire.source, w.wire.target, w.wire.target_port) == (source, target, target_port)
    )
    path = item.path()
    for t in (0.5, 0.4, 0.6, 0.3, 0.7):  # a point of the curve with only the wire under it
        point = view_point(window, path.pointAtPercent(t))
        if not any(not isinstance(i, WireItem) and i.zValue() > -10 for i in window.view.items(point)):
            return point
    raise AssertionError("the wire is hidden under nodes everywhere")


def group_point(window: Any, group_id: str) -> QPoint:
    rect = window.scene.groups[group_id].title_rect()
    return view_point(window, QPointF(rect.right() - 6, rect.center().y()))


def height_branches(window: Any) -> list[int]:
    """How many numbers each branch of Panel heights' Result holds."""
    return [len(b) for b in window.doc.results["heights"].output("Result").branches]


def test_right_click_on_a_node_title_opens_the_node_menu(first_steps):
    catcher = right_click(first_steps, title_point(first_steps, "heights"))
    assert catcher.entries[:5] == ["Preview", "Enabled", "Rename…", "Edit expression…", "Help"]
    assert first_steps.scene.selected_node_ids() == ["heights"]


def test_choosing_enabled_from_the_node_menu_disables_the_node(qtbot, first_steps):
    right_click(first_steps, title_point(first_steps, "heights"), pick="Enabled")
    wait_solved(qtbot, first_steps)
    assert first_steps.doc.results["heights"].state == "disabled"


def test_right_click_on_an_input_port_opens_its_menu_and_graft_changes_the_solve(qtbot, first_steps):
    assert height_branches(first_steps) == [12]  # the 12 panel edges, one list
    catcher = right_click(first_steps, port_point(first_steps, "heights", "s", True), pick="Graft")
    assert catcher.entries[:4] == ["Graft", "Flatten", "Simplify", "Reverse"]
    assert "Set value…" in catcher.entries
    wait_solved(qtbot, first_steps)
    assert first_steps.doc.graph.nodes["heights"].inputs["s"].modifiers == ["graft"]
    assert height_branches(first_steps) == [1] * 12  # grafted: each edge on a branch of its own


def test_right_click_on_an_output_port_opens_disconnect_and_export(first_steps):
    catcher = right_click(first_steps, port_point(first_steps, "edges", "Series", False))
    assert catcher.entries == ["Disconnect (1)", "Export…"]


def test_right_click_on_a_wire_opens_its_menu_and_graft_changes_the_solve(qtbot, first_steps):
    assert height_branches(first_steps) == [12]
    catcher = right_click(first_steps, wire_point(first_steps, "edges", "heights", "s"), pick="Graft")
    assert catcher.entries == ["Graft", "Flatten", "Simplify", "Reverse", "Delete wire"]
    wait_solved(qtbot, first_steps)
    assert first_steps.doc.graph.nodes["heights"].inputs["s"].modifiers == ["graft"]
    assert height_branches(first_steps) == [1] * 12


def test_right_click_on_a_group_opens_the_group_menu(first_steps):
    catcher = right_click(first_steps, group_point(first_steps, "layout"))
    assert catcher.entries == ["Rename…", "Colour…", "Ungroup"]


def test_ungroup_from_the_group_menu_removes_the_group(first_steps):
    right_click(first_steps, group_point(first_steps, "layout"), pick="Ungroup")
    assert [g.id for g in first_steps.doc.graph.groups] == ["inputs"]


def test_right_drag_over_a_node_pans_and_opens_no_menu(first_steps):
    view = first_steps.view
    start = title_point(first_steps, "heights")
    before = view.mapToScene(start)
    catcher = MenuCatcher()
    viewport = view.viewport()
    QTest.mousePress(viewport, RIGHT, NONE, start)
    for i in range(1, 9):
        QTest.mouseMove(viewport, start + QPoint(10 * i, 5 * i))
    QTest.mouseRelease(viewport, RIGHT, NONE, start + QPoint(80, 40))
    QApplication.processEvents()
    moved = view.mapToScene(start) - before
    assert (round(moved.x() * view.zoom()), round(moved.y() * view.zoom())) == (-80, -40)
    assert catcher.menus == []


def test_a_platform_context_menu_event_during_a_right_press_opens_one_menu_on_release(first_steps):
    """X11 sends the context-menu event on the press: the menu still opens once, on release."""
    point = title_point(first_steps, "heights")
    viewport = first_steps.view.viewport()
    catcher = MenuCatcher()
    QTest.mousePress(viewport, RIGHT, NONE, point)
    event = QContextMenuEvent(QContextMenuEvent.Reason.Mouse, point, viewport.mapToGlobal(point))
    QApplication.sendEvent(viewport, event)
    assert catcher.menus == []
    QTest.mouseRelease(viewport, RIGHT, NONE, point)
    QApplication.processEvents()
    assert catcher.entries[0] == "Preview"


def test_a_platform_context_menu_event_after_the_release_opens_no_second_menu(first_steps):
    """Windows sends it after the release, which has already opened the menu."""
    point = title_point(first_steps, "heights")
    viewport = first_steps.view.viewport()
    catcher = right_click(first_steps, point)
    event = QContextMenuEvent(QContextMenuEvent.Reason.Mouse, point, viewport.mapToGlobal(point))
    QApplication.sendEvent(viewport, event)
    QApplication.processEvents()
    assert len(catcher.menus) == 1


def test_a_mouse_context_menu_event_alone_opens_the_menu_where_it_points(first_steps):
    point = port_point(first_steps, "edges", "Step", True)
    viewport = first_steps.view.viewport()
    catcher = MenuCatcher()
    event = QContextMenuEvent(QContextMenuEvent.Reason.Mouse, point, viewport.mapToGlobal(point))
    QApplication.sendEvent(viewport, event)
    QApplication.processEvents()
    assert catcher.entries[0] == "Graft"


def test_the_menu_key_opens_the_menu_of_the_item_under_the_mouse(first_steps):
    viewport = first_steps.view.viewport()
    QTest.mouseMove(viewport, port_point(first_steps, "edges", "Step", True))
    catcher = MenuCatcher(pick="Reverse")
    QTest.keyClick(viewport, Qt.Key.Key_Menu)
    QApplication.processEvents()
    assert catcher.entries[0] == "Graft"
    assert first_steps.doc.graph.nodes["edges"].inputs["Step"].modifiers == ["reverse"]


def test_set_value_from_the_input_menu_sets_the_typed_value(first_steps, monkeypatch):
    monkeypatch.setattr(QInputDialog, "getText", staticmethod(lambda *a, **k: ("[1, 2, 3]", True)))
    right_click(first_steps, port_point(first_steps, "edges", "Start", True), pick="Set value…")
    assert first_steps.doc.graph.nodes["edges"].inputs["Start"].value == [1, 2, 3]


def test_preview_from_the_node_menu_hides_the_node_from_the_viewport(first_steps):
    right_click(first_steps, title_point(first_steps, "heights"), pick="Preview")
    assert not first_steps.doc.graph.nodes["heights"].preview


def test_help_from_the_node_menu_shows_the_node_help(first_steps):
    right_click(first_steps, title_point(first_steps, "heights"), pick="Help")
    dialog = first_steps._help_dialogs[-1]
    assert dialog.isVisible() and "formula" in first_steps.inspector.help.toPlainText()
    dialog.close()
