"""TrueShape nesting in the app: the rows at once, the true-shape sheets when the
background search has found them, the canvas answering meanwhile, Esc keeping the best
(torsal/app/gui/improvements.py, torsal/engine/improve.py)."""

from __future__ import annotations

import json
import time

from PySide6.QtCore import Qt
from PySide6.QtTest import QTest

from tests.app.gui.test_live_solving import watch_event_loop
from tests.support.fixtures_gui import EXAMPLES, wait_solved
from torsal.nodes.io.formats import cutfiles


def _example(tmp_path, budget: float):  # type: ignore[no-untyped-def]
    """kaohsiung-cut-sheets with Nesting = TrueShape and a small TimeBudget."""
    data = json.loads((EXAMPLES / "kaohsiung-cut-sheets.graph").read_text(encoding="utf-8"))
    (cut,) = [n for n in data["nodes"] if n["id"] == "cut"]
    cut["inputs"]["Nesting"] = {"value": "TrueShape"}
    cut["inputs"]["TimeBudget"] = {"value": budget}
    path = tmp_path / "cut-sheets.graph"
    path.write_text(json.dumps(data), encoding="utf-8")
    return path


def _layout(window):  # type: ignore[no-untyped-def]
    return window.doc.results["cut"].output("Layout").all_items()[0]


def test_rows_at_once_then_the_true_shape_sheets_while_the_canvas_answers(qtbot, window, tmp_path):
    assert window.open_file(_example(tmp_path, 3.0), ask=False)
    wait_solved(qtbot, window, timeout=60000)
    first = _layout(window)
    assert first.nesting == cutfiles.SHELF  # shown at once
    improvements = window.doc.improvements
    assert improvements.running()
    watch = watch_event_loop(qtbot, 1000)  # the search runs; the GUI thread never waits for it
    assert max(watch.gaps[1:]) < 500 and len(watch.gaps) > 20
    with qtbot.waitSignal(improvements.improved, timeout=600000):
        pass
    wait_solved(qtbot, window, timeout=60000)
    better = _layout(window)
    assert better.nesting == cutfiles.TRUE_SHAPE and better.stock_usage > first.stock_usage
    texts = [m.text for m in window.doc.results["cut"].messages]
    assert any(t.startswith("TrueShape nesting: ") for t in texts), texts
    (preview,) = window.doc.results["cut"].output("Preview").all_items()
    assert preview.layout is better  # what the viewport draws now


def test_esc_stops_the_search_and_keeps_its_best(qtbot, window, tmp_path):
    assert window.open_file(_example(tmp_path, 60.0), ask=False)
    wait_solved(qtbot, window, timeout=60000)
    improvements = window.doc.improvements
    assert improvements.running()
    qtbot.wait(1500)
    window.view.setFocus()
    pressed = time.perf_counter()
    QTest.keyClick(window.view, Qt.Key.Key_Escape)
    qtbot.waitUntil(lambda: not improvements.running(), timeout=30000)
    print(f"\nthe search stopped {time.perf_counter() - pressed:.2f} s after Esc")
    wait_solved(qtbot, window, timeout=60000)
    layout = _layout(window)
    assert layout.parts  # the rows, or the best true-shape layout found by then: never nothing
    assert window.doc.results["cut"].state == "ok"
