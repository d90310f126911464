"""Move nodes of the bundled examples so that each opens on something readable, and
keep their previews from fighting.

The app frames an opened file whole when it can be read at 0.6 zoom, otherwise the
region around its last (most downstream) previewed node and what feeds it
(``torsal/app/gui/canvas/opening_focus.py``). So that region must be compact: a slider
that feeds only the result sits beside it (as a Grasshopper user places it), not in the
inputs column two metres of canvas away, and empty columns are closed up.

Previews never fight: a flat development is laid beside the model (the
development-placement rule, Placement 0), never under it, and a check that would draw
the same development again has its preview off (its numbers still read in the panels).

Only positions, group membership, those placements and previews change; node ids,
other values and wires stay as they are. The example files are data edited since
``tools/build_examples.py`` last wrote them, so this script edits them in place, through
the engine's own reader and writer. Run ``.venv/bin/python tools/relayout_examples.py``;
it is idempotent.
"""

from __future__ import annotations

from pathlib import Path

from torsal.engine.graph import Graph
from torsal.engine.graphfile import read_graph, write_graph
from torsal.nodes.catalogue import default_registry

OUT = Path(__file__).resolve().parent.parent / "torsal" / "resources" / "examples"

#: example → (columns from this x on move left by this much, or None), {node: new position},
#: {node: (group it leaves, group it joins)}
KAOHSIUNG = (
    (1340.0, 260.0),
    {"segments": (1860.0, 590.0)},
    {"segments": ("inputs", "strips")},
)
MOVES = {
    "kaohsiung-stadium": KAOHSIUNG,
    "kaohsiung-cut-sheets": KAOHSIUNG,
    "guggenheim-ny": (None, {"segments": (1080.0, 260.0)}, {"segments": ("inputs", "rings")}),
    "zve-roof-edge": (None, {"segments": (1340.0, 350.0)}, {"segments": ("inputs", "surface")}),
    "spline-approximation": (
        None,
        {"edge_a": (820.0, 40.0), "segments": (1600.0, 240.0)},
        {"segments": ("inputs", "approx")},
    ),
}


#: example → ({(node, input): value}, nodes whose preview goes off)
PREVIEWS = {
    # the strip's Development beside the bent strip, not under it; the re-unrolled check
    # would lie exactly on it: its preview is off
    "paper-strip": ({("strip", "Placement"): 0}, ["unroll"]),
    # the developable roof edge and the plain loft it is compared with share their rims and
    # most of their middle: the loft's preview is off (turn it on to compare)
    "zve-roof-edge": ({}, ["loft"]),
    # the first approximation and the finished strip lie within millimetres of each other:
    # the finished strip is shown
    "spline-approximation": ({}, ["approx"]),
}


def separate_previews(graph: Graph, values: dict[tuple[str, str], object], hidden: list[str]) -> None:
    for (node_id, port), value in values.items():
        graph.set_input_value(node_id, port, value)
    for node_id in hidden:
        graph.set_preview(node_id, False)


def relayout(graph: Graph, close: tuple[float, float] | None, moves: dict, regroup: dict) -> None:
    if close is not None:
        start, step = close
        gap = [r for r in graph.nodes.values() if start - step <= r.position[0] < start]
        if not gap:  # the empty column is still there: close it up
            for record in graph.nodes.values():
                if record.position[0] >= start:
                    record.position = (record.position[0] - step, record.position[1])
    for node_id, position in moves.items():
        graph.nodes[node_id].position = position
    groups = {g.id: g for g in graph.groups}
    for node_id, (leave, join) in regroup.items():
        if node_id in groups[leave].nodes:
            groups[leave].nodes.remove(node_id)
        if node_id not in groups[join].nodes:
            groups[join].nodes.append(node_id)


def main() -> None:
    registry = default_registry(plugins=False)
    for name in sorted(set(MOVES) | set(PREVIEWS)):
        path = OUT / f"{name}.graph"
        graph = read_graph(path, registry)
        if name in MOVES:
            relayout(graph, *MOVES[name])
        if name in PREVIEWS:
            separate_previews(graph, *PREVIEWS[name])
        write_graph(graph, path)
        print(f"relaid {name}.graph")


if __name__ == "__main__":
    main()
