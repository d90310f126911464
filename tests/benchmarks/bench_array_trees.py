"""Numbers flowing as arrays: a Series of 10⁶ through five Expression nodes against numpy.

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_array_trees.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

The bar (issue 16): re-solving the five Expressions costs at most 3× numpy doing the five
formulas on the same arrays, already built, and allocates at most 3× the memory numpy
does. The graph keeps every node's result, so the numpy baseline keeps its five results
too. What the nodes compute is checked by ``make test`` (``tests/nodes/``,
``tests/engine/test_array_branches.py``).
"""

from __future__ import annotations

import tracemalloc
from collections.abc import Callable

import numpy as np

from tests.benchmarks.timing import ratio_to_baseline
from torsal.engine.graph import Graph
from torsal.engine.solver import Solver
from torsal.nodes.maths.expression import Expression
from torsal.nodes.maths.sequences import Series

MILLION = 1_000_000
#: the five formulas, each fed by the one before; y is 0.5 throughout
FORMULAS = ("x * 2 + y", "sin(x) * y", "x ** 2 + 1", "sqrt(x) - y", "x / (1 + y)")


def _chain() -> tuple[Graph, Solver]:
    graph = Graph()
    graph.add_node(Series(), "s")
    graph.set_input_value("s", "Count", MILLION)
    source = "s", "Series"
    for i, formula in enumerate(FORMULAS):
        node_id = f"e{i}"
        graph.add_node(Expression({"expression": formula, "variables": ["x", "y"]}), node_id)
        graph.set_input_value(node_id, "y", 0.5)
        graph.connect(*source, node_id, "x")
        source = node_id, "Result"
    solver = Solver(graph)
    solver.solve()
    return graph, solver


def _numpy_on(x: np.ndarray) -> Callable[[], list[np.ndarray]]:
    def five() -> list[np.ndarray]:
        y = 0.5
        r0 = x * 2 + y
        r1 = np.sin(r0) * y
        r2 = r1**2 + 1
        r3 = np.sqrt(r2) - y
        r4 = r3 / (1 + y)
        return [r0, r1, r2, r3, r4]  # every result kept, as the graph keeps them

    return five


def _peak(function: Callable[[], object]) -> int:
    """Bytes allocated at the peak while ``function`` runs (what it keeps included)."""
    tracemalloc.start()
    try:
        kept = function()  # noqa: F841 - held until the peak is read, as the graph holds its results
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


def test_a_series_of_a_million_through_five_expressions_is_within_3x_numpy():
    graph, solver = _chain()
    x = np.arange(MILLION, dtype=np.float64)

    def resolve() -> None:
        graph.expire("e0")  # the Series' array stays: the arrays already built
        solver.solve()

    ratio = ratio_to_baseline(
        "Series 10^6 -> 5 Expressions, re-solve", resolve,
        "numpy, the 5 formulas on the built array", _numpy_on(x), 7,
    )
    expected = _numpy_on(x)()[-1]
    result = solver.result("e4").output("Result")
    assert result.item_count == MILLION
    assert np.allclose(result.all_items()[:5], expected[:5], rtol=1e-15)
    assert ratio <= 3.0


def test_a_series_of_a_million_through_five_expressions_allocates_within_3x_numpy():
    graph, solver = _chain()
    x = np.arange(MILLION, dtype=np.float64)

    def resolve() -> Solver:
        graph.expire("e0")
        solver.solve()
        return solver

    ours, theirs = _peak(resolve), _peak(_numpy_on(x))
    print(f"\nSeries 10^6 -> 5 Expressions, peak allocation {ours / 2**20:.1f} MiB\n"
          f"  baseline, numpy keeping its 5 results: {theirs / 2**20:.1f} MiB\n"
          f"  ratio {ours / theirs:.2f}")
    assert ours <= 3.0 * theirs
