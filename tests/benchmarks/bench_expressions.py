"""The expression language against plain numpy, measured in the same run (``make bench``).

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_expressions.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

The bars: compiled expressions evaluate as fast as numpy (within 30 %); ``maths.Expression``
solves 10⁶ items in a graph well under a second (here: within 3× numpy doing the same
formula on the same list); hostile texts (a power tower, a megabyte of text) cost no
more than an ordinary expression. What they compute is checked by ``make test``
(``tests/test_expression_*.py``, ``tests/nodes/maths/test_maths_expression.py``).
"""

from __future__ import annotations

import numpy as np

from tests.benchmarks.timing import ratio_to_baseline
from torsal.engine.graph import Graph
from torsal.engine.solver import Solver
from torsal.nodes.expressions import ExpressionError, compile_expression
from torsal.nodes.maths.expression import Expression
from torsal.nodes.maths.sequences import Series

MILLION = 1_000_000


def test_vectorised_evaluation_is_as_fast_as_numpy():
    rng = np.random.default_rng(0)
    x, y = rng.random(MILLION), rng.random(MILLION)
    f = compile_expression("sin(x) * y + 2")
    ratio = ratio_to_baseline(
        "'sin(x) * y + 2' on 10^6 points", lambda: f(x=x, y=y), "numpy", lambda: np.sin(x) * y + 2, 15
    )
    assert ratio <= 1.3


def test_expression_node_solves_a_million_items_within_3x_numpy_on_the_same_list():
    graph = Graph()
    graph.add_node(Series(), "s")
    graph.set_input_value("s", "Count", MILLION)
    graph.add_node(Expression({"expression": "sin(x) * y + x ** 2 / (1 + y)", "variables": ["x", "y"]}), "e")
    graph.set_input_value("e", "y", 0.5)
    graph.connect("s", "Series", "e", "x")
    solver = Solver(graph)
    solver.solve()
    items = solver.result("s").output("Series").all_items()

    def resolve() -> None:
        graph.expire("e")
        solver.solve()

    def numpy_on_the_list() -> list[float]:  # what the node must do at least: list → array → list
        x = np.asarray(items, dtype=float)
        return (np.sin(x) * 0.5 + x**2 / 1.5).tolist()

    ratio = ratio_to_baseline(
        "maths.Expression re-solve, 10^6 items", resolve, "numpy on the same list", numpy_on_the_list, 7
    )
    assert len(solver.result("e").output("Result").all_items()) == MILLION
    assert ratio <= 3.0


def test_a_power_tower_costs_what_an_ordinary_expression_costs():
    folded = ratio_to_baseline(
        "compile '9**9**9' (folds to inf)",
        lambda: compile_expression("9**9**9"),
        "compile '9*9*9'",
        lambda: compile_expression("9*9*9"),
        200,
    )
    x = np.full(1000, 9.0)
    tower = compile_expression("x**x**x**x", ["x"])

    def numpy_tower() -> np.ndarray:
        with np.errstate(over="ignore"):
            return x**x**x**x

    evaluated = ratio_to_baseline(
        "'x**x**x**x' on 1000 nines (inf)", lambda: tower(x=x), "numpy", numpy_tower, 200
    )
    assert folded <= 2.0
    assert evaluated <= 2.0


def test_a_megabyte_of_text_is_refused_faster_than_a_short_expression_compiles():
    text = "x+" * 500_000 + "x"

    def refuse() -> None:
        try:
            compile_expression(text)
        except ExpressionError:
            return
        raise AssertionError("a megabyte of text was accepted")

    ratio = ratio_to_baseline(
        "refuse 1 MB of text", refuse, "compile 'x + 1'", lambda: compile_expression("x + 1"), 200
    )
    assert ratio <= 1.0
