"""A node pasted onto a wire it does not connect to: the wire re-routes round it, as it
does round a node moved onto it (driven as a person does: click, Ctrl+C, mouse, Ctrl+V)."""

from __future__ import annotations

from PySide6.QtCore import QPointF, QRectF, Qt
from PySide6.QtGui import QCursor
from PySide6.QtTest import QTest

from tests.support.fixtures_gui import view_point, wait_solved
from torsal.engine.graph import Graph

CTRL = Qt.KeyboardModifier.ControlModifier


def crosses(path, rect: QRectF, count: int = 400) -> bool:
    return any(rect.contains(path.pointAtPercent(k / count)) for k in range(count + 1))


def spare_and_wire(registry) -> Graph:
    """A slider wired to an Expression far to its right, and a spare slider well below."""
    graph = Graph()
    graph.add_node(registry.create("params.NumberSlider"), "source", position=(0.0, 0.0))
    graph.add_node(registry.create("maths.Expression"), "target", position=(700.0, 0.0))
    graph.add_node(registry.create("params.NumberSlider"), "spare", position=(300.0, 300.0))
    graph.connect("source", "Value", "target", "x")
    return graph


def test_a_wire_a_pasted_node_lands_on_goes_round_it(qtbot, window, registry):
    window.doc.replace(spare_and_wire(registry), None)
    wait_solved(qtbot, window)
    scene, viewport = window.scene, window.view.viewport()
    (wire,) = scene.wires.values()
    assert wire.path().elementCount() == 4, "nothing is meant to be in the wire's way yet"
    title = scene.nodes["spare"].mapToScene(QPointF(20, 8))
    QTest.mouseClick(viewport, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier,
                     view_point(window, title))
    QTest.keyClick(viewport, Qt.Key.Key_C, CTRL)
    # the mouse over the wire's middle, a little above it: the paste's top-left goes there
    middle = wire.path().pointAtPercent(0.5)
    QCursor.setPos(viewport.mapToGlobal(view_point(window, middle - QPointF(40, 20))))
    QTest.keyClick(viewport, Qt.Key.Key_V, CTRL)
    (pasted,) = set(window.doc.graph.nodes) - {"source", "target", "spare"}
    rect = scene.nodes[pasted].sceneBoundingRect()
    assert rect.contains(QPointF(middle.x(), middle.y())), "the scene is meant to paste onto the wire"
    qtbot.waitUntil(lambda: not crosses(wire.path(), rect), timeout=3000)
    assert wire.path().elementCount() > 4  # a detour, not the plain curve
