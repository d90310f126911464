"""SplineApproximation's Optimise, against the same node not optimising (``make bench``).

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_spline_approximation.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

The bar of the toolbox issue: optimising the 20 segments of a twisted strip cuts its
summed warp over 100 times in under 2 s. Here the optimising solve is timed against a
baseline measured in the same run, the node solving the same strip at the given angles
(stations, rulings, warps and outputs, without the least-squares search), so the ratio
is what optimising adds. The warp it reaches is checked by ``make test``
(``tests/nodes/developable/test_spline_approximation.py``).
"""

from __future__ import annotations

from tests.benchmarks.timing import ratio_to_baseline
from tests.nodes.developable.test_spline_approximation import only, solve, texts, twisted_strip


def test_optimising_a_twisted_strip_costs_at_most_3_plain_solves():
    surface, edge = twisted_strip()
    result = solve(surface, edge, Segments=20, Optimise=True)
    ratio = ratio_to_baseline(
        "SplineApproximation, 20 segments, Optimise on",
        lambda: solve(surface, edge, Segments=20, Optimise=True),
        "the same solve with Optimise off",
        lambda: solve(surface, edge, Segments=20),
        15,
    )
    print(f"  {texts(result)[0]}")
    assert only(solve(surface, edge, Segments=20), "Fitness") / only(result, "Fitness") >= 100
    assert ratio <= 3.0
