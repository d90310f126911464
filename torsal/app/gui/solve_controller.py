"""Live solving on a worker thread, with the graph kept single-writer.

The GUI thread is the only writer of the graph. Before an edit that changes what is
solved, :meth:`SolveController.pause` cancels the running solve through its
:class:`~torsal.engine.node.CancelToken` and waits for the worker to stop; the edit is then
applied and :meth:`SolveController.request` starts a new solve on the next turn of
the event loop (so several edits made in one turn give one solve). The worker reads
the graph and writes only the solver's results; those reach the GUI as a snapshot in
:attr:`SolveController.finished`. Layout edits (moving a node, renaming, groups,
preview) touch fields the solver never reads and do not interrupt a solve.
"""

from __future__ import annotations

import sys
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from PySide6.QtCore import QObject, QTimer, Signal

from torsal.engine.node import CancelToken
from torsal.engine.solver import NodeResult, Solver, SolveReport

PROGRESS_INTERVAL = 0.05  # seconds between progress signals from the worker
#: The status bar shows its progress bar once a solve has run this long (seconds). The
#: worker sends no progress before then (from one interval before, so the bar has a value
#: when it appears): a slider drag's stream of short solves then wakes the GUI thread for
#: nothing it would show, and each wake-up is a GIL hand-over that stalls the solve (on
#: a loaded machine the GUI thread may wait for a CPU while it holds the GIL).
PROGRESS_AFTER = 0.5
#: Steps of the progress bar per node, so a long node's own progress moves it.
STEPS = 1000
#: A solve running longer than this shows what it has so far (``partial``), and again at
#: this interval, so a long solve fills the viewport as it goes. Shorter solves show only
#: their whole result: a partial frame would cost a render for nothing new.
PARTIAL_INTERVAL = 0.25
#: How long a Python thread may hold the GIL before handing it over (CPython's default is
#: 5 ms). Every Qt callback on the GUI thread needs the GIL; with a node computing in pure
#: Python on the worker, 1 ms keeps the GUI's event loop answering within a few ms.
GIL_SWITCH_INTERVAL = 0.0005


#: Controllers of closed documents whose worker outlived the close (see
#: :meth:`SolveController.shutdown`): kept, silenced, for the rest of the process — a Qt
#: object may only be deleted on its own (the GUI) thread, and this is rare and small.
_DRAINING: set[SolveController] = set()


@dataclass
class SolveOutcome:
    """What one solve produced: its report and a snapshot of every node's result."""

    generation: int
    report: SolveReport
    results: dict[str, NodeResult] = field(default_factory=dict)
    error: str = ""
    prepared: Any = None  # what :attr:`SolveController.prepare` made on the worker

    @property
    def cancelled(self) -> bool:
        return self.report.cancelled

    def count(self, state: str) -> int:
        return sum(1 for r in self.results.values() if r.state == state)


