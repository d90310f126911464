"""Small real graphs for the direct-modelling and patching node tests.

``Chain`` adds nodes, sets persistent input values (as a ``.graph`` file holds them),
wires ports and solves with the real Solver. ``helix`` adds a curves.ParametricCurve
node for C(t) = (R cos t, R sin t, c t).
"""

from __future__ import annotations

import math
from typing import Any

from tests.support.node_helpers import Source, tree
from torsal.engine.graph import Graph
from torsal.engine.node import Node
from torsal.engine.solver import NodeResult, Solver
from torsal.engine.types import encode_value
from torsal.engine.values import Domain
from torsal.nodes.curves.splines import ParametricCurve


class Chain:
    """A graph under construction: ``add`` nodes, ``wire`` them, ``solve``, read ``result``."""

    def __init__(self) -> None:
        self.graph = Graph()
        self.solver = Solver(self.graph)

    def add(self, node_id: str, node: Node, **values: Any) -> str:
        self.graph.add_node(node, node_id)
        for name, value in values.items():
            self.set(node_id, name, value)
        return node_id

    def set(self, node_id: str, name: str, value: Any) -> None:
        self.graph.set_input_value(node_id, name, encode_value(value))

    def source(self, node_id: str, *items: Any) -> str:
        """A node that outputs ``items`` as one list (kernel objects with no persistent form)."""
        self.graph.add_node(Source(tree({(0,): list(items)})), node_id)
        return node_id

    def wire(self, source: str, port: str, target: str, target_port: str) -> None:
        src_port = "Tree" if isinstance(self.graph.nodes[source].node, Source) else port
        self.graph.connect(source, src_port, target, target_port)

    def solve(self) -> Chain:
        self.solver.solve()
        return self

    def result(self, node_id: str) -> NodeResult:
        return self.solver.result(node_id)

    def items(self, node_id: str, port: str) -> list[Any]:
        """All items of an output, branch after branch."""
        return [item for branch in self.result(node_id).output(port).branches for item in branch]

    def item(self, node_id: str, port: str) -> Any:
        (value,) = self.items(node_id, port)
        return value

    def texts(self, node_id: str) -> list[str]:
        return [m.text for m in self.result(node_id).messages]


def helix(chain: Chain, radius: float, rise: float, turns: float, node_id: str = "helix") -> str:
    """curves.ParametricCurve for C(t) = (R cos t, R sin t, c·t), t from 0 to 2π·turns."""
    return chain.add(
        node_id, ParametricCurve(),
        X=f"{radius!r} * cos(t)", Y=f"{radius!r} * sin(t)", Z=f"{rise!r} * t",
        Domain=Domain(0.0, 2 * math.pi * turns),
    )
