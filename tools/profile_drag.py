"""Where a slider drag's time goes, measured from inside the app (issue "Fluid", item 2).

Run under Xvfb from the repository's root::

    xvfb-run -a -s "-screen 0 1600x1000x24" .venv/bin/python tools/profile_drag.py \
        [--graph FILE] [--strips N] [--rounds 3] [--seconds 2] [--profile] [--render] [--after-flush]

Each round re-solves the graph headless in this process (the bench's edit of its main
slider), then drags the slider in the real window by QTest mouse moves (every 15 ms, as
``tests/app/gui/test_slider_drag_rate.py`` does). Per frame it reports, in ms:

- the worker's solve: wall, its own CPU, its wait for a core (the kernel's run delay,
  ``/proc/self/task/<tid>/schedstat``) and the rest (waiting for the GIL);
- the CPU the process's other threads used during that solve (the GUI thread, llvmpipe's
  rasterisers, others), which on a loaded machine is taken from the solve's share;
- the worker's preparation of the viewport's arrays;
- on the GUI thread: taking the result in (each view's handler), the VTK render, the
  canvas's paints;

and, with ``--profile``, cProfile of the GUI thread over the drag, of the worker over its
solves and of the headless re-solves. The headless re-solve is reported the same way
(wall, CPU, run delay). ``--render`` times renders of the opened graph's preview by
variant of the actors' properties instead of dragging; ``--after-flush`` starts a drag's
next solve a turn of the event loop after the render (once Qt has composed the window)
instead of as the render ends, for an A/B of the pacing.

The drag waits with a ``QEventLoop`` (as ``qtbot.wait``), never ``QTest.qWait``: PySide's
``qWait`` takes the GIL about a thousand times a second (measured: a spinning thread got
60-75 ms of CPU in 0.5 s beside it, 150-210 ms beside ``time.sleep``, with 540-620 GIL
waits against 0), which would put a drag's solve at 2-3x the headless one by itself.
"""

from __future__ import annotations

import argparse
import cProfile
import io
import json
import os
import pstats
import statistics
import sys
import tempfile
import threading
import time
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from PySide6.QtCore import QEventLoop, QPoint, QPointF, Qt, QTimer  # noqa: E402
from PySide6.QtTest import QTest  # noqa: E402
from PySide6.QtWidgets import QApplication, QGraphicsView  # noqa: E402

EXAMPLE = ROOT / "torsal" / "resources" / "examples" / "kaohsiung-stadium.graph"


def thread_stats() -> dict[int, tuple[str, float, float]]:
    """Every thread of this process: its name, CPU seconds and run-queue wait seconds."""
    named = {t.native_id: t.name for t in threading.enumerate()}
    out = {}
    for tid in os.listdir("/proc/self/task"):
        try:
            with open(f"/proc/self/task/{tid}/schedstat") as f:
                cpu, delay, _ = f.read().split()
            with open(f"/proc/self/task/{tid}/comm") as f:
                name = f.read().strip()
        except OSError:
            continue
        name = named.get(int(tid), name).split("-")[0] if int(tid) in named else name
        name = named.get(int(tid), name) if int(tid) in named and "torsal" in named[int(tid)] else name
        out[int(tid)] = (name, int(cpu) / 1e9, int(delay) / 1e9)
    return out


def switches(tid: int) -> int:
    """How many times the thread went to sleep (voluntary context switches: a GIL wait is one)."""
    with open(f"/proc/self/task/{tid}/status") as f:
        for line in f:
            if line.startswith("voluntary_ctxt_switches"):
                return int(line.split()[1])
    return 0


def others_cpu(before: dict, after: dict, me: int) -> dict[str, float]:
    """CPU seconds each kind of thread (by name) used between two snapshots, ``me`` left out."""
    used: dict[str, float] = defaultdict(float)
    for tid, (name, cpu, _) in after.items():
        if tid == me:
            continue
        start = before.get(tid, (name, 0.0, 0.0))[1]
        kind = "gui" if tid == os.getpid() else ("llvmpipe" if name.startswith("llvmpipe") else name)
        used[kind] += cpu - start
    return dict(used)


