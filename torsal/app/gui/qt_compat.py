"""Work-arounds for bugs in the Qt binding in use (imported before Qt is used much).

PySide6 6.12.0 returns ``None`` from *static* functions that return nothing
(``QTimer.singleShot``, ``QCoreApplication.processEvents``, every ``QTest`` mouse and key
function …) without taking a reference to it: each call lowers ``None``'s reference
count by one, and after a few thousand calls CPython 3.11 aborts with "none_dealloc:
deallocating None". (Python 3.12+ makes ``None`` immortal, so the bug is harmless there.)

The same happens on many ordinary void methods too (``setPen``, ``setObjectName``,
``QRectF.setWidth`` …: one reference per call), so painting alone drops tens of
thousands an hour. When the bug is detected at import, ``None``'s reference count is
raised once by :data:`RESERVE` (a count, never handed back, so nothing is freed at exit
either): 2**60, which a million lost references a second would take 36,000 years to
use up, and far from the 2**63 where the count would overflow. The app also avoids
static void calls on paths taken per user action (:func:`defer` replaces
``QTimer.singleShot``).
"""

from __future__ import annotations

import ctypes
import sys
from collections.abc import Callable

from PySide6.QtCore import QCoreApplication, QObject, QTimer

RESERVE = 1 << 60


def static_void_calls_leak_none() -> bool:
    """Whether calling a static void Qt function drops a reference to ``None``."""
    before = sys.getrefcount(None)
    for _ in range(16):
        QCoreApplication.sendPostedEvents()
    return sys.getrefcount(None) < before - 8


def _reserve_none_references() -> bool:
    """Raise ``None``'s reference count by :data:`RESERVE` (CPython < 3.12 release builds)."""
    debug_build = hasattr(sys, "gettotalrefcount")  # its objects start with two extra pointers
    if sys.implementation.name != "cpython" or sys.version_info >= (3, 12) or debug_build:
        return False
    refcount = ctypes.c_ssize_t.from_address(id(None))  # ob_refcnt: the first field of every object
    refcount.value += RESERVE
    return True


LEAK_DETECTED = static_void_calls_leak_none()
RESERVED = _reserve_none_references() if LEAK_DETECTED else False


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
