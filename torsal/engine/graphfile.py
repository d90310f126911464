"""Reading and writing ``.graph`` files (see ``docs/graph-format.md``).

A ``.graph`` file is JSON data and is only ever *parsed*: nothing in it is executed.
The shape is checked with msgspec; what a schema cannot say (unique ids, wires that
point at real ports, no loops) is checked by building the graph through its normal,
validated edits. Anything that goes wrong raises :class:`GraphFileError` with one
clear sentence.

Reading is bounded before it starts: only a regular file of at most 64 MB is read
(:mod:`torsal.engine.bounded_read`), the format and version are read from the top-level
object before the document is built (:func:`check_header`), and every step after the
parse costs C time per number, so the time grows with the file's size alone.

Round trip: every object keeps the dictionary it was read from, and saving writes
those dictionaries back with only the changed fields replaced, so load → save gives
the same bytes for any file Torsal wrote, and fields this version does not know
survive. Saving is atomic and keeps the previous file as ``<name>.graph.bak``
(see :mod:`torsal.engine.atomic`).
"""

from __future__ import annotations

import copy
import json
import math
import os
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Annotated, Any, Literal

import msgspec

from torsal.engine import __version__
from torsal.engine.atomic import replace_keeping_backup
from torsal.engine.bounded_read import UnreadableFileError, read_bounded
from torsal.engine.cluster import (
    CLUSTER_TYPE,
    INPUT_TYPE,
    MAX_EXPANDED_NODES,
    OUTPUT_TYPE,
    ClusterDefinition,
    ClusterInput,
    ClusterNode,
    ClusterOutput,
    dependency_order,
    nesting_problem_of,
    reachable_definitions,
)
from torsal.engine.graph import Graph, GraphError, Group, InputState, NodeRecord, PlaceholderNode, Wire
from torsal.engine.registry import Registry, provider

FORMAT = "torsal.graph"
VERSION = 1
MAX_FILE_BYTES = 64 * 1024 * 1024
MAX_DEPTH = 64

Coordinate = Annotated[float, msgspec.Meta(ge=-1e15, le=1e15)]
Identifier = Annotated[str, msgspec.Meta(min_length=1, max_length=200)]


class GraphFileError(ValueError):
    """A ``.graph`` file (or fragment) that cannot be used; the message says why."""


class NewerVersionError(GraphFileError):
    """The file was written by a newer Torsal; it is never overwritten."""


# --------------------------------------------------------------------------- schema

class _Input(msgspec.Struct):
    value: Any = None
    modifiers: list[Literal["graft", "flatten", "simplify", "reverse"]] = []


class _Node(msgspec.Struct):
    id: Identifier
    type: Identifier
    label: str = ""
    position: tuple[Coordinate, Coordinate] = (0.0, 0.0)
    settings: dict[str, Any] = {}
    inputs: dict[str, _Input] = {}
    preview: bool = True
    enabled: bool = True
    plugin: Identifier | None = None  # the distribution providing a plug-in's type (docs/plugins.md)


class _Wire(msgspec.Struct, rename={"source": "from", "target": "to"}):
    source: tuple[Identifier, Identifier]
    target: tuple[Identifier, Identifier]


class _Group(msgspec.Struct):
    id: Identifier
    title: str = ""
    colour: str = "#d8e4f0"
    nodes: list[str] = []


class _Cluster(msgspec.Struct):
    """A cluster definition (see ``docs/graph-format-clusters.md``)."""

    id: Identifier
    name: str = ""
    inputs: list[Identifier] = []
    outputs: list[Identifier] = []
    anchor: tuple[Coordinate, Coordinate] = (0.0, 0.0)
    nodes: list[_Node] = []
    wires: list[_Wire] = []
    groups: list[_Group] = []


class _File(msgspec.Struct):
    format: Literal["torsal.graph"]
    version: int
    nodes: list[_Node]
    wires: list[_Wire] = []
    groups: list[_Group] = []
    clusters: list[_Cluster] = []
    meta: dict[str, Any] = {}
    units: Literal["mm", "cm", "m", "in", "ft"] = "m"