class Timed:
    """Wraps methods of classes (before the window is made) to time each call."""

    def __init__(self) -> None:
        self.calls: dict[str, list[tuple[float, float]]] = defaultdict(list)  # name -> (start, seconds)
        self.on = False

    def wrap(self, cls: type, name: str, label: str) -> None:
        original = getattr(cls, name)
        calls = self.calls[label]

        def timed(*args, **kwargs):
            start = time.perf_counter()
            try:
                return original(*args, **kwargs)
            finally:
                if self.on:
                    calls.append((start, time.perf_counter() - start))

        timed.__name__ = name
        setattr(cls, name, timed)


def main_slider(graph) -> str:
    """The first number slider the example's description names (as the drag test picks it)."""
    import re

    sliders = {r.label: n for n, r in graph.nodes.items() if r.type_id == "params.NumberSlider"}
    for quoted in re.findall(r"'([^']+)'", str(graph.meta.get("description", ""))):
        if quoted in sliders:
            return sliders[quoted]
    return next(iter(sliders.values()))


def slider_handle(window, node_id: str) -> tuple[QPoint, int, int]:
    item = window.scene.nodes[node_id]
    window.view.centerOn(item)
    rect = item.layout.widget_rect
    track = item.widget.track(rect)
    y = rect.center().y()

    def at(x: float) -> QPoint:
        return window.view.mapFromScene(item.mapToScene(QPointF(x, y)))

    return at(item.widget.handle_x(rect)), at(track.left() + 2).x(), at(track.right() - 2).x()


def wait_ms(ms: int) -> None:
    """Run the event loop for ``ms`` (as pytest-qt's ``qtbot.wait``). Not ``QTest.qWait``:
    PySide's takes the GIL about a thousand times a second, halving a solving thread's CPU."""
    loop = QEventLoop()
    QTimer.singleShot(ms, loop.quit)
    loop.exec()


def wait_idle(window, timeout: float = 120.0) -> None:
    end = time.perf_counter() + timeout
    while not window.doc.solves.idle():
        if time.perf_counter() > end:
            raise TimeoutError("the solve did not finish")
        wait_ms(5)
    QApplication.processEvents()


HEADLESS_PROFILE: list[cProfile.Profile] = []


def headless(path: Path, repeats: int = 7) -> list[tuple[float, float, float, int]]:
    """(wall, CPU, run delay, sleeps) of each headless re-solve after the main slider moves."""
    from torsal.app.headless import run_file

    run = run_file(path)
    me = threading.get_native_id()
    out = []
    for index in range(repeats + 1):
        run.graph.set_setting("scale", "value", 0.70 + 0.005 * index)
        before, sleeps = thread_stats()[me], switches(me)
        start = time.perf_counter()
        for prof in HEADLESS_PROFILE[-1:]:
            prof.enable()
        run.solver.solve()
        for prof in HEADLESS_PROFILE[-1:]:
            prof.disable()
        wall = time.perf_counter() - start
        after = thread_stats()[me]
        if index:
            out.append((wall, after[1] - before[1], after[2] - before[2], switches(me) - sleeps))
    return out


