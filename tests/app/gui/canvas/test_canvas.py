"""Canvas interactions: zoom, pan, box select, wiring modes, search on a dropped wire,
delete, copy/paste, duplicate, align, groups, context menus, inline widgets, states."""

from __future__ import annotations

import json

import pytest
from PySide6.QtCore import QPoint, QPointF, Qt
from PySide6.QtGui import QGuiApplication, QWheelEvent
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication, QInputDialog

from tests.support.fixtures_gui import FIXTURES, double_click, drag, port_point, view_point, wait_solved
from torsal.app.gui.canvas import inline_widgets, slider_dialog
from torsal.app.gui.canvas.inline_widgets import SliderWidget, ToggleWidget, ValueListWidget
from torsal.app.gui.fuzzy import build_entries, search
from torsal.app.gui.icons import node_letters
from torsal.engine.graphfile import loads


def node_centre(window, node_id: str) -> QPoint:
    item = window.scene.nodes[node_id]
    return view_point(window, item.mapToScene(QPointF(item.size()[0] / 2, 10)))


def empty_spot(window) -> QPoint:
    """A point of the canvas with nothing under it."""
    rect = window.view.viewport().rect()
    for x in range(rect.width() - 30, 30, -40):
        for y in range(rect.height() - 30, 30, -40):
            if window.view.itemAt(QPoint(x, y)) is None:
                return QPoint(x, y)
    raise AssertionError("no empty spot on the canvas")


def test_wheel_zooms_about_the_cursor(first_steps):
    view = first_steps.view
    cursor = QPoint(300, 200)
    before_scene = view.mapToScene(cursor)
    zoom = view.zoom()
    event = QWheelEvent(
        QPointF(cursor),
        QPointF(view.viewport().mapToGlobal(cursor)),
        QPoint(0, 0),
        QPoint(0, 240),
        Qt.MouseButton.NoButton,
        Qt.KeyboardModifier.NoModifier,
        Qt.ScrollPhase.NoScrollPhase,
        False,
    )
    QApplication.sendEvent(view.viewport(), event)
    assert view.zoom() == pytest.approx(zoom * 1.15**2, rel=1e-6)
    after_scene = view.mapToScene(cursor)
    assert abs(after_scene.x() - before_scene.x()) < 1.5 and abs(after_scene.y() - before_scene.y()) < 1.5


def test_middle_drag_pans(first_steps):
    view = first_steps.view
    centre = view.viewport().rect().center()
    before = view.mapToScene(centre)
    QTest.mousePress(view.viewport(), Qt.MouseButton.MiddleButton, Qt.KeyboardModifier.NoModifier, centre)
    for dx in range(10, 101, 10):
        QTest.mouseMove(view.viewport(), centre + QPoint(dx, 0))
    QTest.mouseRelease(
        view.viewport(), Qt.MouseButton.MiddleButton, Qt.KeyboardModifier.NoModifier, centre + QPoint(100, 0)
    )
    after = view.mapToScene(centre)
    assert after.x() == pytest.approx(before.x() - 100 / view.zoom(), abs=2)


def test_box_select_selects_the_nodes_inside(first_steps):
    window = first_steps
    scene = window.scene
    corner_a = view_point(window, scene.nodes["width"].sceneBoundingRect().topLeft() - QPointF(20, 20))
    bottom = scene.nodes["wave"].sceneBoundingRect().bottomRight() + QPointF(12, 12)
    drag(window, corner_a, view_point(window, bottom))
    assert set(scene.selected_node_ids()) == {"width", "count", "wave"}


def test_dragging_a_node_moves_it_in_one_undo_step(first_steps):
    window = first_steps
    start = node_centre(window, "edges")
    before = window.doc.graph.nodes["edges"].position
    drag(window, start, start + QPoint(40, 60))
    after = window.doc.graph.nodes["edges"].position
    assert after[0] > before[0] + 20 and after[1] > before[1] + 30
    window.doc.undo_stack.undo()
    assert window.doc.graph.nodes["edges"].position == before


