"""Wires bend around the nodes they do not connect to, and follow when nodes move."""

from __future__ import annotations

from PySide6.QtCore import QPointF, QRectF, Qt
from PySide6.QtTest import QTest

from tests.support.fixtures_gui import drag, view_point, wait_solved
from torsal.app.gui.canvas.wire_routing import NodeGrid, route
from torsal.engine.graph import Graph


def points_on(path, count: int = 400) -> list[QPointF]:
    return [path.pointAtPercent(k / count) for k in range(count + 1)]


def crosses(path, rect: QRectF) -> bool:
    return any(rect.contains(p) for p in points_on(path))


def test_a_wire_with_a_node_in_its_way_goes_round_it():
    grid = NodeGrid()
    obstacle = QRectF(180, -30, 100, 60)  # straddles the straight line from (0, 0) to (460, 0)
    grid.set("other", obstacle)
    path = route(QPointF(0, 0), QPointF(460, 0), grid, ("a", "b"))
    assert not crosses(path, obstacle)
    assert path.pointAtPercent(0) == QPointF(0, 0) and path.pointAtPercent(1) == QPointF(460, 0)


def test_a_wire_goes_round_the_nodes_it_connects_to_only_if_they_are_other_nodes():
    grid = NodeGrid()
    grid.set("b", QRectF(180, -30, 100, 60))  # the wire's own target, wherever it is drawn
    path = route(QPointF(0, 0), QPointF(460, 0), grid, ("a", "b"))
    assert path.elementCount() == 4  # one plain cubic: a move-to and three cubic points


def test_a_wire_with_nothing_in_its_way_is_the_plain_curve():
    grid = NodeGrid()
    grid.set("far", QRectF(180, 200, 100, 60))
    path = route(QPointF(0, 0), QPointF(460, 0), grid, ("a", "b"))
    assert path.elementCount() == 4


def test_a_detour_takes_in_a_second_node_its_first_try_would_hit():
    grid = NodeGrid()
    first, second = QRectF(150, -20, 100, 50), QRectF(260, -90, 100, 60)  # second above the first
    grid.set("first", first)
    grid.set("second", second)
    path = route(QPointF(0, 0), QPointF(600, 0), grid)
    assert not crosses(path, first) and not crosses(path, second)


def test_the_grid_forgets_a_node_removed_and_follows_one_moved():
    grid = NodeGrid()
    grid.set("n", QRectF(0, 0, 100, 50))
    grid.set("n", QRectF(1000, 1000, 100, 50))
    assert grid.overlapping((0, 0, 100, 50)) == {}
    assert list(grid.overlapping((990, 990, 1010, 1010))) == ["n"]
    grid.remove("n")
    assert grid.overlapping((990, 990, 1010, 1010)) == {}


def crossing_graph(registry) -> Graph:
    """A slider wired to an Expression far to its right, and an unrelated slider between."""
    graph = Graph()
    graph.add_node(registry.create("params.NumberSlider"), "source", position=(0.0, 0.0))
    graph.add_node(registry.create("maths.Expression"), "target", position=(600.0, 0.0))
    graph.add_node(registry.create("params.NumberSlider"), "between", position=(300.0, 0.0))
    graph.connect("source", "Value", "target", "x")
    return graph


def test_on_the_canvas_a_wire_bends_round_an_unrelated_node_and_straightens_when_it_moves(
    qtbot, window, registry
):
    window.doc.replace(crossing_graph(registry), None)
    wait_solved(qtbot, window)
    scene = window.scene
    (wire,) = scene.wires.values()
    between = scene.nodes["between"]
    assert between.sceneBoundingRect().contains(
        QPointF(between.sceneBoundingRect().center().x(), wire.source_port.anchor().y())
    ), "the scene is meant to put the node in the straight wire's way"
    assert not crosses(wire.path(), between.sceneBoundingRect())
    # drag the unrelated node well away (a real mouse drag on its title): the wire goes straight
    title = between.mapToScene(QPointF(20, 8))
    drag(window, view_point(window, title), view_point(window, title + QPointF(0, 400)))
    qtbot.waitUntil(lambda: wire.path().elementCount() == 4, timeout=3000)
    # undo puts it back in the way: the wire bends again
    window.doc.undo_stack.undo()
    qtbot.waitUntil(lambda: wire.path().elementCount() > 4, timeout=3000)
    assert not crosses(wire.path(), scene.nodes["between"].sceneBoundingRect())


def test_deleting_the_node_a_wire_went_round_makes_it_the_plain_curve_again(qtbot, window, registry):
    window.doc.replace(crossing_graph(registry), None)
    wait_solved(qtbot, window)
    (wire,) = window.scene.wires.values()
    assert wire.path().elementCount() > 4
    title = window.scene.nodes["between"].mapToScene(QPointF(20, 8))
    QTest.mouseClick(window.view.viewport(), Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier,
                     view_point(window, title))
    QTest.keyClick(window.view.viewport(), Qt.Key.Key_Delete)
    assert "between" not in window.doc.graph.nodes
    qtbot.waitUntil(lambda: wire.path().elementCount() == 4, timeout=3000)
