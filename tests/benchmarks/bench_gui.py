"""The desktop app's timed bars (``make bench``, under Xvfb), measured with the real window.

Run alone with::

    xvfb-run -a -s "-screen 0 1600x1000x24" .venv/bin/python -m pytest tests/benchmarks/bench_gui.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

- ``torsal gui FILE`` shows its window in < 3 s. Since 5 December 2026 the window follows
  the Qt-free imports its first 3D frame needs (``torsal/app/gui/before_qt.py``: pyvista
  with VTK and matplotlib, the file's node modules), which makes that frame ~0.25 CPU s
  sooner and the window later: first-steps' window at 0.90 CPU s (0.35 before), 3.2-4.0 s
  wall at load ~15 on the shared machine, where this absolute bar then fails;
- during a 10 s solve the event loop answers within 100 ms, and Esc stops the solve
  within 0.5 s;
- dragging the main slider of the Kaohsiung example updates the viewport at least 10
  times a second. Its baseline, measured in the same run, is the headless re-solve of
  the same edit of the same graph (today's example, 28 strips) by the version of Torsal
  at the start of issue 10 (commit 1353a06, read from git history:
  :mod:`tests.benchmarks.from_history`): a fixed amount of the solver's kind of work, and
  the same work on both sides. The bar is on the ratio of the GUI's frame interval
  (solving today's roof, previewing, drawing, answering the mouse) to it, and the limit
  says "10 updates a second on the quiet machine": 100 ms over that re-solve's time on
  the quiet machine, :data:`QUIET_SOLVE_S`. Measured on 2 December 2026 (engineer K; the
  2-core machine is shared, so 22 runs of 15-20 re-solves each, each the median of its
  re-solves as here, with the 1-minute load noted): run medians 25.1-121 ms as the load
  went between 1.6 and 4.8; the quietest runs' medians 25.1, 25.4, 26.2, 26.8 ms, the
  fastest single re-solve 23.1 ms.
  So 25 ms, and the limit is 100 ms / 25 ms = 4.0: a frame at most 4 times the
  reference's re-solve is 100 ms or less when the reference takes its quiet 25 ms. (The
  limit before, 2.86, was 100 ms over 35 ms, the reference's re-solve of its own
  20-strip example on the machine of issue 10; on this machine and today's graph it
  asked for 71 ms frames, 14 updates a second, not the bar's 10.) When other jobs slow
  the machine both times grow together and the printed rate falls with them; of
  :data:`DRAGS` rounds (a reference run, today's headless re-solve, a drag) the fastest
  drag is held against the quickest reference run, each side's quietest moment. Today's
  headless re-solve is printed beside it (the share of the frame the solve takes).

- issue "Fluid": dragging the Kaohsiung slider gives at least 25 updates a second with
  the drag's median solve at most 1.2 times the headless re-solve of the same round (so
  nothing of the drag slows the solve), and the flagship with ten times its strips (280)
  at least 5. These are absolute: on the shared 2-core machine at load 8–14 they were not
  met (4.4/s, drag solve 0.79–2.43× headless in wall time, its CPU time 0.97–1.03× the
  headless solve's; 280 strips 0.5/s). Where the drag's extra wall goes is measured by
  ``tools/profile_drag.py``: no GIL waits, the solve's CPU equal to headless, the rest the
  processor share the last frame's composition and the mouse take beside it (see
  docs/architecture.md). On 5 December 2026, nine rounds each at load 10-11.7, alternating
  with the code before: drag solve / headless 0.53-1.80 (median 1.32) against 0.66-1.53
  (median 1.38); 3.5-8.9 updates/s against 3.0-8.0.

The functional side of each (the window appears, the loop ticks, Esc cancels, every
solve of a drag reaches the viewport) is checked by ``make test`` in ``tests/app/gui``.
"""

from __future__ import annotations

import json
import statistics
import subprocess
import sys
import time

import pytest

from tests.app.gui.conftest import unavailable_reason

REASON = unavailable_reason()
if REASON:
    pytest.skip(REASON, allow_module_level=True)


from tests.app.gui.test_live_solving import press_escape, start_long_solve, watch_event_loop  # noqa: E402
from tests.app.gui.test_slider_drag_rate import drag_main_slider  # noqa: E402
from tests.app.gui.test_startup import start_app  # noqa: E402
from tests.benchmarks.from_history import extract_tree  # noqa: E402
from tests.support.fixtures_gui import *  # noqa: E402, F403 - the window, registry and dialog fixtures
from tests.support.fixtures_gui import EXAMPLES, FIXTURES  # noqa: E402
from torsal.app.headless import run_file  # noqa: E402

