"""The incremental solver: solve expired nodes in topological order from cached results.

Each node's inputs are gathered from its wires' cached output trees (or from its
persistent values and defaults), modified, cast to the port types and *matched* the
Grasshopper way (:mod:`torsal.engine.matching`, ``docs/data-trees.md``); ``solve`` is then
called once per match. A node ends ``ok``, ``warning``, ``error``, ``disabled`` or
``missing`` with its messages and solve time. An exception in one node never stops the others.
"""

from __future__ import annotations

import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from torsal.engine.bounds import within_bounds
from torsal.engine.call_budget import BudgetExceeded, SolveBudget
from torsal.engine.casting import (  # noqa: F401 - also exported here, where callers found them
    TRIPLE_OF,
    array_fits,
    cast_array_branch,
    cast_tree,
    merge_trees,
)
from torsal.engine.cluster import PORT, ClusterDefinition, ClusterInput, ClusterNode, clone_graph
from torsal.engine.datatree import DataTree, apply_modifiers
from torsal.engine.graph import Graph, GraphError, NodeRecord, Wire, is_placeholder
from torsal.engine.matching import run_node as run_node  # where callers found it
from torsal.engine.matching import store
from torsal.engine.node import (
    Cancelled,
    CancelToken,
    Level,
    Message,
    Node,
    NodeError,
    NodeWarning,
)
from torsal.engine.solve_context import SolveContext, solving
from torsal.engine.types import CastError, decode_value
from torsal.engine.writes import WriteAccess

OK, WARNING, ERROR, DISABLED, MISSING = "ok", "warning", "error", "disabled", "missing"

Progress = Callable[[int, int, str], None]
#: A node's own progress within its solve: (node id, fraction 0 to 1).
NodeProgress = Callable[[str, float], None]


@dataclass
class NodeResult:
    """What one node produced in its last solve."""

    state: str = OK
    messages: list[Message] = field(default_factory=list)
    seconds: float = 0.0
    outputs: dict[str, DataTree] = field(default_factory=dict)
    #: what improves this result after the solve (torsal/engine/improve.py), or None
    improver: Any = None

    def output(self, port: str) -> DataTree:
        return self.outputs.get(port) or DataTree()


@dataclass
class SolveReport:
    """The outcome of one call of :meth:`Solver.solve`."""

    solved: list[str] = field(default_factory=list)
    seconds: float = 0.0
    cancelled: bool = False

    def count(self, results: dict[str, NodeResult], state: str) -> int:
        return sum(1 for r in results.values() if r.state == state)


