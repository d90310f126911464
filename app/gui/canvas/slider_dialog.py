"""The slider's edit dialog: value, minimum, maximum and step (decimal places)."""

from __future__ import annotations

from typing import Any

from PySide6.QtWidgets import QDialog, QDialogButtonBox, QDoubleSpinBox, QFormLayout, QSpinBox, QWidget

BIG = 1e12


class SliderDialog(QDialog):
    """Edit a number or integer slider's settings in one go."""

    def __init__(
        self, title: str, settings: dict[str, Any], integer: bool, parent: QWidget | None = None
    ) -> None:
        super().__init__(parent)
        self.setWindowTitle(f"Slider — {title}")
        self.integer = integer
        form = QFormLayout(self)
        decimals = 0 if integer else int(settings.get("decimals", 2) or 0)
        self.value, self.minimum, self.maximum = (self._box(decimals) for _ in range(3))
        self.minimum.setValue(float(settings.get("min", 0)))
        self.maximum.setValue(float(settings.get("max", 1)))
        self.value.setValue(float(settings.get("value", 0)))
        form.addRow("Value", self.value)
        form.addRow("Minimum", self.minimum)
        form.addRow("Maximum", self.maximum)
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
        box.setRange(-BIG, BIG)
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


def edit_slider(title: str, settings: dict[str, Any], integer: bool) -> dict[str, Any] | None:
    """Show the dialog; the new settings, or None when cancelled."""
    dialog = SliderDialog(title, settings, integer)
    if dialog.exec() == QDialog.DialogCode.Accepted:
        return dialog.values()
    return None
