"""The data-tree rules in one place: a node's input trees become a :class:`Plan` of calls.

:func:`plan` is the one implementation of the matching rules of ``docs/data-trees.md``
(access, "collected no data", longest tree, longest list, master paths, ``{p;i}`` list
outputs, the call budget). Two executors carry a plan out — :func:`run_batched` hands every
call of the solve to a node's ``solve_many`` at once, :func:`run_rows` calls ``solve`` row by
row — and both put what they get back with :func:`store`. The solver
(:mod:`torsal.engine.solver`) only gathers the trees and runs :func:`run_node`.

A plan is built before the first call, so a solve over budget is refused before any work.
"""

from __future__ import annotations

import time
from collections.abc import Iterable
from dataclasses import dataclass, field
from itertools import chain, repeat
from typing import Any

import numpy as np

from torsal.engine.call_budget import BudgetExceeded
from torsal.engine.casting import TRIPLE_OF
from torsal.engine.datatree import Branch, DataTree, Path, Triples, as_list, format_path
from torsal.engine.node import ITEM, LIST, TREE, In, Node, NodeError, NodeWarning
from torsal.engine.solve_context import active


@dataclass
class Group:
    """The calls of one branch iteration: the output path they write to and each call's
    arguments in port order (an iterable read once, unless :meth:`Plan.materialise` made it
    a list)."""

    path: Path
    rows: Iterable[Any]


@dataclass
class Plan:
    """Every call one solve of a node makes, and what the node says before making them.

    ``missing`` is the "collected no data" warning that stops the node before any call;
    ``refusal`` the sentence of a solve over budget (the node is put in error with it,
    after its remarks); ``remarks`` say where trees matched unevenly. ``iterated``: some
    input has item access, so a group holds one call per item; ``sub_branches``: some group
    makes several calls, so each call's list output goes to its own branch ``{p;i}``.
    """

    groups: list[Group] = field(default_factory=list)
    calls: int = 0
    iterated: bool = False
    sub_branches: bool = False
    remarks: list[str] = field(default_factory=list)
    missing: str | None = None
    refusal: str | None = None
    #: the inputs matched, for a message naming the one that multiplied the calls
    matched: list[tuple[In, DataTree]] = field(default_factory=list)

    def materialise(self) -> None:
        """Make every group's rows a list, to read them more than once."""
        for group in self.groups:
            if not isinstance(group.rows, list):
                group.rows = list(group.rows)


def run_node(node: Node, trees: list[DataTree], wired: list[bool] | None = None) -> dict[str, DataTree]:
    """Match ``trees`` to ``node``'s inputs, call ``solve`` (or ``solve_many``) per match,
    and collect the output trees."""
    outputs = {p.name: DataTree() for p in node.output_ports()}
    matching = plan(node, trees, wired)
    if matching.missing:
        node.warn(matching.missing)
        return outputs
    for text in matching.remarks:
        node.remark(text)
    if matching.refusal:
        raise BudgetExceeded(matching.refusal)
    context = active()
    if context is not None and context.budget is not None:  # the solve's calls, every node together
        context.budget.spend(matching.calls, lambda: _too_many_calls(
            node, matching.matched, matching.calls, "counted in the solve"))
    if context is not None and context.dry is not None and context.dry(node):
        return outputs  # planned and within its budgets: a dry solve (torsal check) stops here
    if not run_batched(node, matching, outputs):
        run_rows(node, matching, outputs)
    return outputs


# --------------------------------------------------------------------------- the plan


