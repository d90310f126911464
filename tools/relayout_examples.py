"""Move nodes of the bundled examples so that each opens on something readable.

The app frames an opened file whole when it can be read at 0.6 zoom, otherwise the
region around its last (most downstream) previewed node and what feeds it
(``torsal/app/gui/canvas/opening_focus.py``). So that region must be compact: a slider
that feeds only the result sits beside it (as a Grasshopper user places it), not in the
inputs column two metres of canvas away, and empty columns are closed up.

Only positions and group membership change (a group is layout only); node ids, values
and wires stay as they are. The example files are data edited since
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
    "zve-roof-edge": (None, {"segments": (1080.0, 260.0)}, {"segments": ("inputs", "surface")}),
    "spline-approximation": (
        None,
        {"edge_a": (820.0, 40.0), "segments": (1600.0, 150.0)},
        {"segments": ("inputs", "approx")},
    ),
}


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
    for name, (close, moves, regroup) in MOVES.items():
        path = OUT / f"{name}.graph"
        graph = read_graph(path, registry)
        relayout(graph, close, moves, regroup)
        write_graph(graph, path)
        print(f"relaid {name}.graph")


if __name__ == "__main__":
    main()
