"""Opening a graph in the app writes no file until the user allows it, once per document.

The question is a real modal QMessageBox; the test answers it as a person does, with a
mouse click on its button (a timer finds the dialog while its event loop runs).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from PySide6.QtCore import Qt, QTimer
from PySide6.QtTest import QTest
from PySide6.QtWidgets import QApplication, QMessageBox

from tests.support.fixtures_gui import wait_solved
from torsal.engine.graph import Graph
from torsal.engine.graphfile import write_graph
from torsal.nodes.io.data import ExportCSV
from torsal.nodes.params.panel import Panel


def exporting_graph(folder: Path, target: str) -> Path:
    graph = Graph()
    graph.add_node(Panel({"text": "P-001\nP-002"}), "ids")
    graph.add_node(ExportCSV(), "csv")
    graph.connect("ids", "Output", "csv", "Data")
    graph.set_input_value("csv", "Path", target)
    graph.set_input_value("csv", "Write", True)
    path = folder / "exports.graph"
    write_graph(graph, path)
    return path


class Answerer:
    """Clicks ``button`` on the next question box that opens, and keeps what it said."""

    def __init__(self, button: str) -> None:
        self.button = button
        self.seen: list[str] = []
        self.timer = QTimer()
        self.timer.setInterval(20)
        self.timer.timeout.connect(self._poll)
        self.timer.start()

    def _poll(self) -> None:
        box = QApplication.activeModalWidget()
        if not isinstance(box, QMessageBox):
            return
        self.seen.append(f"{box.windowTitle()}\n{box.text()}\n{box.informativeText()}")
        (button,) = [b for b in box.buttons() if b.text() == self.button]
        QTest.mouseClick(button, Qt.MouseButton.LeftButton)

    def stop(self) -> None:
        self.timer.stop()


def open_and_answer(qtbot: Any, window: Any, path: Path, button: str) -> Answerer:
    answerer = Answerer(button)
    try:
        window.open_file(path, ask=False)
        wait_solved(qtbot, window)
        qtbot.wait(200)  # the question is asked on the turn after the results arrive
        wait_solved(qtbot, window)
    finally:
        answerer.stop()
    return answerer


def test_opening_a_graph_asks_before_writing_and_dont_write_writes_nothing(qtbot, window, tmp_path):
    path = exporting_graph(tmp_path, "out/ids.csv")
    answerer = open_and_answer(qtbot, window, path, "Don't Write")
    assert len(answerer.seen) == 1
    assert "out/ids.csv" in answerer.seen[0] and "exports.graph" in answerer.seen[0]
    assert not (tmp_path / "out").exists()
    result = window.doc.result("csv")
    assert result.state == "warning"
    assert "Nothing written to out/ids.csv" in result.messages[0].text
    window.doc.solves.request()  # another solve does not ask again
    wait_solved(qtbot, window)
    assert len(answerer.seen) == 1


def test_allow_writes_the_files_in_the_graphs_folder(qtbot, window, tmp_path):
    path = exporting_graph(tmp_path, "out/ids.csv")
    answerer = open_and_answer(qtbot, window, path, "Allow")
    assert len(answerer.seen) == 1
    assert (tmp_path / "out" / "ids.csv").read_text().count("P-00") == 2
    assert window.doc.result("csv").state == "ok"
    assert window.actions_by_name["allow_writes"].isChecked()


def test_a_graph_aiming_outside_its_folder_is_refused_without_a_question(
    qtbot, window, tmp_path, monkeypatch
):
    home = tmp_path / "home"
    home.mkdir()
    monkeypatch.setenv("HOME", str(home))
    project = tmp_path / "project"
    project.mkdir()
    path = exporting_graph(project, "~/.bashrc")
    answerer = open_and_answer(qtbot, window, path, "Allow")
    assert answerer.seen == []
    assert not (home / ".bashrc").exists()
    result = window.doc.result("csv")
    assert result.state == "error" and "starts with ~" in result.messages[0].text
