"""A slider drag's solves take turns with the viewport's frames: the next value is solved
once the last result has been drawn, so no solve shares the processor with the views
taking in and rendering the result before it (issue "Fluid", item 2; the timed bars are
in tests/benchmarks/bench_gui.py)."""

from __future__ import annotations

from tests.app.gui.test_slider_drag_rate import drag_main_slider
from tests.support.fixtures_gui import EXAMPLES, FIXTURES


def record_drag(qtbot, window, path):
    """Drag the main slider of ``path``; at every solve started while the slider is held
    (after its first), whether the viewport showed the results so far and had drawn a
    frame since the last of them arrived."""
    starts: list[tuple[bool, bool]] = []
    state = {"held": False, "frames": 0}

    def started() -> None:
        if state["held"] and window.doc.results:
            preview = window.viewport.preview
            shown = all(entry.result is window.doc.results.get(node) for node, entry in preview.nodes.items())
            starts.append((shown, window.viewport.frames > state["frames"]))

    def drag_started() -> None:
        state["held"] = True

    window.editor.drag_started.connect(drag_started)
    window.editor.drag_ended.connect(lambda: state.update(held=False))
    window.doc.solves.started.connect(started)
    window.doc.results_changed.connect(lambda _outcome: state.update(frames=window.viewport.frames))
    drag = drag_main_slider(qtbot, window, path)
    return drag, starts[1:]


def test_a_drags_next_solve_starts_once_the_viewport_has_drawn_the_last_result(qtbot, window):
    _, starts = record_drag(qtbot, window, EXAMPLES / "kaohsiung-stadium.graph")
    assert len(starts) >= 2
    assert starts == [(True, True)] * len(starts)


def test_with_the_viewport_hidden_a_drag_still_solves_again_and_again(qtbot, window):
    window.viewport_dock.hide()
    qtbot.waitUntil(lambda: not window.viewport.plotter.isVisible())
    drag, starts = record_drag(qtbot, window, FIXTURES / "showcase.graph")
    assert len(starts) >= 4
    assert len(drag.solves) >= 5
