"""The incremental solver: solve expired nodes in topological order from cached results.

Each node's inputs are gathered from its wires' cached output trees (or from its
persistent values and defaults), modified, cast to the port types and *matched* the
Grasshopper way (see ``shared/spec/data-trees.md``); ``solve`` is then called once per
match. A node ends ``ok``, ``warning``, ``error``, ``disabled`` or ``missing`` with its
messages and solve time. An exception in one node never stops the others.
"""

from __future__ import annotations

import time
import traceback
from collections.abc import Callable
from dataclasses import dataclass, field
from itertools import chain, repeat
from typing import Any

import numpy as np

from torsal.engine.bounds import within_bounds
from torsal.engine.casting import (  # noqa: F401 - also exported here, where callers found them
    TRIPLE_OF,
    array_fits,
    cast_array_branch,
    cast_tree,
    merge_trees,
)
from torsal.engine.cluster import PORT, ClusterDefinition, ClusterInput, ClusterNode, clone_graph
from torsal.engine.datatree import Branch, DataTree, Path, Triples, apply_modifiers, as_list, format_path
from torsal.engine.graph import Graph, NodeRecord, Wire, is_placeholder
from torsal.engine.node import (
    ITEM,
    LIST,
    TREE,
    Cancelled,
    CancelToken,
    In,
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

    def __init__(self, graph: Graph, files: WriteAccess | None = None, anytime: bool = False) -> None:
        self.graph = graph
        #: nodes may answer at once and improve their result later (the app): improve.py
        self.anytime = anytime
        self._adopted: list[str] = []  # improved since the last solve: reported as solved
        self.results: dict[str, NodeResult] = {}
        #: where the graph's nodes may write files, and whether the user allows it
        self.files = files if files is not None else WriteAccess()
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

    def solve(self, token: CancelToken | None = None, progress: Progress | None = None,
              node_progress: NodeProgress | None = None) -> SolveReport:
        """Solve every expired node; cancelled solves leave the rest expired.
        ``node_progress`` hears what long nodes report with :meth:`Node.progress`."""
        graph = self.graph
        token = token or CancelToken()
        report = SolveReport()
        start = time.perf_counter()
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
        out_ports = node.output_ports()
        outputs = {p.name: DataTree() for p in out_ports}
        try:
            _store(node, out_ports, outputs, [((0,), [values])], iterated=False)
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
            text = f"node type {record.type_id!r} is not installed; its data is kept as it is"
            return NodeResult(MISSING, [Message(Level.WARNING, text)], 0.0, _empty_outputs(node))
        if not record.enabled:
            return NodeResult(DISABLED, [], 0.0, _empty_outputs(node))
        if isinstance(node, ClusterNode):
            return self._solve_cluster(record, node, token, on_progress)
        context = SolveContext(node, token, self.files.for_node(record.id), on_progress, anytime=self.anytime)
        messages = context.messages
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
                messages.append(Message(Level.ERROR, str(exc)))
            except NodeWarning as exc:
                messages.append(Message(Level.WARNING, str(exc)))
            except Exception as exc:  # a bug in a node must not stop the rest of the graph
                messages.append(Message(Level.ERROR, _describe_exception(exc)))
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
            run = self._clusters[record.id] = ClusterRun(definition, self.files)
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

    def __init__(self, definition: ClusterDefinition, files: WriteAccess) -> None:
        self.definition = definition
        self.revision = definition.revision
        self.graph = clone_graph(definition.graph)
        self.solver = Solver(self.graph, files)
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

def run_node(node: Node, trees: list[DataTree], wired: list[bool] | None = None) -> dict[str, DataTree]:
    """Match ``trees`` to ``node``'s inputs, call ``solve`` per match, collect output trees.

    A required input with no data, or a wired non-optional input whose source produced
    nothing, makes the node warn and produce nothing (Grasshopper's "collected no
    data"): a default never silently replaces an upstream failure. Optional inputs may
    be empty.
    """
    in_ports = node.input_ports()
    out_ports = node.output_ports()
    outputs = {p.name: DataTree() for p in out_ports}
    wired = wired or [False] * len(in_ports)

    matched: list[tuple[In, DataTree]] = []
    single = True  # every matched input is one branch {0} of one item: the common case
    trees = list(trees)
    for index, (port, tree, is_wired) in enumerate(zip(in_ports, trees, wired, strict=True)):
        if tree.is_empty():
            if not port.optional and (is_wired or not port.has_default):
                node.warn(f"Input {port.name} collected no data")
                return outputs
            if port.access is ITEM:  # an empty optional item arrives as None
                trees[index] = tree = DataTree({(0,): [None]})
        if port.access is not TREE:
            matched.append((port, tree))
            if single and not (tree.paths == [(0,)] and len(tree.raw_branches[0]) == 1):
                single = False
        else:
            single = False

    if not matched:  # no inputs, or only tree inputs: one call
        _store(node, out_ports, outputs, [((0,), [_call(node, trees)])], iterated=False)
        return outputs
    if single:
        args = [_for_port(t.raw_branches[0], p) for p, t in matched]
        args = [a[0] if p.access is ITEM else a for (p, _), a in zip(matched, args, strict=True)]
        _store(node, out_ports, outputs, [((0,), [_call(node, args)])], iterated=False)
        return outputs
    if len(matched) > 1:
        _remark_uneven(node, matched)

    branch_lists = [[_for_port(b, p) for b in t.raw_branches] or [[]] for p, t in matched]
    path_lists = [t.paths or [(0,)] for _, t in matched]
    branch_count = max(len(b) for b in branch_lists)
    master = next(i for i, b in enumerate(branch_lists) if len(b) == branch_count)
    item_slots = [i for i, (p, _) in enumerate(matched) if p.access is ITEM]
    iterated = bool(item_slots)
    # arguments in port order: tree inputs fixed, the others filled per call
    template = [t if p.access is TREE else None for p, t in zip(in_ports, trees, strict=True)]
    slot_of_port = [i for i, p in enumerate(in_ports) if p.access is not TREE]
    no_tree_inputs = len(slot_of_port) == len(in_ports)
    # list outputs go to {p;i} when any branch makes several calls, so depths never mix
    # (each item input's branches are all read by some branch of the longest)
    sub_branches = iterated and any(max(map(len, branch_lists[i])) > 1 for i in item_slots)

    # plan every call first, so the budget is checked before the first one is made
    plan: list[tuple[Path, Any, bool]] = []  # (path, args of one call or rows of calls, is rows)
    calls = 0
    # each input's branch for every branch of the longest tree (a shorter tree's last one reused)
    per_branch = zip(*(bl + [bl[-1]] * (branch_count - len(bl)) for bl in branch_lists), strict=True)
    paths = path_lists[master]
    if not iterated:
        for path, branches in zip(paths, per_branch, strict=True):
            args = list(template)
            for slot, port_index in enumerate(slot_of_port):
                args[port_index] = branches[slot]
            plan.append((path, args, False))
            calls += 1
    else:
        # the calls a branch makes: its longest item list (none when one is empty)
        lengths = [[len(branch) for branch in branch_lists[i]] for i in item_slots]
        lengths = [ls + [ls[-1]] * (branch_count - len(ls)) for ls in lengths]
        counts = list(map(max, *lengths)) if len(lengths) > 1 else lengths[0]
        fewest = list(map(min, *lengths)) if len(lengths) > 1 else lengths[0]
        listed = [p.access is LIST for p, _ in matched]
        for path, branches, count, least in zip(paths, per_branch, counts, fewest, strict=True):
            if least == 0:
                continue
            columns: list[Any] = [
                repeat(branch, count) if is_list else branch if len(branch) == count
                else branch + [branch[-1]] * (count - len(branch))
                for branch, is_list in zip(branches, listed, strict=True)
            ]
            if no_tree_inputs:
                arg_rows: Any = zip(*columns, strict=False)
            else:
                placed = list(zip(slot_of_port, columns, strict=True))
                arg_rows = (_fill(template, placed, row) for row in zip(*columns, strict=False))
            plan.append((path, arg_rows, True))
            calls += count
    if calls > node.max_calls:
        raise NodeError(_too_many_calls(node, matched, calls, f"at most {node.max_calls:,} at once"))
    if node.max_work is not None:
        plan = [(path, list(rows) if is_rows else rows, is_rows) for path, rows, is_rows in plan]
        work = sum(
            sum(_work(node, row) for row in rows) if is_rows else _work(node, rows)
            for _, rows, is_rows in plan
        )
        if work > node.max_work:
            raise NodeError(_too_many_calls(
                node, matched, calls,
                f"{work:,} {node.work_unit} in all, at most {node.max_work:,} (the work of "
                f"{node.max_work / max(work / calls, 1):,.0f} such runs)",
            ))

    if iterated and type(node).solve_many is not Node.solve_many and plan:
        plan = [(path, list(rows), True) for path, rows, _ in plan]  # read again if it declines
        node.check_cancelled()
        results = node.solve_many(*zip(*chain.from_iterable(rows for _, rows, _ in plan), strict=True))
        if results is not None:  # each branch's rows' results, in order
            groups, start = [], 0
            for path, rows, _ in plan:
                groups.append((path, results[start:start + len(rows)]))
                start += len(rows)
            _store(node, out_ports, outputs, groups, iterated=sub_branches)
            return outputs

    for path, rows, is_rows in plan:
        node.check_cancelled()
        if not is_rows:
            _store(node, out_ports, outputs, [(path, [_call(node, rows)])], iterated=False)
            continue
        _store(node, out_ports, outputs, [(path, _call_rows(node, rows))], iterated=sub_branches)
    return outputs


def _for_port(branch: Branch, port: In) -> Branch:
    """A branch as ``port`` receives it: an array as it is for a list input that takes
    arrays (``In(..., arrays=True)``; points and vectors as an (n, 3) array into a Point
    or Vector input, as Triples into any other, which keeps what its rows are), otherwise
    a list of Python values."""
    if port.arrays and port.access is LIST:
        return branch.array if isinstance(branch, Triples) and port.type.name in TRIPLE_OF else branch
    return as_list(branch)


def _work(node: Node, args: Any) -> int:
    """One call's :meth:`Node.call_work`; a value it cannot count costs 1 (solve refuses it)."""
    try:
        return max(int(node.call_work(*args)), 1)
    except Exception:  # a bad value: solve's own message names it
        return 1


def _too_many_calls(node: Node, matched: list[tuple[In, DataTree]], calls: int, limit: str) -> str:
    """"UDensity has 200 values: SurfaceAnalysis would run 200 times; …": names the input
    with the most values (or branches, for a node that runs once per branch)."""
    def size(tree: DataTree) -> int:
        return tree.item_count

    items = [(p, t) for p, t in matched if p.access is ITEM]
    if items:
        port, tree = max(items, key=lambda pt: size(pt[1]))
        many = f"{port.name} has {size(tree):,} values"
    else:
        port, tree = max(matched, key=lambda pt: pt[1].branch_count)
        many = f"{port.name} has {tree.branch_count:,} branches"
    if tree.branch_count > 1 and items:
        many += f" in {tree.branch_count:,} branches"
    return f"{many}: {node.name()} would run {calls:,} times; {limit}"


def _fill(template: list[Any], columns: list[Any], row: tuple[Any, ...]) -> list[Any]:
    args = list(template)
    for (port_index, _), value in zip(columns, row, strict=True):
        args[port_index] = value
    return args


def _call(node: Node, args: list[Any]) -> Any:
    try:
        return node.solve(*args)
    except NodeWarning as exc:
        node.warn(str(exc))
        return None


def _call_rows(node: Node, rows: Any) -> list[Any]:
    """Call ``solve`` per argument row; the hot loop of item access. The token is checked
    before a call once 20 ms have passed since the last check: the clock is read after
    every call that takes 1 ms or more (a cancel waits for one call), after every 8 quicker
    ones (reading it after each cost a trivial loop 30 %). Never after the last call: a
    node that answered a cancel with its best result so far (a nesting) keeps it."""
    solve = node.solve
    token = node.token
    clock = time.perf_counter
    looked = clock()
    due = looked + 0.02
    look_at = 1  # the call after which the clock is read next
    check_first = False  # look at the token before the next call
    results: list[Any] = []
    append = results.append
    for count, row in enumerate(rows, 1):
        if check_first:
            token.check()
            check_first = False
        try:
            append(solve(*row))
        except NodeWarning as exc:
            node.warn(str(exc))
            append(None)
        if count >= look_at:
            now = clock()
            if now >= due:
                check_first = True
                due = now + 0.02
            look_at = count + (8 if now - looked < 1e-3 else 1)
            looked = now
    return results


def _store(
    node: Node,
    out_ports: tuple[Any, ...],
    outputs: dict[str, DataTree],
    groups: list[tuple[Path, list[Any]]],
    iterated: bool,
) -> None:
    """Place branch iterations' results in the output trees: ``groups`` holds each
    iteration's path and its calls' results, in order.

    With ``iterated``, each call's list goes to its own branch ``{p;i}``; otherwise
    lists are appended to ``{p}``. The caller sets ``iterated`` when some branch of
    an item-access node makes several calls, so a single call (one curve divided)
    keeps the path ``{p}`` as in Grasshopper, and depths never mix within a solve.
    """
    width = len(out_ports)
    if width == 1:
        split = [(path, [results]) for path, results in groups]
    else:  # each iteration's results as one column per output
        blank = (None,) * width  # a call that made nothing: None on every output
        split = []
        for path, results in groups:
            rows = [blank if result is None else result for result in results]
            if not all(isinstance(row, tuple) and len(row) == width for row in rows):
                raise NodeError(f"{type(node).__name__}.solve must return {width} values")
            split.append((path, list(zip(*rows, strict=True)) if rows else [() for _ in out_ports]))
    for index, port in enumerate(out_ports):
        tree = outputs[port.name]
        triples = port.access is LIST and port.type.name in TRIPLE_OF  # (n, 3) arrays: Triples
        for path, columns in split:
            column = columns[index]
            if triples:
                column = [_as_triples(values, port) for values in column]
            if port.access is ITEM:
                tree.extend(path, column)
            elif port.access is LIST:
                if iterated:
                    for i, values in enumerate(column):
                        tree.extend((*path, i), [] if values is None else values)
                else:
                    for values in column:
                        tree.extend(path, [] if values is None else values)
            else:  # TREE: the node built its own tree
                for value in column:
                    if isinstance(value, DataTree):
                        for sub_path, branch in value.raw_items():
                            tree.extend(sub_path, branch)


def _as_triples(values: Any, port: Any) -> Any:
    """A node's ``(n, 3)`` float array for a list output of points or vectors, as Triples."""
    if (isinstance(values, np.ndarray) and values.ndim == 2 and values.shape[1] == 3
            and values.dtype.kind in "fi"):
        return Triples(values, TRIPLE_OF[port.type.name])
    return values


def _remark_uneven(node: Node, matched: list[tuple[In, DataTree]]) -> None:
    """Say in plain words when trees match unevenly (a branch or item gets reused)."""
    counts = [(p.name, t.branch_count) for p, t in matched if not t.is_empty()]
    if len(counts) < 2:
        return
    most = max(c for _, c in counts)
    for name, count in counts:
        if 1 < count < most:
            other = next(n for n, c in counts if c == most)
            node.remark(
                f"{other} has {most} branches, {name} has {count}: "
                f"{name}'s last branch is reused"
            )
    items = [(p.name, t) for p, t in matched if p.access is ITEM and not t.is_empty()]
    if len(items) < 2:
        return
    branch_lists = [(n, t.raw_branches) for n, t in items]  # built once: ``branches`` copies the tree's list
    if sum(max(map(len, bl)) > 1 for _, bl in branch_lists) < 2:
        return  # an item is reused only between two inputs that both have several in a branch
    for path_index in range(max(t.branch_count for _, t in items)):
        lengths = [(n, len(bl[min(path_index, len(bl) - 1)])) for n, bl in branch_lists]
        longest = max(length for _, length in lengths)
        for name, length in lengths:
            if 1 < length < longest:
                other = next(n for n, length2 in lengths if length2 == longest)
                path = items[0][1].paths[min(path_index, items[0][1].branch_count - 1)]
                node.remark(
                    f"{other} has {longest} items, {name} has {length} in branch "
                    f"{format_path(path)}: {name}'s last item is reused"
                )
                return
