"""The search popup: type a few letters, press Enter, the node is placed.

Opened by a double-click on empty canvas, or by dropping a wire on empty canvas (then
only nodes that can take, or give, the wire's type are listed). A typed number (``6``) or
range (``0<6<10``) lists a slider set to it first. The popup is kept inside the window.
"""

from __future__ import annotations

from collections.abc import Callable

from PySide6.QtCore import QEvent, QObject, QPoint, QRect, QSize, Qt, Signal
from PySide6.QtGui import QGuiApplication
from PySide6.QtWidgets import QFrame, QLabel, QLineEdit, QListWidget, QListWidgetItem, QVBoxLayout, QWidget

from torsal.app.gui.fuzzy import Entry, build_entries, search, slider_settings
from torsal.app.gui.icons import node_icon
from torsal.engine.registry import Registry


class SearchPopup(QFrame):
    """A frameless popup with a query line and the matching node types."""

    chosen = Signal(str, object)  # type_id, the settings to give it (None: its defaults)
    dismissed = Signal()

    def __init__(self, registry: Registry, parent: QWidget | None = None) -> None:
        super().__init__(parent, Qt.WindowType.Popup)
        self.setFrameShape(QFrame.Shape.StyledPanel)
        self.setObjectName("searchPopup")
        self.registry = registry
        self._entries: list[Entry] | None = None
        self.accept: Callable[[Entry], bool] | None = None
        self.rank: Callable[[Entry], tuple] | None = None
        self._chose = False
        layout = QVBoxLayout(self)
        layout.setContentsMargins(4, 4, 4, 4)
        layout.setSpacing(3)
        self.query = QLineEdit()
        self.query.setPlaceholderText("Search nodes by name, nickname, Grasshopper name or description…")
        self.note = QLabel()
        self.note.setStyleSheet("color: #555; font-size: 8pt;")
        self.list = QListWidget()
        self.list.setIconSize(QSize(20, 20))
        self.list.setUniformItemSizes(True)
        layout.addWidget(self.query)
        layout.addWidget(self.note)
        layout.addWidget(self.list)
        self.resize(380, 320)
        self.query.textChanged.connect(self.refresh)
        self.query.installEventFilter(self)
        self.list.itemActivated.connect(lambda _item: self.choose())

    @property
    def entries(self) -> list[Entry]:
        """The catalogue, read when first searched (listing it imports every palette)."""
        if self._entries is None:
            self._entries = build_entries(list(self.registry))
        return self._entries

    def open_at(
        self,
        global_pos: QPoint,
        accept: Callable[[Entry], bool] | None = None,
        note: str = "",
        rank: Callable[[Entry], tuple] | None = None,
    ) -> None:
        """Show at ``global_pos`` listing the entries ``accept`` lets through, ordered by
        ``rank`` where the typed text does not decide (the likeliest preselected)."""
        self.accept = accept
        self.rank = rank
        self._chose = False
        self.note.setText(note)
        self.note.setVisible(bool(note))
        self.query.clear()
        self.refresh()
        self.move(self.inside_window(global_pos))
        self.show()
        self.raise_()
        self.activateWindow()
        self.query.setFocus()

    def inside_window(self, global_pos: QPoint) -> QPoint:
        """Where to put the popup's top-left so all of it lies inside the main window (and the
        screen): moved left and up from ``global_pos`` as far as needed."""
        parent = self.parentWidget()
        if parent is not None:
            window = parent.window()
            bounds = QRect(window.mapToGlobal(QPoint(0, 0)), window.size())
        else:
            bounds = QRect()
        screen = QGuiApplication.screenAt(global_pos) or QGuiApplication.primaryScreen()
        if screen is not None:
            bounds = bounds.intersected(screen.availableGeometry()) if bounds.isValid() else (
                screen.availableGeometry()
            )
        if not bounds.isValid():
            return global_pos
        x = max(bounds.left(), min(global_pos.x(), bounds.right() + 1 - self.width()))
        y = max(bounds.top(), min(global_pos.y(), bounds.bottom() + 1 - self.height()))
        return QPoint(x, y)

    def refresh(self) -> None:
        self.list.clear()
        slider = slider_settings(self.query.text())
        if slider is not None and self._accepts("params.NumberSlider"):
            text = f"Number slider = {self.query.text().strip()}   ·  {slider['min']:g} to {slider['max']:g}"
            item = QListWidgetItem(text)
            item.setToolTip("A NumberSlider set to the typed value (type lo<value<hi to set its range)")
            item.setData(Qt.ItemDataRole.UserRole, "params.NumberSlider")
            item.setData(Qt.ItemDataRole.UserRole + 1, slider)
            self.list.addItem(item)
        for entry in search(self.entries, self.query.text(), self.accept, rank=self.rank):
            first_line = entry.description.splitlines()[0] if entry.description else ""
            label = f"{entry.title}  ({entry.nickname})   ·  {entry.palette}"
            item = QListWidgetItem(node_icon(entry.cls, 20), label)
            item.setToolTip(f"{entry.type_id}\n{first_line}")
            item.setData(Qt.ItemDataRole.UserRole, entry.type_id)
            self.list.addItem(item)
        if self.list.count():
            self.list.setCurrentRow(0)

    def choose(self) -> None:
        item = self.list.currentItem()
        if item is None:
            return
        self._chose = True
        type_id = item.data(Qt.ItemDataRole.UserRole)
        settings = item.data(Qt.ItemDataRole.UserRole + 1)
        self.hide()
        self.chosen.emit(type_id, settings)

    def _accepts(self, type_id: str) -> bool:
        if self.accept is None:
            return True
        entry = next((e for e in self.entries if e.type_id == type_id), None)
        return entry is not None and bool(self.accept(entry))

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:
        if watched is self.query and event.type() == QEvent.Type.KeyPress:
            key = event.key()
            if key in (Qt.Key.Key_Return, Qt.Key.Key_Enter):
                self.choose()
                return True
            if key in (Qt.Key.Key_Down, Qt.Key.Key_Up):
                step = 1 if key == Qt.Key.Key_Down else -1
                row = max(0, min(self.list.count() - 1, self.list.currentRow() + step))
                self.list.setCurrentRow(row)
                return True
            if key == Qt.Key.Key_Escape:
                self.hide()
                return True
        return super().eventFilter(watched, event)

    def hideEvent(self, event: QEvent) -> None:
        super().hideEvent(event)
        if not self._chose:
            self.dismissed.emit()
