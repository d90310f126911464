"""Issue 24's bars on time: hostile inputs are refused before the work they ask for (``make bench``).

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_hardening.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

Each refusal is timed against a baseline of the same run:

- ``torsal check`` of a graph feeding a Series of 1,000,000 into RulingDevelopable's
  WarpTolerance (a million strip solves, hours) against checking the same graph with a
  Series of 3: the calls are counted from the branches' lengths, so refusing a million
  costs about what checking three does (ratio < 5; 76 ms against 0.66 s before the count
  moved ahead of the plan).
- ``torsal check`` of a cluster bomb (16 levels × 10 instances of empty definitions)
  against checking the first-steps example: refused when the file is read (ratio < 5).
- ImportMesh on a 1 GB sparse STL against reading a one-triangle STL: refused on its size
  before reading (ratio < 3).
"""

from __future__ import annotations

import contextlib
import io
from pathlib import Path

from tests.app.test_cli_hardening import EXAMPLE, cluster_bomb, warp_series_graph
from tests.benchmarks.timing import ratio_to_baseline
from torsal.app.cli import main
from torsal.nodes.io.common import FileFailure
from torsal.nodes.io.formats import meshfiles


def quiet_check(path: Path) -> int:
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        return main(["check", str(path)])


def test_check_refuses_a_million_strip_solves_at_the_cost_of_checking_three(tmp_path):
    bomb = warp_series_graph(tmp_path / "million.graph", 1_000_000)
    three = warp_series_graph(tmp_path / "three.graph", 3)
    assert quiet_check(bomb) == 2 and quiet_check(three) == 0
    ratio = ratio_to_baseline("check of a Series of 1,000,000 into WarpTolerance", lambda: quiet_check(bomb),
                              "check of the same graph with a Series of 3", lambda: quiet_check(three),
                              repeats=5)
    assert ratio < 5.0


def test_check_refuses_a_cluster_bomb_as_fast_as_a_small_example(tmp_path):
    bomb = cluster_bomb(tmp_path / "bomb.graph")
    assert quiet_check(bomb) == 2
    ratio = ratio_to_baseline("check of a 16 x 10 cluster bomb", lambda: quiet_check(bomb),
                              "check of first-steps", lambda: quiet_check(EXAMPLE), repeats=7)
    assert ratio < 5.0


def test_a_1_gb_sparse_mesh_is_refused_before_reading(tmp_path):
    big = tmp_path / "huge.stl"
    with big.open("wb") as handle:
        handle.truncate(2**30)
    small = tmp_path / "one.stl"
    small.write_text("solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                     "endloop\nendfacet\nendsolid t\n")

    def refused() -> None:
        try:
            meshfiles.read_mesh(big)
        except FileFailure:
            return
        raise AssertionError("a 1 GB mesh was read")

    ratio = ratio_to_baseline("ImportMesh refusing a 1 GB sparse STL", refused,
                              "reading a one-triangle STL", lambda: meshfiles.read_mesh(small), repeats=7)
    assert ratio < 3.0
