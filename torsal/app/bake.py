"""Bake: the geometry of a set of nodes (the GUI passes the previewed ones) into one .3dm.

As Grasshopper's Bake puts what the canvas previews into the Rhino document, :func:`bake`
writes every curve, surface, mesh and point that the given nodes output to one Rhino file,
through the same writer as ``io.Export3dm`` (:func:`torsal.nodes.io.formats.threedm.write_3dm`, whose
entries come from :func:`~torsal.nodes.io.formats.threedm.tree_entries`):

- one layer per node, ``Parent::Title``, where Parent names the graph (its file's stem
  in the GUI) and Title is the node's label, or its type's name when it has none; the
  layer has the colour of the node's group on the canvas. Two
  nodes with the same title are told apart by their ids: ``Curvature analysis
  (torus_analysis)``. Characters Rhino refuses in a name (control characters, ``::``, a
  leading bracket or space) are replaced or dropped.
- every object named after its output and its number there (``Surface 1``, ``Rulings
  12``), with the user strings ``TorsalNode``, ``TorsalOutput``, ``TorsalPath`` and
  ``TorsalIndex`` saying where it came from; a developable strip goes face by face along
  its rulings (:mod:`torsal.nodes.io.formats.threedm_strips`), each face also carrying
  ``TorsalRulings`` (``3-14``) and ``TorsalFace`` (torsal or fan), the strip's faces in
  one Rhino group;
- the file in the graph's units.

Values that are not geometry (numbers, text, vectors, domains, planes, cut layouts) are
left out and counted. Nothing here imports Qt.

Example:
    >>> baked = bake(graph, results, ["cylinder", "helicoid"], Path("model.3dm"))  # doctest: +SKIP
    >>> baked.objects, baked.layers["cylinder"]  # doctest: +SKIP
    (100, ('Torsal::Cylinder', 50))
"""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

from torsal.app.exports import ExportError
from torsal.engine.graph import Graph
from torsal.engine.solver import NodeResult

#: The parent layer when the graph has no name of its own (an untitled document).
DEFAULT_PARENT = "Torsal"


@dataclass(frozen=True)
class Baked:
    """What :func:`bake` wrote."""

    path: Path
    objects: int
    layers: dict[str, tuple[str, int]]  #: node id -> (layer path, objects on it), nodes with geometry only
    skipped: int  #: items of the baked nodes that are not geometry
    deviation: float  #: the largest distance of an interpolated NURBS form from its object


def is_geometry(value: Any) -> bool:
    """Whether ``value`` is something a .3dm file holds: a curve, surface, mesh or point."""
    from torsal.engine.values import Point
    from torsal.nodes.geometry.curve_base import Curve
    from torsal.nodes.geometry.mesh_surface import MeshSurface
    from torsal.nodes.geometry.surface_base import Surface
    from torsal.nodes.geometry.trimesh_type import TriangleMesh

    return isinstance(value, Curve | Surface | MeshSurface | TriangleMesh | Point)


def layer_name(text: str, fallback: str = DEFAULT_PARENT) -> str:
    """``text`` as a valid Rhino layer name: no control characters, no ``::`` (the path
    separator), not beginning with a space or bracket; ``fallback`` if nothing is left."""
    name = re.sub(r"[\x00-\x1f\x7f]+", " ", text).replace("::", ":")
    name = name.strip().lstrip("()[]{} ").strip()
    return name or fallback


def node_layers(graph: Graph, node_ids: Iterable[str], parent: str = DEFAULT_PARENT) -> dict[str, str]:
    """The layer path of each node, in graph order: ``parent::title``, with `` (id)`` added
    to titles that two of the nodes share (Rhino compares layer names without case)."""
    ordered = [n for n in graph.nodes if n in set(node_ids)]
    titles = {n: layer_name(graph.nodes[n].title, n) for n in ordered}
    counts = Counter(title.casefold() for title in titles.values())
    top = layer_name(parent)
    return {
        n: f"{top}::{title}" if counts[title.casefold()] == 1 else f"{top}::{title} ({n})"
        for n, title in titles.items()
    }


