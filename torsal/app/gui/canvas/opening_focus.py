"""What an opened file should show first when the whole graph cannot be read at once.

A graph reads from its inputs (left) to its result (right); a designer opening a file
wants the result and what feeds it. :func:`focus_regions` names, from the widest to the
narrowest, the node sets worth framing: the last (most downstream) previewed nodes with
what feeds them two wires back, then with what feeds them directly, then the single
last node with its direct inputs, then that node alone. The view frames the first that
is readable (see ``CanvasView.frame_opened``).

"Previewed" means the node's preview is on, it is enabled, and one of its previewed
outputs carries geometry (not a number, text, true/false or a domain).
"""

from __future__ import annotations

from collections.abc import Iterable

from torsal.engine.graph import Graph

#: Value types the viewport never draws: a node giving only these is not "previewed".
NOT_DRAWN = frozenset({"Number", "Integer", "Boolean", "Text", "Domain", "Colour"})


def depths(graph: Graph) -> dict[str, int]:
    """Each node's longest count of wires from a node nothing feeds (0 for those)."""
    feeds: dict[str, set[str]] = {n: set() for n in graph.nodes}
    for wire in graph.wires:
        if wire.source in feeds and wire.target in feeds:
            feeds[wire.target].add(wire.source)
    depth: dict[str, int] = {}
    for start in graph.nodes:
        stack = [(start, False)]
        while stack:  # iterative depth-first walk: a long chain cannot overflow the stack
            node, ready = stack.pop()
            if node in depth:
                continue
            if ready:
                depth[node] = 1 + max((depth[s] for s in feeds[node]), default=-1)
                continue
            stack.append((node, True))
            stack.extend((s, False) for s in feeds[node] if s not in depth)
    return depth


def previewed(graph: Graph, node_id: str) -> bool:
    record = graph.nodes[node_id]
    if not record.preview or not record.enabled:
        return False
    outputs = [p for p in record.node.output_ports() if p.preview]
    return any(p.type.name not in NOT_DRAWN for p in outputs)


def _upstream(graph: Graph, nodes: Iterable[str], hops: int) -> set[str]:
    found = set(nodes)
    frontier = set(found)
    for _ in range(hops):
        frontier = {w.source for w in graph.wires if w.target in frontier} - found
        found |= frontier
    return found


def focus_regions(graph: Graph, x_of: dict[str, float]) -> list[set[str]]:
    """Node sets to frame, widest first (empty when nothing is previewed). ``x_of``: each
    node's position along the canvas, to pick the rightmost of equally deep nodes."""
    depth = depths(graph)
    shown = [n for n in graph.nodes if previewed(graph, n)]
    if not shown:
        shown = list(graph.nodes)
    if not shown:
        return []
    deepest = max(depth[n] for n in shown)
    last = sorted((n for n in shown if depth[n] == deepest), key=lambda n: -x_of.get(n, 0.0))
    one = last[:1]
    return [
        _upstream(graph, last, 2),
        _upstream(graph, last, 1),
        _upstream(graph, one, 1),
        set(one),
    ]