# --------------------------------------------------------------------------- migrations

def _migrate_0_to_1(data: dict[str, Any]) -> dict[str, Any]:
    """Version 0 (the pre-release drafts) wrote wires as ``{"source": "a.Out", "target":
    "b.In"}`` and positions as ``"x"``/``"y"`` fields; version 1 uses ``from``/``to`` pairs
    and a ``position`` list."""
    data = copy.deepcopy(data)
    nodes, wires_in = data.get("nodes"), data.get("wires", [])
    for node in nodes if isinstance(nodes, list) else []:
        if isinstance(node, dict) and ("x" in node or "y" in node):
            node["position"] = [node.pop("x", 0.0), node.pop("y", 0.0)]
    if not isinstance(wires_in, list):
        data["version"] = 1
        return data  # the schema check reports the malformed wires
    wires = []
    for wire in wires_in:
        if isinstance(wire, dict) and "source" in wire and "target" in wire:
            source, target = str(wire.pop("source")), str(wire.pop("target"))
            wire["from"] = source.rsplit(".", 1) if "." in source else [source, ""]
            wire["to"] = target.rsplit(".", 1) if "." in target else [target, ""]
        wires.append(wire)
    data["wires"] = wires
    data["version"] = 1
    return data


MIGRATIONS: dict[int, Callable[[dict[str, Any]], dict[str, Any]]] = {0: _migrate_0_to_1}


def _newer_message(version: int) -> str:
    return (
        f"this file was written by a newer Torsal (file format version {version}); "
        f"this Torsal {__version__} reads up to version {VERSION}. Update Torsal to open "
        "it; the file has not been changed."
    )


def migrate(data: dict[str, Any]) -> dict[str, Any]:
    """Bring ``data`` up to :data:`VERSION` one step at a time."""
    version = data.get("version")
    if isinstance(version, bool) or not isinstance(version, int):
        raise GraphFileError("the file has no valid 'version' number")
    if version > VERSION:
        raise NewerVersionError(_newer_message(version))
    while version < VERSION:
        step = MIGRATIONS.get(version)
        if step is None:
            raise GraphFileError(f"file format version {version} is too old to be read")
        data = step(data)
        version = data["version"]
    return data


# --------------------------------------------------------------------------- reading

def read_graph(path: str | os.PathLike[str], registry: Registry) -> Graph:
    """Open a ``.graph`` file; raises :class:`GraphFileError` with the reason.

    Only a regular file of at most 64 MB is read (see :mod:`torsal.engine.bounded_read`).
    """
    return loads(read_file(path), registry)


def read_file(path: str | os.PathLike[str]) -> bytes:
    """The bytes of a graph file: a regular file of at most :data:`MAX_FILE_BYTES`."""
    try:
        return read_bounded(path, MAX_FILE_BYTES, "a graph file")
    except UnreadableFileError as exc:
        raise GraphFileError(str(exc)) from None


def loads(content: bytes | str, registry: Registry) -> Graph:
    """Build a :class:`Graph` from the text of a ``.graph`` file."""
    data = parse(content)
    data = migrate(data)
    try:
        msgspec.convert(data, _File)
    except msgspec.ValidationError as exc:
        raise GraphFileError(f"the file's content is not a valid graph: {exc}") from None
    return _build(data, registry)


class _Header(msgspec.Struct):
    """The two top-level fields read before anything else; every other field is skipped."""

    format: Any = None
    version: Any = None


_HEADER = msgspec.json.Decoder(_Header)


# Numbers with a fraction or exponent go through ``float``, which takes about the same time
# for any of them; msgspec's own parser needs ~2 µs a byte for ones like 1e308. A number
# too large for a float becomes infinity there: :func:`_check_tree` refuses it.
_DOCUMENT = msgspec.json.Decoder(float_hook=float)


def _newer_version(header: _Header) -> int | None:
    """The header's version if it is newer than this Torsal reads."""
    version = header.version
    if isinstance(version, int) and not isinstance(version, bool) and version > VERSION:
        return version
    return None


