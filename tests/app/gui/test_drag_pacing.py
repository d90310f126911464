"""A slider drag's solves take turns with the viewport's frames: the next value is solved
once the last result has been drawn, so no solve shares the processor with the views
taking in and rendering the result before it (issue "Fluid", item 2; the timed bars are
in tests/benchmarks/bench_gui.py)."""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import QPoint, Qt
from PySide6.QtTest import QTest

from tests.app.gui.test_slider_drag_rate import drag_main_slider
from tests.support.fixtures_gui import EXAMPLES, FIXTURES, SOLVE_TIMEOUT_MS, slider_handle, wait_solved


def record_drag(qtbot, window, path):
    """Drag the main slider of ``path``; at every solve started while the slider is held
    (after its first, before the release's), whether the viewport showed the results so far
    and had drawn a frame since the last of them arrived (or had none to draw)."""
    starts: list[tuple[bool, bool]] = []
    state = {"held": False, "frames": 0}

    def started() -> None:
        if state["held"] and window.doc.results:
            preview = window.viewport.preview
            shown = all(entry.result is window.doc.results.get(node) for node, entry in preview.nodes.items())
            # drawn since the last result, or that result asked for no frame (it changed
            # nothing the viewport shows)
            drawn = window.viewport.frames > state["frames"] or not window.viewport.frame_due()
            starts.append((shown, drawn))

    def drag_started() -> None:
        state["held"] = True

    window.editor.drag_started.connect(drag_started)
    window.editor.drag_ended.connect(lambda: state.update(held=False))
    window.doc.solves.started.connect(started)
    window.doc.results_changed.connect(lambda _outcome: state.update(frames=window.viewport.frames))
    drag = drag_main_slider(qtbot, window, path)
    # (the first start is the drag's first value; the last may be the release's, which is
    # applied at once by design: see Editor.end_drag)
    return drag, starts[1:-1]


def test_a_drags_next_solve_starts_once_the_viewport_has_drawn_the_last_result(qtbot, window):
    _, starts = record_drag(qtbot, window, EXAMPLES / "kaohsiung-stadium.graph")
    assert len(starts) >= 2
    assert starts == [(True, True)] * len(starts)


def test_with_the_viewport_hidden_a_drag_still_solves_again_and_again(qtbot, window):
    window.viewport_dock.hide()
    qtbot.waitUntil(lambda: not window.viewport.interactor.isVisible())
    drag, starts = record_drag(qtbot, window, FIXTURES / "showcase.graph")
    assert len(starts) >= 4
    assert len(drag.solves) >= 5


def strip_outputs(results) -> tuple[np.ndarray, np.ndarray]:
    """The Kaohsiung strip node's rulings (their ends) and warp angles."""
    outputs = results["strip"].outputs
    ends = np.array([[line.point_at(0.0), line.point_at(1.0)] for line in outputs["Rulings"].all_items()])
    return ends, np.array(outputs["WarpAngles"].all_items(), dtype=float)


def test_a_drag_collapses_to_the_latest_value_and_ends_on_its_solved_outputs(qtbot, window):
    """Moves made while a solve runs are not solved one by one: the latest value waits and
    is solved next (as in Grasshopper), and the drag ends on the last value's outputs, the
    same as a headless solve of that value, shown in the viewport."""
    path = EXAMPLES / "kaohsiung-stadium.graph"
    assert window.open_file(path, ask=False)
    wait_solved(qtbot, window)
    settings = window.doc.graph.nodes["scale"].node.settings
    low, high = settings["min"], settings["max"]
    start, left, right = slider_handle(window, "scale")
    viewport = window.view.viewport()
    starts: list[float] = []
    window.doc.solves.started.connect(lambda: starts.append(settings["value"]))
    QTest.mousePress(viewport, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, start)
    moves = 0
    for x in range(start.x(), left - 20, -4):  # to past the left end, while the first solve runs
        QTest.mouseMove(viewport, QPoint(x, start.y()))
        moves += 1
        qtbot.wait(1)
    qtbot.waitUntil(lambda: settings["value"] == low, timeout=SOLVE_TIMEOUT_MS)  # held there: solved
    for x in range(left - 20, right + 20, 4):  # then past the right end
        QTest.mouseMove(viewport, QPoint(x, start.y()))
        moves += 1
        qtbot.wait(1)
    end = QPoint(right + 20, start.y())
    QTest.mouseRelease(viewport, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, end)
    wait_solved(qtbot, window)
    assert settings["value"] == high  # the handle was let go past the track's right end
    assert low in starts and starts[-1] == high
    assert len(starts) < moves / 4  # latest wins: far fewer solves than values moved through
    assert window.doc.results["scale"].outputs["Value"].all_items() == [high]
    preview = window.viewport.preview
    assert all(entry.result is window.doc.results[node] for node, entry in preview.nodes.items())

    from torsal.app.headless import run_file

    run = run_file(path)  # the same value solved headless, from the file
    run.graph.set_setting("scale", "value", high)
    run.solver.solve()
    shown, headless = strip_outputs(window.doc.results), strip_outputs(run.solver.results)
    np.testing.assert_array_equal(shown[0], headless[0])
    np.testing.assert_array_equal(shown[1], headless[1])
