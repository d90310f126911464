"""Culling: removing items from a list by a pattern."""

from __future__ import annotations

import numpy as np

from torsal.engine.datatree import Branch, is_array, take
from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import BOOLEAN, GENERIC


class CullPattern(Node):
    """Keep or drop the items of a list by a repeating true/false pattern.

    Item i is kept when the pattern's item (i modulo the pattern's length) is true:
    the pattern [true, false] keeps every other item, starting with the first.
    """

    type_id = "lists.CullPattern"
    nickname, aliases = "Cull", ("Cull Pattern", "keep by pattern")
    inputs = (
        In("List", GENERIC, "L", "The list to cull.", access=LIST, arrays=True),
        In("Pattern", BOOLEAN, "P", "True keeps an item, false drops it; repeats along the list.",
           access=LIST, arrays=True),
    )
    outputs = (Out("List", GENERIC, "L", "The items the pattern keeps.", access=LIST),)

    def solve(self, items: Branch, pattern: Branch) -> Branch:
        if not len(pattern):
            raise NodeWarning("The pattern is empty: give at least one true or false")
        if not is_array(pattern) and any(p is None for p in pattern):  # an array holds no nulls
            raise NodeWarning("The pattern contains empty (null) items: use true or false")
        repeats = -(-len(items) // len(pattern))  # the pattern repeated along the list
        keep = np.tile(np.asarray(pattern, dtype=bool), repeats)[:len(items)]
        if is_array(items):
            return items[keep]
        return take(items, np.flatnonzero(keep))