def check_header(content: bytes) -> None:
    """Refuse, before the whole file is parsed, a document that is not a Torsal graph or
    was written by a newer Torsal. Reading the two fields skips the rest of the file
    without building it (16 MB in about 20 ms), wherever in the top-level object they
    are. Content that is not even JSON passes: the full parse says what is wrong."""
    try:
        header = _HEADER.decode(content)
    except msgspec.ValidationError:  # the top level is not an object
        raise GraphFileError(_NOT_A_GRAPH) from None
    except (msgspec.DecodeError, RecursionError):
        return
    if header.format != FORMAT:
        raise GraphFileError(_NOT_A_GRAPH)
    newer = _newer_version(header)
    if newer is not None:
        raise NewerVersionError(_newer_message(newer))


_NOT_A_GRAPH = "this is not a Torsal graph file (it lacks \"format\": \"torsal.graph\")"


def parse(content: bytes | str) -> dict[str, Any]:
    """Decode JSON and check it claims to be a Torsal graph (that claim, and the format
    version, are checked first: see :func:`check_header`)."""
    if isinstance(content, str):
        content = content.encode("utf-8", "surrogatepass")
    content = content.removeprefix(b"\xef\xbb\xbf")  # a UTF-8 byte-order mark some editors add
    check_header(content)
    try:
        data = _DOCUMENT.decode(content)
    except msgspec.ValidationError as exc:  # a subclass of DecodeError: catch it first
        raise GraphFileError(f"the file holds a number Torsal cannot read ({exc})") from None
    except msgspec.DecodeError as exc:
        raise GraphFileError(f"the file is not valid JSON ({exc})") from None
    except UnicodeError:
        raise GraphFileError("the file is not UTF-8 text") from None
    except RecursionError:
        raise GraphFileError("the file is nested too deeply to be a graph") from None
    _check_tree(data)
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise GraphFileError(_NOT_A_GRAPH)
    return data


_CONTAINERS = (list, dict)
_TOO_LARGE = "the file holds a number Torsal cannot read (a number too large for a float)"


def _levels(data: Any, refuse_infinity: bool = False) -> Iterator[int]:
    """Walk the lists and objects in ``data`` level by level; yields each level's depth.

    Each container is searched at C speed (``set(map(type, ...))``), so a list of a
    million numbers costs little more than the numbers' types. With ``refuse_infinity``
    a float that is infinite (a JSON number too large for a float) raises
    :class:`GraphFileError`.
    """
    level = [data] if type(data) in _CONTAINERS else []
    depth = 0
    while level:
        depth += 1
        yield depth
        below = []
        for value in level:
            children = value.values() if type(value) is dict else value
            kinds = set(map(type, children))
            if refuse_infinity and float in kinds and (math.inf in children or -math.inf in children):
                raise GraphFileError(_TOO_LARGE)
            if list in kinds or dict in kinds:
                below.extend(child for child in children if type(child) in _CONTAINERS)
        level = below


def nesting_depth(data: Any) -> int:
    """How deeply lists and objects nest in ``data`` (counted level by level, not by
    recursion, and only to one level past :data:`MAX_DEPTH`)."""
    deepest = 0
    for deepest in _levels(data):
        if deepest > MAX_DEPTH:
            break
    return deepest


def _check_tree(data: Any) -> None:
    """Refuse decoded JSON nested deeper than :data:`MAX_DEPTH`, or holding a number too
    large for a float (decoded as infinity)."""
    for depth in _levels(data, refuse_infinity=True):
        if depth > MAX_DEPTH:
            raise GraphFileError(f"the file is nested more than {MAX_DEPTH} levels deep; a graph never is")


def copy_data(value: Any) -> Any:
    """A deep copy of JSON data, at C speed (through msgpack, which keeps every float's
    bits); :func:`copy.deepcopy` for anything msgpack cannot hold (integers over 64 bits)."""
    try:
        return msgspec.msgpack.decode(msgspec.msgpack.encode(value))
    except (TypeError, OverflowError, msgspec.MsgspecError):
        return copy.deepcopy(value)


