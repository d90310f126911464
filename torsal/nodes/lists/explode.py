"""Explode Tree: one output per branch of a data tree, as Grasshopper's Explode Tree."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from torsal.engine.datatree import DataTree, format_path
from torsal.engine.node import TREE, In, Node, Out, Setting
from torsal.engine.types import GENERIC

#: The most outputs an Explode Tree node has: a canvas node with more ports than this is
#: unreadable, and a tree of more branches is better taken apart by Tree Branch or List Item.
MAX_OUTPUTS = 64
#: Outputs of a new node.
DEFAULT_OUTPUTS = 2


def _branch_port(index: int) -> Out:
    return Out(
        f"Branch{index}", GENERIC, str(index),
        f"The items of the tree's branch number {index} (counting in path order from 0), "
        "as one list in {0}; empty when the tree has fewer branches.",
        access=TREE,
    )


def outputs_setting(value: Any) -> tuple[int, str]:
    """The number of outputs the ``outputs`` setting asks for, kept within 1 to
    :data:`MAX_OUTPUTS`, and why it was changed ("" when it was not)."""
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        return DEFAULT_OUTPUTS, (f"the Outputs setting must be a whole number, not {value!r}: "
                                 f"{DEFAULT_OUTPUTS} used")
    count = int(value)
    if count != value:
        return max(1, min(count, MAX_OUTPUTS)), f"the Outputs setting must be a whole number, not {value!r}"
    if count < 1:
        return 1, f"the Outputs setting must be at least 1, not {count}: 1 used"
    if count > MAX_OUTPUTS:
        return MAX_OUTPUTS, f"the Outputs setting is at most {MAX_OUTPUTS}, not {count}: {MAX_OUTPUTS} used"
    return count, ""


class ExplodeTree(Node):
    """Give each branch of a tree an output of its own: Branch0, Branch1, ...

    The branches are taken in path order: {0;0} goes to Branch0, {0;1} to Branch1, and
    so on; each output holds its branch's items as one list in {0}. How many outputs
    the node has is its **Outputs** setting (2 for a new node, at most 64): change it in
    the inspector's Settings, or right-click the node and choose *Match outputs* to give
    it one output per branch of the tree it last received, as in Grasshopper. Wires to
    outputs that a smaller count removes are unplugged.

    A tree with more branches than outputs: the branches past the last output are not
    passed on, and the node warns how many; with fewer, the outputs past its last branch
    are empty. To pick one branch by its path instead, use Tree Branch.
    """

    type_id = "lists.ExplodeTree"
    nickname, aliases = "BANG!", ("Explode Tree", "BANG", "explode branches", "split tree",
                                  "one output per branch")
    inputs = (In("Data", GENERIC, "D", "The tree to take apart.", access=TREE),)
    outputs = tuple(_branch_port(i) for i in range(DEFAULT_OUTPUTS))
    settings_spec = (
        Setting("outputs", int, DEFAULT_OUTPUTS,
                f"How many outputs the node has, 1 to {MAX_OUTPUTS}: one per branch of the tree."),
    )

    def output_ports(self) -> tuple[Out, ...]:
        count, _ = outputs_setting(self.settings.get("outputs"))
        return self.outputs if count == DEFAULT_OUTPUTS else tuple(_branch_port(i) for i in range(count))

    def match_outputs(self, trees: Sequence[DataTree]) -> dict[str, Any] | None:
        """The settings that give the node one output per branch of ``trees[0]`` (the tree
        it last received): Grasshopper's *Match outputs*. None for an empty tree: its
        outputs, and the wires from them, are left as they are."""
        branches = len(trees[0].paths) if trees else 0
        return {"outputs": min(branches, MAX_OUTPUTS)} if branches else None

    def solve(self, tree: DataTree) -> tuple[DataTree, ...] | DataTree:
        count, problem = outputs_setting(self.settings.get("outputs"))
        if problem:
            self.warn(problem[:1].upper() + problem[1:])
        branches = list(tree.raw_items())
        left = len(branches) - count
        if left > 0:
            first = format_path(branches[count][0])
            what = (f"its last branch, {first}, is" if left == 1
                    else f"its last {left} branches, from {first}, are")
            most = "" if len(branches) <= MAX_OUTPUTS else f" (at most {MAX_OUTPUTS})"
            self.warn(f"The tree has {len(branches)} branches and the node {count} outputs: {what} not "
                      f"passed on. Right-click the node → Match outputs{most}.")
        trees = tuple(DataTree({(0,): branch}) for _, branch in branches[:count])
        trees += (DataTree(),) * (count - len(trees))
        return trees if count > 1 else trees[0]  # a node of one output returns its value alone