def plan(node: Node, trees: list[DataTree], wired: list[bool] | None = None) -> Plan:
    """The calls ``node`` makes for its input ``trees`` (``wired``: which inputs have a wire)."""
    in_ports = node.input_ports()
    wired = wired or [False] * len(in_ports)
    matched: list[tuple[In, DataTree]] = []
    single = True  # every matched input is one branch {0} of one item: the common case
    trees = list(trees)
    for index, (port, tree, is_wired) in enumerate(zip(in_ports, trees, wired, strict=True)):
        if tree.is_empty():
            # rule 1: a default never silently replaces an upstream failure
            if not port.optional and (is_wired or not port.has_default):
                return Plan(missing=f"Input {port.name} collected no data")
            if port.access is ITEM:  # an empty optional item arrives as None
                trees[index] = tree = DataTree({(0,): [None]})
        if port.access is not TREE:
            matched.append((port, tree))
            if single and not (tree.paths == [(0,)] and len(tree.raw_branches[0]) == 1):
                single = False
        else:
            single = False

    if not matched:  # no inputs, or only tree inputs: one call
        return Plan([Group((0,), [trees])], calls=1)
    if single:  # rule 6
        args = [_for_port(t.raw_branches[0], p) for p, t in matched]
        args = [a[0] if p.access is ITEM else a for (p, _), a in zip(matched, args, strict=True)]
        return Plan([Group((0,), [args])], calls=1)

    result = Plan(remarks=uneven_remarks(matched) if len(matched) > 1 else [], matched=matched)
    counted = _call_count(matched)  # from the branches' lengths, before any value is converted
    if counted > node.max_calls:  # a list of 1,000,000 is refused without building its calls
        result.calls = counted
        return _budgeted(node, matched, result)
    branch_lists = [[_for_port(b, p) for b in t.raw_branches] or [[]] for p, t in matched]
    path_lists = [t.paths or [(0,)] for _, t in matched]
    branch_count = max(len(b) for b in branch_lists)
    master = next(i for i, b in enumerate(branch_lists) if len(b) == branch_count)  # rule 4
    item_slots = [i for i, (p, _) in enumerate(matched) if p.access is ITEM]
    result.iterated = bool(item_slots)
    # arguments in port order: tree inputs fixed, the others filled per call
    template = [t if p.access is TREE else None for p, t in zip(in_ports, trees, strict=True)]
    slot_of_port = [i for i, p in enumerate(in_ports) if p.access is not TREE]
    no_tree_inputs = len(slot_of_port) == len(in_ports)
    # rule 5: list outputs go to {p;i} when any branch makes several calls, so depths never
    # mix (each item input's branches are all read by some branch of the longest)
    result.sub_branches = result.iterated and any(max(map(len, branch_lists[i])) > 1 for i in item_slots)

    # rule 2: each input's branch for every branch of the longest tree (a shorter tree's last reused)
    per_branch = zip(*(bl + [bl[-1]] * (branch_count - len(bl)) for bl in branch_lists), strict=True)
    paths = path_lists[master]
    if not result.iterated:
        for path, branches in zip(paths, per_branch, strict=True):
            args = list(template)
            for slot, port_index in enumerate(slot_of_port):
                args[port_index] = branches[slot]
            result.groups.append(Group(path, [args]))
            result.calls += 1
        return _budgeted(node, matched, result)
    # rule 3: the calls a branch makes: its longest item list (none when one is empty)
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
            rows: Any = zip(*columns, strict=False)
        else:
            placed = list(zip(slot_of_port, columns, strict=True))
            rows = (_fill(template, placed, row) for row in zip(*columns, strict=False))
        result.groups.append(Group(path, rows))
        result.calls += count
    return _budgeted(node, matched, result)


def _call_count(matched: list[tuple[In, DataTree]]) -> int:
    """The calls rules 2 and 3 make, from the lengths of the branches alone."""
    lengths = [[len(b) for b in t.raw_branches] or [0] for _, t in matched]
    branch_count = max(len(ls) for ls in lengths)
    items = [ls for ls, (p, _) in zip(lengths, matched, strict=True) if p.access is ITEM]
    if not items:
        return branch_count
    padded = [ls + [ls[-1]] * (branch_count - len(ls)) for ls in items]
    return sum(max(column) for column in zip(*padded, strict=True) if min(column) > 0)


def _budgeted(node: Node, matched: list[tuple[In, DataTree]], result: Plan) -> Plan:
    """``result`` with its refusal when it makes more calls, or more work, than the node allows."""
    if result.calls > node.max_calls:
        result.refusal = _too_many_calls(node, matched, result.calls, f"at most {node.max_calls:,} at once")
        return result
    if node.max_work is None:
        return result
    result.materialise()
    work = sum(_work(node, row) for group in result.groups for row in group.rows)
    if work > node.max_work:
        result.refusal = _too_many_calls(
            node, matched, result.calls,
            f"{work:,} {node.work_unit} in all, at most {node.max_work:,} (the work of "
            f"{node.max_work / max(work / result.calls, 1):,.0f} such runs)",
        )
    return result


