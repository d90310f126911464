"""The inspector shows the image a plot node drew (display.Plot here), on a Plot tab."""

from __future__ import annotations

from PySide6.QtCore import QPointF, Qt
from PySide6.QtGui import QImage
from PySide6.QtTest import QTest

from tests.support.fixtures_gui import view_point, wait_solved
from torsal.engine.graph import Graph
from torsal.engine.graphfile import write_graph
from torsal.engine.types import encode_value
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
    qtbot.waitUntil(lambda: not area.shown_size().isEmpty(), timeout=3000)
    shown = inspector.plot.pixmap()
    assert not shown.isNull() and not drawn.isNull()
    # the whole chart shows: scaled to the tab's width, its aspect kept
    room = area.viewport().width()
    assert shown.width() <= room and shown.width() == min(room - 2, drawn.width())
    assert abs(shown.height() / shown.width() - drawn.height() / drawn.width()) < 0.01
    # a click shows it 1:1, pixel for pixel; another fits it again
    QTest.mouseClick(inspector.plot, Qt.MouseButton.LeftButton)
    one_to_one = inspector.plot.pixmap()
    assert (one_to_one.width(), one_to_one.height()) == (drawn.width(), drawn.height())
    assert one_to_one.toImage().convertToFormat(drawn.format()) == drawn
    QTest.mouseClick(inspector.plot, Qt.MouseButton.LeftButton)
    assert inspector.plot.pixmap().width() == shown.width()


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
