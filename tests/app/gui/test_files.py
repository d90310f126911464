"""Files: refused files leave the document untouched; dirty marker, close prompt, drops, recents."""

from __future__ import annotations

import json

import pytest
from PySide6.QtCore import QMimeData, QPointF, Qt, QUrl
from PySide6.QtGui import QDragEnterEvent, QDropEvent
from PySide6.QtWidgets import QMessageBox

from tests.support.fixtures_gui import EXAMPLES, copy_fixture, wait_solved
from torsal.engine.graphfile import dumps


@pytest.fixture
def opened(qtbot, window, tmp_path):
    path = copy_fixture(EXAMPLES / "first-steps.graph", tmp_path)
    assert window.open_file(path, ask=False)
    wait_solved(qtbot, window)
    window.editor.move({"width": (60.0, 40.0)})  # unsaved work that must survive
    return window, path


def corrupt(tmp_path):
    path = tmp_path / "corrupt.graph"
    path.write_text('{"format": "torsal.graph", "version": 1, "nodes": [ {"id": ', encoding="utf-8")
    return path, "not valid JSON"


def newer(tmp_path):
    path = tmp_path / "future.graph"
    path.write_text(json.dumps({"format": "torsal.graph", "version": 99, "nodes": []}), encoding="utf-8")
    return path, "newer Torsal"


@pytest.mark.parametrize("make_file", [corrupt, newer], ids=["corrupt", "newer-version"])
def test_a_file_that_cannot_be_opened_gives_the_reason_and_leaves_the_document_untouched(
    opened, dialogs, tmp_path, make_file
):
    window, path = opened
    graph, before = window.doc.graph, dumps(window.doc.graph)
    depth = window.doc.undo_stack.count()
    bad, reason = make_file(tmp_path)
    content = bad.read_bytes()
    assert not window.open_file(bad, ask=False)
    kind, _title, text = dialogs.calls[-1]
    assert kind == "critical" and bad.name in text and reason in text
    assert window.doc.graph is graph and dumps(graph) == before
    assert window.doc.path == path.resolve() and window.doc.dirty
    assert window.doc.undo_stack.count() == depth
    assert bad.read_bytes() == content


def test_saving_over_a_newer_version_file_is_refused_with_a_dialog(opened, dialogs, tmp_path):
    window, _ = opened
    future, _reason = newer(tmp_path)
    content = future.read_bytes()
    assert not window.save_as(future)
    assert dialogs.calls[-1][0] == "critical" and "newer Torsal" in dialogs.calls[-1][2]
    assert future.read_bytes() == content and window.doc.dirty


def test_title_shows_the_dirty_marker_and_saving_clears_it(opened):
    window, path = opened
    assert window.isWindowModified() and window.windowTitle().startswith("first-steps.graph")
    assert window.save()
    assert not window.isWindowModified()
    assert path.with_name(path.name + ".bak").exists()  # the engine's atomic save keeps the old file


def test_closing_with_unsaved_work_asks_and_cancel_keeps_the_window(opened, dialogs):
    window, _ = opened
    dialogs.answer = QMessageBox.StandardButton.Cancel
    assert not window.close()
    assert window.isVisible() and dialogs.kinds()[-1] == "question"
    dialogs.answer = QMessageBox.StandardButton.Discard
    assert window.new_document()
    assert window.doc.graph.nodes == {} and not window.doc.dirty


def test_closing_with_save_writes_the_file(opened, dialogs):
    window, path = opened
    dialogs.answer = QMessageBox.StandardButton.Save
    assert window.close()
    assert json.loads(path.read_text())["nodes"][0]["position"] == [60.0, 40.0]


def test_dropping_a_graph_file_on_the_window_opens_it(qtbot, window, tmp_path):
    path = copy_fixture(EXAMPLES / "first-steps.graph", tmp_path)
    mime = QMimeData()
    mime.setUrls([QUrl.fromLocalFile(str(path))])
    point, action = QPointF(200, 200), Qt.DropAction.CopyAction
    buttons, keys = Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier
    enter = QDragEnterEvent(point, action, mime, buttons, keys)
    window.dragEnterEvent(enter)  # (QApplication does not route synthetic drops without a drag)
    assert enter.isAccepted()
    window.dropEvent(QDropEvent(point, action, mime, buttons, keys))
    qtbot.waitUntil(lambda: window.doc.path == path.resolve(), timeout=3000)
    assert "width" in window.doc.graph.nodes


def test_dragging_other_files_over_the_window_is_refused(window, tmp_path):
    mime = QMimeData()
    mime.setUrls([QUrl.fromLocalFile(str(tmp_path / "picture.png"))])
    enter = QDragEnterEvent(
        QPointF(10, 10),
        Qt.DropAction.CopyAction,
        mime,
        Qt.MouseButton.LeftButton,
        Qt.KeyboardModifier.NoModifier,
    )
    enter.setAccepted(False)
    window.dragEnterEvent(enter)
    assert not enter.isAccepted()


def test_opened_and_saved_files_are_remembered_as_recent(qtbot, window, tmp_path):
    first = copy_fixture(EXAMPLES / "first-steps.graph", tmp_path)
    assert window.open_file(first, ask=False)
    second = tmp_path / "copy.graph"
    assert window.save_as(second)
    assert window.settings.recent_files()[:2] == [second.resolve(), first.resolve()]