START_LIMIT_S = 3.0
LOOP_LIMIT_MS = 100.0
ESC_LIMIT_S = 0.5
RATE_LIMIT = 10.0
#: The version whose headless re-solve of today's Kaohsiung example is the drag's baseline.
REFERENCE_COMMIT = "1353a06"
#: That version's re-solve of today's (28-strip) Kaohsiung example on this machine when
#: quiet: the median of its quietest runs (25.1-26.2 ms on 2 December 2026, see above).
QUIET_SOLVE_S = 0.025
#: 10 updates a second when the reference takes its quiet time: 100 ms / 25 ms = 4.0.
FRAME_RATIO_LIMIT = (1 / RATE_LIMIT) / QUIET_SOLVE_S
DRAGS = 3  # the best of three 2 s drags (the machine is shared and noisy)


def test_torsal_gui_shows_its_window_within_3_s(tmp_path):
    stamps = start_app(tmp_path)
    assert "window-shown" in stamps, "the app never reported its window"
    shown, ready = stamps["window-shown"], stamps.get("viewport-ready", float("nan"))
    print(f"\nstart-up: window shown after {shown:.2f} s, 3D viewport and example ready after {ready:.2f} s")
    assert shown < START_LIMIT_S


def test_the_event_loop_answers_within_100_ms_during_a_10_s_solve_and_esc_stops_it_in_half_a_second(
    qtbot, window, registry, tmp_path
):
    start_long_solve(qtbot, window, registry, tmp_path)
    worst = max(watch_event_loop(qtbot).gaps[1:])
    _, stopped_after, outcome = press_escape(qtbot, window)
    print(
        f"\nevent loop: worst gap between 10 ms ticks during the solve {worst:.1f} ms "
        f"(limit {LOOP_LIMIT_MS:.0f}); Esc stopped the solve after {stopped_after * 1000:.0f} ms"
    )
    assert outcome.cancelled
    assert worst < LOOP_LIMIT_MS
    assert stopped_after < ESC_LIMIT_S


def headless_resolve_seconds(repeats: int = 7) -> float:
    """Median headless re-solve of the Kaohsiung example after its 'Inward scale' moves."""
    run = run_file(EXAMPLES / "kaohsiung-stadium.graph")
    times = []
    for index in range(repeats + 1):
        run.graph.set_setting("scale", "value", 0.70 + 0.005 * index)
        start = time.perf_counter()
        run.solver.solve()
        if index:  # the first re-solve warms caches up
            times.append(time.perf_counter() - start)
    return statistics.median(times)


_REFERENCE_SOLVE = """
import os, statistics, sys, time
sys.path.insert(0, sys.argv[1])
if os.path.isdir(os.path.join(sys.argv[1], "torsal")):
    from torsal.app.headless import run_file
else:  # (before commit 6f94a22 the packages were top-level: app, engine, nodes)
    from app.headless import run_file
run = run_file(sys.argv[3])
times = []
for index in range(int(sys.argv[2]) + 1):
    run.graph.set_setting("scale", "value", 0.70 + 0.005 * index)
    start = time.perf_counter()
    run.solver.solve()
    if index:
        times.append(time.perf_counter() - start)
print(statistics.median(times))
"""


def reference_resolve_seconds(tree, repeats: int = 7) -> float:
    """Median headless re-solve of today's Kaohsiung example after its 'Inward scale' moves,
    by the version of :data:`REFERENCE_COMMIT` (its code, in ``tree``), in a subprocess so
    that it imports nothing of today's (that version reads today's graph: the same nodes
    and ports)."""
    graph = EXAMPLES / "kaohsiung-stadium.graph"
    done = subprocess.run(
        [sys.executable, "-c", _REFERENCE_SOLVE, str(tree), str(repeats), str(graph)],
        capture_output=True, text=True, check=True, timeout=300, cwd=tree,  # (not today's torsal)
    )
    return float(done.stdout.split()[-1])


