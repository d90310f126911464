"""Reading lists: one item by its position, and how many items there are."""

from __future__ import annotations

from typing import Any

from torsal.engine.datatree import Branch, item_at
from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import BOOLEAN, GENERIC, INTEGER
from torsal.nodes.common.checks import whole


class ListItem(Node):
    """Pick the item at a position in a list, counting from 0.

    With Wrap on, positions past the end start again from the front (index 4 of a
    3-item list is item 1) and negative positions count from the end (-1 is the
    last item). With Wrap off, a position outside the list gives a warning and no
    item. Give several indices to pick several items.
    """

    type_id = "lists.ListItem"
    nickname, aliases = "Item", ("get item", "index")
    inputs = (
        In("List", GENERIC, "L", "The list to pick from.", access=LIST, arrays=True),
        In("Index", INTEGER, "i", "Position of the item, 0 for the first.", default=0),
        In("Wrap", BOOLEAN, "W", "Whether positions outside the list wrap around.", default=False),
    )
    outputs = (Out("Item", GENERIC, "i", "The item at Index."),)

    def solve(self, items: Branch, index: int, wrap: bool) -> Any:
        i = whole("Index", index)
        if not len(items):
            raise NodeWarning("The list is empty: there is no item to pick")
        if wrap:
            return item_at(items, i % len(items))
        if not 0 <= i < len(items):
            raise NodeWarning(
                f"Index {i} is outside the list of {len(items)} items (0 to {len(items) - 1}); "
                "turn on Wrap to wrap around"
            )
        return item_at(items, i)


class ListLength(Node):
    """Count the items in a list: one count per branch of a tree."""

    type_id = "lists.ListLength"
    nickname, aliases = "Lng", ("count", "how many")
    inputs = (In("List", GENERIC, "L", "The list to count.", access=LIST, arrays=True),)
    outputs = (Out("Length", INTEGER, "L", "How many items the list holds, empty ones included."),)

    def solve(self, items: Branch) -> int:
        return len(items)
