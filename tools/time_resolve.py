"""CPU time of the flagship's re-solve after its main slider moves, in alternating processes.

``python tools/time_resolve.py [TREE ...] [--rounds 3] [--repeats 25] [--count N]``

Each round runs one process per tree (a checkout holding a ``torsal`` package: this one
when none is given; e.g. a second worktree at main, ``git worktree add --detach DIR main``)
in turn, so that all of them see the same load. A process loads the Kaohsiung example,
solves it, then moves 'Inward scale' and re-solves ``repeats`` times (after two re-solves
that warm caches up) and reports the median and the least CPU time of a re-solve
(``time.process_time``: the waits for a core on a shared machine are not counted) with the
strips made; ``--count N`` sets 'Edge points' first (276 makes 280 strips). Each line ends
with the load average, to be reported beside the figures.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
from pathlib import Path

EXAMPLE = Path("torsal") / "resources" / "examples" / "kaohsiung-stadium.graph"

_RESOLVE = """
import gc, statistics, sys, time
from torsal.app.headless import run_file
run = run_file(sys.argv[1])
repeats, count = int(sys.argv[2]), int(sys.argv[3])
if count:
    run.graph.set_setting("count", "max", max(count, 60))
    run.graph.set_setting("count", "value", count)
cpu = []
for index in range(repeats + 2):
    run.graph.set_setting("scale", "value", 0.70 + 0.02 * (index % 2))
    gc.disable()
    start = time.process_time()
    run.solver.solve()
    took = time.process_time() - start
    gc.enable()
    if index >= 2:
        cpu.append(took)
strips = sum(len(branch) for branch in run.solver.results["strip"].outputs["Surface"].branches)
print(f"{statistics.median(cpu) * 1e3:.2f} {min(cpu) * 1e3:.2f} {strips}")
"""


def resolve_cpu(tree: Path, repeats: int, count: int) -> tuple[float, float, int]:
    """Median and least CPU milliseconds of a re-solve, and the strips made, by ``tree``'s
    package (run from ``tree``: its ``torsal`` is the one imported)."""
    done = subprocess.run(
        [sys.executable, "-c", _RESOLVE, str(tree / EXAMPLE), str(repeats), str(count)],
        capture_output=True, text=True, check=True, timeout=1800, cwd=tree,
    )
    median, least, strips = done.stdout.split()[-3:]
    return float(median), float(least), int(strips)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("trees", nargs="*", type=Path, help="checkouts to time (default: this one)")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--repeats", type=int, default=25)
    parser.add_argument("--count", type=int, default=0, help="'Edge points' (0: the file's)")
    args = parser.parse_args()
    trees = [tree.resolve() for tree in args.trees] or [Path(__file__).resolve().parents[1]]
    for _ in range(args.rounds):
        figures = []
        for tree in trees:
            median, least, strips = resolve_cpu(tree, args.repeats, args.count)
            figures.append(f"{tree.name}: {median:.1f} ms (least {least:.1f}, {strips} strips)")
        print(" | ".join(figures), f"| load {os.getloadavg()[0]:.1f}", flush=True)


if __name__ == "__main__":
    main()