def test_plain_drag_replaces_shift_adds_and_ctrl_removes(first_steps):
    window = first_steps
    graph = window.doc.graph
    # Panel.Input takes a tree: Shift adds a second wire, a plain drag replaces both
    drag(
        window,
        port_point(window, "wave", "Value", False),
        port_point(window, "show_total", "Input", True),
        modifiers=Qt.KeyboardModifier.ShiftModifier,
    )
    assert {w.source for w in graph.wires_into("show_total")} == {"total", "wave"}
    drag(window, port_point(window, "count", "Value", False), port_point(window, "show_total", "Input", True))
    assert [w.source for w in graph.wires_into("show_total")] == ["count"]
    drag(
        window,
        port_point(window, "count", "Value", False),
        port_point(window, "show_total", "Input", True),
        modifiers=Qt.KeyboardModifier.ControlModifier,
    )
    assert graph.wires_into("show_total") == []
    # dragging from an input back to an output works too
    drag(
        window, port_point(window, "show_total", "Input", True), port_point(window, "total", "Result", False)
    )
    assert [w.source for w in graph.wires_into("show_total")] == ["total"]


def test_a_wire_that_cannot_be_made_is_refused_with_a_message(first_steps):
    window = first_steps
    wires = list(window.doc.graph.wires)
    drag(window, port_point(window, "heights", "Result", False), port_point(window, "width", "Value", False))
    assert window.doc.graph.wires == wires  # output to output: nothing
    drag(window, port_point(window, "heights", "Result", False), port_point(window, "edges", "Step", True))
    assert window.doc.graph.wires == wires  # edges feeds heights: a loop
    assert "loop" in window.log.app_messages[-1][2]


def test_dropping_a_wire_on_empty_canvas_searches_nodes_that_take_its_type(qtbot, first_steps):
    window = first_steps
    spot = empty_spot(window)
    drag(window, port_point(window, "width", "Value", False), spot)
    qtbot.waitUntil(window.popup.isVisible, timeout=3000)
    assert "Number" in window.popup.note.text()
    listed = [
        window.popup.list.item(i).data(Qt.ItemDataRole.UserRole) for i in range(window.popup.list.count())
    ]
    assert "maths.Series" in listed and "params.NumberSlider" not in listed  # a slider takes no input
    QTest.keyClicks(window.popup.query, "series")
    QTest.keyClick(window.popup.query, Qt.Key.Key_Return)
    new = [n for n in window.doc.graph.nodes if n.startswith("series")]
    assert new and window.doc.graph.wires[-1].source == "width"
    assert window.doc.graph.wires[-1].target == new[0]
    window.doc.undo_stack.undo()  # "Add and connect" is one step
    assert new[0] not in window.doc.graph.nodes


def test_delete_key_removes_the_selection_and_undo_restores_it(first_steps):
    window = first_steps
    wires = list(window.doc.graph.wires)
    window.scene.select_nodes(["edges", "total"])
    window.view.setFocus()
    QTest.keyClick(window.view, Qt.Key.Key_Delete)
    assert "edges" not in window.doc.graph.nodes and "total" not in window.doc.graph.nodes
    assert "edges" not in window.scene.nodes
    window.doc.undo_stack.undo()
    assert window.doc.graph.wires == wires and "edges" in window.scene.nodes


def test_copy_puts_a_graph_fragment_on_the_clipboard_and_paste_adds_renamed_nodes(first_steps, registry):
    window = first_steps
    window.scene.select_nodes(["width", "edges"])
    assert window.copy_selection()
    text = QGuiApplication.clipboard().text()
    fragment = loads(text, registry)  # the engine's reader accepts it
    assert set(fragment.nodes) == {"width", "edges"} and len(fragment.wires) == 1
    new = window.paste()
    assert sorted(new) == ["edges2", "width2"]
    assert any(w.source == "width2" and w.target == "edges2" for w in window.doc.graph.wires)
    assert set(window.scene.selected_node_ids()) == set(new)


