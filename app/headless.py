"""Solving a ``.graph`` file without a GUI: the engine side of ``torsal run``.

No Qt, VTK or pyvista is imported here (a test checks it).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from engine.graph import Graph, GraphError
from engine.graphfile import GraphFileError, read_graph
from engine.registry import Registry
from engine.solver import ERROR, MISSING, OK, WARNING, NodeProgress, Solver, SolveReport
from engine.types import summarize_value
from engine.writes import WriteAccess
from nodes.catalogue import default_registry


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


def open_graph(path: str | Path, registry: Registry | None = None) -> tuple[Graph, Registry]:
    registry = registry if registry is not None else default_registry()  # `or` would load every palette
    return read_graph(path, registry), registry


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
    return node_id, port or None, value


def apply_assignment(graph: Graph, text: str) -> None:
    """Apply one ``--set``: a node's ``value`` setting, or an input's persistent value."""
    node_id, port, value = parse_assignment(text)
    if node_id not in graph.nodes:
        raise UsageError(f"--set {text}: there is no node with id {node_id!r}")
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


def run_file(
    path: str | Path,
    assignments: list[str] = (),
    registry: Registry | None = None,
    *,
    allow_writes: bool = False,
    write_folder: Path | None = None,
    node_progress: NodeProgress | None = None,
) -> Run:
    """Open, adjust with ``--set`` assignments, and solve a graph file.

    Nodes write files only when ``allow_writes`` (``--allow-writes``) is given, and only
    inside ``write_folder`` (``--out``), or the graph's own folder without one.
    ``node_progress`` hears long nodes' progress (node id, fraction).
    """
    try:
        graph, registry = open_graph(path, registry)
    except GraphFileError as exc:
        raise UsageError(f"{path}: {exc}") from None
    try:
        for assignment in assignments:
            apply_assignment(graph, assignment)
    except GraphError as exc:
        raise UsageError(str(exc)) from None
    folder = write_folder if write_folder is not None else Path(path).resolve().parent
    solver = Solver(graph, WriteAccess(folder.resolve(), allowed=allow_writes))
    report = solver.solve(node_progress=node_progress)
    return Run(Path(path), graph, solver, report, registry)


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
