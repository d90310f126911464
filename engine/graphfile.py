"""Reading and writing ``.graph`` files (see ``shared/spec/graph-format.md``).

A ``.graph`` file is JSON data and is only ever *parsed*: nothing in it is executed.
The shape is checked with msgspec; what a schema cannot say (unique ids, wires that
point at real ports, no loops) is checked by building the graph through its normal,
validated edits. Anything that goes wrong raises :class:`GraphFileError` with one
clear sentence.

Round trip: every object keeps the dictionary it was read from, and saving writes
those dictionaries back with only the changed fields replaced, so load → save gives
the same bytes for any file Torsal wrote, and fields this version does not know
survive. Saving is atomic and keeps the previous file as ``<name>.graph.bak``
(see :mod:`engine.atomic`).
"""

from __future__ import annotations

import copy
import json
import os
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any, Literal

import msgspec

from engine import __version__
from engine.atomic import replace_keeping_backup
from engine.graph import Graph, GraphError, Group, InputState, NodeRecord, PlaceholderNode, Wire
from engine.registry import Registry

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


class _Wire(msgspec.Struct, rename={"source": "from", "target": "to"}):
    source: tuple[Identifier, Identifier]
    target: tuple[Identifier, Identifier]


class _Group(msgspec.Struct):
    id: Identifier
    title: str = ""
    colour: str = "#d8e4f0"
    nodes: list[str] = []


class _File(msgspec.Struct):
    format: Literal["torsal.graph"]
    version: int
    nodes: list[_Node]
    wires: list[_Wire] = []
    groups: list[_Group] = []
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


def migrate(data: dict[str, Any]) -> dict[str, Any]:
    """Bring ``data`` up to :data:`VERSION` one step at a time."""
    version = data.get("version")
    if isinstance(version, bool) or not isinstance(version, int):
        raise GraphFileError("the file has no valid 'version' number")
    if version > VERSION:
        raise NewerVersionError(
            f"this file was written by a newer Torsal (file format version {version}); "
            f"this Torsal {__version__} reads up to version {VERSION}. Update Torsal to open "
            "it; the file has not been changed."
        )
    while version < VERSION:
        step = MIGRATIONS.get(version)
        if step is None:
            raise GraphFileError(f"file format version {version} is too old to be read")
        data = step(data)
        version = data["version"]
    return data


# --------------------------------------------------------------------------- reading

def read_graph(path: str | os.PathLike[str], registry: Registry) -> Graph:
    """Open a ``.graph`` file; raises :class:`GraphFileError` with the reason."""
    path = Path(path)
    try:
        size = path.stat().st_size
        if size > MAX_FILE_BYTES:
            raise GraphFileError(f"{path.name} is {size // 2**20} MB; a graph file is at most 64 MB")
        content = path.read_bytes()
    except OSError as exc:
        raise GraphFileError(f"cannot read {path}: {exc.strerror or exc}") from None
    return loads(content, registry)


def loads(content: bytes | str, registry: Registry) -> Graph:
    """Build a :class:`Graph` from the text of a ``.graph`` file."""
    data = parse(content)
    data = migrate(data)
    try:
        msgspec.convert(data, _File)
    except msgspec.ValidationError as exc:
        raise GraphFileError(f"the file's content is not a valid graph: {exc}") from None
    return _build(data, registry)


def parse(content: bytes | str) -> dict[str, Any]:
    """Decode JSON and check it claims to be a Torsal graph."""
    if isinstance(content, str):
        content = content.encode("utf-8", "surrogatepass")
    content = content.removeprefix(b"\xef\xbb\xbf")  # a UTF-8 byte-order mark some editors add
    try:
        data = msgspec.json.decode(content)
    except msgspec.ValidationError as exc:  # a subclass of DecodeError: catch it first
        raise GraphFileError(f"the file holds a number Torsal cannot read ({exc})") from None
    except msgspec.DecodeError as exc:
        raise GraphFileError(f"the file is not valid JSON ({exc})") from None
    except UnicodeError:
        raise GraphFileError("the file is not UTF-8 text") from None
    except RecursionError:
        raise GraphFileError("the file is nested too deeply to be a graph") from None
    if nesting_depth(data) > MAX_DEPTH:
        raise GraphFileError(f"the file is nested more than {MAX_DEPTH} levels deep; a graph never is")
    if not isinstance(data, dict) or data.get("format") != FORMAT:
        raise GraphFileError("this is not a Torsal graph file (it lacks \"format\": \"torsal.graph\")")
    return data