def test_duplicate_and_alt_drag_copy_nodes(first_steps):
    window = first_steps
    window.scene.select_nodes(["count"])
    assert window.duplicate_selection() == ["count2"]
    start = node_centre(window, "wave")
    drag(window, start, start + QPoint(0, 90), modifiers=Qt.KeyboardModifier.AltModifier)
    graph = window.doc.graph
    assert "wave2" in graph.nodes
    assert graph.nodes["wave2"].position[1] > graph.nodes["wave"].position[1] + 50
    assert graph.wires_from("wave") and not graph.wires_from("wave2")  # the original keeps its wires
    window.doc.undo_stack.undo()
    assert "wave2" not in graph.nodes


def test_align_left_lines_up_the_selection(first_steps):
    window = first_steps
    window.scene.select_nodes(["edges", "heights", "show_total"])
    window.align_selection("left")
    xs = {window.doc.graph.nodes[n].position[0] for n in ("edges", "heights", "show_total")}
    assert len(xs) == 1


def test_group_and_ungroup(first_steps, monkeypatch):
    window = first_steps
    window.scene.select_nodes(["heights", "show_heights"])
    window.group_selection()
    group = window.doc.graph.groups[-1]
    assert group.nodes == ["heights", "show_heights"]
    box = window.scene.groups[group.id].boundingRect()
    assert box.contains(window.scene.nodes["heights"].sceneBoundingRect())
    monkeypatch.setattr(QInputDialog, "getText", staticmethod(lambda *a, **k: ("Output", True)))
    title_bar = window.scene.groups[group.id].title_rect().center()
    window.view.centerOn(title_bar)
    double_click(window, view_point(window, title_bar))  # a double-click on the title renames
    assert window.doc.graph.groups[-1].title == "Output"
    assert window.scene.groups[group.id].title == "Output"
    window.scene.select_nodes(["heights"])
    window.ungroup_selection()
    assert all(g.id != group.id for g in window.doc.graph.groups)


def test_inline_toggle_value_list_panel_and_slider_dialog(qtbot, window, monkeypatch):
    editor = window.editor
    ids = {
        t: editor.add_node(t, (40.0 * i, 120.0 * i))
        for i, t in enumerate(["params.Toggle", "params.ValueList", "params.Panel", "params.NumberSlider"])
    }
    wait_solved(qtbot, window)
    toggle = window.scene.nodes[ids["params.Toggle"]]
    window.view.centerOn(toggle)
    assert isinstance(toggle.widget, ToggleWidget)
    QTest.mouseClick(
        window.view.viewport(),
        Qt.MouseButton.LeftButton,
        Qt.KeyboardModifier.NoModifier,
        view_point(window, toggle.mapToScene(toggle.layout.widget_rect.center())),
    )
    assert window.doc.graph.nodes[ids["params.Toggle"]].node.settings["value"] is True

    value_list = window.scene.nodes[ids["params.ValueList"]]
    window.view.centerOn(value_list)
    assert isinstance(value_list.widget, ValueListWidget)
    monkeypatch.setattr(inline_widgets, "pick", lambda names, selected: 2)
    QTest.mouseClick(
        window.view.viewport(),
        Qt.MouseButton.LeftButton,
        Qt.KeyboardModifier.NoModifier,
        view_point(window, value_list.mapToScene(value_list.layout.widget_rect.center())),
    )
    assert window.doc.graph.nodes[ids["params.ValueList"]].node.settings["selected"] == 2

    panel = window.scene.nodes[ids["params.Panel"]]
    window.view.centerOn(panel)
    height = panel.size()[1]
    monkeypatch.setattr(
        QInputDialog, "getMultiLineText", staticmethod(lambda *a, **k: ("a\nb\nc\nd\ne", True))
    )
    double_click(window, view_point(window, panel.mapToScene(panel.layout.widget_rect.center())))
    wait_solved(qtbot, window)
    assert window.doc.results[ids["params.Panel"]].outputs["Output"].all_items() == list("abcde")
    assert panel.size()[1] > height  # the panel grew with its text

    slider = window.scene.nodes[ids["params.NumberSlider"]]
    window.view.centerOn(slider)
    assert isinstance(slider.widget, SliderWidget)
    monkeypatch.setattr(
        slider_dialog,
        "edit_slider",
        lambda title, settings, integer, bounds=None: {
            "min": -5.0, "max": 5.0, "value": 2.5, "decimals": 1
        },
    )
    depth = window.doc.undo_stack.count()
    rect = slider.layout.widget_rect  # (the mouse route to double_click is covered by the panel above)
    assert slider.widget.double_click(rect.center(), rect)
    settings = window.doc.graph.nodes[ids["params.NumberSlider"]].node.settings
    assert (settings["min"], settings["max"], settings["value"], settings["decimals"]) == (-5.0, 5.0, 2.5, 1)
    assert window.doc.undo_stack.count() == depth + 1  # one step for the whole dialog
    assert slider.widget.text() == "2.5"


