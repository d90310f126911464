"""Putting a graph's nodes, wires and groups back in a remembered order.

Undoing a deletion must give back the *same file bytes*, and a ``.graph`` file lists
nodes, wires and groups in the graph's order. The engine appends what is added, so
after re-adding removed items these helpers restore the order they had.

Engine gap (reported): ``Graph.add_record``/``connect_wire``/``add_group`` could take
an ``index``; until then nodes and groups are reordered in their public containers
(same ids, same edges: the solver's cached topological order stays valid) and wires
are reconnected through the graph's own validated ``disconnect``/``connect_wire``, so
the per-input wire order the solver merges by is kept consistent.
"""

from __future__ import annotations

from torsal.engine.graph import Graph, Group, Wire


def restore_node_order(graph: Graph, order: list[str]) -> None:
    """Reorder ``graph.nodes`` to follow ``order`` (ids not in it keep their place at the end)."""
    if list(graph.nodes) == order:
        return
    records = dict(graph.nodes)
    graph.nodes.clear()
    for node_id in order:
        if node_id in records:
            graph.nodes[node_id] = records.pop(node_id)
    graph.nodes.update(records)


def restore_wire_order(graph: Graph, order: list[Wire]) -> None:
    """Reconnect wires so that ``graph.wires`` follows ``order`` (extra wires go last)."""
    current = list(graph.wires)
    present = set(current)
    wanted = [w for w in order if w in present]
    listed = set(wanted)
    wanted += [w for w in current if w not in listed]
    first = next((i for i, (a, b) in enumerate(zip(current, wanted, strict=True)) if a != b), None)
    if first is None:
        return
    by_key = {w: w for w in current}  # the very objects (they carry the file's raw data)
    tail = wanted[first:]
    for wire in current[first:]:
        graph.disconnect(wire)
    for wire in tail:
        graph.connect_wire(by_key[wire])


def restore_group_order(graph: Graph, order: list[str]) -> None:
    """Reorder ``graph.groups`` by id to follow ``order``."""
    position = {gid: i for i, gid in enumerate(order)}
    graph.groups.sort(key=lambda g: position.get(g.id, len(order)))


def group_by_id(graph: Graph, group_id: str) -> Group | None:
    return next((g for g in graph.groups if g.id == group_id), None)


def fresh_id(base: str, taken: set[str]) -> str:
    """An id from ``base`` not in ``taken`` (``slider``, ``slider2``, ...)."""
    stem = "".join(c for c in base.lower() if c.isalnum() or c in "_-") or "node"
    stem = stem.rstrip("0123456789") or stem
    if stem not in taken:
        return stem
    n = 2
    while f"{stem}{n}" in taken:
        n += 1
    return f"{stem}{n}"