class SolveController(QObject):
    """Starts, cancels and reports solves of one :class:`Solver` on a worker thread."""

    started = Signal()
    progress = Signal(int, int, str)
    finished = Signal(object)  # SolveOutcome
    partial = Signal(object)  # SolveOutcome of a solve still running: the nodes solved so far
    _worker_done = Signal(object)
    _worker_partial = Signal(object)
    _worker_progress = Signal(int, int, str)

    def __init__(self, parent: QObject | None = None) -> None:
        super().__init__(parent)
        sys.setswitchinterval(min(sys.getswitchinterval(), GIL_SWITCH_INTERVAL))
        self._solver: Solver | None = None
        self._thread: threading.Thread | None = None
        self._token: CancelToken | None = None
        self._generation = 0
        self.auto = True
        #: Called on the worker after each solve with the solver and its report; what it
        #: returns travels with the outcome (the viewport makes its meshes there).
        self.prepare: Callable[[Solver, SolveReport], Any] | None = None
        self._request = QTimer(self)
        self._request.setSingleShot(True)
        self._request.setInterval(0)
        self._request.timeout.connect(self._start)
        self._worker_done.connect(self._on_worker_done)
        self._worker_partial.connect(self._on_worker_partial)
        self._worker_progress.connect(self.progress)

    # -- state -----------------------------------------------------------------------
    def set_solver(self, solver: Solver) -> None:
        """Solve ``solver`` from now on (a new document); a running solve is stopped."""
        self.pause()
        self._solver = solver

    def busy(self) -> bool:
        """Whether a worker is solving right now."""
        return self._thread is not None and self._thread.is_alive()

    def in_flight(self) -> bool:
        """A solve is running, or has finished and its outcome has not reached the GUI yet."""
        return self._thread is not None

    def idle(self) -> bool:
        """No solve running, none requested and no outcome still on its way to the GUI."""
        return self._thread is None and not self._request.isActive()

    # -- control ---------------------------------------------------------------------
    def request(self) -> None:
        """Solve soon: on the next event-loop turn, once, however many edits came before."""
        if self.auto:
            self._request.start()

    def solve_now(self) -> None:
        self._request.stop()
        self._start()

    def pause(self) -> None:
        """Stop the running solve and wait for the worker, so the graph may be edited.

        The stopped solve's outcome is dropped; nodes it did not reach stay expired and
        are solved by the next solve.
        """
        thread = self._thread
        if thread is None:
            return
        if thread.is_alive() and self._token is not None:
            self._generation += 1  # the outcome in flight is now stale
            self._token.cancel()
        thread.join()
        self._thread = None

    def cancel(self) -> bool:
        """Stop the running solve without waiting (Esc); its partial results are reported."""
        self._request.stop()
        if self.busy() and self._token is not None:
            self._token.cancel()
            return True
        return False

    def shutdown(self, timeout: float = 1.0) -> None:
        """Stop for good (the document is closing): cancel, wait up to ``timeout`` s, and
        if a node that never checks for cancellation keeps the worker running, silence
        this controller and keep it alive: its Qt object must not be deleted with the
        document while the worker may still emit through it (a signal of a deleted
        object, emitted from another thread, aborts the process)."""
        self.auto = False
        self.cancel()
        if self.wait(timeout):
            return
        self.prepare = None  # the viewport it drew for is going too
        self.blockSignals(True)
        self.setParent(None)  # owned by Python from now on, not by the closing document
        _DRAINING.add(self)

    def wait(self, timeout: float | None = None) -> bool:
        """Block until the worker stops (tests and shutdown); True if it did."""
        thread = self._thread
        if thread is not None:
            thread.join(timeout)
            return not thread.is_alive()
        return True

    # -- worker ----------------------------------------------------------------------
    def _start(self) -> None:
        if self._solver is None:
            return
        self.pause()
        self._generation += 1
        self._token = CancelToken()
        self._thread = threading.Thread(
            target=self._run,
            args=(self._solver, self._token, self._generation),
            name="torsal-solver",
            daemon=True,
        )
        self._thread.start()
        self.started.emit()

    def _run(self, solver: Solver, token: CancelToken, generation: int) -> None:
        started = time.perf_counter()
        # no progress signal before PROGRESS_AFTER (less one interval) into the solve
        last_progress, last_partial = [started + PROGRESS_AFTER - 2 * PROGRESS_INTERVAL], [started]
        done: list[str] = []  # nodes solved so far in this solve
        shown = [0]  # how many of them the last partial outcome carried
        current: list[str | None] = [None]

        position = [0, 1]  # the node being solved and how many there are

        def progress(index: int, total: int, node_id: str) -> None:
            if current[0] is not None:
                done.append(current[0])  # called before each node: the previous one is done
            current[0] = node_id
            position[:] = [index, total]
            now = time.perf_counter()
            if now - last_progress[0] >= PROGRESS_INTERVAL:
                last_progress[0] = now
                self._worker_progress.emit(index * STEPS, total * STEPS, node_id)

        def node_progress(node_id: str, fraction: float) -> None:
            """A long node's own progress moves the bar within its share of the solve."""
            now = time.perf_counter()
            if now - last_progress[0] >= PROGRESS_INTERVAL:
                last_progress[0] = now
                index, total = position
                step = int(STEPS * min(max(float(fraction), 0.0), 1.0))
                self._worker_progress.emit(index * STEPS + step, total * STEPS, node_id)
            if now - last_partial[0] >= PARTIAL_INTERVAL and len(done) > shown[0]:
                last_partial[0] = now
                fresh = SolveReport(solved=done[shown[0] :])
                shown[0] = len(done)
                prepared = self._prepare_safely(solver, fresh)
                partial = SolveOutcome(
                    generation, SolveReport(list(done)), dict(solver.results), "", prepared
                )
                self._worker_partial.emit(partial)

        error = ""
        try:
            report = solver.solve(token, progress, node_progress=node_progress)
        except Exception as exc:  # a graph the engine cannot order: report, never crash the app
            report = SolveReport(cancelled=True)
            error = f"{type(exc).__name__}: {exc}"
        prepared = None
        if not error and not token.cancelled:
            prepared = self._prepare_safely(solver, SolveReport(solved=report.solved[shown[0] :]))
        outcome = SolveOutcome(generation, report, dict(solver.results), error, prepared)
        self._worker_done.emit(outcome)

    def _prepare_safely(self, solver: Solver, report: SolveReport) -> Any:
        if self.prepare is None or not report.solved:
            return None
        try:
            return self.prepare(solver, report)
        except Exception:
            return None

    def _on_worker_partial(self, outcome: SolveOutcome) -> None:
        if outcome.generation == self._generation and self.busy():
            self.partial.emit(outcome)

    def _on_worker_done(self, outcome: SolveOutcome) -> None:
        if outcome.generation != self._generation:
            return  # stopped by an edit: a newer solve follows
        if self._thread is not None:
            self._thread.join()
            self._thread = None
        self.finished.emit(outcome)
