"""Export… on an output, Bake to Rhino, and the group menu (Rename…, Colour…, Ungroup)."""

from __future__ import annotations

import csv
import json

import numpy as np
import pytest
import rhino3dm as rh
from PySide6.QtCore import QPoint, QPointF, Qt
from PySide6.QtGui import QColor, QKeySequence
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QColorDialog, QFileDialog, QMenu

from tests.support.fixtures_gui import (
    EXAMPLES,
    copy_fixture,
    port_point,
    title_point,
    view_point,
    wait_solved,
)
from tests.support.fixtures_gui import right_click as right_click_menu
from tests.support.io_helpers import rhino_points, rhino_surface_points
from torsal.app.gui.canvas.view import CanvasView


class SaveDialog:
    """Stands in for QFileDialog.getSaveFileName: records what it was offered, answers ``answer``."""

    def __init__(self, answer):
        self.answer = answer
        self.offered: list[tuple[str, str, str]] = []

    def __call__(self, parent, caption, start, filters, selected="", *args, **kwargs):
        self.offered.append((start, filters, selected))
        return str(self.answer), selected


def open_example(qtbot, window, name, folder):
    assert window.open_file(copy_fixture(EXAMPLES / name, folder), ask=False)
    wait_solved(qtbot, window)
    return window


def save_as(monkeypatch, path) -> SaveDialog:
    dialog = SaveDialog(path)
    monkeypatch.setattr(QFileDialog, "getSaveFileName", staticmethod(dialog))
    return dialog


def trigger(menu: QMenu, text: str) -> None:
    for action in menu.actions():
        if action.menu() is not None:
            found = [a for a in action.menu().actions() if a.text() == text]
            if found:
                found[0].trigger()
                return
        elif action.text() == text:
            action.trigger()
            return
    raise AssertionError(f"no {text!r} in {[a.text() for a in menu.actions()]}")


def export_from_port(window, node_id, port):
    """Right-click the output port and choose Export… (real events on the canvas)."""
    window.view.centerOn(window.scene.nodes[node_id])
    catcher = right_click_menu(window, port_point(window, node_id, port, False), "Export…")
    assert "Export…" in catcher.entries


# -- Export… -------------------------------------------------------------------------
def test_export_on_an_output_port_writes_its_rulings_to_3dm_point_for_point(
    qtbot, window, tmp_path, monkeypatch
):
    open_example(qtbot, window, "textbook-ruled-surfaces.graph", tmp_path)
    dialog = save_as(monkeypatch, tmp_path / "out" / "rulings.3dm")
    export_from_port(window, "helicoid", "Rulings")
    start, filters, selected = dialog.offered[0]
    assert start == str(tmp_path / "Helicoid-Rulings.3dm")  # the label, beside the graph file
    assert selected == "Rhino 3D model (*.3dm)"
    offered = filters.split(";;")
    assert offered[:3] == ["Rhino 3D model (*.3dm)", "CSV table (*.csv)", "JSON data tree (*.json)"]
    assert len(offered) == 10 and offered[-1] == "All files (*)"
    model = rh.File3dm.Read(str(tmp_path / "out" / "rulings.3dm"))
    lines = window.doc.results["helicoid"].outputs["Rulings"].all_items()
    objects = list(model.Objects)
    assert len(objects) == len(lines) == 49
    assert model.Settings.ModelUnitSystem == rh.UnitSystem.Meters
    t = np.linspace(0.0, 1.0, 50)
    expected = np.array([line.point_at(t) for line in lines])
    found = np.array([rhino_points(obj.Geometry, t) for obj in objects])
    size = float(np.ptp(expected.reshape(-1, 3), axis=0).max())
    assert np.abs(found - expected).max() <= 1e-9 * size
    assert str(tmp_path / "out" / "rulings.3dm") in window.status.currentMessage()


def test_export_of_a_surface_from_the_node_menu_matches_it_within_1e_9(qtbot, window, tmp_path, monkeypatch):
    open_example(qtbot, window, "textbook-ruled-surfaces.graph", tmp_path)
    save_as(monkeypatch, tmp_path / "mobius.3dm")
    item = window.scene.nodes["mobius"]
    window.view.centerOn(item)
    title = view_point(window, item.mapToScene(QPointF(item.size()[0] / 2, 8)))
    right_click_menu(window, title, ("Export output", "Surface…"))
    (obj,) = list(rh.File3dm.Read(str(tmp_path / "mobius.3dm")).Objects)
    surface = window.doc.results["mobius"].outputs["Surface"].first()
    rng = np.random.default_rng(11)
    u, v = rng.random(400), rng.random(400)
    expected = surface.point_at(u, v)
    size = float(np.ptp(expected, axis=0).max())
    assert np.abs(rhino_surface_points(obj.Geometry, u, v) - expected).max() <= 1e-9 * size


