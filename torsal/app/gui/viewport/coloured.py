"""Previews that never fight: an analysis's colour map replaces the surface it colours.

An analysis node (BendingCheck, SurfaceAnalysis...) draws its colours on the very surface
its input node draws; two coincident surfaces z-fight into streaks. While both are
previewed, the surfaces of the nodes wired into a node that draws a colour map are hidden
(their curves and rulings stay), and every colour map is drawn with a polygon offset
towards the camera, so it wins over any other surface lying on it (a design surface
that strips approximate within tolerance).
"""

from __future__ import annotations

from typing import Any

from torsal.engine.graph import Graph

#: the colour maps' offset (VTK's polygon offset: factor, units), towards the camera
COLOUR_MAP_OFFSET = (-2.0, -4.0)


def coloured_sources(graph: Graph, nodes: dict[str, Any]) -> set[str]:
    """Previewed nodes whose surfaces a previewed colour map lies on: the direct sources of
    every node drawing a colour map."""
    colouring = {n for n, entry in nodes.items() if any(p.kind == "scalars" for p in entry.pieces.values())}
    if not colouring:
        return set()
    return {w.source for w in graph.wires if w.target in colouring and w.source in nodes} - colouring


def replace_coloured(graph: Graph, nodes: dict[str, Any]) -> set[str]:
    """Hide the surfaces under colour maps, show every other surface, offset the colour
    maps; the ids of the nodes whose surfaces are hidden."""
    hidden = coloured_sources(graph, nodes)
    for node_id, entry in nodes.items():
        for name, piece in entry.pieces.items():
            actor = entry.actors[name]
            if piece.kind == "surfaces":
                visible = node_id not in hidden
                if bool(actor.GetVisibility()) != visible:
                    actor.SetVisibility(visible)
            elif piece.kind == "scalars":
                mapper = actor.GetMapper()
                mapper.SetResolveCoincidentTopologyToPolygonOffset()
                mapper.SetRelativeCoincidentTopologyPolygonOffsetParameters(*COLOUR_MAP_OFFSET)
    return hidden
