"""The development map's point location costs what the points cost, not what the strip's
sampling costs (``make bench``; issue 16). Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_development_map.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

``DevelopmentMap.locate`` of the same 2·10⁴ points on a cone unrolled from 8,701 rulings
(17,400 sliver triangles, 2,000 times longer than wide) against the same cone from 201
rulings, in the same run. Before the coarse-to-fine start (nodes/geometry/strip_walk.py)
the fine cone took 12.8 times as long (its k-d tree start searched thousands of equally
near samples); with it 2.3–3.3 times. What it computes is checked by ``make test``
(tests/nodes/geometry/test_development_map_index.py).
"""

from __future__ import annotations

import numpy as np

from tests.benchmarks.timing import ratio_to_baseline
from tests.nodes.geometry.test_development_map_index import cone_to_apex
from torsal.nodes.geometry.unroll import unroll_rulings


def _points(m, count: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    tri = rng.choice(m.proper, size=count)
    weights = rng.dirichlet(np.ones(3), size=count)
    return np.einsum("kj,kjd->kd", weights, m.vertices2d[m.triangles[tri]])


def test_locating_points_on_an_8701_ruling_cone_costs_at_most_4x_a_201_ruling_one():
    fine, coarse = unroll_rulings(*cone_to_apex(8701)).map, unroll_rulings(*cone_to_apex(201)).map
    # the same points: the cones are the same sector, sampled more or less finely
    points = _points(coarse, 20_000, seed=5)
    for m in (fine, coarse):
        m.locate(points[:10])  # the indexes are built once
    ratio = ratio_to_baseline(
        "DevelopmentMap.locate, 2·10^4 points, cone of 8,701 rulings",
        lambda: fine.locate(points),
        "the same points on the same cone of 201 rulings",
        lambda: coarse.locate(points),
        9,
    )
    assert ratio <= 4.0
