"""A wire dropped on empty canvas lists the likeliest nodes first, the first preselected:
nodes whose first input takes the wire's type exactly, then by a cast, then those taking
it on another input — driven by a real drag on the canvas viewport."""

from __future__ import annotations

from PySide6.QtCore import QPoint, Qt
from PySide6.QtTest import QTest

from tests.support.fixtures_gui import drag, port_point
from torsal.engine.types import can_cast, get_type


def empty_spot(window) -> QPoint:
    rect = window.view.viewport().rect()
    for x in range(rect.width() - 30, 30, -40):
        for y in range(rect.height() - 30, 30, -40):
            if window.view.itemAt(QPoint(x, y)) is None:
                return QPoint(x, y)
    raise AssertionError("no empty spot on the canvas")


def listed(window) -> list[str]:
    rows = window.popup.list
    return [rows.item(i).data(Qt.ItemDataRole.UserRole) for i in range(rows.count())]


def tier(type_id: str, registry, value_type) -> int:
    """0: the first input takes the type exactly; 1: by a cast; 2: another input exactly; 3: by a cast."""
    inputs = registry.get(type_id).inputs
    if inputs and inputs[0].type is value_type:
        return 0
    if inputs and can_cast(value_type, inputs[0].type):
        return 1
    return 2 if any(p.type is value_type for p in inputs) else 3


def test_a_dropped_number_wire_lists_nodes_fed_first_by_a_number_first_and_preselects_one(qtbot, first_steps):
    window = first_steps
    drag(window, port_point(window, "width", "Value", False), empty_spot(window))
    qtbot.waitUntil(window.popup.isVisible, timeout=3000)
    rows = listed(window)
    QTest.keyClick(window.popup.query, Qt.Key.Key_Escape)
    number = get_type("Number")
    tiers = [tier(type_id, window.registry, number) for type_id in rows]
    assert tiers == sorted(tiers), list(zip(rows, tiers, strict=True))[:12]
    assert tiers[0] == 0 and window.popup.list.currentRow() == 0
    assert "analysis.BendingCheck" not in rows[:10]