class Solver:
    """Solves a :class:`Graph` incrementally and keeps each node's :class:`NodeResult`."""

    def __init__(self, graph: Graph, files: WriteAccess | None = None, anytime: bool = False, *,
                 dry: Callable[[Node], bool] | None = None, budget: SolveBudget | None = None) -> None:
        self.graph = graph
        #: nodes may answer at once and improve their result later (the app): improve.py
        self.anytime = anytime
        self._adopted: list[str] = []  # improved since the last solve: reported as solved
        self.results: dict[str, NodeResult] = {}
        #: where the graph's nodes may write files, and whether the user allows it
        self.files = files if files is not None else WriteAccess()
        #: the calls of a solve, every node together (a cluster's solver shares its parent's)
        self.budget, self._own_budget = budget or SolveBudget(), budget is None
        self.dry = dry  # torsal check: the nodes it names are planned and checked, not run
        self.refused: list[tuple[str, str]] = []  # (node id, message) of budget refusals
        self._removals_seen = graph.removals
        self._clusters: dict[str, ClusterRun] = {}  # cluster node id → its inner solve

    def result(self, node_id: str) -> NodeResult:
        return self.results.get(node_id) or NodeResult()

    def _fed_the_same(self, node_id: str, visited: set[str], same: set[str]) -> bool:
        """Whether every node visited this solve that feeds ``node_id`` gave the very outputs
        it had (a cluster whose changed input did not reach the outputs ``node_id`` takes...)."""
        sources = {w.source for w in self.graph.wires_into(node_id)} & visited
        return bool(sources) and sources <= same

    def cluster_solver(self, node_id: str) -> Solver | None:
        """The inner solver of the cluster node ``node_id`` (its inner graph is a private
        copy of the definition's, with this instance's inputs), once it has been solved."""
        run = self._clusters.get(node_id)
        return None if run is None else run.solver

    def cluster_inputs(self, node_id: str) -> dict[str, DataTree]:
        """The trees the cluster node ``node_id`` last received, by inner Input node id
        (for showing an instance's values while its definition is edited)."""
        run = self._clusters.get(node_id)
        return {} if run is None else dict(run.fed)

    def inputs_of(self, node_id: str) -> list[DataTree]:
        """The trees the node ``node_id`` is given, one per input port (modified and cast as a
        solve gives them), from the results at hand; [] when they cannot be made."""
        try:
            trees, _ = self._gather(self.graph.record(node_id))
        except (NodeError, GraphError):
            return []
        return trees

    def solve(self, token: CancelToken | None = None, progress: Progress | None = None,
              node_progress: NodeProgress | None = None) -> SolveReport:
        """Solve every expired node; cancelled solves leave the rest expired.
        ``node_progress`` hears what long nodes report with :meth:`Node.progress`."""
        graph = self.graph
        token = token or CancelToken()
        report = SolveReport()
        start = time.perf_counter()
        if self._own_budget:
            self.budget.reset()
        self.refused.clear()
        if graph.removals != self._removals_seen:  # forget removed nodes' results
            self._removals_seen = graph.removals
            for stale in self.results.keys() - graph.nodes.keys():
                del self.results[stale]
            for stale in self._clusters.keys() - graph.nodes.keys():
                del self._clusters[stale]
        # only the expired nodes are visited: sorted by their topological rank
        pending = graph.in_order(graph.expired)
        touched = graph.touched
        same: set[str] = set()  # visited this solve and gave the very outputs they had
        visited: set[str] = set()
        index = 0
        try:
            for index, node_id in enumerate(pending):
                token.check()
                if same and node_id not in touched and node_id in self.results and self._fed_the_same(
                        node_id, visited, same):
                    same.add(node_id)  # nothing it takes has changed: its result stands
                else:
                    if progress is not None:
                        progress(index, len(pending), node_id)
                    on_progress = None if node_progress is None else (
                        lambda fraction, node_id=node_id: node_progress(node_id, fraction))
                    record = graph.nodes[node_id]
                    before = self.results.get(node_id)
                    result = self.results[node_id] = self._solve_node(record, token, on_progress)
                    if isinstance(record.node, ClusterNode) and _same_outputs(before, result):
                        same.add(node_id)
                    report.solved.append(node_id)
                visited.add(node_id)
                graph.expired.discard(node_id)
                touched.discard(node_id)
        except Cancelled:
            report.cancelled = True
            touched.update(pending[index:])  # what is left is solved in full next time
        if not graph.expired:  # a set keeps its largest table, and iterating it costs that
            graph.expired.clear()
            touched.clear()
        report.seconds = time.perf_counter() - start
        if self._adopted:  # improved after their solve: shown as if solved now
            report.solved[:0] = [n for n in self._adopted if n not in report.solved]
            self._adopted.clear()
        return report

    # -- results that improve after the solve (torsal/engine/improve.py) --------------
    def improvers(self) -> dict[str, Any]:
        """node id → the improver of its current result, for every result that has one."""
        return {node_id: r.improver for node_id, r in self.results.items() if r.improver is not None}

    def adopt(self, node_id: str, values: Any, remarks: list[str] | None = None,
              improver: Any = None) -> bool:
        """Take an improvement of ``node_id``'s result: ``values`` as its ``solve`` would
        return them, ``remarks`` replacing its remarks; what is downstream of it expires
        (the next :meth:`solve` solves it and reports this node as solved). False when the
        node has been solved again since (the improvement is stale) or is gone."""
        record = self.graph.nodes.get(node_id)
        result = self.results.get(node_id)
        if record is None or result is None or result.improver is None:
            return False
        node = record.node
        outputs = {p.name: DataTree() for p in node.output_ports()}
        try:
            store(node, outputs, [((0,), [values])], iterated=False)
        except NodeError:
            return False
        messages = [m for m in result.messages if m.level != Level.REMARK]
        messages += [Message(Level.REMARK, text) for text in remarks or []]
        self.results[node_id] = NodeResult(result.state, messages, result.seconds, outputs, result.improver)
        for wire in self.graph.wires_from(node_id):
            self.graph.expire(wire.target)
        if node_id not in self._adopted:
            self._adopted.append(node_id)
        return True

    # -- one node -------------------------------------------------------------------
    def _solve_node(self, record: NodeRecord, token: CancelToken,
                    on_progress: Callable[[float], None] | None = None) -> NodeResult:
        """Solve one node in a fresh :class:`SolveContext` (its token, files, progress and
        messages): nothing of the solve is written on the node object."""
        node = record.node
        started = time.perf_counter()
        if is_placeholder(node):
            package = record.raw.get("plugin")  # the plug-in the file says provides it
            source = f" (it comes from the plug-in package {package!r})" if isinstance(package, str) else ""
            text = f"node type {record.type_id!r} is not installed{source}; its data is kept as it is"
            return NodeResult(MISSING, [Message(Level.WARNING, text)], 0.0, _empty_outputs(node))
        if not record.enabled:
            return NodeResult(DISABLED, [], 0.0, _empty_outputs(node))
        if isinstance(node, ClusterNode):
            return self._solve_cluster(record, node, token, on_progress)
        context = SolveContext(node, token, self.files.for_node(record.id, token), on_progress,
                               budget=self.budget, dry=self.dry, anytime=self.anytime)
        outputs: dict[str, DataTree] = {}
        with solving(context):
            try:
                trees, wired = self._gather(record)
                node.before_solve()
                outputs = run_node(node, trees, wired)
                node.after_solve()
            except Cancelled:
                raise
            except NodeError as exc:
                context.say(Message(Level.ERROR, str(exc)))
                if isinstance(exc, BudgetExceeded):
                    self.refused.append((record.id, str(exc)))
            except NodeWarning as exc:
                context.say(Message(Level.WARNING, str(exc)))
            except Exception as exc:  # a bug in a node must not stop the rest of the graph
                context.say(Message(Level.ERROR, _describe_exception(exc)))
        messages = context.messages
        seconds = time.perf_counter() - started
        state = OK
        if messages:
            worst = max(m.level for m in messages)
            state = {Level.ERROR: ERROR, Level.WARNING: WARNING}.get(worst, OK)
        if state == ERROR or not outputs:
            outputs = _empty_outputs(node)
        improver = context.improver if state != ERROR and self.anytime else None
        return NodeResult(state, messages, seconds, outputs, improver)

    def _solve_cluster(self, record: NodeRecord, node: ClusterNode, token: CancelToken,
                       on_progress: Callable[[float], None] | None) -> NodeResult:
        """Solve a cluster instance through its inner graph: only the inner nodes
        downstream of inputs whose trees changed are solved again."""
        started = time.perf_counter()
        definition = node.definition
        run = self._clusters.get(record.id)
        if run is None or run.definition is not definition or run.revision != definition.revision:
            run = self._clusters[record.id] = ClusterRun(definition, self.files, self)
        try:
            trees, wired = self._gather(record)
        except NodeError as exc:
            return NodeResult(ERROR, [Message(Level.ERROR, str(exc))], time.perf_counter() - started,
                              _empty_outputs(node))
        present = [
            is_wired or (port.name in record.inputs and record.inputs[port.name].has_value)
            for port, is_wired in zip(node.input_ports(), wired, strict=True)
        ]
        run.feed(trees, present)
        progress = None if on_progress is None else (
            lambda index, count, _node: on_progress(index / max(count, 1)))
        if run.solver.solve(token, progress).cancelled:
            raise Cancelled
        inner = run.solver
        outputs = {
            port.name: inner.result(node_id).output(PORT)
            for port, node_id in zip(definition.output_ports(), definition.outputs, strict=True)
        }
        state, messages = run.summary()
        return NodeResult(state, messages, time.perf_counter() - started, outputs)

    def _gather(self, record: NodeRecord) -> tuple[list[DataTree], list[bool]]:
        """The modified, cast input trees of ``record``, one per input port, and which are wired."""
        trees, wired = [], []
        wires = self.graph.wires_into(record.id)
        for port in record.node.input_ports():
            state = record.inputs.get(port.name)
            feeding = [w for w in wires if w.target_port == port.name]
            wired.append(bool(feeding))
            if feeding:
                tree = merge_trees(
                    [self.result(w.source).output(w.source_port) for w in feeding]
                )
            elif state is not None and state.has_value:
                try:
                    tree = DataTree.from_value(decode_value(state.value))
                except CastError as exc:
                    raise NodeError(f"input {port.name}: {exc}") from None
            elif port.has_default and port.default is not None:
                tree = DataTree.from_value(port.default)
            else:
                tree = DataTree()
            if state is not None and state.modifiers:
                tree = apply_modifiers(tree, state.modifiers)
            trees.append(within_bounds(cast_tree(tree, port), port))
        return trees, wired


