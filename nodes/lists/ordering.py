"""Reordering lists: shift, reverse and sort."""

from __future__ import annotations

import math
from typing import Any

from engine.node import LIST, In, Node, NodeWarning, Out
from engine.types import BOOLEAN, GENERIC, INTEGER, NUMBER
from nodes.common.checks import whole


class Shift(Node):
    """Move every item of a list along by Shift places.

    Shift = 1 moves each item one place towards the front: [a, b, c] becomes
    [b, c, a] with Wrap on, or [b, c] with Wrap off (the items shifted past the end
    are dropped). A negative Shift moves items towards the back. Pair a list with its
    shifted copy to join each point to the next one.
    """

    type_id = "lists.Shift"
    inputs = (
        In("List", GENERIC, "L", "The list to shift.", access=LIST),
        In("Shift", INTEGER, "S", "How many places to move the items; negative moves them back.",
           default=1),
        In("Wrap", BOOLEAN, "W", "Whether items moved off one end come back at the other.",
           default=True),
    )
    outputs = (Out("List", GENERIC, "L", "The shifted list.", access=LIST),)

    def solve(self, items: list[Any], shift: int, wrap: bool) -> list[Any]:
        s = whole("Shift", shift)
        n = len(items)
        if n == 0:
            return []
        if wrap:
            s %= n
            return items[s:] + items[:s]
        if s >= 0:
            return items[s:]
        return items[:max(n + s, 0)]


class Reverse(Node):
    """Reverse the order of a list: the last item comes first."""

    type_id = "lists.Reverse"
    inputs = (In("List", GENERIC, "L", "The list to reverse.", access=LIST),)
    outputs = (Out("List", GENERIC, "L", "The same items, last first.", access=LIST),)

    def solve(self, items: list[Any]) -> list[Any]:
        return items[::-1]


class Sort(Node):
    """Sort numbers from smallest to largest, and reorder other data the same way.

    Keys are the numbers sorted; Values, if given, are moved alongside their keys,
    so sorting points by their distance to a target gives the nearest point first.
    Equal keys keep their original order.
    """

    type_id = "lists.Sort"
    inputs = (
        In("Keys", NUMBER, "K", "The numbers to sort by, such as lengths or distances.",
           access=LIST),
        In("Values", GENERIC, "V", "Data to reorder like the keys; one item per key.",
           access=LIST, optional=True),
    )
    outputs = (
        Out("Keys", NUMBER, "K", "The keys, smallest first.", access=LIST),
        Out("Values", GENERIC, "V", "The values, in the order of their keys.", access=LIST),
    )

    def solve(self, keys: list[float], values: list[Any]) -> tuple[list[float], list[Any]]:
        if any(k is None for k in keys):
            raise NodeWarning("Keys contain empty (null) items, which cannot be sorted")
        if any(math.isnan(k) for k in keys):
            raise NodeWarning("Keys contain NaN (not a number), which cannot be sorted")
        if values and len(values) != len(keys):
            raise NodeWarning(
                f"There are {len(keys)} keys but {len(values)} values: give one value per key"
            )
        order = sorted(range(len(keys)), key=keys.__getitem__)
        return [keys[i] for i in order], [values[i] for i in order] if values else []
