"""A killed app's autosave is offered at the next start and restores the graph."""

from __future__ import annotations

import os
import subprocess
import sys
import threading

from PySide6.QtWidgets import QMessageBox

from tests.support.fixtures_gui import EXAMPLES, HERE, ROOT, close_window, copy_fixture, wait_solved
from torsal.app.gui.autosave import find_recoveries
from torsal.app.gui.main_window import MainWindow


def run_and_kill_after_autosave(path, config_folder) -> None:
    env = dict(
        os.environ, TORSAL_CONFIG_DIR=str(config_folder), TORSAL_AUTOSAVE_SECONDS="0.3", PYTHONPATH=str(ROOT)
    )
    child = subprocess.Popen(
        [sys.executable, str(HERE / "autosave_child.py"), str(path)],
        cwd=ROOT,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    said: list[str] = []
    reader = threading.Thread(target=lambda: said.append(child.stdout.readline()), daemon=True)
    reader.start()
    reader.join(timeout=60)
    child.kill()  # no clean exit: the recovery file stays behind
    child.wait(timeout=10)
    assert said and said[0].strip() == "autosaved", child.stderr.read()


def start_window(qtbot, registry, config_folder) -> MainWindow:
    window = MainWindow(registry=registry, settings_folder=config_folder)
    qtbot.addWidget(window)
    window.show()
    qtbot.waitExposed(window)
    window.start(None, offer_recovery=True)
    return window


def test_a_killed_apps_autosave_is_offered_at_next_start_and_restores_the_graph(
    qtbot, registry, config_folder, dialogs, tmp_path
):
    path = copy_fixture(EXAMPLES / "first-steps.graph", tmp_path)
    original = path.read_bytes()
    run_and_kill_after_autosave(path, config_folder)
    assert len(find_recoveries(config_folder)) == 1

    dialogs.answer = QMessageBox.StandardButton.Yes
    window = start_window(qtbot, registry, config_folder)
    try:
        kind, _title, text = dialogs.calls[0]
        assert kind == "question" and "first-steps.graph" in text and "Restore" in text
        graph = window.doc.graph
        assert graph.nodes["width"].position == (111.0, 222.0)
        assert graph.nodes["count"].node.settings["value"] == 7
        assert window.doc.path == path.resolve() and window.doc.dirty  # restored, not yet saved
        assert path.read_bytes() == original
        assert find_recoveries(config_folder) == []  # the dead session's files are gone
        wait_solved(qtbot, window)
        assert window.doc.results["edges"].outputs["Series"].item_count == 7
    finally:
        close_window(window)


def test_declining_the_recovery_discards_it(qtbot, registry, config_folder, dialogs, tmp_path):
    path = copy_fixture(EXAMPLES / "first-steps.graph", tmp_path)
    run_and_kill_after_autosave(path, config_folder)
    dialogs.answer = QMessageBox.StandardButton.No
    window = start_window(qtbot, registry, config_folder)
    try:
        assert dialogs.kinds() == ["question"]
        assert window.doc.graph.nodes == {} and not window.doc.dirty
        assert find_recoveries(config_folder) == []
    finally:
        close_window(window)
