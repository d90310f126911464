"""A strip between two curves at site coordinates solves, unrolls and is summarised within
2× the time and 2× the peak memory of the same at the origin (``make bench``).

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_site_strips.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

The pairs are ``tests/app/test_site_strips.py``'s: random rational NURBS moved on their
control points, and curves given as functions of their world coordinates (finite
differences). Before adaptive integrals stopped at the derivatives' rounding noise, the
functions' strip took 84 s for its area and 83 s to unroll at 1e6 m (0.02 s and 0.05 s at
the origin). RulingDevelopable → IsoMapping → the JSON summaries of both (areas, lengths,
boxes), timed in pairs with the origin in one run.
"""

from __future__ import annotations

import pytest

from tests.app.test_site_strips import FAR, SITE, solved
from tests.benchmarks.timing import peak_bytes, ratio_to_baseline

REPEATS = 3
BAR = 2.0


@pytest.mark.parametrize("offset", [SITE, FAR], ids=["1e6", "1e9"])
@pytest.mark.parametrize("kind", ["rational", "functions"])
def test_a_strip_far_from_the_origin_solves_within_2x_of_its_time_and_memory_at_the_origin(kind, offset):
    ratio = ratio_to_baseline(
        f"{kind} strip moved by {offset[0]:.0e}: solve, unroll, summarise",
        lambda: solved(kind, offset),
        "at the origin",
        lambda: solved(kind, (0.0, 0.0, 0.0)),
        REPEATS,
    )
    far, origin = peak_bytes(lambda: solved(kind, offset)), peak_bytes(lambda: solved(kind, (0.0, 0.0, 0.0)))
    print(f"  peak memory {far / 2**20:.1f} MiB against {origin / 2**20:.1f} MiB: ratio {far / origin:.2f}")
    assert ratio <= BAR
    assert far <= BAR * origin
