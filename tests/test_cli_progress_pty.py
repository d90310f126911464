"""``torsal run`` in a terminal shows a long node's progress on stderr (a real
pseudo-terminal, as a user's shell gives it; piped stderr stays quiet)."""

from __future__ import annotations

import os
import pty
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
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


def test_run_in_a_pseudo_terminal_prints_the_nesting_progress():
    leader, follower = pty.openpty()
    done = subprocess.run(
        [sys.executable, "-m", "torsal.app.cli", "run", str(GRAPH), *NESTING],
        stdout=subprocess.PIPE, stderr=follower, cwd=ROOT, timeout=300, check=False,
    )
    os.close(follower)
    err = read_all(leader)
    os.close(leader)
    assert done.returncode == 0, err
    shown = [part for part in err.replace("\r", "\n").split("\n") if part.strip().startswith("cut ")]
    assert len(shown) >= 3, err
    assert shown[-1].strip() == "cut 100 %"


def test_piped_stderr_gets_no_progress_line():
    done = subprocess.run(
        [sys.executable, "-m", "torsal.app.cli", "run", str(GRAPH), *NESTING],
        capture_output=True, text=True, cwd=ROOT, timeout=300, check=False,
    )
    assert done.returncode == 0, done.stderr
    assert "%" not in done.stderr
