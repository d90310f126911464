"""Time the Kaohsiung example's re-solve after its main slider moves, in this process.

``python -P tools/resolve_loop.py GRAPH REPEATS COUNT`` with ``PYTHONPATH`` set to the
checkout whose ``torsal`` is to be timed (``-P`` keeps this folder off the path, so the
same loop times any checkout, an old one from git history included). It loads GRAPH,
solves it, then sets 'Inward scale' to 0.70 and 0.72 in turn and re-solves REPEATS times
after two re-solves that warm caches up, the garbage collector held during each one;
COUNT, when not 0, sets 'Edge points' first (276 makes 280 strips).

It prints one line: the median and least wall seconds of a re-solve, the median and least
CPU seconds (``time.process_time``: a wait for a core on a shared machine is not counted)
and the strips made. :func:`run_loop` reads it; ``python -m tools.time_resolve`` and
``tests/benchmarks/bench_strips_together.py`` call it.
"""

from __future__ import annotations

import gc
import os
import statistics
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

HERE = Path(__file__).resolve()


@dataclass(frozen=True)
class Resolves:
    """One process's re-solve times, in seconds, and the strips it made."""

    median: float
    least: float
    median_cpu: float
    least_cpu: float
    strips: int


def run_loop(tree: Path, graph: Path, repeats: int, count: int = 0, timeout: float = 1800) -> Resolves:
    """The re-solve times of ``graph`` by the ``torsal`` package in ``tree``, in a fresh
    process run from ``tree``."""
    env = dict(os.environ, PYTHONPATH=str(tree))
    done = subprocess.run(
        [sys.executable, "-P", str(HERE), str(graph), str(repeats), str(count)],
        capture_output=True, text=True, check=True, timeout=timeout, cwd=tree, env=env,
    )
    *seconds, strips = done.stdout.split()[-5:]
    return Resolves(*(float(s) for s in seconds), int(strips))


def main(graph: str, repeats: int, count: int) -> None:
    from torsal.app.headless import run_file

    run = run_file(graph)
    if count:
        run.graph.set_setting("count", "max", max(count, 60))
        run.graph.set_setting("count", "value", count)
    wall, cpu = [], []
    for index in range(repeats + 2):
        run.graph.set_setting("scale", "value", 0.70 + 0.02 * (index % 2))
        gc.disable()
        start, start_cpu = time.perf_counter(), time.process_time()
        run.solver.solve()
        took, took_cpu = time.perf_counter() - start, time.process_time() - start_cpu
        gc.enable()
        if index >= 2:  # (the first re-solves warm caches up)
            wall.append(took)
            cpu.append(took_cpu)
    strips = sum(len(branch) for branch in run.solver.results["strip"].outputs["Surface"].branches)
    print(statistics.median(wall), min(wall), statistics.median(cpu), min(cpu), strips)


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), int(sys.argv[3]))
