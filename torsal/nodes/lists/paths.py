"""Data-tree paths: simplify them, pick a branch by its path, trim levels off, map paths
by a mask (a small Path Mapper), and read a tree's paths and counts."""

from __future__ import annotations

import re
from typing import Any

from torsal.engine.datatree import DataTree, as_list, format_path, parse_path
from torsal.engine.node import LIST, TREE, In, Node, NodeWarning, Out
from torsal.engine.types import GENERIC, INTEGER, TEXT
from torsal.nodes.common.checks import count

#: A path mask: ``{a;b}`` or ``{a;b}(i)``; each part a name, or a number in a target.
_MASK = re.compile(r"^\{([^{}()]*)\}(?:\((\w+)\))?$")
_NAME = re.compile(r"^[A-Za-z_]\w*$")


class SimplifyTree(Node):
    """Remove the path levels every branch shares, as the Simplify modifier does.

    {0;0;1}: [a], {0;0;2}: [b] becomes {1}: [a], {2}: [b]; at least one level is kept.
    """

    type_id = "lists.SimplifyTree"
    nickname, aliases = "Simplify", ("Simplify Tree", "simplify", "shorten paths")
    inputs = (In("Tree", GENERIC, "T", "The tree to simplify.", access=TREE),)
    outputs = (Out("Tree", GENERIC, "T", "The same branches, their shared leading levels removed.",
                   access=TREE),)

    def solve(self, tree: DataTree) -> DataTree:
        return tree.simplified()


class TreeBranch(Node):
    """The items of one branch of a tree, picked by its path (typed as {0;1}).

    A path the tree does not hold gives a warning naming it and the paths it has.
    """

    type_id = "lists.TreeBranch"
    nickname, aliases = "Branch", ("Tree Branch", "branch", "get branch", "pick branch")
    inputs = (
        In("Tree", GENERIC, "T", "The tree to read.", access=TREE),
        In("Path", TEXT, "P", "The branch's path, such as {0;1}.", default="{0}"),
    )
    outputs = (Out("Items", GENERIC, "I", "The branch's items.", access=LIST),)

    def solve(self, tree: DataTree, path: Any) -> list[Any]:
        try:
            wanted = parse_path(str(path))
        except ValueError as refused:
            raise NodeWarning(f"Path: {refused}") from None
        if wanted not in tree.paths:
            have = ", ".join(format_path(p) for p in tree.paths[:6]) + (" …" if tree.branch_count > 6 else "")
            raise NodeWarning(f"The tree has no branch {format_path(wanted)}; it has {have or 'no branches'}")
        return tree.branch(wanted)


class TrimTree(Node):
    """Remove the last Depth levels of every path, merging the branches that then share one.

    {0;0}: [a], {0;1}: [b], {1;0}: [c] trimmed by 1 gives {0}: [a, b], {1}: [c], so lists
    made per item can be gathered again. At least one level is kept.
    """

    type_id = "lists.TrimTree"
    nickname, aliases = "Trim", ("Trim Tree", "trim", "merge branches", "shorten tree")
    inputs = (
        In("Tree", GENERIC, "T", "The tree to trim.", access=TREE),
        In("Depth", INTEGER, "D", "How many levels to remove from the end of each path.", default=1),
    )
    outputs = (Out("Tree", GENERIC, "T", "The trimmed tree.", access=TREE),)

    def solve(self, tree: DataTree, depth: Any) -> DataTree:
        levels = count("Depth", depth, least=0, limit=64)
        trimmed = DataTree()
        for path, branch in tree.raw_items():
            trimmed.extend(path[: max(1, len(path) - levels)], branch)
        return DataTree(dict(trimmed.raw_items()))


class PathMapper(Node):
    """Move branches to new paths by a mask, as Grasshopper's Path Mapper does for
    rearranging: ``{a;b}`` → ``{b;a}`` swaps the two levels, ``{a;b}`` → ``{a}`` gathers
    each a's branches into one, ``{a}(i)`` → ``{i}`` sends item i of every branch to
    branch i (transposing a grid of rows into columns).

    The source names each level of a path (and, with ``(i)``, each item's index); the
    target is built from those names and whole numbers. Names only — no arithmetic.
    Branches whose path has a different number of levels than the source are warned
    about and left out.
    """

    type_id = "lists.PathMapper"
    nickname, aliases = "PMap", ("Path Mapper", "map paths", "transpose tree", "swap levels")
    inputs = (
        In("Tree", GENERIC, "T", "The tree to rearrange.", access=TREE),
        In("Source", TEXT, "S", "The mask of the paths as they are, such as {a;b} or {a;b}(i).",
           default="{a;b}"),
        In("Target", TEXT, "T2", "The mask of the new paths, such as {b;a}.", default="{b;a}"),
    )
    outputs = (Out("Tree", GENERIC, "T", "The rearranged tree.", access=TREE),)

    def solve(self, tree: DataTree, source: Any, target: Any) -> DataTree:
        names, item = _source(str(source))
        parts = _target(str(target), set(names) | ({item} if item else set()))
        mapped = DataTree()
        skipped = 0
        for path, branch in tree.raw_items():
            if len(path) != len(names):
                skipped += 1
                continue
            values = dict(zip(names, path, strict=True))
            if item is None:
                mapped.extend(_build(parts, values), branch)
                continue
            for i, value in enumerate(as_list(branch)):
                mapped.append(_build(parts, {**values, item: i}), value)
        if skipped:
            self.warn(f"{skipped} branches have paths of another depth than Source {source}: left out")
        return DataTree(dict(mapped.raw_items()))


def _source(text: str) -> tuple[list[str], str | None]:
    match = _MASK.match(text.strip().replace(" ", ""))
    if not match:
        raise NodeWarning(f"Source {text!r} is not a mask: write it like {{a;b}} or {{a;b}}(i)")
    names = match.group(1).split(";") if match.group(1) else []
    if not names or not all(_NAME.match(n) for n in names) or len(set(names)) < len(names):
        raise NodeWarning(f"Source {text!r} must name each level once, with letters: {{a;b}}")
    item = match.group(2)
    if item is not None and (not _NAME.match(item) or item in names):
        raise NodeWarning(f"Source {text!r}: the item index needs a name of its own, such as (i)")
    return names, item


def _target(text: str, known: set[str]) -> list[str | int]:
    match = _MASK.match(text.strip().replace(" ", ""))
    if not match or match.group(2) or not match.group(1):
        raise NodeWarning(f"Target {text!r} is not a path mask: write it like {{b;a}}")
    parts: list[str | int] = []
    for part in match.group(1).split(";"):
        if part.isdigit():
            parts.append(int(part))
        elif part in known:
            parts.append(part)
        else:
            raise NodeWarning(f"Target {text!r} uses {part!r}, which Source does not name: "
                              f"use {', '.join(sorted(known))} or whole numbers")
    return parts


def _build(parts: list[str | int], values: dict[str, int]) -> tuple[int, ...]:
    return tuple(values[p] if isinstance(p, str) else p for p in parts)
