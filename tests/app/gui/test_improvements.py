"""A background search (an improver, as Cut sheets' nesting) that ends after its window has
closed ends quietly: nothing is left to tell, and its thread raises nothing."""

from __future__ import annotations

import threading
from types import SimpleNamespace

import shiboken6
from PySide6.QtCore import QObject, Signal

from torsal.app.gui.improvements import Improvements


class _Solves(QObject):
    finished = Signal(object)

    def in_flight(self) -> bool:
        return False


def test_a_search_that_ends_after_its_window_closed_raises_nothing(qtbot, monkeypatch):
    failures: list[BaseException] = []
    monkeypatch.setattr(threading, "excepthook", lambda args: failures.append(args.exc_value))
    gate, began = threading.Event(), threading.Event()

    def improver(stopped, publish, progress):
        began.set()
        gate.wait(10.0)

    solves = _Solves()
    improvements = Improvements(solves, lambda: SimpleNamespace(improvers=lambda: {"cut": improver}))
    solves.finished.emit(SimpleNamespace(cancelled=False))
    assert began.wait(10.0)
    (thread,) = [t for t in threading.enumerate() if t.name == "torsal-improve-cut"]
    shiboken6.delete(improvements)  # the window and all it owns closed
    gate.set()
    thread.join(10.0)
    assert not thread.is_alive()
    assert failures == []
