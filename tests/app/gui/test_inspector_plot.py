"""The inspector shows the image a plot node drew (display.Plot here), on a Plot tab."""

from __future__ import annotations

import json

from PySide6.QtCore import QPointF, QSize, Qt
from PySide6.QtGui import QImage
from PySide6.QtTest import QTest

from tests.support.fixtures_gui import view_point, wait_solved
from torsal.app.gui.plot_view import MIN_CHART
from torsal.engine.graph import Graph
from torsal.engine.graphfile import write_graph
from torsal.engine.types import encode_value
from torsal.nodes.common.charts import read_recipe
from torsal.nodes.display.plot import Plot
from torsal.nodes.params.panel import Panel


def plot_graph(folder):
    graph = Graph()
    graph.add_node(Plot(), "plot", position=(0.0, 0.0))
    graph.set_input_value("plot", "Values", encode_value([0.0, 1.5, 3.0, 2.0, 4.5, 1.0]))
    graph.set_input_value("plot", "Title", encode_value("Warp angle per panel"))
    # no File: the image goes to the temporary folder (a File would ask to write first)
    graph.add_node(Panel(), "note", position=(0.0, 300.0))
    path = folder / "plot.graph"
    write_graph(graph, path)
    return path


def click_node(window, node_id):
    item = window.scene.nodes[node_id]
    point = view_point(window, item.mapToScene(QPointF(item.size()[0] / 2, 10)))
    QTest.mouseClick(window.view.viewport(), Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, point)


def fitted(area):
    """The size the Plot tab draws a chart at: its room, within the least readable size."""
    room = area.viewport().size()
    width = max(MIN_CHART.width(), room.width() - 2)
    return QSize(width, min(width, max(MIN_CHART.height(), room.height() - 2)))


def test_clicking_a_plot_node_shows_its_image_in_the_inspector(qtbot, window, tmp_path):
    assert window.open_file(plot_graph(tmp_path), ask=False)
    wait_solved(qtbot, window)
    qtbot.wait(50)
    click_node(window, "plot")
    inspector = window.inspector
    qtbot.waitUntil(lambda: inspector.node_id == "plot", timeout=3000)
    assert inspector.tabs.tabText(inspector.tabs.currentIndex()) == "Plot"
    (image,) = window.doc.result("plot").output("Image").all_items()
    drawn = QImage(image)
    area = inspector.plot_area
    qtbot.waitUntil(lambda: area.shown_size() == fitted(area), timeout=3000)
    shown = area.shown_size()
    assert not drawn.isNull() and (drawn.width(), drawn.height()) == (640, 400)  # the file, as headless
    # the chart is drawn at the tab's size: as wide as the tab, as tall as it (within the
    # least readable size and no taller than wide), so the whole chart shows
    room = area.viewport().size()
    assert shown.width() == room.width() - 2 and shown.height() <= room.height()
    # a click shows the file 1:1, pixel for pixel; another draws it to fit again
    QTest.mouseClick(inspector.plot, Qt.MouseButton.LeftButton)
    one_to_one = inspector.plot.pixmap()
    assert (one_to_one.width(), one_to_one.height()) == (drawn.width(), drawn.height())
    assert one_to_one.toImage().convertToFormat(drawn.format()) == drawn
    QTest.mouseClick(inspector.plot, Qt.MouseButton.LeftButton)
    assert area.shown_size() == shown


def test_the_chart_is_drawn_again_at_the_new_size_when_the_dock_is_resized(qtbot, window, tmp_path):
    assert window.open_file(plot_graph(tmp_path), ask=False)
    wait_solved(qtbot, window)
    qtbot.wait(50)
    click_node(window, "plot")
    area = window.inspector.plot_area
    qtbot.waitUntil(lambda: area.shown_size() == fitted(area), timeout=3000)
    before = area.shown_size()
    window.resizeDocks([window.inspector_dock], [before.width() - 200], Qt.Orientation.Horizontal)
    qtbot.waitUntil(lambda: area.viewport().width() - 2 < before.width(), timeout=3000)
    qtbot.waitUntil(lambda: area.shown_size() == fitted(area), timeout=3000)
    assert area.shown_size().width() < before.width()


def test_a_recipe_that_is_not_well_formed_is_refused():
    good = {"kind": "line", "y": [1.0, 2.0], "title": "t"}
    assert read_recipe(json.dumps(good)) == good
    for bad in ({"kind": "eval", "y": [1.0]}, {**good, "y": "1,2"}, {**good, "extra": 1},
                {"kind": "warp", "x": [1.0], "warp": [1.0, 2.0], "tolerance": 0.1, "title": "",
                 "along": True}):
        assert read_recipe(json.dumps(bad)) is None
    assert read_recipe("not json {") is None


def test_a_node_without_an_image_has_no_plot_tab(qtbot, window, tmp_path):
    assert window.open_file(plot_graph(tmp_path), ask=False)
    wait_solved(qtbot, window)
    qtbot.wait(50)
    click_node(window, "plot")
    qtbot.waitUntil(lambda: window.inspector.node_id == "plot", timeout=3000)
    click_node(window, "note")
    qtbot.waitUntil(lambda: window.inspector.node_id == "note", timeout=3000)
    tabs = window.inspector.tabs
    assert "Plot" not in [tabs.tabText(i) for i in range(tabs.count())]
