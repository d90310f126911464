"""Start the desktop app: ``torsal gui [FILE]`` calls :func:`launch`."""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

STARTED = time.time()


def launch(path: str | Path | None = None) -> int:
    """Open the main window (on ``path`` if given) and run the event loop; returns the exit code.

    ``TORSAL_REPORT_STARTUP=1`` prints, on stderr, when the window was first shown and when
    the 3D viewport was ready (wall-clock ``time.time()`` values, for start-up benchmarks).
    """
    from PySide6.QtWidgets import QApplication

    from app.gui.main_window import MainWindow
    from app.gui.qt_compat import defer

    app = QApplication.instance() or QApplication(sys.argv[:1])
    app.setApplicationName("Torsal")
    app.setOrganizationName("Torsal")
    window = MainWindow()
    geometry, state = window.settings.window_state()
    if geometry is not None:
        window.restoreGeometry(geometry)
    if state is not None:
        window.restoreState(state)
    window.show()
    report = os.environ.get("TORSAL_REPORT_STARTUP") == "1"

    def started() -> None:
        if report:
            print(
                f"torsal-startup window-shown {time.time():.4f} since-import {time.time() - STARTED:.3f}",
                file=sys.stderr,
                flush=True,
            )
        window.start(Path(path) if path else None)
        if report:
            print(f"torsal-startup viewport-ready {time.time():.4f}", file=sys.stderr, flush=True)

    defer(window, started)
    return app.exec()
