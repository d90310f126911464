"""Write the example graphs in ``resources/examples/`` through the engine's own API.

Run ``.venv/bin/python tools/build_examples.py [NAME ...]`` after changing a node's
ports; the files are data and are committed, this script only documents how they were
made (positions in columns, left to right, groups around each stage).
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable
from pathlib import Path
from typing import Any

from engine.graph import Graph, Group
from engine.graphfile import write_graph
from nodes.catalogue import default_registry

OUT = Path(__file__).resolve().parent.parent / "resources" / "examples"
REGISTRY = default_registry(plugins=False)
COLUMN, ROW = 260.0, 110.0


def point(x: float, y: float, z: float) -> dict[str, Any]:
    return {"type": "Point", "xyz": [round(x, 6), round(y, 6), round(z, 6)]}


class Builder:
    """A graph under construction: nodes placed on a grid of columns and rows."""

    def __init__(self, description: str) -> None:
        self.graph = Graph()
        self.graph.meta = {"description": description, "created_with": "torsal 0.1.0"}

    def node(self, type_id: str, node_id: str, column: float, row: float, label: str = "",
             settings: dict[str, Any] | None = None, **values: Any) -> str:
        self.graph.add_node(REGISTRY.create(type_id, settings), node_id, label=label,
                            position=(40.0 + column * COLUMN, 40.0 + row * ROW))
        for port, value in values.items():
            self.graph.set_input_value(node_id, port, value)
        return node_id

    def slider(self, node_id: str, row: float, label: str, value: float, low: float, high: float,
               decimals: int = 2, column: float = 0) -> str:
        return self.node("params.NumberSlider", node_id, column, row, label,
                         {"value": value, "min": low, "max": high, "decimals": decimals})

    def integer(self, node_id: str, row: float, label: str, value: int, low: int, high: int,
                column: float = 0) -> str:
        return self.node("params.IntegerSlider", node_id, column, row, label,
                         {"value": value, "min": low, "max": high})

    def wire(self, source: str, target: str, modifiers: list[str] | None = None) -> None:
        (a, port_a), (b, port_b) = source.split("."), target.split(".")
        self.graph.connect(a, port_a, b, port_b)
        if modifiers:
            self.graph.set_modifiers(b, port_b, modifiers)

    def group(self, group_id: str, title: str, colour: str, members: list[str]) -> None:
        self.graph.groups.append(Group(group_id, title, colour, members))

    def save(self, name: str) -> None:
        write_graph(self.graph, OUT / f"{name}.graph")
        print(f"wrote {name}.graph: {len(self.graph.nodes)} nodes, {len(self.graph.wires)} wires")


INPUTS, GEOMETRY, RESULT = "#e8e0f4", "#dceee2", "#f6e6d0"


def kaohsiung() -> None:
    """Kaohsiung Solar Stadium (Toyo Ito): a horseshoe base curve, copied up and scaled in;
    edge curves through points shifted by n and 2n along the three curves; a
    RulingDevelopable strip between each pair of neighbouring edges."""
    b = Builder(
        "Kaohsiung Solar Stadium roof (after Toyo Ito), as in the 2011 TU Delft toolbox case "
        "study: a horseshoe base curve is copied up and scaled inwards; the three curves are "
        "divided, and edge curves run through points shifted by n and 2n along them. Between "
        "neighbouring edges, RulingDevelopable makes developable strips: each strip bends one "
        "way only, yet together they read as a double-curved roof. Drag 'Inward scale' or "
        "'Shift n' and watch the strips re-form."
    )
    # a horseshoe: an ellipse open towards +x
    angles = [math.radians(a) for a in range(40, 321, 35)]
    horseshoe = [point(60 * math.cos(a), 42 * math.sin(a), 0.0) for a in angles]
    b.slider("height", 0, "Roof height (m)", 14.0, 4.0, 30.0, 1)
    b.slider("scale", 1, "Inward scale", 0.72, 0.4, 0.95, 2)
    b.integer("count", 2, "Edge points", 24, 8, 60)
    b.integer("shift", 3, "Shift n", 2, 0, 6)
    b.integer("segments", 4, "Segments per strip", 12, 2, 60)
    b.node("curves.Interpolate", "base", 1, 0, "Horseshoe base curve", Vertices=horseshoe, Degree=3)
    b.node("params.UnitZ", "up", 1, 1.5, "Up")
    b.node("transform.Move", "top", 2, 0, "Copied up")
    b.node("params.Point", "centre", 2, 1.5, "Scale centre", X=0.0, Y=0.0, Z=28.0)
    b.node("transform.Scale", "inner", 3, 0, "Scaled inwards")
    b.wire("height.Value", "up.Factor")
    b.wire("base.Curve", "top.Geometry")
    b.wire("up.Vector", "top.Motion")
    b.wire("top.Geometry", "inner.Geometry")
    b.wire("centre.Point", "inner.Centre")
    b.wire("scale.Value", "inner.Factor")
    for column, (node_id, source) in enumerate([("divide0", "base.Curve"), ("divide1", "top.Geometry"),
                                                ("divide2", "inner.Geometry")]):
        b.node("curves.DivideCurve", node_id, 4, 3 + column, f"Divide curve {column}")
        b.wire(source, f"{node_id}.Curve")
        b.wire("count.Value", f"{node_id}.Count")
    # how many edge curves fit once the lists are shifted by n and 2n: count + 1 - 2n
    b.node("maths.Expression", "edges", 1, 3, "Edge count",
           {"expression": "count + 1 - 2 * n", "variables": ["count", "n"]})
    b.node("maths.Expression", "starts", 1, 4.5, "Shifts 0, n, 2n",
           {"expression": "k * n", "variables": ["k", "n"]}, k=[0, 1, 2])
    b.wire("count.Value", "edges.count")
    b.wire("shift.Value", "edges.n")
    b.wire("shift.Value", "starts.n")
    for k in range(3):
        b.node("lists.ListItem", f"start{k}", 2, 3 + k, f"Shift by {k}n", Index=k)
        b.wire("starts.Result", f"start{k}.List")
        b.node("maths.Series", f"index{k}", 3, 3 + k, f"Indices from {k}n")
        b.wire(f"start{k}.Item", f"index{k}.Start")
        b.wire("edges.Result", f"index{k}.Count")
        b.node("lists.ListItem", f"pick{k}", 5, 3 + k, f"Points {k}")
        b.wire(f"divide{k}.Points", f"pick{k}.List")
        b.wire(f"index{k}.Series", f"pick{k}.Index", ["graft"])  # one branch per edge curve
    b.node("curves.Interpolate", "edge_curves", 6, 3, "Strip edge curves", Degree=2)
    for k in range(3):
        b.wire(f"pick{k}.Item", "edge_curves.Vertices")
    b.node("maths.Expression", "strips", 6, 5, "Strip count",
           {"expression": "edges - 1", "variables": ["edges"]})
    b.wire("edges.Result", "strips.edges")
    b.node("maths.Series", "left_index", 7, 5, "Left edges", Start=0)
    b.node("maths.Series", "right_index", 7, 6, "Right edges", Start=1)
    b.wire("strips.Result", "left_index.Count")
    b.wire("strips.Result", "right_index.Count")
    b.node("lists.ListItem", "left", 8, 3, "Left edge")
    b.node("lists.ListItem", "right", 8, 4, "Right edge")
    b.wire("edge_curves.Curve", "left.List", ["flatten"])
    b.wire("edge_curves.Curve", "right.List", ["flatten"])
    b.wire("left_index.Series", "left.Index")
    b.wire("right_index.Series", "right.Index")
    b.node("developable.RulingDevelopable", "strip", 9, 3, "Developable strips", WarpTolerance=0.01)
    b.wire("left.Item", "strip.CurveA")
    b.wire("right.Item", "strip.CurveB")
    b.wire("segments.Value", "strip.Segments")
    b.group("inputs", "Inputs", INPUTS, ["height", "scale", "count", "shift", "segments"])
    b.group("roof", "Base curve, copied up and in", GEOMETRY, ["base", "up", "top", "centre", "inner"])
    b.group("edges", "Edge curves through shifted points", GEOMETRY,
            ["divide0", "divide1", "divide2", "edges", "starts", "start0", "start1", "start2",
             "index0", "index1", "index2", "pick0", "pick1", "pick2", "edge_curves"])
    b.group("strips", "Developable strips", RESULT,
            ["strips", "left_index", "right_index", "left", "right", "strip"])
    b.save("kaohsiung-stadium")


EXAMPLES: dict[str, Callable[[], None]] = {"kaohsiung-stadium": kaohsiung}

if __name__ == "__main__":
    for name in sys.argv[1:] or list(EXAMPLES):
        EXAMPLES[name]()
