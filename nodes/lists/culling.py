"""Culling: removing items from a list by a pattern."""

from __future__ import annotations

from typing import Any

from engine.node import LIST, In, Node, NodeWarning, Out
from engine.types import BOOLEAN, GENERIC


class CullPattern(Node):
    """Keep or drop the items of a list by a repeating true/false pattern.

    Item i is kept when the pattern's item (i modulo the pattern's length) is true:
    the pattern [true, false] keeps every other item, starting with the first.
    """

    type_id = "lists.CullPattern"
    inputs = (
        In("List", GENERIC, "L", "The list to cull.", access=LIST),
        In("Pattern", BOOLEAN, "P", "True keeps an item, false drops it; repeats along the list.",
           access=LIST),
    )
    outputs = (Out("List", GENERIC, "L", "The items the pattern keeps.", access=LIST),)

    def solve(self, items: list[Any], pattern: list[bool]) -> list[Any]:
        if not pattern:
            raise NodeWarning("The pattern is empty: give at least one true or false")
        if any(p is None for p in pattern):
            raise NodeWarning("The pattern contains empty (null) items: use true or false")
        n = len(pattern)
        return [item for i, item in enumerate(items) if pattern[i % n]]
