"""Dragging a slider updates the viewport while dragging: measure the rate (frames/s)."""

from __future__ import annotations

import re
import time

from PySide6.QtCore import QPoint, QPointF, Qt
from PySide6.QtTest import QTest

from tests.gui.fixtures_gui import EXAMPLES, FIXTURES, view_point, wait_solved

DRAG_SECONDS = 2.0
MIN_RATE = 10.0


def main_example():
    """The Kaohsiung example when it exists, else the geometry showcase."""
    found = sorted(EXAMPLES.glob("*kaohsiung*.graph"))
    return found[0] if found else FIXTURES / "showcase.graph"


def main_slider(graph) -> str:
    """The first number slider the example's description names ('Inward scale' …), else
    the number slider with the most nodes downstream of it."""
    sliders = {r.label: n for n, r in graph.nodes.items() if r.type_id == "params.NumberSlider"}
    for quoted in re.findall(r"'([^']+)'", str(graph.meta.get("description", ""))):
        if quoted in sliders:
            return sliders[quoted]

    def downstream(node_id: str) -> int:
        seen, stack = set(), [node_id]
        while stack:
            for wire in graph.wires_from(stack.pop()):
                if wire.target not in seen:
                    seen.add(wire.target)
                    stack.append(wire.target)
        return len(seen)

    return max(sliders.values(), key=lambda n: (downstream(n), n))


def test_dragging_the_main_slider_updates_the_viewport_at_least_10_times_a_second(qtbot, window):
    path = main_example()
    assert window.open_file(path, ask=False)
    wait_solved(qtbot, window)
    slider_id = main_slider(window.doc.graph)
    item = window.scene.nodes[slider_id]
    rect = item.layout.widget_rect
    track = item.widget.track(rect)
    y = rect.center().y()
    start = view_point(window, item.mapToScene(QPointF(item.widget.handle_x(rect), y)))
    left = view_point(window, item.mapToScene(QPointF(track.left() + 2, y))).x()
    right = view_point(window, item.mapToScene(QPointF(track.right() - 2, y))).x()
    viewport = window.view.viewport()
    value_before = window.doc.graph.nodes[slider_id].node.settings["value"]
    frames_before, solves = window.viewport.frames, []
    window.doc.results_changed.connect(lambda outcome: solves.append(outcome.report.seconds))

    QTest.mousePress(viewport, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, start)
    began = time.perf_counter()
    x, step = start.x(), 3
    while time.perf_counter() - began < DRAG_SECONDS:
        x += step
        if not left <= x <= right:
            step, x = -step, min(max(x, left), right)
        QTest.mouseMove(viewport, QPoint(int(x), start.y()))
        qtbot.wait(15)
    elapsed = time.perf_counter() - began
    frames = window.viewport.frames - frames_before
    QTest.mouseRelease(
        viewport, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, QPoint(int(x), start.y())
    )
    wait_solved(qtbot, window)

    rate = frames / elapsed
    mean_solve = 1000 * sum(solves) / max(1, len(solves))
    print(
        f"\n{path.name}: dragging {slider_id!r} for {elapsed:.1f} s gave {frames} viewport updates "
        f"({rate:.1f}/s); {len(solves)} solves, mean {mean_solve:.1f} ms; last render "
        f"{window.viewport.render_seconds * 1000:.1f} ms"
    )
    assert window.doc.graph.nodes[slider_id].node.settings["value"] != value_before
    assert window.doc.undo_stack.undoText() == "Set value"
    assert rate >= MIN_RATE
