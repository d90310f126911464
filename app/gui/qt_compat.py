"""Work-arounds for bugs in the Qt binding in use (import this before using Qt).

PySide6 6.12.0 returns ``None`` from *static* functions that return nothing
(``QTimer.singleShot``, ``QCoreApplication.processEvents``, every ``QTest`` mouse and key
function …) without taking a reference to it: each call lowers ``None``'s reference
count by one, and after a few thousand calls CPython 3.11 aborts with "none_dealloc:
deallocating None". (Python 3.12+ makes ``None`` immortal, so the bug is harmless there.)

When the bug is detected at import, :data:`NONE_RESERVE` holds two million extra
references to ``None`` (16 MB), which covers any realistic session and test run. The
app itself also avoids static void calls on paths taken per user action
(:func:`defer` uses a QTimer object instead of ``QTimer.singleShot``).
"""

from __future__ import annotations

import sys
from collections.abc import Callable

from PySide6.QtCore import QCoreApplication, QObject, QTimer

RESERVE_SIZE = 2_000_000


def static_void_calls_leak_none() -> bool:
    """Whether calling a static void Qt function drops a reference to ``None``."""
    before = sys.getrefcount(None)
    for _ in range(16):
        QCoreApplication.sendPostedEvents()
    return sys.getrefcount(None) < before - 8


NONE_RESERVE: list[None] = [None] * RESERVE_SIZE if static_void_calls_leak_none() else []


def defer(parent: QObject, callback: Callable[[], object], ms: int = 0) -> QTimer:
    """Call ``callback`` after ``ms`` on the event loop (``QTimer.singleShot`` without the leak)."""
    timer = QTimer(parent)
    timer.setSingleShot(True)
    timer.setInterval(ms)

    def fire() -> None:
        timer.deleteLater()
        callback()

    timer.timeout.connect(fire)
    timer.start()
    return timer