def _build(data: dict[str, Any], registry: Registry) -> Graph:
    graph = Graph()
    graph.raw = data
    graph.units = data.get("units", "m")
    graph.meta = copy_data(data.get("meta", {}))
    _build_clusters(data.get("clusters", []), registry, graph, data["nodes"])
    _fill(graph, data, registry)
    graph.expire_all()
    return graph


def _fill(graph: Graph, data: dict[str, Any], registry: Registry, where: str = "") -> None:
    """Add the nodes, wires and groups of ``data`` (the file, or one cluster definition)."""
    try:
        for raw in data["nodes"]:
            graph.add_record(_record(raw, registry, graph.clusters, where))
        for raw in data.get("wires", []):
            (source, source_port), (target, target_port) = raw["from"], raw["to"]
            wire = Wire(source, source_port, target, target_port, raw=raw)
            if source not in graph.nodes or target not in graph.nodes:
                missing = source if source not in graph.nodes else target
                place = "the definition" if where else "the file"
                raise GraphFileError(f"{where + ': ' if where else ''}wire {wire} refers to a node "
                                     f"{missing!r} that is not in {place}")
            graph.connect_wire(wire, check_loops=False)
        graph.order()  # one topological sort finds any loop among the wires
    except GraphError as exc:
        inside = f" ({where})" if where else ""
        raise GraphFileError(f"the graph in the file is not valid{inside}: {exc}") from None
    for raw in data.get("groups", []):
        members = [n for n in raw.get("nodes", []) if n in graph.nodes]
        graph.groups.append(
            Group(raw["id"], raw.get("title", ""), raw.get("colour", "#d8e4f0"), members, raw=raw)
        )


def _build_clusters(entries: list[dict[str, Any]], registry: Registry, graph: Graph,
                    top_nodes: list[dict[str, Any]]) -> None:
    """Build the file's cluster definitions into ``graph.clusters``, each after those it
    uses; refuse a repeated id, a use of a definition not in the file, a definition
    containing itself, nesting deeper than :data:`torsal.engine.cluster.MAX_NESTING`, and ports
    that are not the definition's Input and Output nodes."""
    raw_of: dict[str, dict[str, Any]] = {}
    for entry in entries:
        if entry["id"] in raw_of:
            raise GraphFileError(f"cluster definition {entry['id']!r} appears twice in the file")
        raw_of[entry["id"]] = entry
    uses: dict[str, set[str]] = {}
    for def_id, entry in raw_of.items():
        uses[def_id] = set()
        for node in entry.get("nodes", []):
            if node["type"] == CLUSTER_TYPE:
                used = _definition_id(node, f"cluster definition {def_id!r}")
                if used not in raw_of:
                    raise GraphFileError(
                        f"cluster definition {def_id!r}: node {node['id']!r} uses cluster definition "
                        f"{used!r}, which is not in the file")
                uses[def_id].add(used)
    problem = nesting_problem_of(uses)
    if problem:
        raise GraphFileError(problem)
    order = dependency_order(uses)
    _check_expansion(raw_of, order, top_nodes)
    for def_id in order:
        entry = raw_of[def_id]
        where = f"cluster definition {def_id!r}"
        if not isinstance(entry.get("nodes"), list):
            raise GraphFileError(f'{where} has no "nodes" list: every definition lists its nodes')
        inner = Graph()
        inner.clusters = graph.clusters
        inner.units = graph.units
        inner.raw = entry
        _fill(inner, entry, registry, where)
        ports = {}
        for kind, cls in (("inputs", ClusterInput), ("outputs", ClusterOutput)):
            listed = entry.get(kind, [])
            for node_id in listed:
                record = inner.nodes.get(node_id)
                if record is None or not isinstance(record.node, cls):
                    raise GraphFileError(f"{where}: its {kind} list names {node_id!r}, which is not one of "
                                         f"its {cls.type_id} nodes")
            if len(set(listed)) != len(listed):
                raise GraphFileError(f"{where}: its {kind} list names a node twice")
            for node_id, record in inner.nodes.items():
                if isinstance(record.node, cls) and node_id not in listed:
                    raise GraphFileError(
                        f"{where}: node {node_id!r} is a {cls.type_id} but not in its {kind} list")
            ports[kind] = list(listed)
        x, y = entry.get("anchor", (0.0, 0.0))
        graph.clusters[def_id] = ClusterDefinition(
            def_id, entry.get("name", "") or def_id, inner, ports["inputs"], ports["outputs"],
            anchor=(x, y), raw=entry)


