"""Launch → first solved frame of the flagship, against launch → first frame of an empty
``QMainWindow`` holding a pyvista ``QtInteractor``, in the same run (``make bench``).

Run alone with::

    xvfb-run -a -s "-screen 0 1600x1000x24" .venv/bin/python -m pytest tests/benchmarks/bench_startup.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

The baseline is what any pyvista-in-Qt app pays before it can show a 3D frame (Python,
Qt, pyvista with the matplotlib.pyplot its ``pyvista.plotting.colors`` imports, VTK, an
OpenGL context), written as such an app usually is: Qt imported first. Torsal adds its
window, the node modules of the flagship's 12 node types (scipy.interpolate, which
imports scipy.spatial, optimize, sparse, linalg and special; Torsal's own modules), the
solve and the first drawing of its strips. It imports the Qt-free part before Qt
(``torsal/app/gui/before_qt.py``: PySide6 reads the source of every module imported after
it, which the baseline pays for pyvista's), keeps the garbage collector off until the first
frame (``torsal/app/gui/collections_policy.py``; the baseline's collector runs, ~0.17 CPU s
of its time) and fills the palette after it. trimesh is not imported on the way (see
``torsal/nodes/geometry/trimesh_type.py``). ``torsal gui`` reports each stage on stderr
(``TORSAL_REPORT_STARTUP``, see :func:`torsal.app.gui.main.launch`) with the wall time, the
process's own CPU seconds (``time.process_time()``, every thread) and the seconds its main
thread waited for a CPU (Linux); they are printed, so a slow start says where its time
went, and launch → first frame less those waits is printed for both sides: close to what
an idle machine takes (a loaded one still slows the CPU seconds themselves, ~10-20 % at
load 10-15 here). Both sides run from compiled bytecode (see :func:`_env`).

Measured on 5 December 2026 on the 2-core machine shared by eight jobs (load 14.5-15.8),
three rounds: Torsal 1.56-1.62 CPU s to its first solved frame, the baseline 1.13-1.25
(ratio 1.29; limit 1.55); window shown at 1.15-1.20 CPU s (after the Qt-free imports),
pyvista's interactor ready at 1.40-1.48, solved +0.11-0.12, first frame +0.03-0.04. Less
the main thread's waits for a CPU: 1.49-1.57 s against 1.15-2.18 s (median 1.56 against
1.25). Wall times 5.26-6.48 s against 3.96-5.91 s (ratio 1.11; limit 2.0), the load
stretching them. The same day, before these changes: 2.25-2.43 CPU s against 1.28-1.42
(ratio 1.67) at load ~8, and in alternating A/B runs at load 10-13, 2.22 against 1.77 CPU
s (median of 4) for the code before and after them.

Where the flagship's CPU seconds go beyond the baseline's: scipy.interpolate ~0.34 (most of
it scipy's own docstring processing at import), the solve and its preview arrays ~0.1,
Torsal's ~190 modules up to the first frame ~0.1, the window, canvas and docks ~0.05; less
the PySide6 source reading and the collections the baseline pays (~0.1 and ~0.17). The
issue's bar, 2 s absolute on a quiet machine, is taken by the lead on a quiet machine; on
this loaded one the figure less the waits for a CPU is ~1.5-1.6 s.

Later the same day (load 7.7-8.8), with shapely no longer imported on the way and the plug-in
entry points scanned once: 1.90-2.57 CPU s against 1.52-1.74 (ratio 1.25), less the waits
1.77-2.52 s against 1.50-1.72. What is still where, each measured alone at load 4-9:
scipy.interpolate and the subpackages it imports 0.51 CPU s (scipy.special ~0.30 of it:
its array-API docstring notes and array_api_compat's copy of numpy's namespace, which
imports numpy.f2py and numpy.testing); the star imports of qtpy under pyvistaqt ~0.20
(every class of QtCore, QtGui and QtWidgets made, ~640 enums; the baseline pays them too,
VTK's own QVTKRenderWindowInteractor imports in 0.035); the viewport's first paint
0.09-0.15 (OpenGL set-up, the gradient background, axes and grid), the solved frame's
0.025-0.04; PySide6 with Torsal's 50 window modules 0.16-0.18, Torsal's node and engine
modules ~0.12; the window, canvas and docks ~0.1; the solve ~0.08. scipy.interpolate is
needed by the solve (the NURBS curves are scipy BSplines).

On 6 December 2026 Torsal's viewport became VTK's own Qt widget with a pyvista plotter of
Torsal's drawing in it (``torsal/app/gui/viewport/interactor.py``), so pyvistaqt and qtpy
are no longer imported on the way (pyvistaqt stays the fallback where Qt gives widgets no
native window: Wayland). The baseline keeps pyvistaqt's QtInteractor: it is what a
pyvista-in-Qt app is usually written with. Window shown → viewport ready 0.36-0.37 CPU s
against 0.50-0.57 before (alternating launches, load ~6); this benchmark at load 9.1-9.4:
Torsal 2.04-2.91 CPU s to its first solved frame against the baseline's 1.83-2.49 (ratio
1.12), less the waits for a CPU 1.95-2.88 s against 1.80-2.48 (medians 2.17 and 2.00).
What is left beyond the baseline is Torsal's own work: scipy.interpolate (~0.45 CPU s, its
imports hold the GIL, so no thread can overlap them), Torsal's ~190 modules, the window,
the solve and the first drawing of the strips.

Issue 28's bar is asserted as such since 6 December 2026 (:data:`QUIET_BAR_S`): the median
over :data:`ROUNDS` rounds of launch -> first solved frame less the main thread's waits for
a CPU, next to the ratios. Where the main thread's CPU seconds went that day (three traced
launches at load ~6.7, ``time.thread_time()`` at each step): Python, the CLI and Torsal's
engine 0.21-0.23; the flagship's node modules with scipy.interpolate (which imports
optimize, special, linalg, sparse, spatial) 0.41-0.42, of which Torsal's own modules
~0.04; ``pyvista.plotting`` 0.75-0.84 (pyvista 0.49's ``plotting/colors.py`` and
``plotting/charts.py`` import ``matplotlib.pyplot`` and the Agg backend at module level:
pyvista's, not Torsal's; the baseline pays it too); PySide6 and the window's modules 0.20;
the window and its first paint 0.06; the file opened and the viewport made 0.19-0.22 (VTK's
widget, pyvista's plotter, the OpenGL context); the empty viewport's paints 0.03-0.04 (they
compile the background's and axes' shaders while the solve runs on its thread, the GIL let
go inside VTK); the solve's results shown and the first frame 0.05. The solve itself takes
0.08-0.09 CPU s on its thread, overlapped. This benchmark that day, less the waits: at load
~5, 2.02-2.54 s (median 2.18) against the baseline's 1.69-1.99 (1.93); at load ~11,
2.26-2.37 (2.27) against 1.79-2.00 (1.92); ratios 1.24 (wall) and 1.23 (CPU) both times.
Tried and of no use: a lazy ``matplotlib.pyplot`` (``importlib.util.LazyLoader``; on
Python 3.11 pyvista's own ``import matplotlib.pyplot`` loads it at once, reading
``__spec__``), ``sys.setdlopenflags(RTLD_LAZY)`` (no change), importing scipy on a thread
beside pyvista (both hold the GIL: wall equals CPU). The empty viewport's paints stay: they
run while the solve does and take the background's and axes' shader compiling off the
solved frame.
Everything on the way is a library's import but ~0.45 s of Torsal's own work (its
modules, window, solve, drawing), so the bar cannot hold by trimming Torsal's imports:
the margin has to come from the second core (the scipy imports and the solve in another
process while this one imports pyvista and Qt).
"""

