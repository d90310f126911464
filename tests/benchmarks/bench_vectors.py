"""analysis.VectorAnalysis against plain numpy and Python, measured in the same run (``make bench``).

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_vectors.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

The bars of the analysis issue: cross, dot and angle of 10⁶ pairs in under a second, and
the node on 10⁶ engine vectors in a few seconds. Here the kernel is timed against numpy
doing the same three products, and the node against the plain way of doing its whole
job: numpy's conversion of the vector lists, the same products, and a list
comprehension building the output vectors. The values are checked by ``make test``
(``tests/nodes/analysis/test_analysis_vectors.py``).
"""

from __future__ import annotations

import numpy as np

from tests.benchmarks.timing import ratio_to_baseline
from tests.nodes.analysis.test_analysis_vectors import numpy_reference
from torsal.engine.values import Vector
from torsal.nodes.analysis.vectors import VectorAnalysis, as_vectors, vector_products

MILLION = 1_000_000


def test_products_of_a_million_pairs_within_2x_numpy():
    rng = np.random.default_rng(2011)
    a, b = rng.normal(size=(MILLION, 3)), rng.normal(size=(MILLION, 3))
    ratio = ratio_to_baseline(
        "vector_products, 10^6 pairs (cross, dot, angle, zero check)",
        lambda: vector_products(a, b),
        "numpy cross, einsum dot, arccos angle",
        lambda: numpy_reference(a, b),
        9,
    )
    assert ratio <= 2.0


def test_node_on_engine_vectors_is_faster_than_plain_numpy_and_python():
    count = 200_000  # the plain way takes ~2 s per million, and the ratio does not depend on it
    rng = np.random.default_rng(7)
    va, vb = as_vectors(rng.normal(size=(count, 3))), as_vectors(rng.normal(size=(count, 3)))

    def plain() -> tuple[list[Vector], list[float], list[float]]:
        cross, dot, angle = numpy_reference(np.array(va, dtype=float), np.array(vb, dtype=float))
        return [Vector(*row) for row in cross.tolist()], dot.tolist(), angle.tolist()

    node = VectorAnalysis()
    ratio = ratio_to_baseline(
        f"VectorAnalysis.solve, {count:,} pairs of engine vectors",
        lambda: node.solve(va, vb),
        "np.array of the lists, numpy products, Vector(*row) for each output",
        plain,
        5,
    )
    assert ratio <= 0.75