def _check_expansion(raw_of: dict[str, dict[str, Any]], order: list[str],
                     top_nodes: list[dict[str, Any]]) -> None:
    """Refuse clusters that would expand to more than :data:`MAX_EXPANDED_NODES` nodes."""
    size: dict[str, int] = {}

    def expanded(nodes: list[dict[str, Any]]) -> int:
        total = 0
        for node in nodes:
            used = node.get("settings", {}).get("definition")
            if node["type"] == CLUSTER_TYPE and isinstance(used, str):
                total += 1 + size.get(used, 0)  # an instance costs one, even of an empty definition
            else:
                total += 1
        return min(total, MAX_EXPANDED_NODES + 1)

    for def_id in order:
        size[def_id] = expanded(raw_of[def_id].get("nodes", []))
    if expanded(top_nodes) > MAX_EXPANDED_NODES or any(n > MAX_EXPANDED_NODES for n in size.values()):
        raise GraphFileError(f"the file's clusters expand to more than {MAX_EXPANDED_NODES:,} nodes "
                             "(instances inside instances multiply); Torsal does not solve that many")


def _definition_id(raw: dict[str, Any], where: str) -> str:
    definition = raw.get("settings", {}).get("definition")
    if not isinstance(definition, str) or not definition:
        raise GraphFileError(f"{where}: node {raw['id']!r} is a cluster but names no definition "
                             "(settings.definition)")
    return definition


def _record(raw: dict[str, Any], registry: Registry, clusters: dict[str, Any] | None = None,
            where: str = "") -> NodeRecord:
    settings = copy_data(raw.get("settings", {}))
    type_id = raw["type"]
    try:
        if type_id == CLUSTER_TYPE:
            definition_id = _definition_id(raw, where or "the file")
            if clusters is None or definition_id not in clusters:
                raise GraphFileError(f"{where + ': ' if where else ''}node {raw['id']!r} is a cluster of "
                                     f"definition {definition_id!r}, which is not in the file")
            node = ClusterNode(clusters[definition_id], settings)
        elif type_id in (INPUT_TYPE, OUTPUT_TYPE):
            node = (ClusterInput if type_id == INPUT_TYPE else ClusterOutput)(settings)
        else:
            cls = registry.get(type_id)
            node = cls(settings) if cls is not None else PlaceholderNode(type_id, settings)
    except (TypeError, ValueError) as exc:
        if isinstance(exc, GraphFileError):
            raise
        raise GraphFileError(f"node {raw['id']!r} has unusable settings: {exc}") from None
    inputs = {}
    for name, entry in raw.get("inputs", {}).items():
        inputs[name] = InputState(value=copy_data(entry.get("value")), has_value="value" in entry,
                                  modifiers=list(entry.get("modifiers", [])), raw=entry)
    x, y = raw.get("position", (0.0, 0.0))
    return NodeRecord(
        id=raw["id"],
        node=node,
        type_id=raw["type"],
        label=raw.get("label", ""),
        position=(x, y),
        inputs=inputs,
        preview=raw.get("preview", True),
        enabled=raw.get("enabled", True),
        raw=raw,
    )


# --------------------------------------------------------------------------- writing

