"""The profiler dock: solve time per node, slowest first; filled when shown."""

from __future__ import annotations

from tests.support.fixtures_gui import EXAMPLES, wait_solved


def test_the_profiler_lists_every_node_slowest_first_once_it_is_shown(qtbot, window):
    assert window.open_file(EXAMPLES / "kaohsiung-stadium.graph", ask=False)
    wait_solved(qtbot, window)
    profiler = window.profiler
    window.log_dock.raise_()
    qtbot.waitUntil(lambda: profiler.visibleRegion().isEmpty(), timeout=2000)
    profiler.setRowCount(0)
    window.editor.set_setting("scale", "value", 0.65)
    wait_solved(qtbot, window)
    qtbot.wait(300)  # the tables' refresh is throttled to 5 a second
    assert profiler.rowCount() == 0  # behind the Messages tab: not refilled while hidden
    window.profiler_dock.raise_()
    qtbot.waitUntil(lambda: not profiler.visibleRegion().isEmpty(), timeout=2000)
    qtbot.waitUntil(lambda: profiler.rowCount() == len(window.doc.graph.nodes), timeout=2000)
    milliseconds = [float(profiler.item(row, 3).text()) for row in range(profiler.rowCount())]
    assert milliseconds == sorted(milliseconds, reverse=True)
    # the slowest node first (the developable strips, mostly; which one is a matter of timing)
    results = window.doc.results
    slowest = max(results, key=lambda node_id: results[node_id].seconds)
    assert profiler.item(0, 0).text().endswith(f"[{slowest}]")
    assert milliseconds[0] == round(results[slowest].seconds * 1000, 2)

    window.editor.set_setting("scale", "value", 0.6)  # a new solve refills the shown profiler
    wait_solved(qtbot, window)
    qtbot.waitUntil(
        lambda: float(profiler.item(0, 3).text())
        == round(max(r.seconds for r in window.doc.results.values()) * 1000, 2),
        timeout=2000,
    )
