"""Groups: a coloured, titled box drawn behind the nodes it holds."""

from __future__ import annotations

from PySide6.QtCore import QRectF, Qt
from PySide6.QtGui import QColor, QFontMetricsF, QPainter, QPen
from PySide6.QtWidgets import QGraphicsItem, QGraphicsRectItem, QStyleOptionGraphicsItem, QWidget

from torsal.app.gui import theme

MARGIN = 12.0
TITLE_H = 18.0


class GroupItem(QGraphicsRectItem):
    """Draws one engine :class:`~torsal.engine.graph.Group` around its members' items."""

    def __init__(self, group_id: str) -> None:
        super().__init__()
        self.group_id = group_id
        self.title = ""
        self.colour = QColor("#d8e4f0")
        self._rect = QRectF()
        self.setPen(QPen(Qt.PenStyle.NoPen))
        self.setZValue(-10)
        self.setCacheMode(QGraphicsItem.CacheMode.DeviceCoordinateCache)
        self.font = theme.ui_font(8.5, bold=True)

    def set_content(self, title: str, colour: str, member_rects: list[QRectF]) -> None:
        """Fit the box around ``member_rects`` (scene rectangles of the member nodes)."""
        self.title = title
        self.colour = QColor(colour) if QColor.isValidColorName(colour) else QColor("#d8e4f0")
        if member_rects:
            rect = member_rects[0]
            for other in member_rects[1:]:
                rect = rect.united(other)
            self._rect = rect.adjusted(-MARGIN, -MARGIN - TITLE_H, MARGIN, MARGIN)
        else:
            self._rect = QRectF()
        self.setRect(self._rect.adjusted(-1, -1, 1, 1))
        self.setVisible(bool(member_rects))
        self.update()

    def title_rect(self) -> QRectF:
        return QRectF(self._rect.left(), self._rect.top(), self._rect.width(), TITLE_H)

    def paint(
        self, painter: QPainter, option: QStyleOptionGraphicsItem, widget: QWidget | None = None
    ) -> None:
        if self._rect.isNull():
            return
        painter.setRenderHint(QPainter.RenderHint.Antialiasing)
        fill = QColor(self.colour)
        fill.setAlpha(190)
        painter.setPen(QPen(self.colour.darker(135), 1.2))
        painter.setBrush(fill)
        painter.drawRoundedRect(self._rect, 6, 6)
        painter.setFont(self.font)
        painter.setPen(self.colour.darker(260))
        text_rect = self.title_rect().adjusted(8, 2, -8, 0)
        elided = QFontMetricsF(self.font).elidedText(
            self.title, Qt.TextElideMode.ElideRight, text_rect.width()
        )
        painter.drawText(text_rect, Qt.AlignmentFlag.AlignLeft | Qt.AlignmentFlag.AlignVCenter, elided)
