"""`torsal gui` with no file opens a blank, untitled document; File ▸ New starts afresh."""

from __future__ import annotations

import json

import torsal.app.gui.main
from tests.support.fixtures_gui import EXAMPLES, wait_solved
from torsal.app.cli import main


def test_torsal_gui_with_no_file_launches_on_no_file(monkeypatch):
    launched = []
    monkeypatch.setattr(torsal.app.gui.main, "launch",
                        lambda path=None, registry=None: launched.append(path) or 0)
    monkeypatch.setenv("DISPLAY", ":99")
    assert main(["gui"]) == 0
    assert launched == [None]


def test_a_window_started_on_no_file_is_untitled_and_its_canvas_empty(window):
    assert window.windowTitle().startswith("Untitled")
    assert window.scene.nodes == {} and window.scene.wires == {} and window.scene.groups == {}
    assert window.doc.path is None


def test_the_makefile_runs_the_app_on_the_flagship_explicitly():
    text = (EXAMPLES.parents[2] / "Makefile").read_text(encoding="utf-8")
    assert "EXAMPLE ?= torsal/resources/examples/kaohsiung-stadium.graph" in text
    assert "torsal gui $(EXAMPLE)" in text


def test_file_new_clears_the_message_log(qtbot, window):
    assert window.open_file(EXAMPLES / "first-steps.graph", ask=False)
    wait_solved(qtbot, window)
    assert window.log.topLevelItemCount() > 0  # "Opened …" at least
    window.doc.undo_stack.setClean()
    assert window.new_document()
    wait_solved(qtbot, window)
    texts = [window.log.topLevelItem(i).text(2) for i in range(window.log.topLevelItemCount())]
    assert not any("Opened" in t for t in texts)
    assert window.windowTitle().startswith("Untitled") and window.scene.nodes == {}


def test_app_messages_leave_the_node_column_empty(window):
    window.report("Saved somewhere")
    row = window.log.topLevelItem(0)
    assert (row.text(0), row.text(1), row.text(2)) == ("info", "", "Saved somewhere")


def test_an_opened_file_too_big_to_fit_shows_its_first_node_with_a_warning(qtbot, window, tmp_path):
    nodes = [{"id": f"s{i}", "type": "params.NumberSlider", "position": [300.0 * i, 0.0]} for i in range(12)]
    nodes.append({"id": "bad", "type": "curves.Circle", "position": [3300.0, 1800.0],
                  "inputs": {"Radius": {"value": -1.0}}})
    path = tmp_path / "wide.graph"
    path.write_text(json.dumps({"format": "torsal.graph", "version": 1, "nodes": nodes, "wires": []}))
    assert window.open_file(path, ask=False)
    wait_solved(qtbot, window)
    assert window.doc.results["bad"].state == "warning"  # a negative radius
    qtbot.wait(50)
    shown = window.view.mapToScene(window.view.viewport().rect()).boundingRect()
    assert shown.contains(window.scene.nodes["bad"].sceneBoundingRect())
    assert window.view.zoom() >= 0.75  # still readable


def test_the_messages_dock_grows_to_show_every_message(qtbot, window):
    for i in range(6):
        window.report(f"message {i}")
    window.editor.add_node("params.NumberSlider", (0.0, 0.0))  # a solve refills the tables
    wait_solved(qtbot, window)
    log = window.log
    assert log.topLevelItemCount() == 6

    def last_row_shown() -> bool:
        last = log.visualItemRect(log.topLevelItem(5))
        return last.height() > 0 and log.viewport().rect().contains(last)

    qtbot.waitUntil(last_row_shown, timeout=2000)  # the tables refill at most ~5 times a second