def test_dragging_the_kaohsiung_slider_updates_the_viewport_at_least_10_times_a_second(qtbot, window):
    tree = extract_tree(REFERENCE_COMMIT, ("app", "engine", "nodes"))
    # rounds measured back to back (the machine's load drifts): the reference re-solve,
    # today's headless re-solve, a drag
    runs = []
    for _ in range(DRAGS):
        reference, today = reference_resolve_seconds(tree), headless_resolve_seconds()
        runs.append((reference, today, drag_main_slider(qtbot, window, EXAMPLES / "kaohsiung-stadium.graph")))
    print()
    for reference, today, drag in runs:
        print(
            f"{drag.line('kaohsiung-stadium.graph')}; headless re-solve {today * 1000:.0f} ms, "
            f"the reference's {reference * 1000:.0f} ms"
        )
    # each side at its quickest in the run (the quietest moment the machine gave it): a
    # reference run slowed by a spike of load cannot excuse a slow drag
    reference = min(run[0] for run in runs)
    today = min(run[1] for run in runs)
    best = max((run[2] for run in runs), key=lambda drag: drag.rate)
    ratio = 1 / best.rate / reference
    print(
        f"best: {best.rate:.1f} updates/s (the fastest drag) against the quickest reference re-solve "
        f"of {reference * 1000:.0f} ms ({REFERENCE_COMMIT} on the same graph): the frame interval is "
        f"{ratio:.2f}× the reference (limit {FRAME_RATIO_LIMIT:.2f}); today's quickest headless "
        f"re-solve is {today / reference:.2f}× the reference"
    )
    assert ratio <= FRAME_RATIO_LIMIT


#: Issue "Fluid": the flagship follows a slider at this many updates a second …
FLUID_RATE = 25.0
#: … its solve during the drag at most this many times the headless re-solve …
DRAG_SOLVE_LIMIT = 1.2
#: … and ten times its strips (280) still at this many.
MANY_STRIPS_RATE = 5.0


def test_dragging_the_kaohsiung_slider_updates_25_times_a_second_solving_at_headless_speed(qtbot, window):
    """The bars of issue "Fluid", absolute (the solve and the frame on this machine): of
    :data:`DRAGS` rounds (today's headless re-solve, then a drag), the fastest drag, and
    the round whose drag solved closest to its headless re-solve (the median solve of the
    drag against the median headless re-solve just before it)."""
    runs = []
    for _ in range(DRAGS):
        today = headless_resolve_seconds()
        drag = drag_main_slider(qtbot, window, EXAMPLES / "kaohsiung-stadium.graph")
        runs.append((today, drag, statistics.median(drag.solves)))
    print()
    for today, drag, solve in runs:
        print(f"{drag.line('kaohsiung-stadium.graph')}; the drag's median solve {solve * 1000:.0f} ms, "
              f"{solve / today:.2f}× the headless re-solve ({today * 1000:.0f} ms)")
    best = max((drag for _, drag, _ in runs), key=lambda drag: drag.rate)
    ratio = min(solve / today for today, _, solve in runs)
    print(f"best: {best.rate:.1f} updates/s (bar {FLUID_RATE:.0f}); the drag's solve {ratio:.2f}× headless "
          f"(limit {DRAG_SOLVE_LIMIT})")
    assert ratio <= DRAG_SOLVE_LIMIT
    assert best.rate >= FLUID_RATE


def test_dragging_kaohsiung_with_280_strips_updates_5_times_a_second(qtbot, window, tmp_path):
    """The flagship with 'Edge points' at 276 (280 strips, ten times the file's)."""
    graph = json.loads((EXAMPLES / "kaohsiung-stadium.graph").read_text(encoding="utf-8"))
    for node in graph["nodes"]:
        if node["id"] == "count":
            node["settings"].update(max=400, value=276)
    path = tmp_path / "kaohsiung-280-strips.graph"
    path.write_text(json.dumps(graph), encoding="utf-8")
    best = max((drag_main_slider(qtbot, window, path) for _ in range(DRAGS)), key=lambda drag: drag.rate)
    print(f"\n{best.line(path.name)} (bar {MANY_STRIPS_RATE:.0f}/s)")
    assert best.rate >= MANY_STRIPS_RATE


def test_dragging_a_slider_of_a_cheap_graph_is_bounded_by_the_gui_not_the_solve(qtbot, window):
    drag = drag_main_slider(qtbot, window, FIXTURES / "showcase.graph")
    print("\n" + drag.line("showcase.graph"))
    assert drag.rate >= RATE_LIMIT
