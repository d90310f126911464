"""The message log: what every node said in the last solve, and what the app did."""

from __future__ import annotations

import time

from PySide6.QtCore import Qt, Signal
from PySide6.QtGui import QBrush
from PySide6.QtWidgets import QTreeWidget, QTreeWidgetItem, QWidget

from torsal.app.gui import theme
from torsal.app.gui.solve_controller import SolveOutcome
from torsal.engine.graph import Graph

APP_MESSAGES_KEPT = 40
ROWS_SHOWN_AT_MOST = 10  # the dock grows to show this many rows, then scrolls


class MessageLog(QTreeWidget):
    """Two kinds of rows: node messages (replaced after each solve) and app messages."""

    node_activated = Signal(str)

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.setHeaderLabels(["Level", "Node", "Message"])
        self.setRootIsDecorated(False)
        self.setColumnWidth(0, 70)
        self.setColumnWidth(1, 160)
        self.setAlternatingRowColors(True)
        self.setUniformRowHeights(True)
        self.setWordWrap(False)
        self.app_messages: list[tuple[str, str, str]] = []
        self.node_rows: list[tuple[str, str, str, str]] = []
        self.fills = 0  # how many times the rows were rebuilt
        self.itemActivated.connect(self._activated)

    def show_solve(self, outcome: SolveOutcome, graph: Graph) -> bool:
        """Show the messages of ``outcome``'s nodes; the rows are rebuilt only if they
        differ from those shown (a slider drag's solves mostly say the same). True if
        they did."""
        rows = []
        for node_id, record in graph.nodes.items():
            result = outcome.results.get(node_id)
            if result is None:
                continue
            for message in result.messages:
                rows.append((message.level.name.lower(), node_id, record.title, message.text))
        if rows == self.node_rows:
            return False
        self.node_rows = rows
        self._fill()
        return True

    def clear_messages(self) -> None:
        """Forget every row (File ▸ New: the last document's messages do not belong to the new one)."""
        self.app_messages.clear()
        self.node_rows = []
        self._fill()

    def wanted_height(self) -> int:
        """The height that shows every row (at most :data:`ROWS_SHOWN_AT_MOST`) under the header."""
        rows = min(max(self.topLevelItemCount(), 1), ROWS_SHOWN_AT_MOST)
        row_h = self.sizeHintForRow(0) if self.topLevelItemCount() else self.fontMetrics().height() + 6
        return self.header().sizeHint().height() + rows * row_h + 2 * self.frameWidth() + 4

    def add(self, text: str, level: str = "info") -> None:
        self.app_messages.append((time.strftime("%H:%M:%S"), level, text))
        del self.app_messages[:-APP_MESSAGES_KEPT]
        self._fill()

    def _fill(self) -> None:
        self.fills += 1
        self.clear()
        order = {"error": 0, "warning": 1, "remark": 2}
        for level, node_id, title, text in sorted(self.node_rows, key=lambda r: order.get(r[0], 3)):
            item = QTreeWidgetItem([level, f"{title} [{node_id}]", text])
            item.setData(0, Qt.ItemDataRole.UserRole, node_id)
            item.setForeground(0, QBrush(theme.MESSAGE_COLOURS.get(level, theme.NODE_TEXT)))
            item.setToolTip(2, text)
            self.addTopLevelItem(item)
        for stamp, level, text in reversed(self.app_messages):
            item = QTreeWidgetItem([level, "", text])  # the app's own: no node; the time in the tip
            item.setForeground(0, QBrush(theme.MESSAGE_COLOURS.get(level, theme.NODE_TEXT)))
            item.setToolTip(0, stamp)
            item.setToolTip(2, f"{stamp}  {text}")
            self.addTopLevelItem(item)

    def _activated(self, item: QTreeWidgetItem) -> None:
        node_id = item.data(0, Qt.ItemDataRole.UserRole)
        if node_id:
            self.node_activated.emit(node_id)
