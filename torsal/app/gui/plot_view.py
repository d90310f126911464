"""The inspector's Plot tab: a chart drawn at the tab's size, or the node's PNG at 1:1 after a click.

A chart node writes a 640 × 400 PNG (the same headless and in the app) and puts the
chart's recipe — its numbers and labels, not its pixels — in the PNG's text
(:mod:`torsal.nodes.common.charts`). The tab draws that recipe again at its own size, so
titles, ticks and labels stay readable in a narrow dock and the axes fill a wide one;
it draws again when the tab is resized (once the resizing pauses). An image without a
recipe (any other PNG a node outputs) is scaled to the tab's width instead, never larger
than drawn. A click toggles the PNG as written, 1:1 pixels (the tab then scrolls), as an
image viewer does.
"""

from __future__ import annotations

from typing import Any

from PySide6.QtCore import QSize, Qt, QTimer
from PySide6.QtGui import QImage, QMouseEvent, QPixmap, QResizeEvent, QShowEvent
from PySide6.QtWidgets import QLabel, QScrollArea, QWidget

#: The smallest chart drawn (a smaller tab scrolls): below it labels would overlap the axes.
MIN_CHART = QSize(280, 160)
#: Resizing waits this long (ms) after the last step before the chart is drawn again.
REDRAW_PAUSE = 120


def chart_image(recipe: dict[str, Any], size: QSize, ratio: float = 1.0) -> QImage:
    """``recipe`` drawn at ``size`` (logical pixels) for a screen of device pixel ``ratio``."""
    from torsal.nodes.common.charts import DPI, render  # matplotlib: only once a chart is shown

    width, height = round(size.width() * ratio), round(size.height() * ratio)
    figure = render(recipe, width, height, DPI * ratio)
    figure.canvas.draw()
    buffer = figure.canvas.buffer_rgba()
    image = QImage(bytes(buffer), width, height, QImage.Format.Format_RGBA8888).copy()
    image.setDevicePixelRatio(ratio)
    return image


class PlotArea(QScrollArea):
    """A scroll area holding a :class:`QLabel` with the chart drawn (or an image scaled) to fit."""

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
        self.recipe: dict[str, Any] | None = None
        self.drawn_size = QSize()  # the size the recipe was last drawn at
        self.actual_size = False  # True: 1:1 pixels (a click toggles)
        self._redraw = QTimer(self)
        self._redraw.setSingleShot(True)
        self._redraw.setInterval(REDRAW_PAUSE)
        self._redraw.timeout.connect(self._update)

    def set_image(self, pixmap: QPixmap, recipe: dict[str, Any] | None = None) -> None:
        """Show ``pixmap``; with its chart's ``recipe``, drawn again at the tab's size."""
        self.original = pixmap
        self.recipe = recipe
        self.drawn_size = QSize()
        if recipe is None or self.isVisible():
            self._update()
        else:  # not laid out yet: drawn when shown, at the size it is shown at
            self.label.setPixmap(QPixmap())

    def clear(self) -> None:
        self.original = QPixmap()
        self.recipe = None
        self.label.clear()

    def set_text(self, text: str) -> None:
        self.original = QPixmap()
        self.recipe = None
        self.label.setText(text)

    def shown_size(self) -> QSize:
        """The size of the pixmap on screen (logical pixels)."""
        pixmap = self.label.pixmap()
        if pixmap is None or pixmap.isNull():
            return QSize()
        return pixmap.deviceIndependentSize().toSize()

    def chart_size(self) -> QSize:
        """The size a chart is drawn at: the room the tab offers, no smaller than
        :data:`MIN_CHART` and no taller than it is wide."""
        room = self.viewport().size() - QSize(2, 2)
        width = max(MIN_CHART.width(), room.width())
        return QSize(width, min(width, max(MIN_CHART.height(), room.height())))

    def _update(self) -> None:
        if self.original.isNull():
            return
        if self.actual_size:
            self.setWidgetResizable(False)
            self.label.setPixmap(self.original)
            self.label.adjustSize()
            self.label.setToolTip("1:1, as written — click to fit the tab")
            return
        self.setWidgetResizable(True)
        if self.recipe is not None:
            size = self.chart_size()
            if size != self.drawn_size:
                self.drawn_size = size
                try:
                    image = chart_image(self.recipe, size, self.devicePixelRatioF())
                except (ValueError, TypeError, OverflowError, RuntimeError, MemoryError):
                    # a recipe matplotlib cannot draw (a title of broken $math$ in a PNG
                    # from elsewhere): show the image as written, scaled, instead
                    self.recipe = None
                    self._update()
                    return
                self.label.setPixmap(QPixmap.fromImage(image))
            self.label.setToolTip("Drawn to fit the tab — click for the image as written, 1:1")
            return
        room = self.viewport().width() - 2
        width = max(1, min(room, self.original.width()))
        scaled = self.original.scaledToWidth(width, Qt.TransformationMode.SmoothTransformation)
        self.label.setPixmap(scaled)
        self.label.setToolTip("Scaled to fit — click for 1:1")

    def showEvent(self, event: QShowEvent) -> None:
        super().showEvent(event)
        if not self.actual_size:
            self._update()

    def resizeEvent(self, event: QResizeEvent) -> None:
        super().resizeEvent(event)
        if self.actual_size:
            return
        if self.recipe is None:
            self._update()
        else:  # a chart is drawn again once the resizing pauses
            self._redraw.start()

    def _clicked(self, event: QMouseEvent) -> None:
        if event.button() == Qt.MouseButton.LeftButton and not self.original.isNull():
            self.actual_size = not self.actual_size
            self.drawn_size = QSize()
            self._update()
