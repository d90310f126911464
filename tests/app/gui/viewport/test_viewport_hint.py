"""The viewport's "Nothing to preview" note waits for results: while the first solve of a
window is on its way it is not shown (nor drawn at once, a frame of nothing before the
first real one); once an empty graph's results are in, it is; geometry hides it."""

from __future__ import annotations

from tests.support.fixtures_gui import EXAMPLES, close_window, make_window, wait_solved

HINT = "decor:hint"


def test_the_hint_waits_for_the_first_results_and_geometry_hides_it(qtbot, registry, config_folder):
    window = make_window(qtbot, registry, config_folder)  # start(): its blank graph's solve requested
    try:
        viewport = window.viewport
        assert not window.doc.solves.idle()
        assert HINT not in viewport.plotter.renderer.actors
        assert viewport.frames == 0  # creating the viewport rendered nothing by itself
        wait_solved(qtbot, window)
        assert HINT in viewport.plotter.renderer.actors  # an empty graph: nothing to preview
        assert window.open_file(EXAMPLES / "paper-strip.graph", ask=False)
        wait_solved(qtbot, window)
        assert viewport.preview.actor_names()
        assert HINT not in viewport.plotter.renderer.actors
    finally:
        close_window(window)
