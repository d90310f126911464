"""Copy and paste as ``.graph`` fragments: JSON text any Torsal window can read.

A fragment is a small, complete graph file (same format, same validation) holding the
copied nodes, the wires between them and the definitions of the clusters among them.
Pasting reads it with the engine's file module (so a pasted fragment is only ever
*parsed*), gives the nodes fresh ids and moves them by an offset; a pasted cluster
shares the graph's definition when it has the same one.
"""

from __future__ import annotations

import dataclasses

from torsal.app.gui.graph_order import fresh_id
from torsal.engine.graph import Graph, NodeRecord, Wire
from torsal.engine.graphfile import (
    FORMAT,
    VERSION,
    adopt_clusters,
    encode,
    fragment_clusters,
    loads,
    node_data,
    wire_data,
)
from torsal.engine.registry import Registry

MIME_TYPE = "application/x-torsal-graph"


def copy_fragment(graph: Graph, node_ids: list[str]) -> str:
    """The text of a fragment holding ``node_ids`` and the wires among them."""
    wanted = set(node_ids)
    chosen = [n for n in graph.nodes if n in wanted]
    inside = set(chosen)
    data = {
        "format": FORMAT,
        "version": VERSION,
        "nodes": [node_data(graph.nodes[n]) for n in chosen],
        "wires": [wire_data(w) for w in graph.wires if w.source in inside and w.target in inside],
        "groups": [],
        "meta": {"fragment": True},
    }
    clusters = fragment_clusters(graph, chosen)  # the definitions its clusters use go with it
    if clusters:
        data["clusters"] = clusters
    return encode(data)


def looks_like_fragment(text: str) -> bool:
    return '"torsal.graph"' in text[:4096]


def paste_fragment(
    text: str,
    graph: Graph,
    registry: Registry,
    offset: tuple[float, float] = (20.0, 20.0),
    anchor: tuple[float, float] | None = None,
) -> tuple[list[NodeRecord], list[Wire]]:
    """Records and wires to add to ``graph`` for the fragment ``text``.

    Ids that clash are renamed (``slider`` → ``slider2``). With ``anchor`` the
    fragment's top-left node goes there; otherwise every node moves by ``offset``.
    Raises :class:`~torsal.engine.graphfile.GraphFileError` for text that is not a fragment.
    """
    fragment = loads(text, registry)
    renamed = fresh_ids(list(fragment.nodes), set(graph.nodes))
    if anchor is not None and fragment.nodes:
        left = min(r.position[0] for r in fragment.nodes.values())
        top = min(r.position[1] for r in fragment.nodes.values())
        offset = (anchor[0] - left, anchor[1] - top)
    records = [
        dataclasses.replace(
            record,
            id=renamed[record.id],
            position=(
                float(round(record.position[0] + offset[0])),
                float(round(record.position[1] + offset[1])),
            ),
        )
        for record in fragment.nodes.values()
    ]
    wires = [
        Wire(renamed[w.source], w.source_port, renamed[w.target], w.target_port, raw=w.raw)
        for w in fragment.wires
    ]
    adopt_clusters(graph, records)  # a definition the graph has already is shared, not doubled
    return records, wires


def fresh_ids(node_ids: list[str], taken: set[str]) -> dict[str, str]:
    """A new id for each of ``node_ids`` that clashes with ``taken`` (or with one given
    before it): the ids :func:`~torsal.app.gui.graph_order.fresh_id` gives one by one, found
    without searching each stem's numbers from 2 again (pasting ``e0``…``e999`` into a
    graph that has ``e0``…``e9999`` tries each number once, not once per node)."""
    taken = set(taken)
    next_number: dict[str, int] = {}  # stem → the smallest number that may still be free
    renamed: dict[str, str] = {}
    for node_id in node_ids:
        new_id = node_id
        if node_id in taken:
            stem = fresh_id(node_id, set())  # the stem fresh_id would use
            n = next_number.get(stem, 2)
            if stem not in taken:
                new_id = stem
            else:
                while f"{stem}{n}" in taken:
                    n += 1
                new_id = f"{stem}{n}"
                next_number[stem] = n + 1
        taken.add(new_id)
        renamed[node_id] = new_id
    return renamed
