"""What graph edits cost as the graph grows (``make bench``): each edit costs what it
touches, loading is linear.

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_graph_edits.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

The bars, each a ratio to a baseline measured in the same run (see
:mod:`tests.benchmarks.timing`):

- building a 10,000-node chain, and a 100 × 100 lattice, through the API (``add_node``
  and ``connect``, every wire checked for loops) costs at most 3× loading the same
  graph from its file;
- changing a setting of a leaf node and re-solving costs at most 3× as much in a
  10,000-node graph as in a 100-node one;
- loading 10,000 nodes costs at most 1.5 × 10 × loading 1,000.

``make test`` checks that the graph's indexes stay equal to a rebuild from scratch
(``tests/engine/test_graph_indexes.py``).
"""

from __future__ import annotations

from tests.benchmarks.timing import ratio_to_baseline
from tests.support.nodekit import make_registry
from torsal.engine import graphfile
from torsal.engine.graph import Graph
from torsal.engine.solver import Solver

REGISTRY = make_registry()
SIDE = 100  # the lattice is SIDE × SIDE nodes


def chain_wires(count: int) -> list[tuple[str, str, str, str]]:
    """``n0 → n1 → …``: each node's Result into the next one's A."""
    return [(f"n{i}", "Result", f"n{i + 1}", "A") for i in range(count - 1)]


def lattice_wires(side: int) -> list[tuple[str, str, str, str]]:
    """Node ``n{i}_{j}`` takes A from the node above it and B from the one to its left."""
    wires = []
    for i in range(side):
        for j in range(side):
            if i:
                wires.append((f"n{i - 1}_{j}", "Result", f"n{i}_{j}", "A"))
            if j:
                wires.append((f"n{i}_{j - 1}", "Result", f"n{i}_{j}", "B"))
    return wires


def build(ids: list[str], wires: list[tuple[str, str, str, str]]) -> Graph:
    """The graph of ``maths.Add`` nodes and ``wires``, through the public edits."""
    graph = Graph()
    for node_id in ids:
        graph.add_node(REGISTRY.create("maths.Add"), node_id)
    for source, source_port, target, target_port in wires:
        graph.connect(source, source_port, target, target_port)
    return graph


def file_text(ids: list[str], wires: list[tuple[str, str, str, str]]) -> str:
    """The same graph as a ``.graph`` file."""
    return graphfile.dumps(build(ids, wires))


def chain_ids(count: int) -> list[str]:
    return [f"n{i}" for i in range(count)]


def lattice_ids(side: int) -> list[str]:
    return [f"n{i}_{j}" for i in range(side) for j in range(side)]


def test_building_a_10000_node_chain_through_the_api_costs_at_most_3x_loading_it():
    ids, wires = chain_ids(10_000), chain_wires(10_000)
    text = file_text(ids, wires)
    ratio = ratio_to_baseline(
        "build a 10,000-node chain with add_node and connect",
        lambda: build(ids, wires),
        "load the same chain from its file",
        lambda: graphfile.loads(text, REGISTRY),
        7,
    )
    assert ratio <= 3.0


def test_building_a_100x100_lattice_through_the_api_costs_at_most_3x_loading_it():
    ids, wires = lattice_ids(SIDE), lattice_wires(SIDE)
    text = file_text(ids, wires)
    ratio = ratio_to_baseline(
        f"build a {SIDE} × {SIDE} lattice with add_node and connect",
        lambda: build(ids, wires),
        "load the same lattice from its file",
        lambda: graphfile.loads(text, REGISTRY),
        7,
    )
    assert ratio <= 3.0


def leaf_edits(count: int, edits: int = 2000):
    """A function making ``edits`` changes to the last node of a ``count``-node chain,
    each followed by a re-solve."""
    graph = build(chain_ids(count), chain_wires(count))
    solver = Solver(graph)
    solver.solve()
    leaf = f"n{count - 1}"
    values = iter(range(10**9))

    def edit_and_solve() -> None:
        for _ in range(edits):
            graph.set_input_value(leaf, "B", float(next(values)))
            solver.solve()

    return edit_and_solve


def test_a_leaf_edit_and_re_solve_costs_at_most_3x_as_much_in_10000_nodes_as_in_100():
    big, small = leaf_edits(10_000), leaf_edits(100)
    ratio = ratio_to_baseline(
        "2,000 leaf edits + re-solves in a 10,000-node chain",
        big,
        "the same in a 100-node chain",
        small,
        15,
    )
    assert ratio <= 3.0


def test_loading_10000_nodes_costs_at_most_15x_loading_1000():
    big = file_text(lattice_ids(SIDE), lattice_wires(SIDE))
    small_side = 32  # 1,024 nodes
    small = file_text(lattice_ids(small_side), lattice_wires(small_side))
    ratio = ratio_to_baseline(
        f"load a {SIDE * SIDE:,}-node lattice",
        lambda: graphfile.loads(big, REGISTRY),
        f"load a {small_side * small_side:,}-node lattice",
        lambda: graphfile.loads(small, REGISTRY),
        9,
    )
    per_node = ratio * small_side * small_side / (SIDE * SIDE)
    print(f"  cost per node: {per_node:.2f}× the small file's")
    assert per_node <= 1.5

