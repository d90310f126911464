"""Solving a ``.graph`` file without a GUI: the engine side of ``torsal run``.

No Qt, VTK or pyvista is imported here (a test checks it).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from torsal.app.plugins import missing_types
from torsal.engine.cluster_edits import cluster_graph, set_cluster_graph
from torsal.engine.graph import Graph, GraphError
from torsal.engine.graphfile import GraphFileError, read_graph
from torsal.engine.registry import Registry
from torsal.engine.solver import ERROR, MISSING, OK, WARNING, NodeProgress, Solver, SolveReport
from torsal.engine.types import summarize_value
from torsal.engine.write_path import OutFolder
from torsal.engine.writes import WriteAccess
from torsal.nodes.catalogue import default_registry


class UsageError(ValueError):
    """A command-line request that cannot be carried out (exit code 2)."""


@dataclass
class Run:
    """A solved file: its graph, solver and report."""

    path: Path
    graph: Graph
    solver: Solver
    report: SolveReport
    registry: Registry = field(repr=False, default_factory=Registry)
    #: the files ``--export`` wrote, in order
    exported: list[Path] = field(default_factory=list)
    #: remarks on the ``--set`` assignments (one reaching every instance of a cluster...)
    notes: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not any(r.state == ERROR for r in self.solver.results.values())

    @property
    def exit_code(self) -> int:
        return 0 if self.ok else 1

    def counts(self) -> dict[str, int]:
        states = [r.state for r in self.solver.results.values()]
        return {state: states.count(state) for state in (OK, WARNING, ERROR, "disabled", MISSING)}

    def to_json(self) -> dict[str, Any]:
        """The result object printed by ``torsal run --json``."""
        nodes = {}
        for node_id, record in self.graph.nodes.items():
            result = self.solver.result(node_id)
            nodes[node_id] = {
                "type": record.type_id,
                "state": result.state,
                "messages": [m.to_json() for m in result.messages],
                "seconds": round(result.seconds, 6),
                "outputs": {
                    port: {
                        path: [summarize_value(v) for v in items]
                        for path, items in tree.to_dict().items()
                    }
                    for port, tree in result.outputs.items()
                },
            }
        return {
            "file": str(self.path),
            "ok": self.ok,
            "solve_seconds": round(self.report.seconds, 6),
            "nodes": nodes,
            "exported": [str(p) for p in self.exported],
        }


def refuse_missing(graph: Graph, path: Path | str) -> None:
    """Raise :class:`UsageError` (exit code 2) when ``graph`` needs node types that are not
    installed, naming each, its nodes and the plug-in package the file says provides it."""
    missing = missing_types(graph)
    if missing:
        sentences = "; ".join(m.sentence() for m in missing)
        raise UsageError(f"{path}: needs node types not installed here: {sentences}")


def open_graph(path: str | Path, registry: Registry | None = None) -> tuple[Graph, Registry]:
    """The graph in ``path``; :class:`UsageError` when it needs node types not installed."""
    registry = registry if registry is not None else default_registry()  # `or` would load every palette
    graph = read_graph(path, registry)
    refuse_missing(graph, path)
    return graph, registry


def parse_assignment(text: str) -> tuple[str, str | None, Any]:
    """``height=4.5`` → ``("height", None, 4.5)``; ``cyl.Segments=48`` → ``("cyl", "Segments", 48)``.

    The value is read as JSON when it parses (numbers, true/false, lists, objects),
    otherwise taken as text.
    """
    target, sep, raw = text.partition("=")
    if not sep or not target.strip():
        raise UsageError(f"--set wants ID=VALUE or ID.Input=VALUE, not {text!r}")
    node_id, _, port = target.strip().partition(".")
    try:
        value = json.loads(raw)
    except ValueError:
        value = raw
    except RecursionError:
        value = None  # refused just below, as too deep
    if (value is None and raw.strip() != "null") or _depth(value) > MAX_SET_DEPTH:
        raise UsageError(f"--set {node_id}: the value nests lists or objects more than {MAX_SET_DEPTH} "
                         "deep; a value holds data trees of a few levels")
    return node_id, port or None, value


#: How deep lists and objects in a ``--set`` value may nest (a data tree needs a few levels).
MAX_SET_DEPTH = 32


def _depth(value: Any) -> int:
    """How deep lists and dicts nest in ``value`` (walked without recursion)."""
    deepest, stack = 0, [(value, 0)]
    while stack:
        item, level = stack.pop()
        if isinstance(item, list | dict):
            level += 1
            deepest = max(deepest, level)
            if deepest > MAX_SET_DEPTH:
                return deepest
            stack.extend((child, level) for child in (item.values() if isinstance(item, dict) else item))
    return deepest


@dataclass
class Target:
    """Where one ``--set`` lands: a node of ``graph`` (the file's graph, or the inner graph
    of the cluster definition ``definition``, shared by every instance of it)."""

    graph: Graph
    node_id: str
    path: str  # as the user wrote it: ``panels/width``
    definition: Any = None  # a ClusterDefinition, or None at the top level
    port: str | None = None  # the input set, or None for the node's value setting


def resolve_target(graph: Graph, node_path: str, text: str) -> Target:
    """The node a ``--set`` names: ``ID`` at the top level, or ``CLUSTER/ID`` (and deeper,
    ``CLUSTER/INNER_CLUSTER/ID``) inside a cluster, each step an instance's node id or a
    definition's id."""
    if node_path in graph.nodes or "/" not in node_path:
        if node_path not in graph.nodes:
            raise UsageError(f"--set {text}: there is no node with id {node_path!r}")
        return Target(graph, node_path, node_path)
    from torsal.engine.cluster import ClusterNode

    *steps, inner_id = node_path.split("/")
    current, definition, walked = graph, None, []
    for step in steps:
        walked.append(step)
        record = current.nodes.get(step)
        if record is not None and isinstance(record.node, ClusterNode):
            definition = record.node.definition
        elif step in graph.clusters:
            definition = graph.clusters[step]
        else:
            place = f"inside {'/'.join(walked[:-1])}" if walked[:-1] else "at the top level"
            raise UsageError(f"--set {text}: there is no cluster or cluster definition {step!r} {place}")
        current = definition.graph
    if inner_id not in current.nodes:
        names = ", ".join(sorted(current.nodes)) or "none"
        raise UsageError(f"--set {text}: cluster definition {definition.id!r} ({definition.name}) has no "
                         f"node {inner_id!r} (its nodes: {names})")
    return Target(current, inner_id, node_path, definition)


