"""Processes Torsal starts never pick up the current folder.

A user's folder may hold packages of its own called ``nodes``, ``engine``, ``app`` — or
``torsal``. Torsal is launched here as its console script is (a script outside the folder,
so the folder is not on ``sys.path``), from such a folder whose decoys raise on import: the
true-shape nesting worker (a subprocess started with ``-P``) and a sweep's local dask
workers (spawned processes that take the parent's ``sys.path``) must still import this
Torsal.
"""

from __future__ import annotations

import csv
import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.support.explore_graphs import formula_graph

ROOT = Path(__file__).resolve().parents[2]
DECOYS = ("nodes", "engine", "app", "torsal")

#: What pip's ``torsal`` console script holds (its own folder, not the current one, is on sys.path).
ENTRY = "import sys\nfrom torsal.app.cli import main\nif __name__ == '__main__':\n    sys.exit(main())\n"


@pytest.fixture
def decoy_folder(tmp_path: Path) -> Path:
    folder = tmp_path / "work"
    for name in DECOYS:
        (folder / name).mkdir(parents=True)
        (folder / name / "__init__.py").write_text(
            f"raise ImportError('the decoy {name}/ of the current folder was imported')\n", encoding="utf-8")
    return folder


def _environment() -> dict[str, str]:
    # this checkout's torsal, as an installed one would be found; nothing else on the path
    return {**os.environ, "PYTHONPATH": str(ROOT)}


def _torsal(folder: Path, tmp_path: Path, *args: str) -> subprocess.CompletedProcess[str]:
    script = tmp_path / "bin" / "torsal_entry.py"
    script.parent.mkdir(exist_ok=True)
    script.write_text(ENTRY, encoding="utf-8")
    return subprocess.run([sys.executable, str(script), *args], capture_output=True, text=True, cwd=folder,
                          env=_environment(), timeout=240)


def test_the_decoys_would_be_picked_up_by_a_plain_module_run(decoy_folder):
    """The fixture bites: ``python -m`` from that folder finds the decoy first."""
    done = subprocess.run([sys.executable, "-m", "torsal.nodes.geometry.sparrow_worker"], input="{}",
                          capture_output=True, text=True, cwd=decoy_folder, env=_environment(), timeout=60)
    assert done.returncode != 0
    assert "the decoy torsal/ of the current folder was imported" in done.stderr


def test_the_nesting_worker_ignores_the_current_folder(decoy_folder, tmp_path):
    """Two squares nested true-shape through the sparrow subprocess, from the decoy folder."""
    script = (
        "import numpy as np\n"
        "from torsal.nodes.geometry.nesting import nest\n"
        "square = np.array([[0, 0], [100, 0], [100, 100], [0, 100]], dtype=float)\n"
        "done = nest([square, square + 5], width=400, height=200, margin=10, spacing=10, budget=0.5)\n"
        "print('sheets', done.sheets, 'placed', int((done.sheet >= 0).sum()), 'worked', done.steps > 0)\n"
    )
    done = subprocess.run([sys.executable, "-P", "-c", script], capture_output=True, text=True,
                          cwd=decoy_folder, env=_environment(), timeout=120)
    assert done.returncode == 0, done.stderr[-3000:]
    # 2 squares of 100 mm, 10 mm apart, fit one 380 × 180 mm usable sheet side by side
    # (steps are sparrow's, counted by the worker: it ran)
    assert done.stdout.split() == ["sheets", "1", "placed", "2", "worked", "True"]


def test_a_sweep_on_local_dask_workers_ignores_the_current_folder(decoy_folder, tmp_path):
    graph = formula_graph(tmp_path / "bowl.graph", {"x": (0, 2, 1)}, {"f": "x * x + 1"})
    out = tmp_path / "out"
    done = _torsal(decoy_folder, tmp_path, "sweep", str(graph), "--vary", "x=0:2:3", "--collect", "f.Result",
                   "--out", str(out), "--workers", "1")
    assert done.returncode == 0, done.stderr[-3000:]
    assert "3 variants — 3 solved" in done.stdout
    with (out / "results.csv").open(newline="", encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    solved = [(float(r["in:x"]), float(r["out:f.Result"])) for r in rows]
    assert solved == [(0.0, 1.0), (1.0, 2.0), (2.0, 5.0)]  # x * x + 1
