"""Small graphs for the exploration tests: sliders feeding one formula each."""

from __future__ import annotations

from pathlib import Path

from torsal.engine.graph import Graph
from torsal.engine.graphfile import write_graph
from torsal.nodes.maths.expression import Expression
from torsal.nodes.params.sliders import IntegerSlider, NumberSlider


def formula_graph(
    path: Path,
    sliders: dict[str, tuple[float, float, float]],
    formulas: dict[str, str],
    decimals: int = 8,
    integers: tuple[str, ...] = (),
) -> Path:
    """A graph of sliders ``{id: (min, max, value)}`` and Expression nodes ``{id: formula}``.

    Each formula may use every slider's id as a variable.
    """
    graph = Graph()
    names = list(sliders)
    for name, (low, high, value) in sliders.items():
        if name in integers:
            graph.add_node(IntegerSlider({"min": int(low), "max": int(high), "value": int(value)}), name)
        else:
            settings = {"min": low, "max": high, "value": value, "decimals": decimals}
            graph.add_node(NumberSlider(settings), name)
    for node_id, formula in formulas.items():
        graph.add_node(Expression({"expression": formula, "variables": list(names)}), node_id)
        for name in names:
            graph.connect(name, "Value", node_id, name)
    write_graph(graph, path)
    return path