def apply_assignment(graph: Graph, text: str) -> Target:
    """Apply one ``--set``: a node's ``value`` setting, or an input's persistent value.

    ``CLUSTER/ID=VALUE`` sets a node inside a cluster's definition; the definition is
    shared, so every instance of it changes (as editing a definition on the canvas does).
    Returns where it landed.
    """
    node_path, port, value = parse_assignment(text)
    target = resolve_target(graph, node_path, text)
    target.port = port
    if target.definition is None:
        _assign(graph, target.node_id, port, value, text)
        return target
    edited = cluster_graph(graph, target.definition.id)
    _assign(edited, target.node_id, port, value, text)
    set_cluster_graph(graph, target.definition.id, edited)
    return target


def _assign(graph: Graph, node_id: str, port: str | None, value: Any, text: str) -> None:
    record = graph.nodes[node_id]
    if port is None:
        if "value" not in record.node.settings:
            names = ", ".join(p.name for p in record.node.input_ports()) or "none"
            raise UsageError(
                f"--set {text}: node {node_id!r} has no value setting; set one of its inputs "
                f"instead ({node_id}.NAME=VALUE; inputs: {names})"
            )
        graph.set_setting(node_id, "value", value)
        return
    known = [p.name for p in record.node.input_ports()]
    if known and port not in known:
        raise UsageError(f"--set {text}: {node_id!r} has no input {port!r} (inputs: {', '.join(known)})")
    feeding = graph.wires_into(node_id, port)
    if feeding:  # a wired input ignores its own value: setting it would change nothing
        sources = " and ".join(f"{w.source}.{w.source_port}" for w in feeding)
        raise UsageError(f"--set {text}: {node_id}.{port} is wired from {sources}: set the source")
    graph.set_input_value(node_id, port, value)


