"""The value list: pick one of several named values from a drop-down."""

from __future__ import annotations

from typing import Any

from torsal.engine.node import Node, NodeError, Out, Setting
from torsal.engine.types import GENERIC, CastError, decode_value
from torsal.engine.widgets import Widget

DEFAULT_ITEMS = [
    {"name": "One", "value": 1},
    {"name": "Two", "value": 2},
    {"name": "Three", "value": 3},
    {"name": "Four", "value": 4},
]


class ValueList(Node):
    """Choose one value from a named list, such as a material thickness or a preset.

    Each item has a name shown in the drop-down and a value: a number, text, true or
    false, or a point/vector/domain written as in the graph file
    (``{"type": "Point", "xyz": [0, 0, 1]}``). ``selected`` is the chosen item's
    position, counting from 0.
    """

    type_id = "params.ValueList"
    nickname, aliases = "List", ("Value List", "dropdown", "preset")
    widget = Widget.VALUE_LIST
    outputs = (Out("Value", GENERIC, "V", "The value of the selected item."),)
    settings_spec = (
        Setting("items", list, DEFAULT_ITEMS, 'The choices, each {"name": ..., "value": ...}.'),
        Setting("selected", int, 0, "Position of the chosen item, counting from 0."),
    )

    def __init__(self, settings: dict[str, Any] | None = None) -> None:
        super().__init__(settings)
        if self.settings["items"] is DEFAULT_ITEMS:  # never share the mutable default
            self.settings["items"] = [dict(item) for item in DEFAULT_ITEMS]

    def solve(self) -> Any:
        items = self.settings.get("items")
        if not isinstance(items, list) or not items:
            raise NodeError("The value list has no items: add at least one {name, value}")
        selected = self.settings.get("selected")
        if isinstance(selected, float) and selected.is_integer():
            selected = int(selected)
        if isinstance(selected, bool) or not isinstance(selected, int):
            raise NodeError(f"The selected position must be a whole number, not {selected!r}")
        if not 0 <= selected < len(items):
            raise NodeError(
                f"Item {selected} is selected but the list has {len(items)} items "
                f"(0 to {len(items) - 1})"
            )
        item = items[selected]
        if not isinstance(item, dict) or "value" not in item:
            raise NodeError(f"Item {selected} must be {{\"name\": ..., \"value\": ...}}, not {item!r}")
        try:
            return decode_value(item["value"])
        except CastError as exc:
            raise NodeError(f"Item {selected} ({item.get('name', '')}): {exc}") from None
