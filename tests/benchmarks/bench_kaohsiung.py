"""The Kaohsiung stadium example re-solved after a slider move (``make bench``).

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_kaohsiung.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

Moving 'Inward scale' expires the scaled top curve and everything downstream: the
divided points, the 21 edge curves through them and the 20 RulingDevelopable strips
(12 segments each). The bar of the toolbox issue: that re-solve in < 50 ms, best of 5
(the machine is shared and noisy, so the best run is the one that measures the code).
"""

from __future__ import annotations

import time
from pathlib import Path

from app.headless import run_file

EXAMPLE = Path(__file__).resolve().parents[2] / "resources" / "examples" / "kaohsiung-stadium.graph"
REPEATS = 5


def test_kaohsiung_resolves_in_under_50_ms_after_the_scale_slider_moves():
    run = run_file(EXAMPLE)
    runs = []
    for index in range(REPEATS + 1):  # the first solve after loading warms caches up: not counted
        run.graph.set_setting("scale", "value", 0.70 if index % 2 else 0.72)
        start = time.perf_counter()
        report = run.solver.solve()
        seconds = time.perf_counter() - start
        by_type: dict[str, float] = {}
        for node_id in report.solved:
            type_id = run.graph.nodes[node_id].type_id
            by_type[type_id] = by_type.get(type_id, 0.0) + run.solver.results[node_id].seconds
        if index:
            runs.append((seconds, len(report.solved), by_type))
    seconds, solved, by_type = min(runs, key=lambda r: r[0])
    strips = run.solver.results["strip"].outputs["Surface"]
    print(f"\nKaohsiung re-solve after moving 'Inward scale': {1e3 * seconds:.1f} ms best of {REPEATS}")
    print(f"  all runs: {', '.join(f'{1e3 * r[0]:.1f}' for r in runs)} ms; {solved} nodes re-solved")
    for type_id, spent in sorted(by_type.items(), key=lambda item: -item[1])[:4]:
        print(f"  {type_id:<34}{1e3 * spent:7.1f} ms")
    assert sum(len(branch) for branch in strips.branches) == 20
    assert seconds < 0.050
