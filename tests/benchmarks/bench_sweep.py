"""A 200-variant sweep of the Kaohsiung stadium example (``make bench``).

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_sweep.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

The variants: Shift n 0 … 4 (5 values) × Inward scale 0.4 … 0.95 (40 steps), collecting
the strip count and the share of valid rulings. Three runs of the same variants, each
timed from the first variant sent to the last one back:

- the baseline, a plain loop in this process: parse the graph, set the two sliders, solve;
- ``torsal sweep --workers 1``: one worker process of a dask LocalCluster;
- ``torsal sweep --workers 2``.

The bars of issue 13: 2 workers give at least 1.6× the throughput of 1 on this 2-core
machine, and at 1 worker a variant costs at most 1.3× the plain loop's. Starting the
cluster (a few seconds, once per sweep) is timed and printed, not counted.
"""

from __future__ import annotations

import time
from pathlib import Path

from tests.benchmarks.timing import duration
from torsal.app.explore.executors import DaskExecutor
from torsal.app.explore.samplers import grid
from torsal.app.explore.study import open_study
from torsal.app.explore.sweep import run_sweep
from torsal.app.headless import open_graph
from torsal.engine.solver import Solver

EXAMPLE = Path(__file__).resolve().parents[2] / "torsal" / "resources" / "examples" / (
    "kaohsiung-stadium.graph"
)
VARY = ["shift=0:4:5", "scale=0.4:0.95:40"]
COLLECT = ["strips.Result", "strip.Valid:mean"]


def _plain_loop(variants: list[dict]) -> list[float]:
    shares = []
    for values in variants:
        graph, _ = open_graph(EXAMPLE)
        for node_id, value in values.items():
            graph.set_setting(node_id, "value", value)
        solver = Solver(graph)
        solver.solve()
        valid = solver.result("strip").outputs["Valid"].all_items()
        shares.append(sum(valid) / len(valid))
    return shares


def _sweep(study, variants, workers: int) -> tuple[float, float, list]:
    started = time.perf_counter()
    with DaskExecutor(workers=workers) as executor:
        run_sweep(study, variants[:workers], executor)  # the workers import the node library
        ready = time.perf_counter()
        result = run_sweep(study, variants, executor)
        finished = time.perf_counter()
    return ready - started, finished - ready, result.outcomes


def test_two_workers_double_the_throughput_and_one_costs_little_more_than_a_plain_loop():
    study = open_study(EXAMPLE, VARY, COLLECT, steps=True)
    variants = grid(study.variables)
    assert len(variants) == 200
    _plain_loop(variants[:2])  # imports and caches, as the workers' warm-up
    start = time.perf_counter()
    shares = _plain_loop(variants)
    loop = time.perf_counter() - start
    startup1, one, outcomes1 = _sweep(study, variants, 1)
    startup2, two, outcomes2 = _sweep(study, variants, 2)
    print("\nKaohsiung sweep, 200 variants (Shift n × Inward scale):")
    print(f"  plain loop in this process: {duration(loop)} ({duration(loop / 200)} a variant)")
    for label, seconds, startup in (("1 worker: ", one, startup1), ("2 workers:", two, startup2)):
        print(f"  {label} {duration(seconds)} ({duration(seconds / 200)} a variant; "
              f"cluster start {duration(startup)})")
    print(f"  throughput 2 workers / 1: {one / two:.2f}×; 1 worker / plain loop: {one / loop:.2f}×")
    assert [o.outputs["strip.Valid:mean"] for o in outcomes1] == shares
    assert [o.outputs for o in outcomes1] == [o.outputs for o in outcomes2]
    assert one / two >= 1.6
    assert one / loop <= 1.3
