"""``torsal run`` in a terminal shows a long node's progress on stderr (a real
pseudo-terminal, as a user's shell gives it: rich's live line); piped, a heartbeat line
every few seconds of long work (torsal/app/progress.py)."""

from __future__ import annotations

import os
import pty
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
GRAPH = ROOT / "torsal" / "resources" / "examples" / "kaohsiung-cut-sheets.graph"
NESTING = ["--set", "cut.Nesting=TrueShape", "--set", "cut.TimeBudget=2"]

pytest.importorskip("spyrrow")


def read_all(fd: int) -> str:
    chunks = []
    while True:
        try:
            data = os.read(fd, 4096)
        except OSError:  # the other end closed
            break
        if not data:
            break
        chunks.append(data)
    return b"".join(chunks).decode(errors="replace")


ANSI = re.compile(r"\x1b\[[0-9;?]*[A-Za-z]")


def test_run_in_a_pseudo_terminal_shows_a_live_line_with_percent_elapsed_and_time_left():
    leader, follower = pty.openpty()
    done = subprocess.run(
        [sys.executable, "-m", "torsal.app.cli", "run", str(GRAPH), *NESTING],
        stdout=subprocess.PIPE, stderr=follower, cwd=ROOT, timeout=300, check=False,
    )
    os.close(follower)
    err = read_all(leader)
    os.close(leader)
    assert done.returncode == 0, err
    shown = [ANSI.sub("", part).strip() for part in err.replace("\r", "\n").split("\n")]
    lines = [line for line in shown if line.startswith("cut ")]
    assert len(lines) >= 2, err  # redrawn as it goes
    # the node, its percent, the time taken (h:mm:ss) and the time left: rich's columns
    columns = re.compile(r"cut\s.*\d+%\s+\d:\d\d:\d\d left (\d:\d\d:\d\d|-:--:--)")
    assert all(columns.fullmatch(line) for line in lines), lines
    assert "100%" in lines[-1], lines[-1]


def _piped(*extra: str, heartbeat: str | None = None) -> subprocess.CompletedProcess[str]:
    env = {k: v for k, v in os.environ.items() if k != "TORSAL_HEARTBEAT"}
    if heartbeat is not None:
        env["TORSAL_HEARTBEAT"] = heartbeat
    return subprocess.run([sys.executable, "-m", "torsal.app.cli", "run", *extra], capture_output=True,
                          text=True, cwd=ROOT, timeout=300, check=False, env=env)


def test_piped_stderr_gets_a_heartbeat_line_every_few_seconds_of_long_work():
    """Off a terminal: a plain line every period (0.3 s here, 5 s by default) once work has
    lasted that long, naming the node, its percent and the time it has taken."""
    done = _piped(str(GRAPH), *NESTING, heartbeat="0.3")
    assert done.returncode == 0, done.stderr
    beats = [line for line in done.stderr.splitlines() if line.startswith("torsal: ")
             and ("after" in line)]
    assert len(beats) >= 2, done.stderr
    assert any(re.fullmatch(r"torsal: cut \d+ % after \d+ s(, about \d+ s left)?", b) for b in beats), beats
    assert "\r" not in done.stderr and "\x1b" not in done.stderr  # no terminal codes in a log


def test_piped_stderr_stays_quiet_for_work_shorter_than_five_seconds():
    done = _piped(str(ROOT / "torsal" / "resources" / "examples" / "first-steps.graph"))
    assert done.returncode == 0, done.stderr
    assert "after" not in done.stderr and "%" not in done.stderr