def drag(window, path: Path, seconds: float, timed: Timed, profile: bool) -> dict:
    assert window.open_file(path, ask=False)
    wait_idle(window)
    solves: list[dict] = []
    controller = window.doc.solves
    solver = controller._solver
    original_solve, original_prepare = solver.solve, controller.prepare
    worker_profile = cProfile.Profile() if profile else None

    def solve(*args, **kwargs):
        me = threading.get_native_id()
        sleeps = switches(me)
        before, start = thread_stats(), time.perf_counter()
        if worker_profile is not None:
            worker_profile.enable()
        try:
            return original_solve(*args, **kwargs)
        finally:
            if worker_profile is not None:
                worker_profile.disable()
            wall, after = time.perf_counter() - start, thread_stats()
            solves.append({
                "start": start, "wall": wall,
                "cpu": after[me][1] - before[me][1], "delay": after[me][2] - before[me][2],
                "others": others_cpu(before, after, me),
                "gui_delay": after[os.getpid()][2] - before[os.getpid()][2],
                "sleeps": switches(me) - sleeps,
            })

    def prepare(*args, **kwargs):
        start = time.perf_counter()
        try:
            return original_prepare(*args, **kwargs)
        finally:
            if solves:
                solves[-1]["prepare"] = time.perf_counter() - start

    solver.solve, controller.prepare = solve, prepare
    renders: list[tuple[float, float]] = []
    composed: list[tuple[float, float]] = []  # (wall, GUI CPU) from a render's end to the next turn

    def rendered() -> None:
        renders.append((time.perf_counter(), window.viewport.render_seconds))
        wall, cpu = time.perf_counter(), time.thread_time()
        QTimer.singleShot(0, lambda: composed.append((time.perf_counter() - wall, time.thread_time() - cpu)))

    window.viewport.frame_rendered.connect(rendered)
    slider_id = main_slider(window.doc.graph)
    start_point, left, right = slider_handle(window, slider_id)
    viewport = window.view.viewport()
    for calls in timed.calls.values():
        calls.clear()
    solves.clear()
    frames_before = window.viewport.frames
    gui_profile = cProfile.Profile() if profile else None
    timed.on = True
    gui_before = thread_stats()
    QTest.mousePress(viewport, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier, start_point)
    began = time.perf_counter()
    if gui_profile is not None:
        gui_profile.enable()
    x, step = start_point.x(), 3
    while time.perf_counter() - began < seconds:
        x += step
        if not left <= x <= right:
            step, x = -step, min(max(x, left), right)
        QTest.mouseMove(viewport, QPoint(int(x), start_point.y()))
        wait_ms(15)
    if gui_profile is not None:
        gui_profile.disable()
    elapsed = time.perf_counter() - began
    frames = window.viewport.frames - frames_before
    gui_after = thread_stats()
    timed.on = False
    QTest.mouseRelease(viewport, Qt.MouseButton.LeftButton, Qt.KeyboardModifier.NoModifier,
                       QPoint(int(x), start_point.y()))
    wait_idle(window)
    solver.solve, controller.prepare = original_solve, original_prepare
    solves = [s for s in solves if s["start"] < began + elapsed]
    return {
        "seconds": elapsed, "frames": frames, "solves": solves,
        "calls": {k: [c[1] for c in v if c[0] < began + elapsed] for k, v in timed.calls.items()},
        "renders": [r[1] for r in renders if r[0] < began + elapsed],
        "composed": list(composed),
        "process": others_cpu(gui_before, gui_after, -1),
        "profiles": (gui_profile, worker_profile),
    }


def render_variants(window, path: Path, repeats: int = 12) -> None:
    """Time renders of ``path``'s preview as a drag makes them (every dataset modified), by
    variant of the actors' properties."""
    assert window.open_file(path, ask=False)
    wait_idle(window)
    wait_ms(500)
    preview, plotter = window.viewport.preview, window.viewport.plotter
    entries = [(name, entry.pieces[name], entry.actors[name], entry.datasets[name])
               for entry in preview.nodes.values() for name in entry.actors]
    for name, piece, actor, data in entries:
        print(f"  {name}: {piece.kind}, {data.n_points} points, {data.n_cells} cells, "
              f"visible {actor.GetVisibility()}, line width {actor.prop.line_width}")
    size = plotter.ren_win.GetSize()
    print(f"  render window {size}")

    def timed(label: str) -> None:
        walls, cpus = [], []
        for _ in range(repeats):
            for *_, data in entries:
                data.GetPoints().Modified()
                data.Modified()
            before, start = thread_stats(), time.perf_counter()
            plotter.render()
            walls.append(time.perf_counter() - start)
            after = thread_stats()
            used = others_cpu(before, after, -1)
            cpus.append((used.get("gui", 0.0), used.get("llvmpipe", 0.0)))
            wait_ms(20)
        gui, pipe = (statistics.median(c) for c in zip(*cpus, strict=True))
        print(f"  {label}: render {1000 * statistics.median(walls):.1f} ms wall, CPU GUI {1000 * gui:.1f} "
              f"+ llvmpipe {1000 * pipe:.1f} (load {os.getloadavg()[0]:.1f})")
    for _ in range(2):
        timed("as the app draws")
        lines = [(a, a.prop.line_width) for _, p, a, _ in entries if p.kind in ("curves", "rulings")]
        for a, _ in lines:
            a.prop.line_width = 1.0
        timed("every line 1 px wide")
        for a, w in lines:
            a.prop.line_width = w
        surf = [a for _, p, a, _ in entries if p.kind == "surfaces"]
        for a in surf:
            a.prop.interpolation = "gouraud"
        timed("surfaces Gouraud")
        for a in surf:
            a.prop.interpolation = "phong"
        pts = [a for _, p, a, _ in entries if p.kind == "points"]
        for a in pts:
            a.prop.render_points_as_spheres = False
        timed("points as squares")
        for a in pts:
            a.prop.render_points_as_spheres = True
        from torsal.app.gui import theme

        plotter.set_background(theme.VIEWPORT_BACKGROUND)
        timed("plain background (no gradient)")
        plotter.set_background(theme.VIEWPORT_BACKGROUND, top=theme.VIEWPORT_BACKGROUND_TOP)
        plotter.hide_axes()
        timed("no orientation axes")
        plotter.show_axes()
        grid = plotter.renderer.actors.get("decor:grid")
        if grid is not None:
            grid.SetVisibility(False)
            timed("no ground grid")
            grid.SetVisibility(True)
        hidden = [a for _, p, a, _ in entries if p.kind in ("curves", "rulings", "points")]
        for a in hidden:
            a.SetVisibility(False)
        timed("surfaces only")
        for a in hidden:
            a.SetVisibility(True)