def bake_entries(
    graph: Graph, results: Mapping[str, NodeResult], node_ids: Iterable[str], parent: str = DEFAULT_PARENT
) -> tuple[list[Any], dict[str, str], int]:
    """The .3dm entries for the geometry of ``node_ids`` (those with results), their
    layers by node id (only nodes with geometry), and how many other items were left out."""
    from torsal.nodes.io.formats import threedm

    wanted = [n for n in node_ids if n in graph.nodes and n in results]
    geometry: dict[str, list[tuple[str, Any]]] = {}
    skipped = 0
    for node_id in wanted:
        drawn = graph.nodes[node_id].node.previewed_outputs()
        for port, tree in results[node_id].outputs.items():
            if port not in drawn:
                continue
            items = [item for item in tree.all_items() if item is not None]
            shapes = sum(is_geometry(item) for item in items)
            skipped += len(items) - shapes
            if shapes:
                kept = tree.map(lambda item: item if is_geometry(item) else None)
                geometry.setdefault(node_id, []).append((port, kept))
    layers = node_layers(graph, geometry, parent)
    entries = []
    for node_id, layer in layers.items():
        for port, tree in geometry[node_id]:
            extra = (("TorsalNode", node_id), ("TorsalOutput", port))
            for entry in threedm.tree_entries(tree, layer, port):
                entries.append(replace(entry, strings=extra + entry.strings))
    return entries, layers, skipped


def node_colours(graph: Graph, layers: Mapping[str, str]) -> dict[str, tuple[int, int, int, int]]:
    """Each baked node's layer coloured as the node's group on the canvas (ungrouped nodes'
    layers keep Rhino's default): ``{layer path: (r, g, b, a)}``."""
    colours = {}
    for group in graph.groups:
        text = str(group.colour).lstrip("#")
        if len(text) != 6:
            continue
        try:
            rgb = tuple(int(text[i:i + 2], 16) for i in (0, 2, 4))
        except ValueError:
            continue
        for node_id in group.nodes:
            if node_id in layers:
                colours.setdefault(layers[node_id], (*rgb, 255))
    return colours


def nothing_to_bake(count: int) -> str:
    """What to say when none of ``count`` nodes has geometry."""
    return (
        f"Nothing to bake: none of the {count} previewed nodes has geometry (curves, surfaces, "
        "meshes or points). Turn on the preview of a node that makes some."
    )


def bake(
    graph: Graph,
    results: Mapping[str, NodeResult],
    node_ids: Iterable[str],
    path: Path,
    parent: str = DEFAULT_PARENT,
) -> Baked:
    """Write the geometry of ``node_ids`` to the .3dm file ``path`` in the graph's units.

    Raises :class:`~torsal.app.exports.ExportError` when none of the nodes has geometry, or the
    file cannot be written.
    """
    from torsal.nodes.io.common import FileFailure
    from torsal.nodes.io.formats import threedm

    node_ids = list(node_ids)
    path = Path(path)
    if path.suffix.lower() != ".3dm":
        raise ExportError(f"Bake writes Rhino .3dm files, not {path.suffix or 'a file without extension'}")
    entries, layers, skipped = bake_entries(graph, results, node_ids, parent)
    if not entries:
        raise ExportError(nothing_to_bake(len([n for n in node_ids if n in results])))
    try:
        written = threedm.write_3dm(path, entries, graph.units, node_colours(graph, layers))
    except FileFailure as exc:
        raise ExportError(str(exc)) from None
    counts = Counter(entry.layer for entry in entries)
    return Baked(
        written.path,
        written.objects,
        {n: (layer, counts[layer]) for n, layer in layers.items()},
        skipped,
        written.deviation,
    )