class ClusterRun:
    """One cluster instance's inner solve: a private copy of its definition's graph (as
    of the definition's ``revision``), its solver, and the trees it was last fed."""

    def __init__(self, definition: ClusterDefinition, files: WriteAccess, parent: Solver | None = None
                 ) -> None:
        self.definition = definition
        self.revision = definition.revision
        self.graph = clone_graph(definition.graph)
        self.solver = Solver(self.graph, files, dry=parent.dry if parent else None,
                             budget=parent.budget if parent else None)
        self.fed: dict[str, DataTree] = {}
        self.cut: dict[str, list[Wire]] = {}  # an absent input's wires, taken out of the copy

    def feed(self, trees: list[DataTree], present: list[bool]) -> None:
        """Give each inner Input node its tree; expire those whose tree changed. An input
        that is neither wired nor given a value is *absent*: its wires are taken out of the
        private copy, so the inner inputs it fed use their own values or defaults, as in
        the expanded graph (and go back when it is wired again)."""
        graph = self.graph
        for node_id, tree, here in zip(self.definition.inputs, trees, present, strict=True):
            record = graph.nodes.get(node_id)
            if record is None or not isinstance(record.node, ClusterInput):
                continue
            if not here:
                if node_id not in self.cut:
                    self.cut[node_id] = graph.wires_from(node_id)
                    for wire in self.cut[node_id]:
                        graph.disconnect(wire)
                self.fed.pop(node_id, None)
                continue
            for wire in self.cut.pop(node_id, ()):
                graph.connect_wire(wire)
            last = self.fed.get(node_id)
            if last is not None and _same_tree(last, tree):
                continue
            self.fed[node_id] = tree
            record.node.feed = tree
            self.graph.expire(node_id)

    def summary(self) -> tuple[str, list[Message]]:
        """The cluster's state (its inner nodes' worst) and its message: the worst inner
        message, naming its node, with how many more there are."""
        found: list[tuple[Level, str]] = []
        graph, results = self.graph, self.solver.results
        for node_id in graph.order():
            result = results.get(node_id)
            if result is None:
                continue
            for message in result.messages:
                found.append((message.level, f"{graph.nodes[node_id].title}: {message.text}"))
        if not found:
            return OK, []
        worst = max(level for level, _ in found)
        text = next(text for level, text in found if level == worst)
        others = sum(1 for level, _ in found if level >= Level.WARNING) - (worst >= Level.WARNING)
        if others:
            text += f" (and {others} more inside the cluster)"
        state = {Level.ERROR: ERROR, Level.WARNING: WARNING}.get(worst, OK)
        return state, [Message(worst, text)]


def _same_outputs(before: NodeResult | None, after: NodeResult) -> bool:
    """Whether ``after`` holds the very output trees ``before`` did (the same objects)."""
    return (before is not None and before.outputs.keys() == after.outputs.keys()
            and all(after.outputs[p] is tree for p, tree in before.outputs.items()))


def _same_tree(a: DataTree, b: DataTree) -> bool:
    if a is b:
        return True
    try:
        return bool(a == b)
    except Exception:  # items that cannot be compared: treat the tree as new
        return False


def _empty_outputs(node: Node) -> dict[str, DataTree]:
    return {p.name: DataTree() for p in node.output_ports()}


def _describe_exception(exc: Exception) -> str:
    frame = traceback.extract_tb(exc.__traceback__)[-1] if exc.__traceback__ else None
    where = f" (in {frame.name}, line {frame.lineno})" if frame else ""
    return f"{type(exc).__name__}: {exc}{where}"


# --------------------------------------------------------------------------- matching