def to_data(graph: Graph) -> dict[str, Any]:
    """The graph as JSON data, keeping every field it was read with."""
    data = copy_data(graph.raw)
    data.update(format=FORMAT, version=VERSION)
    data["nodes"] = [node_data(graph.nodes[node_id]) for node_id in graph.nodes]
    data["wires"] = [wire_data(w) for w in graph.wires]
    data["groups"] = [group_data(g) for g in graph.groups]
    data.pop("clusters", None)  # a file whose last cluster was exploded keeps no empty list
    if clusters := [cluster_data(d) for d in reachable_definitions(graph)]:
        data["clusters"] = clusters
    meta = dict(graph.meta)
    if not graph.raw:
        meta.setdefault("description", "")
        meta.setdefault("created_with", f"torsal {__version__}")
    data["meta"] = meta
    _put(data, "units", graph.units, "m", graph.raw)
    return data


def _put(target: dict[str, Any], key: str, value: Any, default: Any, raw: dict[str, Any]) -> None:
    """Write ``key`` when it was in the file or differs from its default."""
    if key in raw or value != default:
        target[key] = copy.deepcopy(value)
    else:
        target.pop(key, None)


def node_data(record: NodeRecord) -> dict[str, Any]:
    raw = record.raw
    data = copy.deepcopy(raw)
    data.update(id=record.id, type=record.type_id)
    _put(data, "plugin", provider(type(record.node)) or raw.get("plugin"), None, raw)
    _put(data, "label", record.label, "", raw)
    if tuple(raw.get("position", ())) != record.position:  # unchanged: keep 120 as 120
        data["position"] = list(record.position)
    raw_settings = raw.get("settings", {})
    settings = copy.deepcopy(raw_settings)
    defaults = {s.name: s.default for s in record.node.settings_spec}
    for name, value in record.node.settings.items():
        if not raw or name in raw_settings or value != defaults.get(name, object()):
            settings[name] = copy.deepcopy(value)
    _put(data, "settings", settings, {}, raw)
    raw_inputs = raw.get("inputs", {})
    inputs = {}
    for name, state in record.inputs.items():
        entry = copy.deepcopy(state.raw)
        if state.has_value:
            entry["value"] = copy.deepcopy(state.value)
        else:
            entry.pop("value", None)
        _put(entry, "modifiers", state.modifiers, [], state.raw)
        if entry or name in raw_inputs:
            inputs[name] = entry
    _put(data, "inputs", inputs, {}, raw)
    _put(data, "preview", record.preview, True, raw)
    _put(data, "enabled", record.enabled, True, raw)
    return data


def cluster_data(definition: ClusterDefinition) -> dict[str, Any]:
    """One entry of the ``clusters`` section: the definition's ports, anchor and graph."""
    raw = definition.raw
    data = copy_data(raw)
    data.update(id=definition.id, name=definition.name, inputs=list(definition.inputs),
                outputs=list(definition.outputs))
    if tuple(raw.get("anchor", (0.0, 0.0))) != definition.anchor:
        data["anchor"] = list(definition.anchor)
    inner = definition.graph
    data["nodes"] = [node_data(record) for record in inner.nodes.values()]
    data["wires"] = [wire_data(w) for w in inner.wires]
    _put(data, "groups", [group_data(g) for g in inner.groups], [], raw)
    return data


def fragment_clusters(graph: Graph, node_ids: list[str]) -> list[dict[str, Any]]:
    """The ``clusters`` section a fragment (copy and paste) of ``node_ids`` needs: every
    definition their clusters use, directly or inside others."""
    part = Graph()
    part.nodes = {n: graph.nodes[n] for n in node_ids if n in graph.nodes}
    return [cluster_data(d) for d in reachable_definitions(part)]


