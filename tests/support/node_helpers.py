"""Helpers to solve one node on a small graph with the real Solver."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from torsal.engine.datatree import DataTree
from torsal.engine.graph import Graph
from torsal.engine.node import TREE, Node, Out
from torsal.engine.solver import NodeResult, Solver
from torsal.engine.types import GENERIC, encode_value
from torsal.engine.writes import WriteAccess


class Source(Node):
    """Test-only node that outputs the data tree it was built with."""

    type_id = "test.Source"
    outputs = (Out("Tree", GENERIC, "T", "The tree given to the test.", access=TREE),)

    def __init__(self, tree: DataTree) -> None:
        super().__init__()
        self.tree = tree

    def solve(self) -> DataTree:
        return self.tree


def tree(branches: dict[tuple[int, ...], list[Any]]) -> DataTree:
    """``tree({(0,): [1, 2], (1,): [3]})``: a DataTree from paths to lists."""
    return DataTree(branches)


def run(
    node: Node,
    modifiers: dict[str, list[str]] | None = None,
    writes: WriteAccess | None = None,
    **inputs: Any,
) -> NodeResult:
    """Solve ``node`` with ``inputs``: a DataTree is wired in from a Source node, anything
    else is set as the input's persistent value (as a ``.graph`` file would hold it).
    ``writes`` is where the node may write files (by default nowhere)."""
    graph = Graph()
    graph.add_node(node, "node")
    for name, value in inputs.items():
        if isinstance(value, DataTree):
            graph.add_node(Source(value), f"src_{name}")
            graph.connect(f"src_{name}", "Tree", "node", name)
        else:
            graph.set_input_value("node", name, encode_value(value))
    for name, mods in (modifiers or {}).items():
        graph.set_modifiers("node", name, mods)
    solver = Solver(graph, writes)
    solver.solve()
    return solver.result("node")


def allowed(folder: Any) -> WriteAccess:
    """Writes allowed, into ``folder`` (as ``torsal run --allow-writes`` on a graph there)."""
    return WriteAccess(Path(folder), allowed=True)


def out(result: NodeResult, port: str | None = None) -> dict[tuple[int, ...], list[Any]]:
    """An output tree as ``{path: items}`` (the only output when ``port`` is not given)."""
    if port is None:
        (port,) = result.outputs
    return dict(result.output(port).items())


def texts(result: NodeResult) -> list[str]:
    return [m.text for m in result.messages]
