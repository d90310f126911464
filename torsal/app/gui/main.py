"""Start the desktop app: ``torsal gui [FILE]`` calls :func:`launch`."""

from __future__ import annotations

import os
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from torsal.app.gui.collections_policy import StartUpCollectionsHeld
    from torsal.engine.registry import Registry


def launch(path: str | Path | None = None, registry: Registry | None = None) -> int:
    """Open the main window (on ``path`` if given) and run the event loop; returns the exit code.
    ``registry``: the node registry to open it with (``torsal gui`` passes the one whose
    plug-in problems it reported); Torsal's default one if not given.

    First the libraries the first frame needs that do not need Qt are imported, with the
    node modules of the file (:mod:`torsal.app.gui.before_qt` says why before Qt); then
    Qt, checked by :func:`~torsal.app.gui.availability.missing` (raises
    :class:`~torsal.app.gui.availability.Unavailable`). The window is shown next; the 3D
    viewport, an autosave left by a crash and the file follow once it has been painted,
    and the palette's buttons (their icons, the modules of the palette shown) after the
    file's first solved frame.
    ``TORSAL_REPORT_STARTUP=1`` prints, on stderr, the wall-clock ``time.time()`` and the
    CPU seconds the process has used (``time.process_time()``, every thread) at each
    start-up stage (for the start-up benchmark): ``imported`` (Qt and the window's
    modules), ``window-shown`` (its first paint), ``plotter`` (pyvista and VTK set up),
    ``viewport-ready`` (the file opened, its solve started), ``solved`` (the first results)
    ``first-frame`` (the viewport's first render after them) and ``started-up`` (the
    palette filled, garbage collection back on), each with ``collections-held`` or
    ``collections-on``, ``palette-waiting`` or ``palette-filled`` and, on Linux,
    ``runqueue=S`` (the seconds the main thread waited for a CPU: :func:`waited_for_a_cpu`).

    Automatic garbage collection is off from here until just after that first frame (or
    until the process has used :data:`~torsal.app.gui.collections_policy.START_UP_LIMIT_S`
    CPU seconds; the stage ``started-up`` says when it is back on): see
    :class:`~torsal.app.gui.collections_policy.StartUpCollectionsHeld`.
    """
    from torsal.app.gui.availability import Unavailable, missing
    from torsal.app.gui.before_qt import import_before_qt
    from torsal.app.gui.collections_policy import START_UP_LIMIT_S, StartUpCollectionsHeld

    collections = StartUpCollectionsHeld()
    collections.hold()
    try:
        registry = import_before_qt(Path(path) if path else None, registry)
        reason = missing()  # imports Qt
        if reason is not None:
            raise Unavailable(reason)
        return _run(path, registry, collections, START_UP_LIMIT_S)
    finally:
        collections.release()


def waited_for_a_cpu() -> str:
    """`` runqueue=S``: the seconds this thread has spent ready to run but waiting for a
    CPU (Linux's schedstat), or ``""`` where that is not known. A start-up's wall time less
    this is close to what it takes on an idle machine (tests/benchmarks/bench_startup.py)."""
    try:
        with open("/proc/thread-self/schedstat", encoding="ascii") as stat:
            return f" runqueue={int(stat.read().split()[1]) / 1e9:.4f}"
    except (OSError, ValueError, IndexError):
        return ""


def _run(path: str | Path | None, registry: Registry, collections: StartUpCollectionsHeld,
         limit_s: float) -> int:
    report = os.environ.get("TORSAL_REPORT_STARTUP") == "1"

    def stamp(stage: str) -> None:
        if report:
            held = "held" if collections.held else "on"
            palette = "filled" if window is not None and window.palette.populated else "waiting"
            line = (f"torsal-startup {stage} {time.time():.4f} {time.process_time():.4f}"
                    f" collections-{held} palette-{palette}")
            print(line + waited_for_a_cpu(), file=sys.stderr, flush=True)

    window = None
    from PySide6.QtCore import QEvent, QObject, QTimer
    from PySide6.QtWidgets import QApplication

    from torsal.app.gui.main_window import MainWindow
    from torsal.app.gui.qt_compat import defer

    stamp("imported")

    app = QApplication.instance() or QApplication(sys.argv[:1])
    app.setApplicationName("Torsal")
    app.setOrganizationName("Torsal")
    window = MainWindow(registry)
    geometry, state = window.settings.window_state()
    if geometry is not None:
        window.restoreGeometry(geometry)
    if state is not None:
        window.restoreState(state)

    # Collection resumes after the first solved frame, or once start-up has used
    # ``limit_s`` CPU seconds (every thread: what a long first solve may have allocated)
    budget = QTimer(window)
    budget.setInterval(250)

    def started_up() -> None:
        """What the first frame did not need: the palette's buttons, garbage collection."""
        if budget.isActive():
            budget.stop()
            window.palette.populate()
            collections.release()
            stamp("started-up")

    def check_budget() -> None:
        """Every 250 ms, and at each stage (a busy event loop may run the timer late)."""
        if time.process_time() > limit_s:
            started_up()

    budget.timeout.connect(check_budget)

    def started() -> None:
        if report:
            window.viewport.plotter_created.connect(lambda: stamp("plotter"))
        window.doc.results_changed.connect(first_results)
        window.start(Path(path) if path else None, palette=False)
        stamp("viewport-ready")
        check_budget()

    def first_results(_outcome: object) -> None:
        window.doc.results_changed.disconnect(first_results)
        stamp("solved")
        window.viewport.frame_rendered.connect(first_frame)
        check_budget()

    def first_frame() -> None:
        window.viewport.frame_rendered.disconnect(first_frame)
        stamp("first-frame")
        defer(window, started_up)  # after the event that drew the frame has been handled

    class FirstPaint(QObject):
        """Runs ``then`` once, after the window's first paint."""

        def __init__(self, then: Callable[[], None]) -> None:
            super().__init__(window)
            self.then = then

        def eventFilter(self, watched: QObject, event: QEvent) -> bool:
            if event.type() == QEvent.Type.Paint and self.then is not None:
                then, self.then = self.then, None
                window.removeEventFilter(self)
                stamp("window-shown")
                defer(window, then)
            return False

    window.installEventFilter(FirstPaint(started))
    budget.start()
    window.show()
    return app.exec()
