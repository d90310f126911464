"""A small registry of test node types for the engine tests (independent of ``nodes/``).

The classes mimic the shape of the real library (a slider with value/min/max/decimals,
an item-access Add, list-access ListLength, a node whose inputs come from its
settings like ``maths.Expression``) so the engine can be tested on its own.
"""

from __future__ import annotations

from typing import Any

from torsal.engine.datatree import DataTree, parse_path
from torsal.engine.node import LIST, TREE, In, Node, NodeError, Out, Setting
from torsal.engine.registry import Registry
from torsal.engine.types import GENERIC, INTEGER, NUMBER, POINT
from torsal.engine.values import Point


class NumberSlider(Node):
    """A number between ``min`` and ``max``, rounded to ``decimals`` places."""

    type_id = "params.NumberSlider"
    outputs = (Out("Value", NUMBER, "V"),)
    settings_spec = (
        Setting("value", float, 1.0),
        Setting("min", float, 0.0),
        Setting("max", float, 10.0),
        Setting("decimals", int, 2),
    )

    def solve(self) -> float:
        s = self.settings
        value = min(max(float(s["value"]), float(s["min"])), float(s["max"]))
        return round(value, int(s["decimals"]))


class PointParam(Node):
    type_id = "params.Point"
    outputs = (Out("Point", POINT, "P"),)
    settings_spec = (Setting("x", float, 0.0), Setting("y", float, 0.0), Setting("z", float, 0.0))

    def solve(self) -> Point:
        return Point(self.settings["x"], self.settings["y"], self.settings["z"])


class TreeSource(Node):
    """Outputs the tree in its ``branches`` setting: ``{"{0;1}": [items]}``."""

    type_id = "params.Tree"
    outputs = (Out("Tree", GENERIC, "T", access=TREE),)
    settings_spec = (Setting("branches", dict, {}),)

    def solve(self) -> DataTree:
        branches = self.settings["branches"]
        return DataTree({parse_path(path): list(items) for path, items in branches.items()})


class Add(Node):
    type_id = "maths.Add"
    inputs = (In("A", NUMBER, "A", default=0.0), In("B", NUMBER, "B", default=0.0))
    outputs = (Out("Result", NUMBER, "R"),)

    def solve(self, a: float, b: float) -> float:
        return a + b


class AddRequired(Node):
    """Add with required inputs (no defaults)."""

    type_id = "maths.AddRequired"
    inputs = (In("A", NUMBER, "A"), In("B", NUMBER, "B"))
    outputs = (Out("Result", NUMBER, "R"),)

    def solve(self, a: float, b: float) -> float:
        return a + b


class Sum3(Node):
    type_id = "maths.Sum3"
    inputs = (In("A", NUMBER, "A"), In("B", NUMBER, "B"), In("C", NUMBER, "C"))
    outputs = (Out("Result", NUMBER, "R"),)

    def solve(self, a: float, b: float, c: float) -> float:
        return a + b + c


class Series(Node):
    """Item access in, one *list* out per call: ``Count`` numbers from ``Start``."""

    type_id = "maths.Series"
    inputs = (
        In("Start", NUMBER, "S", default=0.0),
        In("Step", NUMBER, "N", default=1.0),
        In("Count", INTEGER, "C", default=3),
    )
    outputs = (Out("Series", NUMBER, "S", access=LIST),)

    def solve(self, start: float, step: float, count: int) -> list[float]:
        if not 0 <= count <= 10_000:
            raise NodeError(f"Count must be between 0 and 10000, not {count}")
        return [start + i * step for i in range(count)]


class ListLength(Node):
    type_id = "lists.ListLength"
    inputs = (In("List", GENERIC, "L", access=LIST),)
    outputs = (Out("Length", INTEGER, "N"),)

    def solve(self, items: list[Any]) -> int:
        return len(items)


class ListItem(Node):
    type_id = "lists.ListItem"
    inputs = (In("List", GENERIC, "L", access=LIST), In("Index", INTEGER, "i", default=0))
    outputs = (Out("Item", GENERIC, "i"),)

    def solve(self, items: list[Any], index: int) -> Any:
        return items[index % len(items)] if items else None


class BranchCount(Node):
    type_id = "trees.BranchCount"
    inputs = (In("Tree", GENERIC, "T", access=TREE),)
    outputs = (Out("Count", INTEGER, "C"),)

    def solve(self, tree: DataTree) -> int:
        return tree.branch_count


class Variables(Node):
    """Inputs named by the ``variables`` setting (like ``maths.Expression``); sums them."""

    type_id = "maths.Variables"
    outputs = (Out("Result", NUMBER, "R"),)
    settings_spec = (Setting("variables", list, ["x", "y"]),)

    def __init__(self, settings: dict[str, Any] | None = None) -> None:
        super().__init__(settings)
        names = self.settings["variables"]
        if not isinstance(names, list) or not all(isinstance(n, str) and n.isidentifier() for n in names):
            raise ValueError("variables must be a list of names")
        if len(set(names)) != len(names):
            raise ValueError("variable names must be unique")
        self._inputs = tuple(In(n, NUMBER, n, default=0.0) for n in names)

    def input_ports(self) -> tuple[In, ...]:
        return self._inputs

    def solve(self, *values: float) -> float:
        return sum(values)


class Fail(Node):
    type_id = "debug.Fail"
    inputs = (In("X", NUMBER, "X", default=0.0),)
    outputs = (Out("Y", NUMBER, "Y"),)

    def solve(self, x: float) -> float:
        raise RuntimeError(f"deliberate failure at {x}")


NODE_CLASSES: tuple[type[Node], ...] = (
    NumberSlider,
    PointParam,
    TreeSource,
    Add,
    AddRequired,
    Sum3,
    Series,
    ListLength,
    ListItem,
    BranchCount,
    Variables,
    Fail,
)


def make_registry() -> Registry:
    registry = Registry()
    for cls in NODE_CLASSES:
        registry.register(cls)
    return registry
