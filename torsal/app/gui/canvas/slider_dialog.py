"""The slider's edit dialog: value, minimum, maximum and step (decimal places).

When the slider is wired into inputs that declare bounds (``In(..., min=1, max=...)``),
the dialog says so and keeps its value, minimum and maximum within them, so a slider
cannot be set to a value the solver would refuse.
"""

from __future__ import annotations

from typing import Any

from PySide6.QtWidgets import (
    QDialog,
    QDialogButtonBox,
    QDoubleSpinBox,
    QFormLayout,
    QLabel,
    QSpinBox,
    QWidget,
)

from torsal.engine.bounds import bounds_text
from torsal.engine.graph import Graph

BIG = 1e12


class SliderDialog(QDialog):
    """Edit a number or integer slider's settings in one go."""

    def __init__(
        self,
        title: str,
        settings: dict[str, Any],
        integer: bool,
        parent: QWidget | None = None,
        bounds: WiredBounds | None = None,
    ) -> None:
        super().__init__(parent)
        self.setWindowTitle(f"Slider — {title}")
        self.integer = integer
        form = QFormLayout(self)
        decimals = 0 if integer else int(settings.get("decimals", 2) or 0)
        self.bounds = bounds or WiredBounds()
        self.value, self.minimum, self.maximum = (self._box(decimals) for _ in range(3))
        self.minimum.setValue(float(settings.get("min", 0)))
        self.maximum.setValue(float(settings.get("max", 1)))
        self.value.setValue(float(settings.get("value", 0)))
        form.addRow("Value", self.value)
        form.addRow("Minimum", self.minimum)
        form.addRow("Maximum", self.maximum)
        self.takes: QLabel | None = None
        if self.bounds.notes:
            self.takes = QLabel("; ".join(self.bounds.notes))
            self.takes.setWordWrap(True)
            form.addRow("Wired into", self.takes)
        self.decimals: QSpinBox | None = None
        if not integer:
            self.decimals = QSpinBox()
            self.decimals.setRange(0, 15)
            self.decimals.setValue(decimals)
            self.decimals.setToolTip("Step: the slider moves in steps of 10^-decimals")
            self.decimals.valueChanged.connect(self._set_decimals)
            form.addRow("Decimals (step)", self.decimals)
        buttons = QDialogButtonBox(
            QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel
        )
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        form.addRow(buttons)

    def _box(self, decimals: int) -> QDoubleSpinBox:
        box = QDoubleSpinBox()
        low = -BIG if self.bounds.low is None else max(-BIG, float(self.bounds.low))
        high = BIG if self.bounds.high is None else min(BIG, float(self.bounds.high))
        box.setRange(low, max(low, high))
        box.setDecimals(decimals)
        return box

    def _set_decimals(self, decimals: int) -> None:
        for box in (self.value, self.minimum, self.maximum):
            box.setDecimals(decimals)

    def values(self) -> dict[str, Any]:
        if self.integer:
            return {
                "value": int(self.value.value()),
                "min": int(self.minimum.value()),
                "max": int(self.maximum.value()),
            }
        values = {"value": self.value.value(), "min": self.minimum.value(), "max": self.maximum.value()}
        if self.decimals is not None:
            values["decimals"] = self.decimals.value()
        return values


class WiredBounds:
    """The bounds of the inputs a slider feeds: the largest least value, the smallest
    greatest one, and one note per bounded input ("CylindricalSurface.Segments: 1 to 100,000")."""

    def __init__(self, graph: Graph | None = None, node_id: str | None = None) -> None:
        self.low: float | None = None
        self.high: float | None = None
        self.notes: list[str] = []
        if graph is None or node_id is None:
            return
        for wire in graph.wires_from(node_id):
            target = graph.nodes.get(wire.target)
            if target is None:
                continue
            port = next((p for p in target.node.input_ports() if p.name == wire.target_port), None)
            if port is None or (port.min is None and port.max is None):
                continue
            self.notes.append(f"{target.title}.{port.name}: {bounds_text(port)}")
            if port.min is not None:
                self.low = port.min if self.low is None else max(self.low, port.min)
            if port.max is not None:
                self.high = port.max if self.high is None else min(self.high, port.max)


def edit_slider(
    title: str, settings: dict[str, Any], integer: bool, bounds: WiredBounds | None = None
) -> dict[str, Any] | None:
    """Show the dialog; the new settings, or None when cancelled."""
    dialog = SliderDialog(title, settings, integer, bounds=bounds)
    if dialog.exec() == QDialog.DialogCode.Accepted:
        return dialog.values()
    return None