def shared_note(graph: Graph, target: Target) -> str | None:
    """A sentence when a ``--set`` inside a definition changes more than the instance named
    (the definition is shared by all its instances); None otherwise."""
    if target.definition is None:
        return None
    from torsal.engine.cluster import instances

    definition = target.definition
    users = [*instances(graph, definition.id),
             *(f"{d.id}/{n}" for d in graph.clusters.values() for n in instances(d.graph, definition.id))]
    if len(users) < 2:
        return None
    return (f"--set {target.path} changes cluster definition {definition.id!r} ({definition.name}), "
            f"shared by {len(users)} instances ({', '.join(users)}): all of them get the new value")


def run_file(
    path: str | Path,
    assignments: list[str] = (),
    registry: Registry | None = None,
    *,
    allow_writes: bool = False,
    write_folder: Path | OutFolder | None = None,
    node_progress: NodeProgress | None = None,
    anytime: bool = False,
) -> Run:
    """Open, adjust with ``--set`` assignments, and solve a graph file.

    Nodes write files only when ``allow_writes`` (``--allow-writes``) is given, and only
    inside ``write_folder`` (``--out``), or the graph's own folder without one.
    ``node_progress`` hears long nodes' progress (node id, fraction). ``anytime``: nodes
    may answer at once and improve later (torsal/engine/improve.py; the caller runs the
    improvements, as ``torsal run --nesting-time`` does).
    """
    try:
        graph, registry = open_graph(path, registry)
    except GraphFileError as exc:
        raise UsageError(f"{path}: {exc}") from None
    notes: list[str] = []
    inside: dict[tuple[str, str, str | None], Target] = {}  # (definition, inner node, port) → --set
    try:
        for assignment in assignments:
            target = apply_assignment(graph, assignment)
            if target.definition is None:
                continue
            key = (target.definition.id, target.node_id, target.port)
            earlier = inside.get(key)
            if earlier is not None and earlier.path != target.path:
                raise UsageError(
                    f"--set {assignment} and --set {earlier.path}=… reach the same node "
                    f"{target.node_id!r} of "
                    f"cluster definition {target.definition.id!r}, which every instance shares: "
                    "a definition's nodes have one value for all its instances (set it once)")
            inside[key] = target
            note = shared_note(graph, target)
            if note is not None:
                notes.append(note)
    except GraphError as exc:
        raise UsageError(str(exc)) from None
    home = Path(path).resolve().parent  # files the graph reads are found from here, with or without --out
    if isinstance(write_folder, OutFolder) and write_folder.identity is not None:
        access = WriteAccess.held(write_folder.path, write_folder.identity, allowed=allow_writes)
        access.read_folder = home
    else:
        folder = Path(write_folder) if write_folder is not None else home
        access = WriteAccess(folder.resolve(), allowed=allow_writes, read_folder=home)
    solver = Solver(graph, access, anytime=anytime)
    report = solver.solve(node_progress=node_progress)
    return Run(Path(path), graph, solver, report, registry, notes=notes)


def summary(run: Run) -> str:
    """A few human lines: what was solved, and every node message."""
    counts = run.counts()
    lines = [
        f"{run.path}: solved {len(run.report.solved)} nodes in {run.report.seconds:.3f} s — "
        f"{counts[OK]} ok, {counts[WARNING]} warnings, {counts[ERROR]} errors"
        + (f", {counts[MISSING]} missing node types" if counts[MISSING] else "")
    ]
    for node_id, record in run.graph.nodes.items():
        result = run.solver.result(node_id)
        for message in result.messages:
            lines.append(f"  {record.title} [{node_id}] {message.level.name.lower()}: {message.text}")
    return "\n".join(lines)
