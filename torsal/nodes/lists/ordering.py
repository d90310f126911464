"""Reordering lists: shift, reverse and sort."""

from __future__ import annotations

import math

import numpy as np

from torsal.engine.datatree import Branch, concatenated, is_array, take
from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import BOOLEAN, GENERIC, INTEGER, NUMBER
from torsal.nodes.common.checks import whole


class Shift(Node):
    """Move every item of a list along by Shift places.

    Shift = 1 moves each item one place towards the front: [a, b, c] becomes
    [b, c, a] with Wrap on, or [b, c] with Wrap off (the items shifted past the end
    are dropped). A negative Shift moves items towards the back. Pair a list with its
    shifted copy to join each point to the next one.
    """

    type_id = "lists.Shift"
    nickname, aliases = "Shift", ("Shift List",)
    inputs = (
        In("List", GENERIC, "L", "The list to shift.", access=LIST, arrays=True),
        In("Shift", INTEGER, "S", "How many places to move the items; negative moves them back.",
           default=1),
        In("Wrap", BOOLEAN, "W", "Whether items moved off one end come back at the other.",
           default=True),
    )
    outputs = (Out("List", GENERIC, "L", "The shifted list.", access=LIST),)

    def solve(self, items: Branch, shift: int, wrap: bool) -> Branch:
        s = whole("Shift", shift)
        n = len(items)
        if n == 0:
            return []
        if wrap:
            s %= n
            return concatenated(items[s:], items[:s])
        if s >= 0:
            return items[s:]
        return items[:max(n + s, 0)]


class Reverse(Node):
    """Reverse the order of a list: the last item comes first."""

    type_id = "lists.Reverse"
    nickname, aliases = "Rev", ("Reverse List",)
    inputs = (In("List", GENERIC, "L", "The list to reverse.", access=LIST, arrays=True),)
    outputs = (Out("List", GENERIC, "L", "The same items, last first.", access=LIST),)

    def solve(self, items: Branch) -> Branch:
        return items[::-1]


class Sort(Node):
    """Sort numbers from smallest to largest, and reorder other data the same way.

    Keys are the numbers sorted; Values, if given, are moved alongside their keys,
    so sorting points by their distance to a target gives the nearest point first.
    Equal keys keep their original order.
    """

    type_id = "lists.Sort"
    nickname, aliases = "Sort", ("Sort List",)
    inputs = (
        In("Keys", NUMBER, "K", "The numbers to sort by, such as lengths or distances.",
           access=LIST, arrays=True),
        In("Values", GENERIC, "V", "Data to reorder like the keys; one item per key.",
           access=LIST, optional=True, arrays=True),
    )
    outputs = (
        Out("Keys", NUMBER, "K", "The keys, smallest first.", access=LIST),
        Out("Values", GENERIC, "V", "The values, in the order of their keys.", access=LIST),
    )

    def solve(self, keys: Branch, values: Branch) -> tuple[Branch, Branch]:
        if is_array(keys):  # an array holds no nulls
            if np.isnan(keys).any():
                raise NodeWarning("Keys contain NaN (not a number), which cannot be sorted")
        else:
            if any(k is None for k in keys):
                raise NodeWarning("Keys contain empty (null) items, which cannot be sorted")
            if any(math.isnan(k) for k in keys):
                raise NodeWarning("Keys contain NaN (not a number), which cannot be sorted")
        if len(values) and len(values) != len(keys):
            raise NodeWarning(
                f"There are {len(keys)} keys but {len(values)} values: give one value per key"
            )
        if not is_array(keys):
            order = sorted(range(len(keys)), key=keys.__getitem__)
            picked = take(values, np.asarray(order, dtype=np.int64)) if len(values) else []
            return [keys[i] for i in order], picked
        order = np.argsort(keys, kind="stable")  # equal keys keep their order, as sorted() does
        return keys[order], take(values, order) if len(values) else []
