"""The message log: what every node said in the last solve, and what the app did.

Node messages are grouped by node, as Grasshopper keeps a component's messages in its
balloon: one row per node (its worst level, its title, its first message and how many
more), its messages beneath. Warnings and errors are shown; remarks only on request
(right-click ▸ Show Remarks), and a last row says how many are hidden.
"""

from __future__ import annotations

import time

from PySide6.QtCore import QPoint, Qt, Signal
from PySide6.QtGui import QBrush
from PySide6.QtWidgets import QMenu, QTreeWidget, QTreeWidgetItem, QWidget

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
        self.setRootIsDecorated(True)
        self.setColumnWidth(0, 70)
        self.setColumnWidth(1, 160)
        self.setAlternatingRowColors(True)
        self.setUniformRowHeights(True)
        self.setWordWrap(False)
        self.app_messages: list[tuple[str, str, str]] = []
        self.node_rows: list[tuple[str, str, str, str]] = []
        self.fills = 0  # how many times the rows were rebuilt
        self.show_remarks = False  # remarks are listed only on request
        self.hidden_remarks = 0
        self.itemActivated.connect(self._activated)
        self.setContextMenuPolicy(Qt.ContextMenuPolicy.CustomContextMenu)
        self.customContextMenuRequested.connect(self._menu)

    def set_show_remarks(self, show: bool) -> None:
        """List remarks too (True) or only warnings and errors (False)."""
        if show != self.show_remarks:
            self.show_remarks = show
            self._fill()

    def _menu(self, pos: QPoint) -> None:
        menu = QMenu(self)
        action = menu.addAction("Show Remarks")
        action.setCheckable(True)
        action.setChecked(self.show_remarks)
        action.toggled.connect(self.set_show_remarks)
        menu.exec(self.viewport().mapToGlobal(pos))

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

    def node_groups(self) -> list[tuple[str, str, list[tuple[str, str]]]]:
        """The node rows as shown: ``(node id, title, [(level, text), ...])`` per node, the
        nodes with errors first, then warnings (then remarks, when shown)."""
        order = {"error": 0, "warning": 1, "remark": 2}
        groups: dict[str, tuple[str, list[tuple[str, str]]]] = {}
        for level, node_id, title, text in self.node_rows:
            if level == "remark" and not self.show_remarks:
                continue
            groups.setdefault(node_id, (title, []))[1].append((level, text))
        rows = [(node_id, title, sorted(messages, key=lambda m: order.get(m[0], 3)))
                for node_id, (title, messages) in groups.items()]
        rows.sort(key=lambda row: order.get(row[2][0][0], 3))
        return rows

    def _fill(self) -> None:
        self.fills += 1
        self.clear()
        for node_id, title, messages in self.node_groups():
            level, text = messages[0]
            more = f"  (+{len(messages) - 1} more)" if len(messages) > 1 else ""
            item = QTreeWidgetItem([level, f"{title} [{node_id}]", text + more])
            item.setData(0, Qt.ItemDataRole.UserRole, node_id)
            item.setForeground(0, QBrush(theme.MESSAGE_COLOURS.get(level, theme.NODE_TEXT)))
            item.setToolTip(2, "\n".join(f"{lv}: {tx}" for lv, tx in messages))
            if len(messages) > 1:
                for child_level, child_text in messages:
                    child = QTreeWidgetItem([child_level, "", child_text])
                    child.setData(0, Qt.ItemDataRole.UserRole, node_id)
                    child.setForeground(0, QBrush(theme.MESSAGE_COLOURS.get(child_level, theme.NODE_TEXT)))
                    child.setToolTip(2, child_text)
                    item.addChild(child)
            self.addTopLevelItem(item)
        self.hidden_remarks = 0 if self.show_remarks else sum(r[0] == "remark" for r in self.node_rows)
        if self.hidden_remarks:
            plural = "s" if self.hidden_remarks != 1 else ""
            item = QTreeWidgetItem(["remark", "", f"{self.hidden_remarks} remark{plural} hidden "
                                    "(right-click ▸ Show Remarks, or hover a node's balloon)"])
            item.setForeground(0, QBrush(theme.MESSAGE_COLOURS.get("remark", theme.NODE_TEXT)))
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
