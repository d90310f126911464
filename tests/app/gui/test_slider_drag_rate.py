"""Dragging a slider updates the viewport while dragging; the rate is printed (frames/s).

Two drags: the geometry showcase, where solving is cheap, and the Kaohsiung example. A
drag never cancels a solve, so the viewport changes once per solve (plus partial results
for long solves); the tests check that every solve that finishes during the drag reaches
the viewport and the whole drag is one undo step. The rate itself (at least 10 updates a
second) is a benchmark: ``tests/benchmarks/bench_gui.py``, run by ``make bench``.
"""

from __future__ import annotations

import re
import time
from dataclasses import dataclass

from PySide6.QtCore import QPoint, Qt
from PySide6.QtTest import QTest

from tests.support.fixtures_gui import EXAMPLES, FIXTURES, downstream_of, slider_handle, wait_solved

DRAG_SECONDS = 2.0


def main_slider(graph) -> str:
    """The first number slider the example's description names ('Inward scale' …), else
    the number slider with the most nodes downstream of it."""
    sliders = {r.label: n for n, r in graph.nodes.items() if r.type_id == "params.NumberSlider"}
    for quoted in re.findall(r"'([^']+)'", str(graph.meta.get("description", ""))):
        if quoted in sliders:
            return sliders[quoted]

    def downstream(node_id: str) -> int:
        return len(downstream_of(graph, node_id))

    return max(sliders.values(), key=lambda n: (downstream(n), n))


@dataclass
class Drag:
    slider: str
    seconds: float
    frames: int
    solves: list[float]
    partials: int

    @property
    def rate(self) -> float:
        return self.frames / self.seconds

    def line(self, name: str) -> str:
        mean = 1000 * sum(self.solves) / max(1, len(self.solves))
        return (
            f"{name}: dragging {self.slider!r} for {self.seconds:.1f} s gave {self.frames} viewport "
            f"updates ({self.rate:.1f}/s); {len(self.solves)} solves (mean {mean:.0f} ms), "
            f"{self.partials} partial updates"
        )


def drag_main_slider(qtbot, window, path) -> Drag:
    """Open ``path`` and drag its main slider back and forth for :data:`DRAG_SECONDS`."""
    assert window.open_file(path, ask=False)
    wait_solved(qtbot, window)
    slider_id = main_slider(window.doc.graph)
    start, left, right = slider_handle(window, slider_id)
    viewport = window.view.viewport()
    value_before = window.doc.graph.nodes[slider_id].node.settings["value"]
    solves: list[float] = []
    partials: list[object] = []
    unshown: list[str] = []

    def solved(outcome) -> None:  # connected after the viewport: it has had its turn
        if outcome.report.solved:
            solves.append(outcome.report.seconds)
        preview = window.viewport.preview
        unshown.extend(n for n, entry in preview.nodes.items() if entry.result is not outcome.results.get(n))

    window.doc.results_changed.connect(solved)
    window.doc.solves.partial.connect(partials.append)
    frames_before = window.viewport.frames

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
    solved = list(solves)
    QTest.mouseRelease(
        viewport, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, QPoint(int(x), start.y())
    )
    wait_solved(qtbot, window)
    assert window.doc.graph.nodes[slider_id].node.settings["value"] != value_before
    assert window.doc.undo_stack.undoText().startswith("Set value of ")  # the drag: one undo step
    assert not unshown, f"results not shown in the viewport: {unshown}"
    return Drag(slider_id, elapsed, frames, solved, len(partials))


def test_dragging_a_slider_updates_the_viewport_with_every_solve(qtbot, window):
    drag = drag_main_slider(qtbot, window, FIXTURES / "showcase.graph")
    print("\n" + drag.line("showcase.graph"))
    assert len(drag.solves) >= 5 and drag.frames >= 5


def test_dragging_the_kaohsiung_slider_shows_every_solve_while_dragging(qtbot, window):
    path = EXAMPLES / "kaohsiung-stadium.graph"
    if not path.exists():
        import pytest

        pytest.skip("the Kaohsiung example is not in torsal/resources/examples")
    drag = drag_main_slider(qtbot, window, path)
    print("\n" + drag.line(path.name))
    assert len(drag.solves) >= 3  # it solved again and again while dragging (and each
    assert drag.frames >= 3  # solve's result reached the viewport: checked in the drag)
