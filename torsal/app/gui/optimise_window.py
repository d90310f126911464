"""The Optimise… window: a Galapagos-like search over the open document's sliders.

Pick sliders (genes, each searched over its own min … max), a number output (fitness)
and minimise or maximise; Start runs CMA-ES on a
worker thread over a snapshot of the graph, so the canvas and viewport stay live. The
plot shows the best and mean fitness of every generation. Stop cancels the variant
being solved at its next node. "Apply best" sets the sliders to the best values found,
as one undo step.
"""

from __future__ import annotations

import math
import numbers
import threading
from pathlib import Path
from typing import Any

from PySide6.QtCore import QObject, QPointF, QRectF, Qt, Signal
from PySide6.QtGui import QColor, QPainter, QPen, QPolygonF
from PySide6.QtWidgets import (
    QComboBox,
    QDialog,
    QFormLayout,
    QHBoxLayout,
    QLabel,
    QListWidget,
    QListWidgetItem,
    QPushButton,
    QRadioButton,
    QSpinBox,
    QVBoxLayout,
    QWidget,
)

from torsal.app.explore.executors import InlineExecutor
from torsal.app.explore.optimise import Generation, OptimiseResult, optimise
from torsal.app.explore.study import Study, study_from_text
from torsal.app.explore.variables import REDUCERS
from torsal.app.gui.commands import SetSetting
from torsal.app.gui.hosts import OptimiseOwner
from torsal.app.headless import UsageError
from torsal.engine.graphfile import dumps
from torsal.engine.node import CancelToken
from torsal.engine.types import BOOLEAN, GENERIC, INTEGER, NUMBER
from torsal.engine.widgets import Widget

#: outputs offered as fitness: numbers (a Generic output only while it holds numbers)
FITNESS_TYPES = (NUMBER, INTEGER, BOOLEAN)


def holds_numbers(tree: Any) -> bool:
    """True when an output's last value is numbers only (a list is reduced to one)."""
    if tree is None or tree.item_count == 0:
        return False
    return all(isinstance(item, numbers.Real) for item in tree.all_items())