def uneven_remarks(matched: list[tuple[In, DataTree]]) -> list[str]:
    """Where trees match unevenly (a branch or an item gets reused), in plain words."""
    remarks: list[str] = []
    counts = [(p.name, t.branch_count) for p, t in matched if not t.is_empty()]
    if len(counts) < 2:
        return remarks
    most = max(c for _, c in counts)
    for name, count in counts:
        if 1 < count < most:
            other = next(n for n, c in counts if c == most)
            remarks.append(f"{other} has {most} branches, {name} has {count}: {name}'s last branch is reused")
    items = [(p.name, t) for p, t in matched if p.access is ITEM and not t.is_empty()]
    if len(items) < 2:
        return remarks
    branch_lists = [(n, t.raw_branches) for n, t in items]  # built once: ``branches`` copies the tree's list
    if sum(max(map(len, bl)) > 1 for _, bl in branch_lists) < 2:
        return remarks  # an item is reused only between two inputs that both have several in a branch
    for path_index in range(max(t.branch_count for _, t in items)):
        lengths = [(n, len(bl[min(path_index, len(bl) - 1)])) for n, bl in branch_lists]
        longest = max(length for _, length in lengths)
        for name, length in lengths:
            if 1 < length < longest:
                other = next(n for n, length2 in lengths if length2 == longest)
                path = items[0][1].paths[min(path_index, items[0][1].branch_count - 1)]
                remarks.append(
                    f"{other} has {longest} items, {name} has {length} in branch "
                    f"{format_path(path)}: {name}'s last item is reused"
                )
                return remarks
    return remarks


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
    items = [(p, t) for p, t in matched if p.access is ITEM]
    if items:
        port, tree = max(items, key=lambda pt: pt[1].item_count)
        many = f"{port.name} has {tree.item_count:,} values"
    elif matched:
        port, tree = max(matched, key=lambda pt: pt[1].branch_count)
        many = f"{port.name} has {tree.branch_count:,} branches"
    else:
        return f"{node.name()} would run {calls:,} times; {limit}"
    if tree.branch_count > 1 and items:
        many += f" in {tree.branch_count:,} branches"
    return f"{many}: {node.name()} would run {calls:,} times; {limit}"


def _fill(template: list[Any], columns: list[Any], row: tuple[Any, ...]) -> list[Any]:
    args = list(template)
    for (port_index, _), value in zip(columns, row, strict=True):
        args[port_index] = value
    return args


# --------------------------------------------------------------------------- the executors


def run_batched(node: Node, matching: Plan, outputs: dict[str, DataTree]) -> bool:
    """Hand every call of an item-access solve to the node's ``solve_many`` at once and store
    what it returns; False (nothing stored, nothing said) when the node has none or declines."""
    if not (matching.iterated and matching.groups and type(node).solve_many is not Node.solve_many):
        return False
    matching.materialise()  # read again if it declines
    node.check_cancelled()
    said = len(node.messages)
    rows = chain.from_iterable(group.rows for group in matching.groups)
    results = node.solve_many(*zip(*rows, strict=True))
    if results is None:  # declined: what it said is forgotten, solve says it row by row
        node.context().forget_since(said)
        return False
    # each group's rows' results, in order (with the rows' messages said in order)
    groups, start = [], 0
    for group in matching.groups:
        count = len(group.rows)  # type: ignore[arg-type]
        groups.append((group.path, results[start:start + count]))
        start += count
    store(node, outputs, groups, iterated=matching.sub_branches)
    return True


def run_rows(node: Node, matching: Plan, outputs: dict[str, DataTree]) -> None:
    """Call ``solve`` once per row of every group, storing each group's results."""
    for group in matching.groups:
        node.check_cancelled()
        store(node, outputs, [(group.path, call_rows(node, group.rows))], iterated=matching.sub_branches)


def call_rows(node: Node, rows: Iterable[Any]) -> list[Any]:
    """Call ``solve`` per argument row; the hot loop of item access. A :class:`NodeWarning`
    refuses its row (the node warns, the row makes nothing) and the others go on. The token
    is checked before a call once 20 ms have passed since the last check: the clock is read
    after every call that takes 1 ms or more (a cancel waits for one call), after every 8
    quicker ones (reading it after each cost a trivial loop 30 %). Never after the last
    call: a node that answered a cancel with its best result so far (a nesting) keeps it."""
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


def store(
    node: Node, outputs: dict[str, DataTree], groups: list[tuple[Path, list[Any]]], iterated: bool
) -> None:
    """Place branch iterations' results in the output trees: ``groups`` holds each
    iteration's path and its calls' results, in order.

    With ``iterated``, each call's list goes to its own branch ``{p;i}``; otherwise
    lists are appended to ``{p}``. A single call (one curve divided) keeps the path ``{p}``
    as in Grasshopper, and depths never mix within a solve.
    """
    out_ports = node.output_ports()
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
