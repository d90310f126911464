"""The node palette: one tab per palette (Params, Maths, …), a letter icon per node type.

Click an icon to place the node in the middle of the canvas, or drag it onto the
canvas to place it where it is dropped. A tab's node modules are imported when the tab
is first shown, so starting the app imports only the first palette's.
"""

from __future__ import annotations

from PySide6.QtCore import QByteArray, QMimeData, QPoint, QSize, Qt, Signal
from PySide6.QtGui import QDrag, QMouseEvent
from PySide6.QtWidgets import QHBoxLayout, QLabel, QScrollArea, QTabWidget, QToolButton, QWidget

from torsal.app.gui.canvas.view import NODE_MIME
from torsal.app.gui.icons import node_icon
from torsal.app.gui.theme import PALETTE_TABS
from torsal.engine.node import words
from torsal.engine.registry import Registry

#: The tabs a Grasshopper user expects, in order; other palettes (plug-ins) follow.
TABS = PALETTE_TABS
#: Tab titles that are not the palette's name capitalised
TAB_TITLES = {"io": "IO"}
ICON_SIZE = 30


class NodeButton(QToolButton):
    """A palette entry: click to place, drag to drop on the canvas."""

    def __init__(self, cls: type, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.type_id = cls.type_id
        self.setIcon(node_icon(cls, ICON_SIZE))
        self.setIconSize(QSize(ICON_SIZE, ICON_SIZE))
        self.setAutoRaise(True)
        help_text = cls.help()
        first = help_text.splitlines()[0] if help_text else ""
        nickname = getattr(cls, "nickname", "")
        nick = f" ({nickname})" if nickname else ""
        self.setToolTip(f"<b>{words(cls.name())}</b>{nick} <i>{cls.type_id}</i><br>{first}")
        self.setObjectName(f"palette:{cls.type_id}")
        self._press: QPoint | None = None

    def mousePressEvent(self, event: QMouseEvent) -> None:
        if event.button() == Qt.MouseButton.LeftButton:
            self._press = event.position().toPoint()
        super().mousePressEvent(event)

    def mouseMoveEvent(self, event: QMouseEvent) -> None:
        if self._press is not None and (event.position().toPoint() - self._press).manhattanLength() > 8:
            self._press = None
            self.setDown(False)
            mime = QMimeData()
            mime.setData(NODE_MIME, QByteArray(self.type_id.encode("utf-8")))
            drag = QDrag(self)
            drag.setMimeData(mime)
            drag.setPixmap(self.icon().pixmap(ICON_SIZE, ICON_SIZE))
            drag.exec(Qt.DropAction.CopyAction)
            return
        super().mouseMoveEvent(event)


class Palette(QTabWidget):
    """Tabs of node buttons; emits :attr:`place` with a type id when one is clicked."""

    place = Signal(str)

    def __init__(self, registry: Registry, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.registry = registry
        self.populated = False
        #: the palette of each tab, and the palettes whose tab has its buttons
        self.tab_palettes: list[str] = list(TABS)
        self.filled: set[str] = set()
        self.setDocumentMode(True)
        for palette in TABS:
            title = TAB_TITLES.get(palette, palette.capitalize())
            self.addTab(self._note("Loading the node library…"), title)
        self.setFixedHeight(ICON_SIZE + 46)
        self.currentChanged.connect(self._fill)

    def populate(self) -> None:
        """Set up the tabs (after the window is first shown) and fill the current one; the
        others are filled when first shown, importing only their own palette's modules."""
        if self.populated:
            return
        current = self.currentIndex()
        palettes = self.registry.palettes()
        self.tab_palettes = list(TABS) + [p for p in palettes if p not in TABS]
        self.blockSignals(True)
        try:
            self.clear()
            for palette in self.tab_palettes:
                self.addTab(self._note("Loading…"), TAB_TITLES.get(palette, palette.capitalize()))
            self.setCurrentIndex(max(0, current))
        finally:
            self.blockSignals(False)
        self.populated = True
        self._fill(self.currentIndex())

    def refresh_icons(self) -> None:
        """Draw every button's icon again (nicknames instead of icons turned on or off)."""
        for button in self.findChildren(NodeButton):
            cls = self.registry.get(button.type_id)
            if cls is not None:
                button.setIcon(node_icon(cls, ICON_SIZE))

    def _fill(self, index: int) -> None:
        if not self.populated or not 0 <= index < len(self.tab_palettes):
            return
        palette = self.tab_palettes[index]
        if palette in self.filled:
            return
        self.filled.add(palette)
        title, current = self.tabText(index), self.currentIndex()
        self.blockSignals(True)
        try:
            self.removeTab(index)
            self.insertTab(index, self._tab(self.registry.types_in(palette)), title)
            self.setCurrentIndex(current)
        finally:
            self.blockSignals(False)

    @staticmethod
    def _note(text: str) -> QLabel:
        note = QLabel(text)
        note.setStyleSheet("color: #777; padding-left: 8px;")
        return note

    def _tab(self, classes: list[type]) -> QWidget:
        strip = QWidget()
        layout = QHBoxLayout(strip)
        layout.setContentsMargins(4, 2, 4, 2)
        layout.setSpacing(2)
        for cls in classes:
            button = NodeButton(cls)
            button.clicked.connect(lambda _=False, t=cls.type_id: self.place.emit(t))
            layout.addWidget(button)
        if not classes:
            layout.addWidget(self._note("No nodes in this palette yet."))
        layout.addStretch(1)
        scroll = QScrollArea()
        scroll.setWidget(strip)
        scroll.setWidgetResizable(True)
        scroll.setFrameShape(QScrollArea.Shape.NoFrame)
        scroll.setVerticalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        return scroll