from __future__ import annotations

import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

import pytest

from tests.app.gui.conftest import unavailable_reason
from tests.app.gui.test_startup import stages

REASON = unavailable_reason()
if REASON:
    pytest.skip(REASON, allow_module_level=True)

ROOT = Path(__file__).resolve().parents[2]
FLAGSHIP = ROOT / "torsal" / "resources" / "examples" / "kaohsiung-stadium.graph"
RATIO_LIMIT = 2.0  # 1.11 measured at load ~15
#: 1.13-1.23 measured on 6 December 2026; ~1.6 with the collector on or Qt imported first again
CPU_RATIO_LIMIT = 1.35
#: issue 28's bar: launch -> the flagship's first solved frame within 2 s on a quiet machine.
#: Asserted on the median of each round's launch -> first frame less the seconds its main
#: thread waited for a CPU (what a quiet machine would take, but for the loaded one's slower
#: CPU seconds; equal to the wall time on an idle machine)
QUIET_BAR_S = 2.0
ROUNDS = 5

#: the baseline: an empty main window with a QtInteractor, timed to its first render
_BASELINE = """
import sys, time
began = float(sys.argv[1])
from PySide6.QtWidgets import QApplication, QMainWindow
from pyvistaqt import QtInteractor
app = QApplication([])
window = QMainWindow()
plotter = QtInteractor(window, auto_update=False, multi_samples=0)
window.setCentralWidget(plotter)
def rendered(*_):
    stamp = f"torsal-startup first-frame {time.time():.4f} {time.process_time():.4f}"
    try:  # as torsal.app.gui.main.waited_for_a_cpu
        with open("/proc/thread-self/schedstat", encoding="ascii") as stat:
            stamp += f" runqueue={int(stat.read().split()[1]) / 1e9:.4f}"
    except (OSError, ValueError, IndexError):
        pass
    print(stamp, file=sys.stderr, flush=True)
    app.quit()
plotter.ren_win.AddObserver("EndEvent", rendered)
window.resize(1500, 920)
window.show()
app.exec()
"""