def nesting_depth(data: Any) -> int:
    """How deeply lists and objects nest in ``data`` (counted with a loop, not recursion)."""
    deepest = 0
    stack = [(data, 1)]
    while stack:
        value, depth = stack.pop()
        if isinstance(value, dict):
            children = value.values()
        elif isinstance(value, list):
            children = value
        else:
            continue
        deepest = max(deepest, depth)
        if deepest > MAX_DEPTH:
            break
        stack.extend((child, depth + 1) for child in children)
    return deepest


def _build(data: dict[str, Any], registry: Registry) -> Graph:
    graph = Graph()
    graph.raw = data
    graph.units = data.get("units", "m")
    graph.meta = copy.deepcopy(data.get("meta", {}))
    try:
        for raw in data["nodes"]:
            graph.add_record(_record(raw, registry))
        for raw in data.get("wires", []):
            (source, source_port), (target, target_port) = raw["from"], raw["to"]
            wire = Wire(source, source_port, target, target_port, raw=raw)
            if source not in graph.nodes or target not in graph.nodes:
                missing = source if source not in graph.nodes else target
                raise GraphFileError(f"wire {wire} refers to a node {missing!r} that is not in the file")
            graph.connect_wire(wire, check_loops=False)
        graph.order()  # one topological sort finds any loop among the wires
    except GraphError as exc:
        raise GraphFileError(f"the graph in the file is not valid: {exc}") from None
    for raw in data.get("groups", []):
        members = [n for n in raw.get("nodes", []) if n in graph.nodes]
        graph.groups.append(
            Group(raw["id"], raw.get("title", ""), raw.get("colour", "#d8e4f0"), members, raw=raw)
        )
    graph.expire_all()
    return graph


def _record(raw: dict[str, Any], registry: Registry) -> NodeRecord:
    settings = copy.deepcopy(raw.get("settings", {}))
    cls = registry.get(raw["type"])
    try:
        node = cls(settings) if cls is not None else PlaceholderNode(raw["type"], settings)
    except (TypeError, ValueError) as exc:
        raise GraphFileError(f"node {raw['id']!r} has unusable settings: {exc}") from None
    inputs = {}
    for name, entry in raw.get("inputs", {}).items():
        inputs[name] = InputState(
            value=copy.deepcopy(entry.get("value")),
            has_value="value" in entry,
            modifiers=list(entry.get("modifiers", [])),
            raw=entry,
        )
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
    data = copy.deepcopy(graph.raw)
    data.update(format=FORMAT, version=VERSION)
    data["nodes"] = [node_data(graph.nodes[node_id]) for node_id in graph.nodes]
    data["wires"] = [wire_data(w) for w in graph.wires]
    data["groups"] = [group_data(g) for g in graph.groups]
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
    data["id"] = record.id
    data["type"] = record.type_id
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

    def write(temporary: Path) -> None:
        with open(temporary, "w", encoding="utf-8", newline="\n") as stream:
            stream.write(text)

    replace_keeping_backup(path, write)


def _refuse_if_newer(path: Path) -> None:
    try:
        data = msgspec.json.decode(path.read_bytes())
    except (OSError, msgspec.DecodeError, msgspec.ValidationError, RecursionError):
        return
    version = data.get("version") if isinstance(data, dict) else None
    if isinstance(version, int) and not isinstance(version, bool) and version > VERSION:
        raise NewerVersionError(
            f"{path.name} was written by a newer Torsal (format version {version}); "
            "it is not overwritten. Save under another name."
        )
