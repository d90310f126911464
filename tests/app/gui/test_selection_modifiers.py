"""Selection as in Grasshopper, by real mouse events on the canvas viewport: a plain click
or box replaces the selection, Shift adds, Ctrl removes, Ctrl+Shift toggles."""

from __future__ import annotations

from PySide6.QtCore import QPoint, QPointF, Qt
from PySide6.QtTest import QTest

from tests.support.fixtures_gui import drag, title_point, view_point

SHIFT = Qt.KeyboardModifier.ShiftModifier
CTRL = Qt.KeyboardModifier.ControlModifier
NONE = Qt.KeyboardModifier.NoModifier


def click(window, node_id: str, modifiers=NONE) -> None:
    point = title_point(window, node_id)
    QTest.mouseClick(window.view.viewport(), Qt.MouseButton.LeftButton, modifiers, point)


def selected(window) -> set[str]:
    return set(window.scene.selected_node_ids())


def box(window, first: str, last: str, modifiers=NONE) -> None:
    """A box from above-left of ``first`` to below-right of ``last``."""
    nodes = window.scene.nodes
    start = view_point(window, nodes[first].sceneBoundingRect().topLeft() - QPointF(20, 20))
    end = view_point(window, nodes[last].sceneBoundingRect().bottomRight() + QPointF(12, 12))
    drag(window, start, end, modifiers=modifiers)


def test_click_replaces_shift_click_adds_ctrl_click_removes_ctrl_shift_toggles(first_steps):
    window = first_steps
    window.view.centerOn(window.scene.nodes["count"])
    click(window, "width")
    assert selected(window) == {"width"}
    click(window, "count", SHIFT)
    assert selected(window) == {"width", "count"}
    click(window, "count", SHIFT)  # Shift only adds
    assert selected(window) == {"width", "count"}
    click(window, "width", CTRL)
    assert selected(window) == {"count"}
    click(window, "width", CTRL)  # Ctrl only removes
    assert selected(window) == {"count"}
    click(window, "width", CTRL | SHIFT)
    assert selected(window) == {"width", "count"}
    click(window, "count", CTRL | SHIFT)
    assert selected(window) == {"width"}
    click(window, "count")
    assert selected(window) == {"count"}


def test_shift_drag_of_a_node_moves_the_whole_selection(first_steps):
    window = first_steps
    nodes = window.scene.nodes
    window.view.centerOn(nodes["count"])
    click(window, "width")
    start = title_point(window, "count")
    before = {n: nodes[n].pos() for n in ("width", "count")}
    drag(window, start, start + QPoint(40, 30), modifiers=SHIFT)
    assert selected(window) == {"width", "count"}
    for node_id, origin in before.items():
        moved = nodes[node_id].pos() - origin
        assert abs(moved.x() * window.view.zoom() - 40) < 2 and abs(moved.y() * window.view.zoom() - 30) < 2


def test_box_with_shift_adds_with_ctrl_removes_with_both_toggles(first_steps):
    window = first_steps
    window.view.centerOn(window.scene.nodes["count"])
    box(window, "width", "wave")
    inside = {"width", "count", "wave"}
    assert selected(window) == inside
    click(window, "edges")
    assert selected(window) == {"edges"}
    box(window, "width", "wave", SHIFT)
    assert selected(window) == inside | {"edges"}
    box(window, "width", "wave", CTRL)
    assert selected(window) == {"edges"}
    click(window, "width", SHIFT)
    box(window, "width", "wave", CTRL | SHIFT)
    assert selected(window) == {"count", "wave", "edges"}
    box(window, "width", "wave")  # a plain box replaces
    assert selected(window) == inside
