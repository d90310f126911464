"""Where things sit inside a node: title bar, port rows, inline widget, icon.

Pure geometry (no painting): computed from the node's ports and its inline widget's
size, so painting, hit-testing and wire ends agree.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from PySide6.QtCore import QPointF, QRectF, QSizeF
from PySide6.QtGui import QFontMetricsF

TITLE_H = 20.0
ROW_H = 16.0  # ports 16 px apart: comfortable targets
PAD = 4.0
PORT_R = 4.5
ICON = 22.0
MIN_W = 96.0
MAX_TITLE_W = 220.0


@dataclass
class PortSlot:
    """One port's place: its centre on the node's edge and the rectangle of its label."""

    name: str
    centre: QPointF
    label_rect: QRectF
    text: str = ""


@dataclass
class NodeLayout:
    width: float
    height: float
    title_rect: QRectF
    inputs: list[PortSlot] = field(default_factory=list)
    outputs: list[PortSlot] = field(default_factory=list)
    widget_rect: QRectF | None = None
    icon_rect: QRectF | None = None

    @property
    def rect(self) -> QRectF:
        return QRectF(0.0, 0.0, self.width, self.height)


def compute_layout(
    title: str,
    input_labels: list[tuple[str, str]],
    output_labels: list[tuple[str, str]],
    title_metrics: QFontMetricsF,
    port_metrics: QFontMetricsF,
    widget_size: QSizeF | None = None,
) -> NodeLayout:
    """Lay a node out. Labels are ``(port name, text drawn)`` pairs."""
    in_w = max((port_metrics.horizontalAdvance(t) for _, t in input_labels), default=0.0)
    out_w = max((port_metrics.horizontalAdvance(t) for _, t in output_labels), default=0.0)
    in_col = in_w + PAD * 2 if input_labels else PAD
    out_col = out_w + PAD * 2 if output_labels else PAD
    middle = widget_size.width() if widget_size is not None else ICON + PAD
    title_w = min(title_metrics.horizontalAdvance(title) + PAD * 2 + 14, MAX_TITLE_W)
    width = max(MIN_W, in_col + middle + out_col, title_w)
    rows = max(len(input_labels), len(output_labels), 1)
    body_h = rows * ROW_H
    if widget_size is not None:
        body_h = max(body_h, widget_size.height())
    height = TITLE_H + body_h + PAD * 2
    # centre the middle column in the space the port columns leave
    spare = width - in_col - out_col - middle
    middle_left = in_col + spare / 2
    layout = NodeLayout(width, height, QRectF(0.0, 0.0, width, TITLE_H))
    body_top = TITLE_H + PAD
    if widget_size is not None:
        layout.widget_rect = QRectF(
            middle_left,
            body_top + (body_h - widget_size.height()) / 2,
            widget_size.width(),
            widget_size.height(),
        )
    else:
        layout.icon_rect = QRectF(middle_left + PAD / 2, body_top + (body_h - ICON) / 2, ICON, ICON)
    for slots, labels, left in ((layout.inputs, input_labels, True), (layout.outputs, output_labels, False)):
        offset = (body_h - len(labels) * ROW_H) / 2
        for i, (name, text) in enumerate(labels):
            y = body_top + offset + i * ROW_H + ROW_H / 2
            if left:
                centre = QPointF(0.0, y)
                label = QRectF(PAD, y - ROW_H / 2, in_w + PAD, ROW_H)
            else:
                centre = QPointF(width, y)
                label = QRectF(width - out_w - PAD * 2, y - ROW_H / 2, out_w + PAD, ROW_H)
            slots.append(PortSlot(name, centre, label, text))
    return layout
