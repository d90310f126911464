"""developable.Rationalise against the plain baseline (``make bench``).

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_rationalise.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

The baseline is what a designer does by hand: strips between evenly spaced isocurves
(the same family Rationalise picks) with RulingDevelopable, as many as it takes for every
strip to be within the tolerance (the count raised one at a time). Both measure a strip's
deviation the same way. Fewer strips at the same tolerance is the win; never more is
asserted, and the counts and times are printed. Times are the solve's alone (no
baseline to take a ratio against: the baseline's time grows with its own search).
"""

from __future__ import annotations

import itertools
import time

import numpy as np
import pytest

from tests.nodes.developable.test_rationalise import DESIGNS, kaohsiung_roof
from torsal.nodes.geometry.developable.guided import IsoBoundaries
from torsal.nodes.geometry.developable.rationalise import boundary_family, rationalise, strip_between

TOLERANCES = (0.01, 0.02, 0.05)


def _even_ok(design, family: str, tolerance: float, count: int) -> bool:
    cuts = np.linspace(0.0, 1.0, count + 1)
    boundaries = IsoBoundaries(design, family)
    return all(strip_between(design, boundaries, lo, hi, tolerance=tolerance).deviation <= tolerance
               for lo, hi in itertools.pairwise(cuts))


def even_strips(design, tolerance: float, limit: int = 128) -> int:
    """The fewest evenly spaced strips that are all within ``tolerance`` (counts doubled until
    one is, then bisected: this takes the deviation to shrink as the count grows)."""
    family = boundary_family(design)
    low, high = 0, 1
    while not _even_ok(design, family, tolerance, high):
        low, high = high, 2 * high
        if high > limit:
            return limit + 1
    while high - low > 1:
        mid = (low + high) // 2
        low, high = (low, mid) if _even_ok(design, family, tolerance, mid) else (mid, high)
    return high


SURFACES = {**{name: field.surface for name, field in DESIGNS.items()}, "kaohsiung": kaohsiung_roof}


@pytest.mark.parametrize("name", SURFACES)
def test_rationalise_needs_no_more_strips_than_evenly_spaced_isocurves(name):
    design = SURFACES[name]()
    lines = []
    for tolerance in TOLERANCES:
        start = time.perf_counter()
        result = rationalise(design, tolerance, 64)
        seconds = time.perf_counter() - start
        start = time.perf_counter()
        baseline = even_strips(design, tolerance)
        base_seconds = time.perf_counter() - start
        lines.append(f"  {100 * tolerance:g} cm: {len(result.strips)} strips (worst {result.deviation:.4f}) "
                     f"in {seconds:.2f} s; baseline {baseline} even strips ({base_seconds:.2f} s to find)")
        assert result.within
        assert len(result.strips) <= baseline
    print(f"\n{name}:\n" + "\n".join(lines))
