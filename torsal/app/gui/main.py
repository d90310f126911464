"""Start the desktop app: ``torsal gui [FILE]`` calls :func:`launch`."""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable
from pathlib import Path


def launch(path: str | Path | None = None) -> int:
    """Open the main window (on ``path`` if given) and run the event loop; returns the exit code.

    The window is shown first; the 3D viewport (pyvista takes a second or two to import),
    an autosave left by a crash and the file follow once it has been painted.
    ``TORSAL_REPORT_STARTUP=1`` prints, on stderr, the wall-clock ``time.time()`` of the
    first paint and of the viewport being ready (for the start-up benchmark).
    """
    from PySide6.QtCore import QEvent, QObject
    from PySide6.QtWidgets import QApplication

    from torsal.app.gui.main_window import MainWindow
    from torsal.app.gui.qt_compat import defer

    app = QApplication.instance() or QApplication(sys.argv[:1])
    app.setApplicationName("Torsal")
    app.setOrganizationName("Torsal")
    window = MainWindow()
    geometry, state = window.settings.window_state()
    if geometry is not None:
        window.restoreGeometry(geometry)
    if state is not None:
        window.restoreState(state)
    report = os.environ.get("TORSAL_REPORT_STARTUP") == "1"

    def started() -> None:
        window.start(Path(path) if path else None)
        if report:
            print(f"torsal-startup viewport-ready {time.time():.4f}", file=sys.stderr, flush=True)

    class FirstPaint(QObject):
        """Runs ``then`` once, after the window's first paint."""

        def __init__(self, then: Callable[[], None]) -> None:
            super().__init__(window)
            self.then = then

        def eventFilter(self, watched: QObject, event: QEvent) -> bool:
            if event.type() == QEvent.Type.Paint and self.then is not None:
                then, self.then = self.then, None
                window.removeEventFilter(self)
                if report:
                    print(f"torsal-startup window-shown {time.time():.4f}", file=sys.stderr, flush=True)
                defer(window, then)
            return False

    window.installEventFilter(FirstPaint(started))
    window.show()
    return app.exec()