def _stages(command: list[str], env: dict[str, str], cpu: dict[str, float],
            idle: dict[str, float] | None = None) -> dict[str, float]:
    """Run ``command`` until it reports its first frame (or 120 s pass); its CPU seconds
    at each stage go to ``cpu``, and to ``idle`` the seconds from launch less those its
    main thread spent waiting for a CPU (where the stage's line says: Linux)."""
    notes: dict[str, list[str]] = {}
    stamps = stages(command, env, until="first-frame", timeout=120, cpu=cpu, notes=notes)
    if idle is not None:
        for stage, words in notes.items():
            waits = [float(w.partition("=")[2]) for w in words if w.startswith("runqueue=")]
            if waits and stage in stamps:
                idle[stage] = stamps[stage] - waits[0]
    return stamps


def _env(folder: str) -> dict[str, str]:
    """A child's environment: a fresh settings folder, and the compiled modules kept in
    ``folder`` across launches (an installed Torsal, as every library, runs from the
    bytecode pip compiled at install; a checkout run with ``PYTHONDONTWRITEBYTECODE``
    would compile Torsal's 250 modules from source at every launch, 0.2-0.3 CPU s a user
    never pays)."""
    env = dict(os.environ, TORSAL_REPORT_STARTUP="1", TORSAL_CONFIG_DIR=tempfile.mkdtemp(dir=folder),
               PYTHONPATH=str(ROOT), PYTHONPYCACHEPREFIX=str(Path(folder) / "bytecode"))
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    return env


def test_launch_to_the_flagships_first_solved_frame_against_an_empty_qtinteractor_window():
    ratios, ours, baselines, cpu_ratios, idle_ours, idle_baselines = [], [], [], [], [], []
    torsal_command = [sys.executable, "-m", "torsal.app.cli", "gui", str(FLAGSHIP)]
    baseline_command = [sys.executable, "-c", _BASELINE, str(time.time())]
    with tempfile.TemporaryDirectory() as folder:
        # a first launch of each compiles every module it imports into the bytecode folder
        _stages(baseline_command, _env(folder), {})
        _stages(torsal_command, _env(folder), {})
        for _ in range(ROUNDS):
            baseline_cpu: dict[str, float] = {}
            torsal_cpu: dict[str, float] = {}
            baseline_idle: dict[str, float] = {}
            torsal_idle: dict[str, float] = {}
            baseline = _stages(baseline_command, _env(folder), baseline_cpu, baseline_idle)
            torsal = _stages(torsal_command, _env(folder), torsal_cpu, torsal_idle)
            assert "first-frame" in baseline and "first-frame" in torsal, (baseline, torsal)
            print("\n  stages: " + "  ".join(f"{k} {v:.2f} s" for k, v in torsal.items())
                  + f"   (baseline first frame {baseline['first-frame']:.2f} s,"
                  + f" load {os.getloadavg()[0]:.1f})"
                  + "\n  CPU seconds: " + "  ".join(f"{k} {v:.2f}" for k, v in torsal_cpu.items())
                  + f"   (baseline {baseline_cpu['first-frame']:.2f})")
            if "first-frame" in torsal_idle and "first-frame" in baseline_idle:
                idle_ours.append(torsal_idle["first-frame"])
                idle_baselines.append(baseline_idle["first-frame"])
                print(f"  less the main thread's waits for a CPU: first frame {idle_ours[-1]:.2f} s"
                      f" (baseline {idle_baselines[-1]:.2f} s)")
            cpu_ratios.append(torsal_cpu["first-frame"] / baseline_cpu["first-frame"])
            ours.append(torsal["first-frame"])
            baselines.append(baseline["first-frame"])
            ratios.append(torsal["first-frame"] / baseline["first-frame"])
    ratio, cpu_ratio = statistics.median(ratios), statistics.median(cpu_ratios)
    print(f"launch → first solved frame of the flagship {min(ours):.2f} s, empty QtInteractor window "
          f"{min(baselines):.2f} s: ratio {ratio:.2f} (limit {RATIO_LIMIT}); in CPU seconds "
          f"{cpu_ratio:.2f} (limit {CPU_RATIO_LIMIT})")
    assert len(idle_ours) == ROUNDS, "no /proc/thread-self/schedstat: the quiet-machine figure is unknown"
    quiet, quiet_baseline = statistics.median(idle_ours), statistics.median(idle_baselines)
    print(f"less the waits for a CPU (near an idle machine's time): {quiet:.2f} s, baseline "
          f"{quiet_baseline:.2f} s (medians; rounds {', '.join(f'{s:.2f}' for s in idle_ours)}; "
          f"bar {QUIET_BAR_S} s)")
    assert ratio <= RATIO_LIMIT
    assert cpu_ratio <= CPU_RATIO_LIMIT
    assert quiet <= QUIET_BAR_S, f"first solved frame after {quiet:.2f} s on a quiet machine"
