"""The inspector's Plot tab: a chart scaled to the tab's width, or at 1:1 after a click.

A chart a node drew (640 × 400 by default) is wider than a docked inspector; shown unscaled
only a corner of it could be seen. It is shown whole, scaled (smoothly, aspect kept) to
the width the tab offers — never larger than drawn — and a click toggles 1:1 pixels (to
read small labels; the tab then scrolls), as an image viewer does.
"""

from __future__ import annotations

from PySide6.QtCore import QSize, Qt
from PySide6.QtGui import QMouseEvent, QPixmap, QResizeEvent
from PySide6.QtWidgets import QLabel, QScrollArea, QWidget


class PlotArea(QScrollArea):
    """A scroll area holding a :class:`QLabel` whose pixmap follows the area's width."""

    def __init__(self, parent: QWidget | None = None) -> None:
        super().__init__(parent)
        self.label = QLabel()
        self.label.setObjectName("inspector:plot")
        self.label.setAlignment(Qt.AlignmentFlag.AlignHCenter | Qt.AlignmentFlag.AlignTop)
        self.label.setCursor(Qt.CursorShape.PointingHandCursor)
        self.label.mousePressEvent = self._clicked  # type: ignore[method-assign]
        self.setWidget(self.label)
        self.setWidgetResizable(True)
        self.original = QPixmap()
        self.actual_size = False  # True: 1:1 pixels (a click toggles)

    def set_image(self, pixmap: QPixmap) -> None:
        self.original = pixmap
        self._update()

    def clear(self) -> None:
        self.original = QPixmap()
        self.label.clear()

    def set_text(self, text: str) -> None:
        self.original = QPixmap()
        self.label.setText(text)

    def shown_size(self) -> QSize:
        """The size of the pixmap on screen."""
        pixmap = self.label.pixmap()
        return QSize() if pixmap is None or pixmap.isNull() else pixmap.size()

    def _update(self) -> None:
        if self.original.isNull():
            return
        if self.actual_size:
            self.setWidgetResizable(False)
            self.label.setPixmap(self.original)
            self.label.adjustSize()
            self.label.setToolTip("1:1 — click to fit the width")
            return
        self.setWidgetResizable(True)
        room = self.viewport().width() - 2
        width = max(1, min(room, self.original.width()))
        scaled = self.original.scaledToWidth(width, Qt.TransformationMode.SmoothTransformation)
        self.label.setPixmap(scaled)
        self.label.setToolTip("Scaled to fit — click for 1:1")

    def resizeEvent(self, event: QResizeEvent) -> None:
        super().resizeEvent(event)
        if not self.actual_size:
            self._update()

    def _clicked(self, event: QMouseEvent) -> None:
        if event.button() == Qt.MouseButton.LeftButton and not self.original.isNull():
            self.actual_size = not self.actual_size
            self._update()
