"""The app's host for results that improve after the solve (torsal/engine/improve.py).

After each solve, every node result that carries an improver (ExportCutSheet nesting
TrueShape) has it run on a thread of its own, so neither the canvas nor other solves wait.
Each improvement it publishes reaches the GUI thread by a queued signal and is adopted
between solves (:meth:`~torsal.engine.solver.Solver.adopt`: the node's outputs replaced,
what is downstream solved again and the viewport redrawn, its usage in the node's
message); one arriving during a solve waits for that solve's end. An improvement of a
result that has been solved again since is dropped. :meth:`Improvements.stop` (Esc) asks
every search to stop: each keeps, and publishes, its best so far. The status bar shows the
search's progress through :attr:`Improvements.progress`.
"""

from __future__ import annotations

import contextlib
import threading
import time
from collections.abc import Callable
from typing import Any

from PySide6.QtCore import QObject, Signal

from torsal.app.gui.solve_controller import SolveController, SolveOutcome
from torsal.engine.solver import Solver

#: Seconds between progress signals of one search.
PROGRESS_EVERY = 0.1


class Improvements(QObject):
    """Runs the improvers of one document's results (see the module)."""

    #: node id, fraction done, of a running search (on the GUI thread)
    progress = Signal(str, float)
    #: a node's result was improved (after the solve that took it in has started)
    improved = Signal(str)
    _published = Signal(str, object, object, object)  # node, improver, values, remarks
    _progressed = Signal(str, float)

    def __init__(self, solves: SolveController, solver: Callable[[], Solver],
                 parent: QObject | None = None) -> None:
        super().__init__(parent)
        self._solves = solves
        self._solver = solver
        self._started: dict[int, tuple[Any, threading.Event, threading.Thread]] = {}
        self._waiting: dict[str, tuple[Any, Any, Any]] = {}
        solves.finished.connect(self._on_solved)
        self._published.connect(self._on_published)
        self._progressed.connect(self.progress)

    # -- control ---------------------------------------------------------------------
    def running(self) -> bool:
        """Whether a search is still going."""
        return any(thread.is_alive() for _, _, thread in self._started.values())

    def stop(self) -> bool:
        """Ask every running search to stop and keep its best (Esc); True if one was running."""
        was = self.running()
        for _, flag, _ in self._started.values():
            flag.set()
        return was

    def wait(self, timeout: float | None = None) -> bool:
        """Block until every search has ended (tests and closing); True if they did."""
        end = None if timeout is None else time.monotonic() + timeout
        for _, _, thread in list(self._started.values()):
            thread.join(None if end is None else max(0.0, end - time.monotonic()))
        return not self.running()

    # -- searches --------------------------------------------------------------------
    def _on_solved(self, outcome: SolveOutcome) -> None:
        if self._waiting and not self._solves.in_flight():
            waiting, self._waiting = self._waiting, {}
            for node_id, (improver, values, remarks) in waiting.items():
                self._adopt(node_id, improver, values, remarks)
        if outcome.cancelled:
            return
        current = self._solver().improvers()
        live = {id(improver) for improver in current.values()}
        for key, (_, flag, _) in list(self._started.items()):
            if key not in live:  # its node was solved again: the old search is of no use
                flag.set()
                if not self._started[key][2].is_alive():
                    del self._started[key]
        for node_id, improver in current.items():
            if id(improver) not in self._started:
                self._start(node_id, improver)

    def _start(self, node_id: str, improver: Any) -> None:
        flag = threading.Event()
        last = [0.0]

        def publish(values: Any, remarks: list[str]) -> None:
            self._published.emit(node_id, improver, values, list(remarks))

        def progress(fraction: float) -> None:
            now = time.monotonic()
            if now - last[0] >= PROGRESS_EVERY or fraction >= 1.0:
                last[0] = now
                self._progressed.emit(node_id, float(fraction))

        def search() -> None:
            try:
                improver(flag.is_set, publish, progress)
            except Exception:  # a failing search leaves the quick result standing
                pass
            finally:
                # (a window closed during the search has no one left to tell)
                with contextlib.suppress(RuntimeError):
                    self._progressed.emit(node_id, 1.0)

        thread = threading.Thread(target=search, name=f"torsal-improve-{node_id}", daemon=True)
        self._started[id(improver)] = (improver, flag, thread)
        thread.start()

    def _on_published(self, node_id: str, improver: Any, values: Any, remarks: Any) -> None:
        if self._solves.in_flight():
            self._waiting[node_id] = (improver, values, remarks)
            return
        self._adopt(node_id, improver, values, remarks)

    def _adopt(self, node_id: str, improver: Any, values: Any, remarks: Any) -> None:
        if self._solver().adopt(node_id, values, remarks, improver=improver):
            self._solves.request()
            self.improved.emit(node_id)
