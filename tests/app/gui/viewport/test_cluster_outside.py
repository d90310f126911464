"""While a cluster is edited, the model outside stays in the viewport, dimmed; going back
out removes the dimmed copy. Driven by real events: a click selects, Ctrl+Alt+G clusters,
a double-click opens the cluster, a click on the breadcrumb goes back out."""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtTest import QTest

from tests.support.fixtures_gui import EXAMPLES, double_click, title_point, wait_solved
from torsal.app.gui.viewport.outside import COLOUR, outside_names
from torsal.engine.cluster import is_cluster


def test_inside_a_cluster_the_outside_model_is_drawn_dimmed(qtbot, window):
    assert window.open_file(EXAMPLES / "paper-strip.graph", ask=False)
    wait_solved(qtbot, window)
    window.view.centerOn(window.scene.nodes["unroll"])
    QTest.mouseClick(window.view.viewport(), Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier,
                     title_point(window, "unroll"))
    assert window.scene.selected_node_ids() == ["unroll"]
    QTest.keyClick(window.view.viewport(), Qt.Key.Key_G,
                   Qt.KeyboardModifier.ControlModifier | Qt.KeyboardModifier.AltModifier)
    (cluster_id,) = [n for n, r in window.doc.graph.nodes.items() if is_cluster(r.node)]
    wait_solved(qtbot, window)
    plotter = window.viewport.plotter
    assert outside_names(plotter) == []
    window.view.centerOn(window.scene.nodes[cluster_id])
    double_click(window, title_point(window, cluster_id))
    qtbot.waitUntil(lambda: len(window.doc.frames) == 1, timeout=3000)
    wait_solved(qtbot, window)
    names = outside_names(plotter)
    assert any(n.startswith("outside:strip:") for n in names), names  # the bent strip, outside
    assert not any(n.startswith(f"outside:{cluster_id}:") for n in names)  # the cluster's own: inside
    actor = plotter.actors[names[0]]
    assert actor.prop.opacity < 0.5 and actor.prop.color.hex_rgb == COLOUR
    QTest.mouseClick(window.breadcrumb.crumbs[0], Qt.MouseButton.LeftButton)
    qtbot.waitUntil(lambda: not window.doc.frames, timeout=3000)
    assert outside_names(plotter) == []
    wait_solved(qtbot, window)