class FitnessPlot(QWidget):
    """Best and mean fitness per generation: a chart with labelled axes (generation,
    fitness), its legend and latest values in a strip above the plotting area (never under
    a line), and a marker on every generation from the first."""

    LEFT, RIGHT, TOP, BOTTOM = 62, 14, 26, 34  # the plotting area's margins, in pixels

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.best: list[float] = []
        self.mean: list[float] = []
        self.setMinimumSize(360, 200)

    def clear(self) -> None:
        self.best, self.mean = [], []
        self.update()

    def add(self, generation: Generation) -> None:
        self.best.append(generation.best)
        self.mean.append(generation.mean)
        self.update()

    def plot_rect(self) -> QRectF:
        """Where the lines are drawn (inside the axes)."""
        return QRectF(self.LEFT, self.TOP, max(1, self.width() - self.LEFT - self.RIGHT),
                      max(1, self.height() - self.TOP - self.BOTTOM))

    def paintEvent(self, event: Any) -> None:
        painter = QPainter(self)
        painter.setRenderHint(QPainter.RenderHint.Antialiasing)
        painter.fillRect(self.rect(), QColor("#1e1f22"))
        area = self.plot_rect()
        values = [v for v in self.best + self.mean if math.isfinite(v)]
        self._axes(painter, area)
        if not self.best or not values:
            painter.setPen(QColor("#888"))
            hint = "best and mean fitness per generation"
            painter.drawText(area, Qt.AlignmentFlag.AlignCenter, hint)
            return
        low, high = min(values), max(values)
        if high == low:
            low, high = low - 0.5 * (abs(low) or 1.0), high + 0.5 * (abs(high) or 1.0)
        count = max(len(self.best), 2)  # generations 1 … n along x (room for the first alone)

        def point(i: int, v: float) -> QPointF:
            x = area.left() + area.width() * i / (count - 1)
            y = area.bottom() - area.height() * (v - low) / (high - low)
            return QPointF(x, y)

        self._ticks(painter, area, low, high, count)
        for series, colour in ((self.mean, MEAN_COLOUR), (self.best, BEST_COLOUR)):
            points = [point(i, v) for i, v in enumerate(series) if math.isfinite(v)]
            painter.setPen(QPen(QColor(colour), 2))
            if len(points) > 1:
                painter.drawPolyline(QPolygonF(points))
            painter.setBrush(QColor(colour))
            for p in points:
                painter.drawEllipse(p, 2.5, 2.5)
        self._legend(painter)

    def _axes(self, painter: QPainter, area: QRectF) -> None:
        painter.setPen(QPen(QColor("#777"), 1))
        painter.drawLine(area.bottomLeft(), area.bottomRight())
        painter.drawLine(area.bottomLeft(), area.topLeft())
        painter.setPen(QColor("#bbb"))
        label = QRectF(area.left(), self.height() - 16, area.width(), 14)
        painter.drawText(label, Qt.AlignmentFlag.AlignCenter, "generation")
        painter.save()
        painter.translate(12, area.center().y())
        painter.rotate(-90)
        upright = QRectF(-area.height() / 2, -8, area.height(), 14)
        painter.drawText(upright, Qt.AlignmentFlag.AlignCenter, "fitness")
        painter.restore()

    def _ticks(self, painter: QPainter, area: QRectF, low: float, high: float, count: int) -> None:
        painter.setPen(QColor("#999"))
        for fraction in (0.0, 0.5, 1.0):
            value = low + fraction * (high - low)
            y = area.bottom() - fraction * area.height()
            painter.drawText(QRectF(14, y - 7, self.LEFT - 18, 14),
                             Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter, f"{value:.4g}")
        for generation in sorted({1, (count + 1) // 2, count} if len(self.best) > 1 else {1}):
            x = area.left() + area.width() * (generation - 1) / (count - 1)
            painter.drawText(QRectF(x - 20, area.bottom() + 2, 40, 14), Qt.AlignmentFlag.AlignCenter,
                             str(generation))

    def _legend(self, painter: QPainter) -> None:
        x = float(self.LEFT)
        for name, series, colour in (("best", self.best, BEST_COLOUR), ("mean", self.mean, MEAN_COLOUR)):
            painter.setPen(QPen(QColor(colour), 3))
            painter.drawLine(QPointF(x, 12), QPointF(x + 16, 12))
            painter.setPen(QColor("#ccc"))
            text = f"{name} {series[-1]:.6g}"
            painter.drawText(QRectF(x + 20, 4, 170, 16), Qt.AlignmentFlag.AlignVCenter, text)
            x += 190


BEST_COLOUR, MEAN_COLOUR = "#f0b43c", "#6aa0d8"


class _Relay(QObject):
    """Carries the worker thread's news to the UI thread (queued signals)."""

    generation = Signal(object)  # Generation
    finished = Signal(object)  # OptimiseResult, or a message when it could not run


class OptimiseWindow(QDialog):
    """Non-modal: the canvas keeps working while a search runs."""

    def __init__(self, window: OptimiseOwner) -> None:
        super().__init__(window)
        self.setWindowTitle("Optimise")
        self.main = window
        self.doc = window.doc
        self.token = CancelToken()
        self.thread: threading.Thread | None = None
        self.result: OptimiseResult | None = None
        self.study: Study | None = None
        self.relay = _Relay(self)
        self.relay.generation.connect(self._on_generation)
        self.relay.finished.connect(self._on_finished)

        self.genes = QListWidget()
        self.fitness = QComboBox()
        self.reducer = QComboBox()
        self.reducer.addItems(["(one value)", *REDUCERS])
        self.minimise = QRadioButton("Minimise")
        self.maximise = QRadioButton("Maximise")
        self.minimise.setChecked(True)
        self.budget = QSpinBox()
        self.budget.setRange(6, 100000)
        self.budget.setValue(200)
        self.seed = QSpinBox()
        self.seed.setRange(0, 2**31 - 1)
        self.plot = FitnessPlot()
        self.status = QLabel("Pick sliders and a fitness, then Start.")
        self.status.setWordWrap(True)
        self.start_button = QPushButton("Start")
        self.stop_button = QPushButton("Stop")
        self.apply_button = QPushButton("Apply best")
        self.stop_button.setEnabled(False)
        self.apply_button.setEnabled(False)
        self.start_button.clicked.connect(self.start)
        self.stop_button.clicked.connect(self.stop)
        self.apply_button.clicked.connect(self.apply_best)

        form = QFormLayout()
        form.addRow("Sliders (genes)", self.genes)
        fitness_row = QHBoxLayout()
        fitness_row.addWidget(self.fitness, 1)
        fitness_row.addWidget(self.reducer)
        form.addRow("Fitness", fitness_row)
        sense = QHBoxLayout()
        sense.addWidget(self.minimise)
        sense.addWidget(self.maximise)
        form.addRow("", sense)
        form.addRow("Budget (evaluations)", self.budget)
        form.addRow("Seed", self.seed)
        buttons = QHBoxLayout()
        for button in (self.start_button, self.stop_button, self.apply_button):
            buttons.addWidget(button)
        layout = QVBoxLayout(self)
        layout.addLayout(form)
        layout.addWidget(self.plot, 1)
        layout.addWidget(self.status)
        layout.addLayout(buttons)
        self.refresh_choices()

    # -- choices ------------------------------------------------------------------------
    def refresh_choices(self) -> None:
        """List the document's sliders and number outputs."""
        self.genes.clear()
        self.fitness.clear()
        for node_id, record in self.doc.graph.nodes.items():
            if record.node.widget is Widget.SLIDER:  # a slider, built in or a plug-in's
                settings = record.node.settings
                limits = f"{settings.get('min')} … {settings.get('max')}"
                item = QListWidgetItem(f"{record.title} [{node_id}]  {limits}")
                item.setData(Qt.ItemDataRole.UserRole, node_id)
                item.setFlags(item.flags() | Qt.ItemFlag.ItemIsUserCheckable)
                item.setCheckState(Qt.CheckState.Unchecked)
                self.genes.addItem(item)
            else:
                result = self.doc.result(node_id)
                for port in record.node.output_ports():
                    if port.type not in FITNESS_TYPES and not (
                        port.type is GENERIC and result is not None
                        and holds_numbers(result.outputs.get(port.name))
                    ):
                        continue
                    label = f"{record.title} [{node_id}] · {port.name}"
                    self.fitness.addItem(label, f"{node_id}.{port.name}")

    def chosen_genes(self) -> list[str]:
        return [
            self.genes.item(i).data(Qt.ItemDataRole.UserRole)
            for i in range(self.genes.count())
            if self.genes.item(i).checkState() == Qt.CheckState.Checked
        ]

    def set_genes(self, node_ids: list[str]) -> None:
        for i in range(self.genes.count()):
            item = self.genes.item(i)
            wanted = item.data(Qt.ItemDataRole.UserRole) in node_ids
            item.setCheckState(Qt.CheckState.Checked if wanted else Qt.CheckState.Unchecked)

    def set_fitness(self, target: str) -> None:
        self.fitness.setCurrentIndex(self.fitness.findData(target))

    # -- running ------------------------------------------------------------------------
    @property
    def running(self) -> bool:
        return self.thread is not None and self.thread.is_alive()

    def start(self) -> None:
        if self.running:
            return
        genes = self.chosen_genes()
        target = self.fitness.currentData()
        if not genes or not target:
            self.status.setText("Tick at least one slider and choose a fitness output.")
            return
        if self.reducer.currentIndex() > 0:
            target = f"{target}:{self.reducer.currentText()}"
        vary = []
        for node_id in genes:
            settings = self.doc.graph.nodes[node_id].node.settings
            vary.append(f"{node_id}={settings.get('min')}:{settings.get('max')}")
        try:
            path = self.doc.path or Path("untitled.graph")
            study = study_from_text(dumps(self.doc.graph), path, vary, [target], steps=False,
                                    collect_flag="fitness")
        except UsageError as exc:
            self.status.setText(str(exc))
            return
        self.study = study
        self.result = None
        self.token = CancelToken()
        self.plot.clear()
        sense = -1 if self.maximise.isChecked() else 1
        budget, seed, token, relay = self.budget.value(), self.seed.value(), self.token, self.relay

        def work() -> None:
            try:
                result = optimise(study, InlineExecutor(token), [sense], budget=budget, seed=seed,
                                  on_generation=relay.generation.emit, should_stop=lambda: token.cancelled)
            except Exception as exc:  # reported in the window, never a crash of the app
                relay.finished.emit(f"The search failed: {type(exc).__name__}: {exc}")
                return
            relay.finished.emit(result)

        self.start_button.setEnabled(False)
        self.stop_button.setEnabled(True)
        self.apply_button.setEnabled(False)
        self.status.setText("Searching…")
        self.thread = threading.Thread(target=work, name="torsal-optimise", daemon=True)
        self.thread.start()

    def stop(self) -> None:
        """Cancel the search: the variant being solved stops at its next node."""
        self.token.cancel()

    def _on_generation(self, generation: Generation) -> None:
        self.plot.add(generation)
        self.status.setText(f"Generation {generation.index + 1} · {generation.evaluations} evaluations · "
                            f"best {generation.best:.6g}")

    def _on_finished(self, outcome: OptimiseResult | str) -> None:
        self.start_button.setEnabled(True)
        self.stop_button.setEnabled(False)
        if isinstance(outcome, str):
            self.status.setText(outcome)
            return
        self.result = outcome
        best = outcome.best
        verb = "Stopped" if outcome.stopped else "Done"
        if best is None:
            tried = outcome.evaluations
            self.status.setText(f"{verb}: no variant had a number for the fitness ({tried} tried).")
            return
        values = ", ".join(f"{k} = {v:g}" for k, v in best.values.items())
        self.status.setText(f"{verb} after {outcome.evaluations} evaluations: best {best.objectives[0]:.6g} "
                            f"at {values}.")
        self.apply_button.setEnabled(True)

    def apply_best(self) -> None:
        """Set the sliders to the best values found: one undo step."""
        if self.result is None or self.result.best is None:
            return
        stack = self.doc.undo_stack
        stack.beginMacro("Apply best")
        try:
            for node_id, value in self.result.best.values.items():
                if node_id in self.doc.graph.nodes:
                    self.doc.push(SetSetting(self.doc, node_id, "value", value))
        finally:
            stack.endMacro()

    def closeEvent(self, event: Any) -> None:
        self.stop()
        super().closeEvent(event)


def open_optimise_window(window: OptimiseOwner) -> OptimiseWindow:
    """Show the window (one per main window), refreshed for the current document."""
    dialog = getattr(window, "_optimise_window", None)
    if dialog is None:
        dialog = OptimiseWindow(window)
        window._optimise_window = dialog
    elif not dialog.running:
        dialog.refresh_choices()
    dialog.show()
    dialog.raise_()
    return dialog