def test_export_of_numbers_offers_csv_and_writes_one_row_per_item(qtbot, window, tmp_path, monkeypatch):
    open_example(qtbot, window, "first-steps.graph", tmp_path)
    dialog = save_as(monkeypatch, tmp_path / "heights")  # typed without an extension
    export_from_port(window, "heights", "Result")
    start, _, selected = dialog.offered[0]
    assert start == str(tmp_path / "Panel heights-Result.csv")
    assert selected == "CSV table (*.csv)"
    heights = window.doc.results["heights"].outputs["Result"].all_items()
    with (tmp_path / "heights.csv").open(encoding="utf-8") as stream:
        rows = list(csv.reader(stream))
    assert rows[0] == ["path", "index", "value"]
    assert len(rows) - 1 == len(heights) == 12  # Count is 12
    assert [float(row[2]) for row in rows[1:]] == pytest.approx(heights, abs=1e-12)


def test_export_before_the_graph_is_solved_warns_and_writes_nothing(
    qtbot, window, tmp_path, monkeypatch, dialogs
):
    window.doc.solves.auto = False
    assert window.open_file(copy_fixture(EXAMPLES / "first-steps.graph", tmp_path), ask=False)
    dialog = save_as(monkeypatch, tmp_path / "x.csv")
    assert window.export_output("heights", "Result") == []
    assert dialogs.calls[-1][:2] == ("warning", "Cannot export")
    assert "has not been solved yet" in dialogs.calls[-1][2]
    assert dialog.offered == [] and not (tmp_path / "x.csv").exists()


def test_export_of_numbers_to_3dm_warns_with_the_reason(qtbot, window, tmp_path, monkeypatch, dialogs):
    open_example(qtbot, window, "first-steps.graph", tmp_path)
    save_as(monkeypatch, tmp_path / "numbers.3dm")
    export_from_port(window, "heights", "Result")
    kind, title, text = dialogs.calls[-1]
    assert (kind, title) == ("warning", "Cannot export")
    assert "cannot export Number to .3dm" in text
    assert not (tmp_path / "numbers.3dm").exists()


def test_export_to_a_path_that_cannot_be_written_warns(qtbot, window, tmp_path, monkeypatch, dialogs):
    open_example(qtbot, window, "first-steps.graph", tmp_path)
    (tmp_path / "blocker").write_text("a file where a folder should be")
    save_as(monkeypatch, tmp_path / "blocker" / "heights.csv")
    assert window.export_output("heights", "Result") == []
    kind, title, text = dialogs.calls[-1]
    assert (kind, title) == ("warning", "Cannot export")
    assert "Cannot create the folder" in text


# -- Bake ----------------------------------------------------------------------------
def test_bake_writes_one_layer_per_previewed_node_with_geometry(qtbot, window, tmp_path, monkeypatch):
    open_example(qtbot, window, "textbook-ruled-surfaces.graph", tmp_path)
    window.editor.set_preview(["torus", "torus_analysis", "hypar_analysis"], False)
    window.editor.set_enabled(["mobius"], False)
    wait_solved(qtbot, window)
    dialog = save_as(monkeypatch, tmp_path / "bake.3dm")
    assert window.actions_by_name["bake"].shortcut() == QKeySequence("Ctrl+B")
    window.actions_by_name["bake"].trigger()
    assert dialog.offered[0][0] == str(tmp_path / "textbook-ruled-surfaces-bake.3dm")
    model = rh.File3dm.Read(str(tmp_path / "bake.3dm"))
    assert model.Settings.ModelUnitSystem == rh.UnitSystem.Meters
    layers = {layer.Index: layer.FullPath for layer in model.Layers}
    counts: dict[str, int] = {}
    for obj in model.Objects:
        counts[layers[obj.Attributes.LayerIndex]] = counts.get(layers[obj.Attributes.LayerIndex], 0) + 1
    top = "textbook-ruled-surfaces"
    assert counts == {  # surfaces with their rulings; nothing whose preview is off, no Möbius, no torus
        f"{top}::Cylinder": 50,
        f"{top}::Helicoid": 50,
        f"{top}::Hyperbolic paraboloid z = xy": 1,
    }
    cylinder = next(o for o in model.Objects if o.Attributes.Name == "Surface 1"
                    and o.Attributes.GetUserString("TorsalNode") == "cylinder")
    surface = window.doc.results["cylinder"].outputs["Surface"].first()
    u, v = np.random.default_rng(5).random((2, 300))
    expected = surface.point_at(u, v)
    size = float(np.ptp(expected, axis=0).max())
    assert np.abs(rhino_surface_points(cylinder.Geometry, u, v) - expected).max() <= 1e-9 * size
    assert "Baked 101 objects from 3 nodes" in window.status.currentMessage()


def test_bake_with_no_previewed_geometry_says_so_and_asks_for_no_file(
    qtbot, window, tmp_path, monkeypatch, dialogs
):
    open_example(qtbot, window, "first-steps.graph", tmp_path)
    dialog = save_as(monkeypatch, tmp_path / "bake.3dm")
    window.actions_by_name["bake"].trigger()
    kind, title, text = dialogs.calls[-1]
    assert (kind, title) == ("warning", "Cannot bake")
    assert text.startswith("Nothing to bake: none of the 6 previewed nodes has geometry")  # panels are not
    assert dialog.offered == [] and not (tmp_path / "bake.3dm").exists()