def test_states_colour_nodes_and_messages_reach_tooltips_log_and_status(qtbot, window):
    node_id = window.editor.add_node("params.NumberSlider", (0.0, 0.0), settings={"min": 2.0, "max": 1.0})
    wait_solved(qtbot, window)
    item = window.scene.nodes[node_id]
    assert item.state == "error" and item.body_colour().name() == "#e0584f"
    assert "greater than its max" in item.tooltip()
    window._fill_tables()
    assert any("greater than its max" in row[3] for row in window.log.node_rows)
    assert "1 error" in window.status.counts_label.text()
    window.scene.select_nodes([node_id])
    assert item.body_colour().name() == "#7cc67a"


def test_wires_are_drawn_by_what_they_carry(first_steps):
    window = first_steps
    kinds = {(w.source, w.target): item.kind for w, item in window.scene.wires.items()}
    assert kinds[("width", "edges")] == "item"
    assert kinds[("edges", "heights")] == "list"
    window.editor.toggle_modifier("heights", "s", "graft")


def test_viewport_highlights_selection_and_changes_views(qtbot, window, tmp_path):
    assert window.open_file(FIXTURES / "showcase.graph", ask=False)
    wait_solved(qtbot, window)
    viewport = window.viewport
    window.scene.select_nodes(["helix"])
    name = viewport.preview.nodes["helix"].names[0]
    assert viewport.plotter.renderer.actors[name].prop.color.hex_rgb == "#30b030"
    window.scene.select_nodes([])
    assert viewport.plotter.renderer.actors[name].prop.color.hex_rgb != "#30b030"
    viewport.set_view("top")
    assert viewport.plotter.renderer.camera.parallel_projection
    viewport.set_view("perspective")
    assert not viewport.plotter.renderer.camera.parallel_projection
    shot = viewport.screenshot(tmp_path / "viewport.png")
    assert shot.stat().st_size > 5000
    window.editor.set_preview(["helix"], False)
    assert "helix" not in viewport.preview.nodes


def test_inspector_edits_a_setting_as_one_undo_step(first_steps):
    window = first_steps
    window.scene.select_nodes(["total"])
    table = window.inspector.settings
    row = next(r for r in range(table.rowCount()) if table.item(r, 0).text() == "expression")
    table.item(row, 1).setText(json.dumps("w * n * 2"))
    assert window.doc.graph.nodes["total"].node.settings["expression"] == "w * n * 2"
    assert window.doc.undo_stack.undoText() == "Set expression of Total length"  # names the node


def test_palette_click_places_a_node_and_icons_carry_the_toolbox_letters(window):
    button = window.palette.findChild(object, "palette:params.Toggle")
    button.click()
    assert any(r.type_id == "params.Toggle" for r in window.doc.graph.nodes.values())

    class Fake:
        icon = ""

    for type_id, letters in (
        ("analysis.SurfaceAnalysis", "A"),
        ("curves.Divide", "C"),
        ("developable.ConicalSurface", "D"),
        ("developable.RulingDevelopable", "R"),
        ("patching.SurfacePatching", "P"),
        ("params.NumberSlider", "NS"),
    ):
        Fake.type_id = type_id
        assert node_letters(Fake) == letters


def test_fuzzy_search_finds_by_letters_in_order_and_by_description(registry):
    entries = build_entries(list(registry))
    assert search(entries, "numsl")[0].type_id == "params.NumberSlider"
    assert search(entries, "slider")[0].type_id in ("params.NumberSlider", "params.IntegerSlider")
    assert "params.ValueList" in [e.type_id for e in search(entries, "material thickness")]
