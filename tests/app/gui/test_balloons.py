"""A node's messages show on the node (a balloon holding their count; hover for the text),
and the Messages dock groups them by node, warnings and errors first, remarks on request."""

from __future__ import annotations

from PySide6.QtCore import QPointF, Qt
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication, QToolTip

from tests.support.fixtures_gui import EXAMPLES, view_point, wait_solved


def test_messages_dock_groups_by_node_and_hides_remarks_until_asked(qtbot, window):
    assert window.open_file(EXAMPLES / "kaohsiung-stadium.graph", ask=False)
    wait_solved(qtbot, window)
    window._fill_tables()
    log = window.log
    rows = log.node_rows
    remarks = [r for r in rows if r[0] == "remark"]
    assert remarks, "the flagship's strips remark on their closing triangles"
    node_items = [log.topLevelItem(i) for i in range(log.topLevelItemCount())
                  if log.topLevelItem(i).data(0, Qt.ItemDataRole.UserRole)]
    shown_nodes = [item.data(0, Qt.ItemDataRole.UserRole) for item in node_items]
    assert len(shown_nodes) == len(set(shown_nodes))  # one row per node
    assert all(item.text(0) != "remark" for item in node_items)
    assert log.hidden_remarks == len(remarks)
    log.set_show_remarks(True)
    every = []
    for i in range(log.topLevelItemCount()):
        item = log.topLevelItem(i)
        if item.data(0, Qt.ItemDataRole.UserRole):
            children = [item.child(k) for k in range(item.childCount())] or [item]
            node_id = item.data(0, Qt.ItemDataRole.UserRole)
            every += [(child.text(0), node_id, child.text(2)) for child in children]
    assert sorted(every) == sorted((level, node, text) for level, node, _title, text in rows)
    assert log.hidden_remarks == 0


def test_a_node_with_messages_draws_a_balloon_with_their_count_and_hovering_shows_them(qtbot, window):
    node_id = window.editor.add_node("params.NumberSlider", (0.0, 0.0), {"min": 5.0, "max": 1.0})
    wait_solved(qtbot, window)
    item = window.scene.nodes[node_id]
    messages = window.doc.results[node_id].messages
    assert messages and item.drawn_state()[1].endswith(str(len(messages)))
    window.view.centerOn(item)
    balloon = view_point(window, item.mapToScene(QPointF(item.size()[0] - 10, 9)))
    QTest.mouseMove(window.view.viewport(), balloon)
    qtbot.waitUntil(lambda: QToolTip.isVisible() or bool(item.toolTip()), timeout=3000)
    QApplication.processEvents()
    assert messages[0].text.split(" ")[0] in item.toolTip()
