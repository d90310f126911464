"""Launch → first solved frame of the flagship, against launch → first frame of an empty
``QMainWindow`` holding a pyvista ``QtInteractor``, in the same run (``make bench``).

Run alone with::

    xvfb-run -a -s "-screen 0 1600x1000x24" .venv/bin/python -m pytest tests/benchmarks/bench_startup.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

The baseline is what any pyvista-in-Qt app pays before it can show a 3D frame (Python,
Qt, pyvista with the matplotlib it imports, VTK, an OpenGL context); Torsal adds its
window, the flagship's node palettes (trimesh, scipy), the solve and the first drawing
of its strips. ``torsal gui`` reports each stage on stderr (``TORSAL_REPORT_STARTUP``,
see :func:`torsal.app.gui.main.launch`); they are printed, so a slow start says where its
time went.

Measured on 5 December 2026 on the 2-core machine shared by eight jobs (load 9.6-10.3),
three rounds: the baseline's first frame 3.79-4.07 s; Torsal's first solved frame
7.34-8.39 s; ratio (median of the rounds) 2.06. Torsal's stages: imports done 1.35-1.53 s,
window shown 1.50-1.69 s, pyvista and VTK set up (the solve running meanwhile on the
worker thread) 6.90-8.07 s, solved 7.22-8.29 s, first frame 7.34-8.39 s. Before this
change the window was shown after 4.6-5.6 s (load 11: the viewport's module, with pyvista
and trimesh behind it, was imported before the first paint) and the solve waited for
VTK. The limit, 2.6, leaves room for the shared machine's noise.

The CPU seconds each process had used at each stage are printed too (user + system, every
thread, from /proc): a figure a loaded machine disturbs far less than time. On 5 December
2026 at load 11-12: Torsal 2.66-2.78 CPU s to its first solved frame, the baseline
1.33-1.44 (ratio 2.00), Torsal's window shown at 0.46-0.49 CPU s and pyvista's interactor
ready at 2.50-2.63 (the palettes' imports, scipy and trimesh, pyvista with matplotlib and
VTK, and the solve on the worker thread in between). On an idle machine the wall time
comes close to the CPU time, so the 2 s bar needs about 0.7 CPU s less than today: more
than all of Torsal's own imports and solve together, which is why it is not met. The issue's bar of 2 s
absolute on a quiet machine could not be measured here: no quiet machine, and the
baseline alone took 3.8 s on this one.
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
CPU_RATIO_LIMIT = 2.0
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
    print(stamp, file=sys.stderr, flush=True)
    app.quit()
plotter.ren_win.AddObserver("EndEvent", rendered)
window.resize(1500, 920)
window.show()
app.exec()
"""


def _stages(command: list[str], env: dict[str, str], cpu: dict[str, float]) -> dict[str, float]:
    """Run ``command`` until it reports its first frame (or 120 s pass); its CPU seconds
    at each stage go to ``cpu``."""
    return stages(command, env, until="first-frame", timeout=120, cpu=cpu)


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
    ratios, ours, baselines, cpu_ratios = [], [], [], []
    torsal_command = [sys.executable, "-m", "torsal.app.cli", "gui", str(FLAGSHIP)]
    baseline_command = [sys.executable, "-c", _BASELINE, str(time.time())]
    with tempfile.TemporaryDirectory() as folder:
        # a first launch of each compiles every module it imports into the bytecode folder
        _stages(baseline_command, _env(folder), {})
        _stages(torsal_command, _env(folder), {})
        for _ in range(ROUNDS):
            baseline_cpu: dict[str, float] = {}
            torsal_cpu: dict[str, float] = {}
            baseline = _stages(baseline_command, _env(folder), baseline_cpu)
            torsal = _stages(torsal_command, _env(folder), torsal_cpu)
            assert "first-frame" in baseline and "first-frame" in torsal, (baseline, torsal)
            print("\n  stages: " + "  ".join(f"{k} {v:.2f} s" for k, v in torsal.items())
                  + f"   (baseline first frame {baseline['first-frame']:.2f} s,"
                  + f" load {os.getloadavg()[0]:.1f})"
                  + "\n  CPU seconds: " + "  ".join(f"{k} {v:.2f}" for k, v in torsal_cpu.items())
                  + f"   (baseline {baseline_cpu['first-frame']:.2f})")
            cpu_ratios.append(torsal_cpu["first-frame"] / baseline_cpu["first-frame"])
            ours.append(torsal["first-frame"])
            baselines.append(baseline["first-frame"])
            ratios.append(torsal["first-frame"] / baseline["first-frame"])
    ratio, cpu_ratio = statistics.median(ratios), statistics.median(cpu_ratios)
    print(f"launch → first solved frame of the flagship {min(ours):.2f} s, empty QtInteractor window "
          f"{min(baselines):.2f} s: ratio {ratio:.2f} (limit {RATIO_LIMIT}); in CPU seconds "
          f"{cpu_ratio:.2f} (limit {CPU_RATIO_LIMIT})")
    assert ratio <= RATIO_LIMIT
    assert cpu_ratio <= CPU_RATIO_LIMIT
