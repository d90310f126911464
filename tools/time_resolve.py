"""CPU time of the flagship's re-solve after its main slider moves, in alternating processes.

``python -m tools.time_resolve [TREE ...] [--rounds 3] [--repeats 25] [--count N]``

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
from pathlib import Path

from tools.resolve_loop import run_loop

EXAMPLE = Path("torsal") / "resources" / "examples" / "kaohsiung-stadium.graph"


def resolve_cpu(tree: Path, repeats: int, count: int) -> tuple[float, float, int]:
    """Median and least CPU milliseconds of a re-solve, and the strips made, by ``tree``'s
    package (:func:`tools.resolve_loop.run_loop`)."""
    done = run_loop(tree, tree / EXAMPLE, repeats, count)
    return done.median_cpu * 1e3, done.least_cpu * 1e3, done.strips


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
