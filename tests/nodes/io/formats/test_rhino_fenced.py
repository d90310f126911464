"""rhino3dm never parses a file in Torsal's own process: a crash there is a node error.

The crashing file is a seeded byte mutant of a valid .3dm made with rhino3dm (the fuzz
target's mutant 141 of seed 18, which makes rhino3dm 8.35 die with SIGSEGV); the other
misbehaviours (a hang, a huge allocation, a malformed reply) come from a stand-in child,
tests/support/hostile_reader.py, so each is certain.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from tests.support.node_helpers import run, texts
from tools.fuzz_3dm import fuzz, mutate, seed_files
from torsal.app.explore.evaluate import Job, solve_variant
from torsal.engine.graph import Graph
from torsal.engine.graphfile import write_graph
from torsal.engine.solver import ERROR
from torsal.nodes.io.formats.fenced import FencedReader, ReaderCrashed
from torsal.nodes.io.rhino import Import3dm

ROOT = Path(__file__).resolve().parents[4]
HOSTILE = "tests.support.hostile_reader"


def crashing_file(folder: Path) -> Path:
    seeds = [path.read_bytes() for path in seed_files(folder / "seeds")]
    rng = np.random.default_rng(18)
    made = [mutate(seeds[k % 2], rng) for k in range(142)]
    path = folder / "damaged.3dm"
    path.write_bytes(made[141][0])
    return path


def import_graph(folder: Path, source: str) -> Path:
    graph = Graph()
    graph.add_node(Import3dm(), "read")
    graph.set_input_value("read", "Path", source)
    path = folder / "read.graph"
    write_graph(graph, path)
    return path


def test_a_file_that_crashes_rhino3dm_is_a_node_error_naming_it(tmp_path):
    path = crashing_file(tmp_path)
    result = run(Import3dm(), Path=str(path))
    assert result.state == ERROR
    assert texts(result) == ["could not read damaged.3dm: the reader crashed (SIGSEGV)"]


def test_torsal_run_survives_the_crash_exit_1_with_the_message(tmp_path):
    crashing_file(tmp_path)
    graph = import_graph(tmp_path, "damaged.3dm")
    done = subprocess.run([sys.executable, "-P", "-m", "torsal.app.cli", "run", str(graph), "--json"],
                          capture_output=True, text=True, cwd=tmp_path, timeout=120,
                          env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})
    assert done.returncode == 1, done.stderr  # a node in error, not 139 (SIGSEGV)
    assert "Traceback" not in done.stderr
    report = json.loads(done.stdout)
    assert "could not read damaged.3dm: the reader crashed" in report["nodes"]["read"]["messages"][0]["text"]


def test_a_sweep_variant_reports_the_crash_and_the_worker_goes_on(tmp_path):
    crashing_file(tmp_path)
    graph = import_graph(tmp_path, "damaged.3dm")
    job = Job((), read_root=str(tmp_path))
    for index in range(2):  # the same worker solves the next variant
        outcome = solve_variant(graph.read_text(), {}, job, index)
        assert "could not read damaged.3dm: the reader crashed" in outcome["status"]


@pytest.mark.parametrize(("do", "needle"), [
    ("segfault", "the reader crashed (SIGSEGV)"),
    ("hang", "the reader took longer than 1 s"),
    ("allocate", "the reader crashed (exit 1)"),
    ("garbage", "the reader sent a malformed reply"),
])
def test_a_misbehaving_child_is_reported_and_the_next_request_gets_a_fresh_one(do, needle):
    fence = FencedReader(HOSTILE, memory=1 << 30, seconds=1.0)
    try:
        first = fence.request({"do": "hello"})["pid"]
        with pytest.raises(ReaderCrashed) as caught:
            fence.request({"do": do})
        assert str(caught.value) == needle
        assert fence.request({"do": "hello"})["pid"] != first
        assert fence.started == 2
    finally:
        fence.close()


def test_one_child_serves_many_requests():
    fence = FencedReader(HOSTILE)
    try:
        assert len({fence.request({"do": "hello"})["pid"] for _ in range(20)}) == 1
    finally:
        fence.close()


def test_fifos_are_refused_by_type_not_read(tmp_path):
    fifo = tmp_path / "pipe.3dm"
    os.mkfifo(fifo)
    assert texts(run(Import3dm(), Path=str(fifo))) == [
        "pipe.3dm is not a regular file (a device or a pipe?), so not a .3dm"]


def test_fuzz_200_mutants_never_break_the_rule(tmp_path):
    report = fuzz(200, seed=1, folder=tmp_path, readers=2, seconds=5.0)
    assert report.mutants == 200
    assert not report.failures, report.failures[:5]
    assert report.outcomes["read"] + report.outcomes["refused"] > 150, report.summary()
