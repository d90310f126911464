"""The profiler: solve time per node in the last solve, slowest first."""

from __future__ import annotations

from PySide6.QtCore import Qt, Signal
from PySide6.QtWidgets import QTableWidget, QTableWidgetItem, QWidget

from torsal.app.gui.solve_controller import SolveOutcome
from torsal.engine.graph import Graph

BAR_WIDTH = 24


class Profiler(QTableWidget):
    """Node, type, state, milliseconds and a share-of-total bar."""

    node_activated = Signal(str)

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(0, 5, parent)
        self.setHorizontalHeaderLabels(["Node", "Type", "State", "ms", "Share"])
        self.verticalHeader().setVisible(False)
        self.setEditTriggers(QTableWidget.EditTrigger.NoEditTriggers)
        self.setSelectionBehavior(QTableWidget.SelectionBehavior.SelectRows)
        self.horizontalHeader().setStretchLastSection(True)
        self.setColumnWidth(0, 150)
        self.setColumnWidth(1, 160)
        self.setColumnWidth(2, 64)
        self.setColumnWidth(3, 64)
        self.cellDoubleClicked.connect(
            lambda row, _col: self.node_activated.emit(self.item(row, 0).data(Qt.ItemDataRole.UserRole))
        )

    def show_solve(self, outcome: SolveOutcome, graph: Graph) -> None:
        rows = [
            (node_id, graph.nodes[node_id], result)
            for node_id, result in outcome.results.items()
            if node_id in graph.nodes
        ]
        rows.sort(key=lambda r: r[2].seconds, reverse=True)
        total = sum(r[2].seconds for r in rows) or 1.0
        self.setRowCount(len(rows))
        for row, (node_id, record, result) in enumerate(rows):
            share = result.seconds / total
            cells = [
                f"{record.title} [{node_id}]",
                record.type_id,
                result.state,
                f"{result.seconds * 1000:.2f}",
                "█" * max(0, round(share * BAR_WIDTH)) + f" {share:.0%}",
            ]
            for column, text in enumerate(cells):
                item = QTableWidgetItem(text)
                if column == 0:
                    item.setData(Qt.ItemDataRole.UserRole, node_id)
                if column == 3:
                    item.setTextAlignment(Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter)
                self.setItem(row, column, item)
