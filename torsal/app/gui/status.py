"""The status bar: last solve time, warning and error counts, a progress bar for long solves."""

from __future__ import annotations

import time

from PySide6.QtCore import QTimer
from PySide6.QtWidgets import QLabel, QProgressBar, QStatusBar, QWidget

from torsal.app.gui.solve_controller import PROGRESS_AFTER, SolveOutcome

PROGRESS_AFTER_MS = round(1000 * PROGRESS_AFTER)
QWIDGETSIZE_MAX = (1 << 24) - 1  # Qt's largest widget size (no maximum)
#: How long the message that a background result was taken in stays.
TAKEN_IN_MS = 8000


class SolveStatus(QStatusBar):
    """Shows how the last solve went; a progress bar appears when a solve takes > 0.5 s."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.solve_label = QLabel("Not solved yet")
        self.counts_label = QLabel("")
        self.progress = QProgressBar()
        self.progress.setMaximumWidth(220)
        self.progress.setTextVisible(True)
        self.progress.setFormat("Solving %p % — Esc cancels")
        self.progress.hide()
        self.search = QProgressBar()  # a background search's (nesting), beside the solves'
        self.search.setMaximumWidth(300)
        self.search.setTextVisible(True)
        self.search.hide()
        self.addPermanentWidget(self.search)
        self.addPermanentWidget(self.progress)
        self.addPermanentWidget(self.solve_label)
        self.addPermanentWidget(self.counts_label)
        self._started = 0.0
        self._taken_in = ""  # the node whose background result the coming solve takes in
        self._reveal = QTimer(self)
        self._reveal.setSingleShot(True)
        self._reveal.setInterval(PROGRESS_AFTER_MS)
        self._reveal.timeout.connect(self._show_progress)

    def solve_started(self) -> None:
        self._started = time.perf_counter()
        self.progress.setRange(0, 1)  # not the animated busy mode: it repaints all the time
        self.progress.setValue(0)
        self._reveal.start()

    def _show_progress(self) -> None:
        self.progress.show()
        self.solve_label.setText("Solving…")

    def search_progress(self, node_id: str, fraction: float) -> None:
        """A background search (torsal/engine/improve.py) of ``node_id``: its own bar."""
        if fraction >= 1.0:
            self.search.hide()
            return
        self.search.setFormat(f"{node_id}: searching %p % — Esc keeps the best")
        self.search.setRange(0, 1000)
        self.search.setValue(round(1000 * max(0.0, fraction)))
        self.search.show()

    def solve_progress(self, index: int, total: int, node_id: str) -> None:
        self.progress.setRange(0, max(1, total))
        self.progress.setValue(index)

    def result_taken_in(self, title: str) -> None:
        """A background search's better result of node ``title`` was taken in: the solve it
        starts (of what lies downstream, often nothing) is reported as that, in a message,
        while the label keeps the last real solve's time."""
        self._taken_in = title

    def solve_finished(self, outcome: SolveOutcome) -> None:
        self._reveal.stop()
        self.progress.hide()
        report = outcome.report
        ms = report.seconds * 1000
        if outcome.error or report.cancelled:
            self.solve_label.setMinimumSize(0, 0)
            self.solve_label.setMaximumSize(QWIDGETSIZE_MAX, QWIDGETSIZE_MAX)
            if outcome.error:
                self.solve_label.setText(f"Solve failed: {outcome.error}")
            else:
                self.solve_label.setText(
                    f"Solve cancelled after {ms:.0f} ms ({nodes(len(report.solved))} solved)"
                )
        elif self._taken_in:
            self.showMessage(f"Took in the background search's better result of {self._taken_in}",
                             TAKEN_IN_MS)
        else:
            self.solve_label.setText(f"Solved {nodes(len(report.solved))} in {ms:.1f} ms")
        self._taken_in = ""
        if not (outcome.error or report.cancelled):
            # the label keeps a fixed size, the largest it has needed since: a new time does
            # not lay the status bar (and with it the window) out again, as a label that may
            # change size does on every new text
            wanted, size = self.solve_label.sizeHint(), self.solve_label.minimumSize()
            if wanted.width() > size.width() or wanted.height() != size.height():
                self.solve_label.setFixedSize(max(wanted.width(), size.width()), wanted.height())
        warnings, errors = outcome.count("warning"), outcome.count("error")
        self.counts_label.setText(
            f"⚠ {warnings} warning{'s' * (warnings != 1)}   ✖ {errors} error{'s' * (errors != 1)}"
        )
        style = "color: #c0281f;" if errors else ("color: #b06800;" if warnings else "")
        if style != self.counts_label.styleSheet():  # restyling costs a polish and a repaint
            self.counts_label.setStyleSheet(style)


def nodes(count: int) -> str:
    """``1 node``, ``2 nodes``."""
    return f"{count} node" if count == 1 else f"{count} nodes"
