"""`torsal gui FILE` starts, shows its window and opens the file in a real process.

The time it takes (< 3 s to the first shown window) is a benchmark:
``tests/benchmarks/bench_gui.py``, run by ``make bench``, which calls :func:`start_app`.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
import threading
import time
from pathlib import Path

from tests.support.fixtures_gui import EXAMPLES, ROOT


def start_app(config_folder: Path, until: str = "viewport-ready",
              notes: dict[str, list[str]] | None = None) -> dict[str, float]:
    """Run ``torsal gui`` on an example until it reports the stage ``until`` (or 60 s
    pass); the seconds from launch to each start-up stage it reported (``window-shown``,
    …), and in ``notes`` what each stage's line said after its CPU seconds."""
    env = dict(
        os.environ, TORSAL_REPORT_STARTUP="1", TORSAL_CONFIG_DIR=str(config_folder), PYTHONPATH=str(ROOT)
    )
    command = [sys.executable, "-m", "torsal.app.cli", "gui", str(EXAMPLES / "first-steps.graph")]
    return stages(command, env, until=until, timeout=60, notes=notes)


def stages(command: list[str], env: dict[str, str], until: str, timeout: float,
           cpu: dict[str, float] | None = None,
           notes: dict[str, list[str]] | None = None) -> dict[str, float]:
    """Run ``command`` until it reports the stage ``until`` (or ``timeout`` seconds pass);
    the seconds from launch to each ``torsal-startup STAGE TIME`` line it wrote on stderr.
    With ``cpu``, also the CPU seconds (user + system, every thread) the process had used
    when it reported each stage: a figure a loaded machine disturbs far less than time.
    With ``notes``, the words each stage's line had after those (``collections-held``)."""
    began = time.time()
    child = subprocess.Popen(command, cwd=ROOT, env=env, stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True)
    stamps: dict[str, float] = {}

    def read() -> None:
        for line in child.stderr:
            parts = line.split()
            if len(parts) >= 3 and parts[0] == "torsal-startup":
                stamps[parts[1]] = float(parts[2]) - began
                if cpu is not None:
                    cpu[parts[1]] = float(parts[3]) if len(parts) >= 4 else cpu_seconds(child.pid)
                if notes is not None:
                    notes[parts[1]] = parts[4:]
                if parts[1] == until:
                    return

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    reader.join(timeout=timeout)
    child.terminate()
    child.wait(timeout=10)
    return stamps


def cpu_seconds(pid: int) -> float:
    """The CPU seconds process ``pid`` has used (Linux's /proc; NaN where there is none)."""
    try:
        with open(f"/proc/{pid}/stat") as stat:
            fields = stat.read().rsplit(")", 1)[1].split()
    except OSError:
        return math.nan
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")  # utime + stime


def test_torsal_gui_shows_its_window_and_the_example(tmp_path):
    notes: dict[str, list[str]] = {}
    stamps = start_app(tmp_path, until="started-up", notes=notes)
    assert "window-shown" in stamps, "the app never reported its window"
    assert "viewport-ready" in stamps, "the 3D viewport never became ready"
    print(
        f"\nstart-up: window shown after {stamps['window-shown']:.2f} s, "
        f"3D viewport and example ready after {stamps['viewport-ready']:.2f} s"
    )
    assert 0 < stamps["window-shown"] <= stamps["viewport-ready"]
    # automatic garbage collection is off and the palette's buttons wait until the
    # example's first solved frame is drawn (collections_policy.StartUpCollectionsHeld)
    assert stamps["solved"] <= stamps["first-frame"] <= stamps["started-up"], stamps
    for stage in ("imported", "window-shown", "viewport-ready", "solved", "first-frame"):
        assert notes[stage][:2] == ["collections-held", "palette-waiting"], (stage, notes)
    assert notes["started-up"][:2] == ["collections-on", "palette-filled"]


def test_garbage_collection_resumes_once_start_up_has_used_its_cpu_seconds(tmp_path):
    """However long the first solve: here a limit of 0 CPU seconds is reached at once (and
    the palette is filled then too)."""
    script = (
        "import sys\n"
        "import torsal.app.gui.collections_policy as policy\n"
        "policy.START_UP_LIMIT_S = 0.0\n"
        "from torsal.app.cli import main\n"
        "sys.exit(main(sys.argv[1:]))\n"
    )
    env = dict(os.environ, TORSAL_REPORT_STARTUP="1", TORSAL_CONFIG_DIR=str(tmp_path), PYTHONPATH=str(ROOT))
    notes: dict[str, list[str]] = {}
    command = [sys.executable, "-c", script, "gui", str(EXAMPLES / "first-steps.graph")]
    stamps = stages(command, env, until="first-frame", timeout=60, notes=notes)
    assert stamps["started-up"] < stamps["first-frame"], stamps
    assert notes["first-frame"][:2] == ["collections-on", "palette-filled"]
