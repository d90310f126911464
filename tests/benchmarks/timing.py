"""Timing for the benchmarks: a measurement and its baseline, taken in the same run.

The machines are shared and noisy. The work and its baseline are therefore timed in
pairs, back to back, so that both see the same machine load; the ratio asserted on is
the median of the pairs' ratios (it shrugs off the pairs another process disturbed),
and the absolute times printed are the best of all runs.
"""

from __future__ import annotations

import gc
import statistics
import time
from collections.abc import Callable


def timed_rounds(functions: list[Callable[[], object]], repeats: int, warm: int = 0) -> list[list[float]]:
    """Wall times in seconds, ``[round][function]``, of ``repeats`` rounds.

    Each function is called once untimed first (caches, lazy imports); then every round
    calls all of them in turn. As in :mod:`timeit`, the garbage collector is paused while
    a call is timed: when it runs depends on what came before, which is noise here. With
    ``warm``, each timed call follows that many untimed calls of the same function, so no
    function is timed in the caches another one left (a 1 ms solve timed right after a 30 ms
    one runs from a refilled L2: a cost of the order of the calls, not of the function).
    """
    for function in functions:
        function()
    rounds = []
    for _ in range(repeats):
        times = []
        for function in functions:
            for _ in range(warm):
                function()
            gc.disable()
            try:
                start = time.perf_counter()
                function()
                times.append(time.perf_counter() - start)
            finally:
                gc.enable()
        rounds.append(times)
    return rounds


def ratio_to_baseline(
    what: str, work: Callable[[], object], baseline: str, reference: Callable[[], object], repeats: int
) -> float:
    """Median ratio of ``work``'s time to ``reference``'s, timed in pairs; prints the figures."""
    rounds = timed_rounds([work, reference], repeats)
    ratio = statistics.median(w / r for w, r in rounds)
    print(
        f"\n{what}: {duration(min(w for w, _ in rounds))}\n"
        f"  baseline, {baseline}: {duration(min(r for _, r in rounds))}\n"
        f"  ratio {ratio:.2f} (median of {repeats} pairs; times: best of {repeats})"
    )
    return ratio


def duration(seconds: float) -> str:
    """``12.3 µs``, ``4.56 ms`` or ``1.23 s``."""
    if seconds < 1e-3:
        return f"{seconds * 1e6:.1f} µs"
    if seconds < 1.0:
        return f"{seconds * 1e3:.2f} ms"
    return f"{seconds:.2f} s"