def ms(values) -> str:
    values = list(values)
    if not values:
        return "-"
    return f"{1000 * statistics.median(values):.1f}"


def report(round_no: int, solves_headless, result) -> None:
    hw, hc, hd, hs = (statistics.median(v) for v in zip(*solves_headless, strict=True))
    s = result["solves"]
    print(f"round {round_no}: load {os.getloadavg()[0]:.1f}")
    print(f"  headless re-solve: wall {hw * 1e3:.1f} ms, CPU {hc * 1e3:.1f}, "
          f"run delay {hd * 1e3:.1f}, sleeps {hs:.0f}")
    rate = result["frames"] / result["seconds"]
    print(f"  drag: {result['frames']} frames in {result['seconds']:.2f} s = {rate:.1f}/s; {len(s)} solves")
    if s:
        wall = statistics.median(x["wall"] for x in s)
        print(f"  drag solve: wall {ms(x['wall'] for x in s)} ms ({wall / hw:.2f}x headless), "
              f"CPU {ms(x['cpu'] for x in s)} ({statistics.median(x['cpu'] for x in s) / hc:.2f}x), "
              f"run delay {ms(x['delay'] for x in s)}, "
              f"other wait {ms(x['wall'] - x['cpu'] - x['delay'] for x in s)}; "
              f"prepare {ms(x.get('prepare', 0) for x in s)}")
        sleeps = statistics.median(x["sleeps"] for x in s)
        print(f"  worker's sleeps during each solve (voluntary switches, a GIL wait is one): {sleeps:.0f}")
        print(f"  GUI thread's run delay during each solve: {ms(x['gui_delay'] for x in s)} ms")
        kinds = sorted({k for x in s for k in x["others"]})
        print("  other threads' CPU during each solve (median ms): " + ", ".join(
            f"{k} {ms(x['others'].get(k, 0.0) for x in s)}" for k in kinds))
    print(f"  render (VTK) {ms(result['renders'])} ms x{len(result['renders'])}; from its end to the "
          f"next event-loop turn (Qt composing the window) {ms(c[0] for c in result['composed'])} ms, "
          f"GUI CPU {ms(c[1] for c in result['composed'])}")
    for label, calls in result["calls"].items():
        print(f"  {label}: median {ms(calls)} ms, x{len(calls)}, total {1000 * sum(calls):.0f} ms")
    per = {k: 1000 * v / max(1, result['frames']) for k, v in result["process"].items()}
    print("  process CPU per frame over the drag (ms): "
          + ", ".join(f"{k} {v:.1f}" for k, v in sorted(per.items())))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--graph", type=Path, default=EXAMPLE)
    parser.add_argument("--strips", type=int, default=0, help="set 'Edge points' to this less 4")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--seconds", type=float, default=2.0)
    parser.add_argument("--profile", action="store_true", help="cProfile the last round's drag")
    parser.add_argument("--sort", default="cumulative", help="the profiles' order (pstats)")
    parser.add_argument("--top", type=int, default=45, help="rows of each profile")
    parser.add_argument("--render", action="store_true", help="time renders of the opened graph by variant")
    parser.add_argument("--ab", action="store_true",
                        help="rounds alternate the pacing: as the app, --after-flush")
    parser.add_argument("--ab-repaint", action="store_true",
                        help="rounds alternate: a dragged slider drawn on every move, or as the app does")
    parser.add_argument("--after-flush", action="store_true",
                        help="(experiment) a drag's next solve starts a turn after the render, once composed")
    args = parser.parse_args()
    path = args.graph
    folder = Path(tempfile.mkdtemp(prefix="profile-drag-"))
    if args.strips:
        graph = json.loads(path.read_text(encoding="utf-8"))
        for node in graph["nodes"]:
            if node["id"] == "count":
                node["settings"].update(max=max(400, args.strips), value=args.strips - 4)
        path = folder / f"{path.stem}-{args.strips}.graph"
        path.write_text(json.dumps(graph), encoding="utf-8")

    app = QApplication.instance() or QApplication(sys.argv)
    from torsal.app.gui.canvas.scene import CanvasScene
    from torsal.app.gui.canvas.view import CanvasView
    from torsal.app.gui.inspector import Inspector
    from torsal.app.gui.main_window import MainWindow
    from torsal.app.gui.solve_controller import SolveController
    from torsal.app.gui.viewport.panel import ViewportPanel

    after_flush = [args.after_flush]
    if args.after_flush or args.ab:
        from torsal.app.gui.editor import Editor

        as_render_ends = Editor.frame_shown

        def frame_shown(self) -> None:
            if not after_flush[0]:
                as_render_ends(self)
            elif self._pending_drag is not None:
                self._check_next_value(0)

        Editor.frame_shown = frame_shown
    from torsal.app.gui.canvas import node_item

    busy_interval = node_item.BUSY_WIDGET_INTERVAL_MS
    timed = Timed()
    timed.wrap(SolveController, "_on_worker_done", "GUI takes the result in (all)")
    timed.wrap(ViewportPanel, "_on_results", "  viewport refresh")
    timed.wrap(CanvasScene, "apply_results", "  canvas apply_results")
    timed.wrap(Inspector, "_solved", "  inspector")
    timed.wrap(MainWindow, "_solved", "  window (status, tables)")

    def paint(self, event):
        QGraphicsView.paintEvent(self, event)

    CanvasView.paintEvent = paint
    timed.wrap(CanvasView, "paintEvent", "canvas paint")

    os.environ.setdefault("TORSAL_CONFIG_DIR", str(folder / "config"))
    window = MainWindow(settings_folder=folder / "config")
    window.resize(1500, 920)
    window.show()
    QTest.qWaitForWindowExposed(window)
    window.start(None, offer_recovery=False)
    print(f"GIL switch interval {sys.getswitchinterval() * 1000:.2f} ms; "
          f"next solve after the flush: {args.after_flush}")
    wait_ms(200)
    while window.viewport.plotter is None:
        wait_ms(50)
    if args.render:
        render_variants(window, path)
        args.rounds = 0
    for round_no in range(1, args.rounds + 1):
        if args.ab:
            after_flush[0] = round_no % 2 == 0
            when = "after the flush" if after_flush[0] else "as the render ends"
            print(f"(round {round_no}: the next solve starts {when})")
        if args.ab_repaint:
            node_item.BUSY_WIDGET_INTERVAL_MS = busy_interval if round_no % 2 == 0 else 0
            print(f"(round {round_no}: a dragged slider is drawn at most every "
                  f"{node_item.BUSY_WIDGET_INTERVAL_MS} ms during a solve)")
        if args.profile and round_no == args.rounds:
            HEADLESS_PROFILE.append(cProfile.Profile())
        result_headless = headless(path)
        result = drag(window, path, args.seconds, timed, args.profile and round_no == args.rounds)
        report(round_no, result_headless, result)
    gui_profile, worker_profile = result["profiles"] if args.rounds else (None, None)
    profiles = [("GUI thread over the drag", gui_profile), ("worker over its solves", worker_profile)]
    profiles += [("headless re-solves (7)", prof) for prof in HEADLESS_PROFILE]
    for name, prof in profiles:
        if prof is None:
            continue
        text = io.StringIO()
        pstats.Stats(prof, stream=text).sort_stats(args.sort).print_stats(args.top)
        print(f"\n===== cProfile: {name} =====\n{text.getvalue()}")
    window.doc.solves.cancel()
    window.doc.solves.wait(30)
    window.doc.undo_stack.setClean()
    window.close()
    app.processEvents()


if __name__ == "__main__":
    main()
