"""Cluster widgets: the breadcrumb bar above the canvas and the cluster's ports dialog.

The breadcrumb shows where the canvas is ("Document ▸ Panels"); clicking a crumb goes
back out to it, committing the edits made inside (see :meth:`Document.leave_cluster`).
The ports dialog renames a cluster and renames and reorders its inputs and outputs.
"""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import (
    QDialog,
    QDialogButtonBox,
    QFormLayout,
    QGridLayout,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QListWidget,
    QListWidgetItem,
    QPushButton,
    QToolButton,
    QVBoxLayout,
    QWidget,
)

from torsal.app.gui.document import Document

SEPARATOR = "\u25b8"  # ▸


class Breadcrumb(QWidget):
    """"Document ▸ Cluster ▸ …": shown while a cluster definition is edited."""

    def __init__(self, doc: Document, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.doc = doc
        self.setObjectName("clusterBreadcrumb")
        self.setAutoFillBackground(True)
        self.row = QHBoxLayout(self)
        self.row.setContentsMargins(6, 2, 6, 2)
        self.row.setSpacing(2)
        self.crumbs: list[QToolButton] = []
        doc.context_changed.connect(self.refresh)
        self.refresh()

    def refresh(self) -> None:
        while self.row.count():
            item = self.row.takeAt(0)
            if item.widget() is not None:
                item.widget().deleteLater()
        self.crumbs = []
        names = self.doc.breadcrumb
        for depth, name in enumerate(names):
            if depth:
                self.row.addWidget(QLabel(SEPARATOR))
            button = QToolButton()
            button.setText(name)
            button.setAutoRaise(True)
            last = depth == len(names) - 1
            if last:  # where the canvas is: bold, and a click goes nowhere
                font = button.font()
                font.setBold(True)
                button.setFont(font)
                button.setToolTip("The cluster shown (its edits go to every instance when you go back)")
            else:
                button.setToolTip(f"Back to {name} (the edits inside are kept)")
            if not last:
                button.clicked.connect(lambda _=False, d=depth: self.doc.leave_to(d))
            self.row.addWidget(button)
            self.crumbs.append(button)
        self.row.addStretch(1)
        self.setVisible(len(names) > 1)


class ClusterPortsDialog(QDialog):
    """The cluster's name and its inputs and outputs: double-click a port to rename it,
    Up/Down to move it."""

    def __init__(
        self, name: str, inputs: list[str], outputs: list[str], parent: QWidget | None = None
    ) -> None:
        super().__init__(parent)
        self.setWindowTitle("Cluster ports")
        self.setObjectName("clusterPortsDialog")
        layout = QVBoxLayout(self)
        form = QFormLayout()
        self.name = QLineEdit(name)
        form.addRow("Name:", self.name)
        layout.addLayout(form)
        grid = QGridLayout()
        self.lists: dict[str, QListWidget] = {}
        for column, (kind, names) in enumerate((("input", inputs), ("output", outputs))):
            grid.addWidget(QLabel(f"{kind.capitalize()}s"), 0, column * 2)
            box = QListWidget()
            box.setObjectName(f"{kind}s")
            for port in names:
                item = QListWidgetItem(port)
                item.setData(Qt.ItemDataRole.UserRole, port)
                item.setFlags(item.flags() | Qt.ItemFlag.ItemIsEditable)
                box.addItem(item)
            self.lists[kind] = box
            grid.addWidget(box, 1, column * 2)
            buttons = QVBoxLayout()
            for text, step in (("Up", -1), ("Down", 1)):
                button = QPushButton(text)
                button.setObjectName(f"{kind}_{text.lower()}")
                button.clicked.connect(lambda _=False, b=box, s=step: self.move(b, s))
                buttons.addWidget(button)
            buttons.addStretch(1)
            grid.addLayout(buttons, 1, column * 2 + 1)
        layout.addLayout(grid)
        standard = QDialogButtonBox.StandardButton
        box_buttons = QDialogButtonBox(standard.Ok | standard.Cancel)
        box_buttons.accepted.connect(self.accept)
        box_buttons.rejected.connect(self.reject)
        layout.addWidget(box_buttons)

    @staticmethod
    def move(box: QListWidget, step: int) -> None:
        row = box.currentRow()
        target = row + step
        if row < 0 or not 0 <= target < box.count():
            return
        item = box.takeItem(row)
        box.insertItem(target, item)
        box.setCurrentRow(target)

    def ports(self, kind: str) -> list[tuple[str, str]]:
        """``(current name, new name)`` of each port, in the order shown."""
        box = self.lists[kind]
        pairs = []
        for row in range(box.count()):
            item = box.item(row)
            pairs.append((item.data(Qt.ItemDataRole.UserRole), item.text().strip()))
        return pairs
