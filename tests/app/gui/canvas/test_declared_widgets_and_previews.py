"""The GUI knows a node only by what it declares: its widget hint, its port bounds, and
geometry that offers plain arrays through the preview protocol — never its type id."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from PySide6.QtCore import QPointF

from tests.support.fixtures_gui import close_window, drag, make_window, view_point, wait_solved
from tests.support.showcase_nodes import showcase_registry
from torsal.app.gui.canvas.inline_widgets import SliderWidget
from torsal.app.gui.canvas.slider_dialog import SliderDialog, WiredBounds
from torsal.app.gui.viewport.datasets import collect, pieces
from torsal.engine.node import In, Node, Out, Setting
from torsal.engine.types import GENERIC, INTEGER, NUMBER
from torsal.engine.widgets import Widget
from torsal.nodes.common.preview import PreviewGeometry

ROOT = Path(__file__).resolve().parents[4]
GUI = ROOT / "torsal" / "app" / "gui"
#: The palette and the search are the GUI's catalogue of node types: they may name them.
CATALOGUE = {GUI / "palette.py", GUI / "search_popup.py", GUI / "fuzzy.py"}
TYPE_STRING = re.compile(r"""["'](?:[a-z]+)\.[A-Z][A-Za-z0-9]*["']""")


class PluginDial(Node):
    """A plug-in's whole-number dial: asks for a slider by its hint alone."""

    type_id = "plugin.Dial"
    widget = Widget.SLIDER
    outputs = (Out("Value", INTEGER, "V", "The dial's number."),)
    settings_spec = (Setting("value", int, 2, "Value."), Setting("min", int, 0, "Min."),
                     Setting("max", int, 10, "Max."))

    def solve(self) -> int:
        return int(self.settings["value"])


class PluginStrips(Node):
    """A plug-in node whose input declares bounds."""

    type_id = "plugin.Strips"
    inputs = (In("Count", INTEGER, "N", "Strips.", default=3, min=2, max=40),)
    outputs = (Out("Twice", NUMBER, "T", "2 × Count."),)

    def solve(self, count: int) -> float:
        return 2.0 * count


class Helix:
    """A geometry type the viewport has never heard of, drawing through the protocol."""

    def preview_geometry(self) -> PreviewGeometry:
        t = np.linspace(0.0, 4.0 * np.pi, 50)
        return PreviewGeometry(polylines=[np.column_stack([np.cos(t), np.sin(t), t / 10.0])],
                               points=[np.zeros((1, 3))])


class HelixSource(Node):
    type_id = "plugin.HelixSource"
    outputs = (Out("Helix", GENERIC, "H", "A helix."),)

    def solve(self) -> Helix:
        return Helix()


def offending_lines(text: str) -> list[str]:
    lines = text.splitlines()
    return [line for line in lines if TYPE_STRING.search(line) and not line.lstrip().startswith("#")]


def test_no_gui_module_outside_the_palette_and_search_names_a_node_type():
    found = {
        str(path.relative_to(ROOT)): offending_lines(path.read_text())
        for path in GUI.rglob("*.py")
        if path not in CATALOGUE
    }
    assert {path: lines for path, lines in found.items() if lines} == {}


def test_the_type_string_check_fails_on_a_switch_on_a_type_id():
    assert offending_lines('    if type_id == "params.NumberSlider":') != []
    assert offending_lines('    if record.type_id == "maths.Expression":') != []
    assert offending_lines("    if node.widget is Widget.SLIDER:") == []


def test_the_viewport_and_canvas_do_not_sniff_attributes_or_class_names():
    for folder in ("viewport", "canvas"):
        for path in (GUI / folder).glob("*.py"):
            text = path.read_text()
            assert "hasattr(" not in text and "__name__ ==" not in text, path


@pytest.fixture
def plugin_window(qtbot, config_folder):
    registry = showcase_registry()
    for cls in (PluginDial, PluginStrips, HelixSource):
        registry.register(cls)
    window = make_window(qtbot, registry, config_folder)
    wait_solved(qtbot, window)
    yield window
    close_window(window)


def test_a_plug_in_node_that_declares_a_slider_gets_one_and_a_drag_sets_it(qtbot, plugin_window):
    window = plugin_window
    node_id = window.editor.add_node("plugin.Dial", (0.0, 0.0))
    wait_solved(qtbot, window)
    item = window.scene.nodes[node_id]
    assert isinstance(item.widget, SliderWidget) and item.widget.integer  # an Integer output: whole numbers
    window.view.centerOn(item)
    qtbot.wait(20)
    rect = item.layout.widget_rect
    handle = QPointF(item.widget.handle_x(rect), rect.center().y())
    track = item.widget.track(rect)
    end = QPointF(track.right(), rect.center().y())
    drag(window, view_point(window, item.mapToScene(handle)), view_point(window, item.mapToScene(end)))
    wait_solved(qtbot, window)
    assert window.doc.graph.nodes[node_id].node.settings["value"] == 10
    assert window.doc.results[node_id].outputs["Value"].all_items() == [10]


def test_the_slider_dialog_keeps_a_slider_within_the_bounds_of_the_input_it_feeds(qtbot, plugin_window):
    window = plugin_window
    slider = window.editor.add_node("plugin.Dial", (0.0, 0.0))
    strips = window.editor.add_node("plugin.Strips", (300.0, 0.0))
    window.editor.connect(slider, "Value", strips, "Count")
    wait_solved(qtbot, window)
    bounds = WiredBounds(window.doc.graph, slider)
    assert (bounds.low, bounds.high) == (2, 40)
    dialog = SliderDialog("Dial", {"value": 2, "min": 0, "max": 100}, True, bounds=bounds)
    qtbot.addWidget(dialog)
    assert (dialog.minimum.minimum(), dialog.maximum.maximum()) == (2.0, 40.0)
    assert dialog.values() == {"value": 2, "min": 2, "max": 40}  # clamped into what Count takes
    assert dialog.takes is not None and dialog.takes.text().endswith("Count: 2 to 40")


def test_the_inspector_shows_an_inputs_declared_bounds(qtbot, plugin_window):
    window = plugin_window
    node_id = window.editor.add_node("plugin.Strips", (0.0, 0.0))
    wait_solved(qtbot, window)
    window.inspector.show_node(node_id)
    row = window.inspector.ports.topLevelItem(0)
    assert row.text(0) == "▸ Count" and row.text(1) == "Integer, 2 to 40"


def test_a_new_geometry_type_draws_by_implementing_the_preview_protocol():
    kinds = {piece.kind: piece for piece in pieces(collect([Helix()]))}
    assert set(kinds) == {"curves", "points"}
    assert kinds["curves"].points.shape == (50, 3)
    np.testing.assert_allclose(kinds["curves"].points[-1], [1.0, 0.0, 0.4 * np.pi], atol=1e-12)
