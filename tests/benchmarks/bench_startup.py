"""Launch → first solved frame of the flagship, against launch → first frame of an empty
``QMainWindow`` holding a pyvista ``QtInteractor``, in the same run (``make bench``).

Run alone with::

    xvfb-run -a -s "-screen 0 1600x1000x24" .venv/bin/python -m pytest tests/benchmarks/bench_startup.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

The baseline is what any pyvista-in-Qt app pays before it can show a 3D frame (Python,
Qt, pyvista with the matplotlib.pyplot its ``pyvista.plotting.colors`` imports, VTK, an
OpenGL context); Torsal adds its window, the flagship's node palettes (scipy.interpolate,
which imports scipy.spatial, optimize, sparse, linalg and special; Torsal's own modules),
the solve and the first drawing of its strips. trimesh is not imported on the way (see
``torsal/nodes/geometry/trimesh_type.py``). ``torsal gui`` reports each stage on stderr
(``TORSAL_REPORT_STARTUP``, see :func:`torsal.app.gui.main.launch`) with the wall time and
the process's own CPU seconds (``time.process_time()``, every thread); they are printed, so
a slow start says where its time went. Both sides run from compiled bytecode (see
:func:`_env`).

Measured on 5 December 2026 on the 2-core machine shared by eight jobs (load 7.5-8.3),
three rounds: Torsal 2.25-2.43 CPU s to its first solved frame, the baseline 1.28-1.42
(ratio 1.67; limit 1.85); window shown at 0.41-0.46 CPU s, pyvista's interactor ready (the
palettes, pyvista and VTK imported, the solve running on the worker thread meanwhile) at
2.11-2.30, solved +0.10, first frame +0.03-0.04. Wall times 4.89-6.61 s against
2.65-3.80 s (ratio 1.97; limit 2.6), the load stretching them. Before these changes, in
the same kind of run: 2.51-2.83 CPU s against 1.30-1.46 (ratio 1.94; trimesh and its
scipy.ndimage imported by the palettes), and from source under ``PYTHONDONTWRITEBYTECODE``
2.76-3.05 (2.66-2.78 the session before).

Where the flagship's CPU seconds go beyond the baseline's (~0.95 s), measured in-process:
scipy.interpolate ~0.38, the solve and its preview arrays ~0.10, Torsal's ~240 modules from
bytecode ~0.15, the window, canvas and docks ~0.1, msgspec and shapely ~0.03. The issue's
bar, 2 s absolute on a quiet machine, could not be measured here (no quiet machine); on an
idle machine the wall time comes close to the CPU time, which puts today's start near 2.3 s:
about 0.3 CPU s over the bar with the baseline alone at 1.3, so the bar is not met while
the first frame needs both pyvista (with matplotlib.pyplot, ~0.3 of the baseline) and
scipy.interpolate.
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
RATIO_LIMIT = 2.6
CPU_RATIO_LIMIT = 1.85  # 1.67 measured; 1.94 with trimesh imported again
ROUNDS = 3

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
    if idle_ours:
        print(f"less the waits for a CPU (near an idle machine's time): {statistics.median(idle_ours):.2f} s,"
              f" baseline {statistics.median(idle_baselines):.2f} s (medians)")
    assert ratio <= RATIO_LIMIT
    assert cpu_ratio <= CPU_RATIO_LIMIT