# -- groups ---------------------------------------------------------------------------
def right_click(window, point: QPoint, moves: tuple[QPoint, ...] = ()) -> None:
    viewport = window.view.viewport()
    QTest.mousePress(viewport, Qt.MouseButton.RightButton, Qt.KeyboardModifier.NoModifier, point)
    for move in moves:
        QTest.mouseMove(viewport, move)
    end = moves[-1] if moves else point
    QTest.mouseRelease(viewport, Qt.MouseButton.RightButton, Qt.KeyboardModifier.NoModifier, end)


@pytest.fixture
def menus(monkeypatch):
    """Menus opened by the canvas are recorded (and not shown); ``choose`` picks an entry."""
    opened: list[list[str]] = []
    choose: list[str] = []

    def show(view, menu, global_pos):
        opened.append([a.text() for a in menu.actions()])
        if choose:
            trigger(menu, choose.pop(0))

    monkeypatch.setattr(CanvasView, "show_menu", show)
    return opened, choose


def group_title_point(window, group_id: str) -> QPoint:
    title_bar = window.scene.groups[group_id].title_rect().center()
    window.view.centerOn(title_bar)
    return view_point(window, title_bar)


def test_group_colour_from_its_menu_is_saved_and_undone(qtbot, window, tmp_path, monkeypatch, menus):
    open_example(qtbot, window, "first-steps.graph", tmp_path)
    opened, choose = menus
    monkeypatch.setattr(QColorDialog, "getColor", staticmethod(lambda *a, **k: QColor("#ff8800")))
    choose.append("Colour…")
    right_click(window, group_title_point(window, "inputs"))
    assert opened == [["Rename…", "Colour…", "", "Ungroup"]]
    group = next(g for g in window.doc.graph.groups if g.id == "inputs")
    assert group.colour == "#ff8800"
    assert window.scene.groups["inputs"].colour == QColor("#ff8800")
    assert window.save()
    saved = json.loads(window.doc.path.read_text(encoding="utf-8"))
    assert next(g for g in saved["groups"] if g["id"] == "inputs")["colour"] == "#ff8800"
    window.doc.undo_stack.undo()
    assert group.colour == "#e8e0f4"
    assert window.scene.groups["inputs"].colour == QColor("#e8e0f4")


def test_group_menu_renames_and_ungroups(qtbot, window, tmp_path, monkeypatch, menus):
    from PySide6.QtWidgets import QInputDialog

    open_example(qtbot, window, "first-steps.graph", tmp_path)
    _, choose = menus
    monkeypatch.setattr(QInputDialog, "getText", staticmethod(lambda *a, **k: ("Sliders", True)))
    choose.append("Rename…")
    right_click(window, group_title_point(window, "inputs"))
    assert next(g for g in window.doc.graph.groups if g.id == "inputs").title == "Sliders"
    choose.append("Ungroup")
    right_click(window, group_title_point(window, "inputs"))
    assert [g.id for g in window.doc.graph.groups] == ["layout"]
    window.doc.undo_stack.undo()
    assert [g.id for g in window.doc.graph.groups] == ["inputs", "layout"]


def test_right_drag_over_a_group_still_pans_and_opens_no_menu(qtbot, window, tmp_path, menus):
    open_example(qtbot, window, "first-steps.graph", tmp_path)
    opened, _ = menus
    start = group_title_point(window, "inputs")
    before = window.view.mapToScene(start)
    right_click(window, start, tuple(start + QPoint(dx, 0) for dx in range(10, 81, 10)))
    after = window.view.mapToScene(start)
    assert opened == []
    assert after.x() == pytest.approx(before.x() - 80 / window.view.zoom(), abs=2)


def test_a_nodes_own_bake_writes_that_node_only_even_with_its_preview_off(
    qtbot, window, tmp_path, monkeypatch
):
    open_example(qtbot, window, "textbook-ruled-surfaces.graph", tmp_path)
    window.editor.set_preview(["cylinder"], False)  # Grasshopper bakes a component whatever its preview
    wait_solved(qtbot, window)
    dialog = save_as(monkeypatch, tmp_path / "cylinder.3dm")
    window.view.centerOn(window.scene.nodes["cylinder"])
    catcher = right_click_menu(window, title_point(window, "cylinder"), "Bake…")
    assert "Bake…" in catcher.menus[0]
    assert dialog.offered[0][0] == str(tmp_path / "textbook-ruled-surfaces-cylinder-bake.3dm")
    model = rh.File3dm.Read(str(tmp_path / "cylinder.3dm"))
    layers = {layer.Index: layer.FullPath for layer in model.Layers}
    assert {layers[o.Attributes.LayerIndex] for o in model.Objects} == {"textbook-ruled-surfaces::Cylinder"}
    assert len(model.Objects) == 50  # the surface and its 49 rulings
    assert "Baked 50 objects from 1 node " in window.status.currentMessage()