def adopt_clusters(graph: Graph, records: list[NodeRecord]) -> None:
    """Make the clusters among ``records`` (read from a fragment, so with definitions of
    their own) use ``graph``'s definitions: one with the same id and the same content is
    shared; one that differs gets a fresh id. Call before adding the records."""
    holder = Graph()
    holder.nodes = {r.id: r for r in records}
    incoming = reachable_definitions(holder)
    by_id = {d.id: d for d in incoming}
    chosen: dict[int, ClusterDefinition] = {}  # id() of a fragment's definition → the one to use

    def repoint(node: ClusterNode) -> None:
        node.definition = chosen[id(node.definition)]
        node.settings["definition"] = node.definition.id

    for def_id in dependency_order({d.id: d.used_definitions() for d in incoming}):
        definition = by_id[def_id]
        for record in definition.graph.nodes.values():
            if isinstance(record.node, ClusterNode):
                repoint(record.node)
        existing = graph.clusters.get(def_id)
        if existing is not None and _content(existing) == _content(definition):
            chosen[id(definition)] = existing
            continue
        if existing is not None:
            n = 2
            while f"{def_id}{n}" in graph.clusters:
                n += 1
            definition.id = f"{def_id}{n}"
        definition.graph.clusters = graph.clusters
        graph.clusters[definition.id] = definition
        chosen[id(definition)] = definition
    for record in records:
        if isinstance(record.node, ClusterNode):
            repoint(record.node)


def _content(definition: ClusterDefinition) -> dict[str, Any]:
    data = cluster_data(definition)
    return {key: data.get(key) for key in ("name", "inputs", "outputs", "nodes", "wires")}


def wire_data(wire: Wire) -> dict[str, Any]:
    data = copy.deepcopy(wire.raw)
    data["from"] = [wire.source, wire.source_port]
    data["to"] = [wire.target, wire.target_port]
    return data


def group_data(group: Group) -> dict[str, Any]:
    data = copy.deepcopy(group.raw)
    data.update(id=group.id, title=group.title, colour=group.colour, nodes=list(group.nodes))
    return data


def dumps(graph: Graph) -> str:
    """The text of the ``.graph`` file: sorted keys, two-space indent, final newline."""
    return encode(to_data(graph))


def encode(data: dict[str, Any]) -> str:
    """JSON with sorted keys and two-space indentation; short lists of plain values
    (positions, xyz triples, wire ends) stay on one line so the file reads well."""
    try:
        return _format(data, "") + "\n"
    except ValueError as exc:
        raise GraphFileError(f"the graph holds a value JSON cannot store: {exc}") from None


_INLINE_WIDTH = 72


def _format(value: Any, indent: str) -> str:
    if isinstance(value, dict):
        if not value:
            return "{}"
        inner = indent + "  "
        items = [
            f"{inner}{_scalar(str(key))}: {_format(value[key], inner)}"
            for key in sorted(value, key=str)
        ]
        return "{\n" + ",\n".join(items) + "\n" + indent + "}"
    if isinstance(value, list | tuple):
        if not value:
            return "[]"
        if all(not isinstance(v, dict | list | tuple) for v in value):
            line = "[" + ", ".join(_scalar(v) for v in value) + "]"
            if len(line) <= _INLINE_WIDTH:
                return line
        inner = indent + "  "
        return "[\n" + ",\n".join(inner + _format(v, inner) for v in value) + "\n" + indent + "]"
    return _scalar(value)


def _scalar(value: Any) -> str:
    return json.dumps(value, ensure_ascii=False, allow_nan=False)


def write_graph(graph: Graph, path: str | os.PathLike[str]) -> None:
    """Save atomically; the file it replaces is kept as ``<name>.graph.bak`` (also atomically).

    Refuses to replace a file written by a newer Torsal.
    """
    path = Path(path)
    text = dumps(graph)
    if path.exists():
        _refuse_if_newer(path)

    replace_keeping_backup(path, text.encode("utf-8"))


def _refuse_if_newer(path: Path) -> None:
    try:
        header = _HEADER.decode(read_file(path).removeprefix(b"\xef\xbb\xbf"))
    except (GraphFileError, msgspec.DecodeError, RecursionError):
        return  # unreadable, or not a graph: replacing it is fine (it is kept as .bak)
    newer = _newer_version(header)
    if newer is not None:
        raise NewerVersionError(
            f"{path.name} was written by a newer Torsal (format version {newer}); "
            "it is not overwritten. Save under another name."
        )
