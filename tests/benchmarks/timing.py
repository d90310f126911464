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


def peak_bytes(function: Callable[[], object]) -> int:
    """Bytes allocated at the peak while ``function`` runs (:mod:`tracemalloc`: Python
    objects and numpy's arrays, which numpy reports to it), from a collected heap."""
    import tracemalloc

    gc.collect()
    tracemalloc.start()
    try:
        kept = function()  # noqa: F841 - held until the peak is read
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def duration(seconds: float) -> str:
    """``12.3 µs``, ``4.56 ms`` or ``1.23 s``."""
    if seconds < 1e-3:
        return f"{seconds * 1e6:.1f} µs"
    if seconds < 1.0:
        return f"{seconds * 1e3:.2f} ms"
    return f"{seconds:.2f} s"


#: Cross products in :func:`check_interval_block`: ≈ 50 ms on the quiet 2-core machine of
#: 2 December 2026 (medians 50.1–53.7 ms at load 0.4–0.8; 12.5 µs a call).
CHECK_INTERVAL_CALLS = 4000


def check_interval_block(repeats: int = 5) -> float:
    """Seconds of the most work a long kernel may do between two looks at its cancel token,
    the "50 ms" of issue 16 on whatever machine and load this runs: the median of
    ``repeats`` blocks of :data:`CHECK_INTERVAL_CALLS` cross products of a 13-point strip's
    ``(13, 3)`` rows through ``np.cross`` — Python and small numpy calls, the kernels' own
    kind of work. (Sorting 2·10⁶ numbers stood in for it before; numpy sorts with AVX-512
    where the processor has it, 4× faster than on the machine it was set on, so it asked
    12 ms between checks there.)"""
    import numpy as np

    rows = np.random.default_rng(1).random((13, 3))
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        for _ in range(CHECK_INTERVAL_CALLS):
            np.cross(rows, rows)
        times.append(time.perf_counter() - start)
    return statistics.median(times)
