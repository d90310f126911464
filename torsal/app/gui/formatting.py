"""Short text for values and data trees, as panels and the inspector show them."""

from __future__ import annotations

from typing import Any

from torsal.engine.datatree import DataTree, format_path
from torsal.engine.types import type_of
from torsal.engine.values import Domain, Plane, Triple

MODIFIER_MARKS = {"graft": "↑", "flatten": "↓", "simplify": "~", "reverse": "⇅"}


def format_number(x: float) -> str:
    return f"{x:.6g}"


def format_item(value: Any) -> str:
    """One item on one line: ``2.5``, ``{1, 0, 0}``, ``Curve (length 3.14)``."""
    if value is None:
        return "<null>"
    if isinstance(value, bool):
        return "True" if value else "False"
    if isinstance(value, float):
        return format_number(value)
    if isinstance(value, int | str):
        return str(value)
    if isinstance(value, Triple):
        return "{" + ", ".join(format_number(c) for c in value) + "}"
    if isinstance(value, Domain):
        return f"{format_number(value.min)} To {format_number(value.max)}"
    if isinstance(value, Plane):
        return f"Plane at {format_item(value.origin)}"
    value_type = type_of(value)
    name = value_type.name if value_type else type(value).__name__
    if value_type is not None and value_type.name == "Mesh":  # the registered value type, not a class name
        return f"Mesh ({len(value.vertices)} vertices, {len(value.faces)} faces)"
    kind = type(value).__name__
    # Geometry is named, not measured: a length or an area can take milliseconds, and
    # panels and tooltips are drawn on the GUI thread (the inspector shows the figures).
    return name if kind == name else f"{name} ({kind})"


def format_tree(tree: DataTree, max_lines: int = 200) -> list[str]:
    """A tree as lines: each path, then its items numbered from 0."""
    lines: list[str] = []
    for path, branch in tree.items():
        lines.append(format_path(path))
        for index, item in enumerate(branch):
            lines.append(f"{index}  {format_item(item)}")
            if len(lines) >= max_lines:
                lines.append(f"… {tree.item_count} items in {tree.branch_count} branches")
                return lines
    return lines
