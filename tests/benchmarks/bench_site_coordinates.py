"""Every example solves as fast at site coordinates as at the origin (``make bench``).

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_site_coordinates.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

The bar of issue 11: moved by (1e6, 2e6, 300) m or by 1e9 m (see ``tests/support/site_shift.py``),
each example is loaded, solved and measured (every curve's length, every surface's area,
as ``torsal run --json`` does) within 2× of the same at the origin, timed in pairs in one
run. Before the kernel kept its curves relative to an anchor, the Guggenheim example
took 149 s at 1e6 m against 0.016 s at the origin, and the ZVE roof edge 160 s.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from tests.benchmarks.timing import ratio_to_baseline
from tests.support.site_shift import FAR, GRAPHS, REGISTRY, SITE, shifted, solve
from torsal.engine import graphfile

REPEATS = 5
BAR = 2.0


CASES = [
    pytest.param(path, offset, id=f"{path.stem}@{offset[0]:.0e}")
    for path in GRAPHS
    for offset in (SITE, FAR)
]


@pytest.mark.parametrize(("path", "offset"), CASES)
def test_example_far_from_the_origin_solves_within_2x_of_its_time_at_the_origin(path: Path, offset):
    ratio = ratio_to_baseline(
        f"{path.stem} moved by {offset[0]:.0e}: load, solve, measure",
        lambda: solve(shifted(path, offset), path.parent),
        "at the origin",
        lambda: solve(graphfile.read_graph(path, REGISTRY), path.parent),
        REPEATS,
    )
    assert ratio <= BAR
