"""Closing a window while a node that never checks for cancellation is still solving.

The document waits a second for the worker, then lets it finish on its own; whatever it
emits afterwards must go nowhere. Before, the worker emitted through the document's
controller after Qt had deleted it with the window: "Signal source has been deleted" on
the worker thread, or, when the deletion raced the emit, an abort of the whole process
(seen as a crash in whichever GUI test ran next).
"""

from __future__ import annotations

import time

import pytest
from PySide6.QtCore import QEvent
from PySide6.QtWidgets import QApplication

from tests.support.fixtures_gui import make_window, wait_solved
from torsal.engine.node import Node, Out
from torsal.engine.types import NUMBER
from torsal.nodes.catalogue import default_registry

SECONDS = 2.5


class Stubborn(Node):
    """Takes SECONDS to solve and never looks at its cancel token."""

    type_id = "test.Stubborn"
    outputs = (Out("Value", NUMBER, "V", "A number, late."),)

    def solve(self) -> float:
        time.sleep(SECONDS)
        return 1.0


@pytest.mark.filterwarnings("error::pytest.PytestUnhandledThreadExceptionWarning")
def test_a_window_closed_mid_solve_leaves_the_worker_to_finish_harmlessly(qtbot, config_folder):
    registry = default_registry(plugins=False)
    registry.register(Stubborn)
    window = make_window(qtbot, registry, config_folder)
    wait_solved(qtbot, window)
    window.editor.add_node("test.Stubborn", (0.0, 0.0))
    qtbot.waitUntil(window.doc.solves.busy, timeout=5000)
    started = time.perf_counter()
    window.doc.undo_stack.setClean()
    window.close()
    assert time.perf_counter() - started < SECONDS  # closing did not wait for the node
    window.deleteLater()
    QApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete.value)  # as the event loop would
    QApplication.processEvents()
    # the worker finishes and emits after the window and its document are gone
    deadline = time.perf_counter() + SECONDS + 1.5
    while time.perf_counter() < deadline:
        QApplication.processEvents()
        time.sleep(0.02)
    # still alive: a fresh window solves as usual
    again = make_window(qtbot, default_registry(plugins=False), config_folder)
    wait_solved(qtbot, again)
    again.doc.undo_stack.setClean()
    again.close()
