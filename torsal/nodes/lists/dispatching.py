"""Dispatching: splitting a list in two by a true/false pattern."""

from __future__ import annotations

import numpy as np

from torsal.engine.datatree import Branch, is_array, take
from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import BOOLEAN, GENERIC


class Dispatch(Node):
    """Send the items of a list to A or to B by a repeating true/false pattern.

    Item i goes to A when the pattern's item (i modulo its length) is true, else to B:
    the pattern [true, false] sends the even items to A and the odd ones to B, each
    keeping its order. Cull Pattern keeps only A.
    """

    type_id = "lists.Dispatch"
    nickname, aliases = "Dispatch", ("split by pattern", "even and odd", "alternate")
    inputs = (
        In("List", GENERIC, "L", "The list to split.", access=LIST, arrays=True),
        In("Pattern", BOOLEAN, "P", "True sends an item to A, false to B; repeats along the list.",
           access=LIST, arrays=True),
    )
    outputs = (
        Out("A", GENERIC, "A", "The items where the pattern is true.", access=LIST),
        Out("B", GENERIC, "B", "The items where the pattern is false.", access=LIST),
    )

    def solve(self, items: Branch, pattern: Branch) -> tuple[Branch, Branch]:
        if not len(pattern):
            raise NodeWarning("The pattern is empty: give at least one true or false")
        if not is_array(pattern) and any(p is None for p in pattern):
            raise NodeWarning("The pattern contains empty (null) items: use true or false")
        repeats = -(-len(items) // len(pattern))
        to_a = np.tile(np.asarray(pattern, dtype=bool), repeats)[:len(items)]
        if is_array(items):
            return items[to_a], items[~to_a]
        return take(items, np.flatnonzero(to_a)), take(items, np.flatnonzero(~to_a))
