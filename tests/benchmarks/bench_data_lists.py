"""List nodes on array branches: 10⁶ random numbers through the list nodes against numpy.

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_data_lists.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

The bar (issue 16, item 1: nodes that take lists receive arrays without conversion):
re-solving the list nodes on a branch of 10⁶ numbers costs at most 3× numpy doing the
same operations on the same array, already built. Each node is timed alone where numpy's
own work is O(n) (Sort, Shift with wrap, Cull Pattern), and the chain Sort → Shift →
Reverse → Cull Pattern → List Item + List Length as a whole (Reverse is a view in both,
so alone it would time only the engine's per-node cost). What the nodes compute is
checked by ``make test`` (``tests/nodes/lists/test_lists_arrays.py``). Points too: Series 10⁶ →
Point → Shift against numpy stacking the (n, 3) array and rolling it
(``tests/nodes/params/test_params_arrays.py``).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

from tests.benchmarks.timing import ratio_to_baseline
from torsal.engine.datatree import Triples
from torsal.engine.graph import Graph
from torsal.engine.node import Node
from torsal.engine.solver import Solver
from torsal.nodes.lists.culling import CullPattern
from torsal.nodes.lists.items import ListItem, ListLength
from torsal.nodes.lists.ordering import Reverse, Shift, Sort
from torsal.nodes.maths.random_numbers import Random
from torsal.nodes.maths.sequences import Series
from torsal.nodes.params.points import Point as PointNode

MILLION = 1_000_000
PATTERN = [True, False, True]


def _graph() -> tuple[Graph, Solver]:
    """Random 10⁶ → Sort → Shift (1, wrap) → Reverse → Cull Pattern → List Item (-1, wrap), List Length."""
    graph = Graph()
    graph.add_node(Random(), "r")
    graph.set_input_value("r", "Number", MILLION)
    graph.add_node(Sort(), "sort")
    graph.connect("r", "Random", "sort", "Keys")
    graph.add_node(Shift(), "shift")
    graph.connect("sort", "Keys", "shift", "List")
    graph.add_node(Reverse(), "reverse")
    graph.connect("shift", "List", "reverse", "List")
    graph.add_node(CullPattern(), "cull")
    graph.connect("reverse", "List", "cull", "List")
    graph.set_input_value("cull", "Pattern", PATTERN)
    graph.add_node(ListItem(), "item")
    graph.connect("cull", "List", "item", "List")
    graph.set_input_value("item", "Index", -1)
    graph.set_input_value("item", "Wrap", True)
    graph.add_node(ListLength(), "length")
    graph.connect("cull", "List", "length", "List")
    solver = Solver(graph)
    solver.solve()
    return graph, solver


def _numbers(solver: Solver) -> np.ndarray:
    (array,) = solver.result("r").output("Random").raw_branches
    assert isinstance(array, np.ndarray)
    return array


def _mask(n: int) -> np.ndarray:
    return np.tile(np.array(PATTERN), -(-n // len(PATTERN)))[:n]


def _numpy_chain(x: np.ndarray) -> Callable[[], list[object]]:
    def chain() -> list[object]:
        keys = x[np.argsort(x, kind="stable")]
        shifted = np.concatenate([keys[1:], keys[:1]])
        reversed_ = shifted[::-1]
        culled = reversed_[_mask(len(reversed_))]
        return [keys, shifted, reversed_, culled, culled[-1].item(), len(culled)]  # all kept, as the graph

    return chain


def test_the_list_node_chain_on_a_million_numbers_is_within_3x_numpy():
    graph, solver = _graph()
    x = _numbers(solver)

    def resolve() -> None:
        graph.expire("sort")  # the random numbers stay: the array already built
        solver.solve()

    ratio = ratio_to_baseline(
        "10^6 numbers -> Sort -> Shift -> Reverse -> Cull Pattern -> List Item, List Length, re-solve",
        resolve, "numpy, the same operations on the built array", _numpy_chain(x), 7,
    )
    expected = _numpy_chain(x)()
    assert solver.result("length").output("Length").first() == expected[5]
    assert solver.result("item").output("Item").first() == expected[4]
    assert ratio <= 3.0


def _alone(node: Node, port: str, **values: object) -> tuple[Graph, Solver]:
    graph = Graph()
    graph.add_node(Random(), "r")
    graph.set_input_value("r", "Number", MILLION)
    graph.add_node(node, "n")
    graph.connect("r", "Random", "n", port)
    for name, value in values.items():
        graph.set_input_value("n", name, value)
    solver = Solver(graph)
    solver.solve()
    return graph, solver


#: node, input, settings, what numpy does, pairs timed (more for the quick ones: a few ms
#: each, where one spike of the machine's load moves a median of 7)
NODES = {
    "Sort": (Sort, "Keys", {}, lambda x: x[np.argsort(x, kind="stable")], 7),
    "Shift": (Shift, "List", {"Shift": 3}, lambda x: np.concatenate([x[3:], x[:3]]), 41),
    "Cull Pattern": (CullPattern, "List", {"Pattern": PATTERN}, lambda x: x[_mask(len(x))], 41),
}


@pytest.mark.parametrize("name", list(NODES))
def test_a_list_node_on_a_million_numbers_is_within_3x_numpy(name):
    make, port, values, numpy_op, repeats = NODES[name]
    graph, solver = _alone(make(), port, **values)
    x = _numbers(solver)

    def resolve() -> None:
        graph.expire("n")
        solver.solve()

    ratio = ratio_to_baseline(
        f"{name} on 10^6 numbers, re-solve", resolve,
        "numpy, the same operation on the built array", lambda: numpy_op(x), repeats,
    )
    (result,) = solver.result("n").outputs[port if name == "Sort" else "List"].raw_branches
    assert isinstance(result, np.ndarray) and np.array_equal(result, numpy_op(x))
    assert ratio <= 3.0


def test_a_million_points_from_series_through_shift_are_within_3x_numpy():
    """Series 10⁶ → Point (X and Y from it) → Shift: one (n, 3) array made and rolled."""
    graph = Graph()
    graph.add_node(Series(), "s")
    graph.set_input_value("s", "Count", MILLION)
    graph.add_node(PointNode(), "p")
    graph.connect("s", "Series", "p", "X")
    graph.connect("s", "Series", "p", "Y")
    graph.add_node(Shift(), "shift")
    graph.connect("p", "Point", "shift", "List")
    solver = Solver(graph)
    solver.solve()
    (x,) = solver.result("s").output("Series").raw_branches

    def resolve() -> None:
        graph.expire("p")
        solver.solve()

    def numpy_points() -> list[np.ndarray]:
        xyz = np.column_stack([x, x, np.zeros(len(x))])
        return [xyz, np.concatenate([xyz[1:], xyz[:1]])]

    ratio = ratio_to_baseline(
        "Series 10^6 -> Point -> Shift, re-solve", resolve,
        "numpy, the (n, 3) array stacked and rolled", numpy_points, 7,
    )
    (shifted,) = solver.result("shift").output("List").raw_branches
    assert isinstance(shifted, Triples) and np.array_equal(shifted.array, numpy_points()[1])
    assert ratio <= 3.0
