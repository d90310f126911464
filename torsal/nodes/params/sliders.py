"""Sliders and toggles: numbers and switches a designer sets by hand, kept in the file."""

from __future__ import annotations

import math
from typing import Any

from torsal.engine.node import Node, NodeError, Out, Setting
from torsal.engine.types import BOOLEAN, INTEGER, NUMBER, CastError, ValueType, cast
from torsal.engine.widgets import Widget


def _setting(node: Node, name: str, value_type: ValueType) -> Any:
    """The setting ``name`` cast to ``value_type``, or a NodeError saying what is wrong."""
    raw = node.settings.get(name)
    if raw is None or (isinstance(raw, bool) and value_type is not BOOLEAN):
        raise NodeError(f"The slider's {name} must be a number, not {raw!r}")
    if isinstance(raw, int) and abs(raw) > 1e300:  # no float holds it: cast and {:g} would overflow
        raise NodeError(f"The slider's {name} has {len(str(abs(raw)))} digits: give a number up to 1e300")
    try:
        value = cast(raw, value_type)
    except CastError as exc:
        raise NodeError(f"The slider's {name}: {exc}") from None
    if isinstance(value, float) and not math.isfinite(value):
        raise NodeError(f"The slider's {name} must be a finite number, not {value!r}")
    return value


def _bounds(node: Node, value_type: ValueType) -> tuple[Any, Any]:
    low, high = _setting(node, "min", value_type), _setting(node, "max", value_type)
    if low > high:
        raise NodeError(f"The slider's min ({low:g}) is greater than its max ({high:g})")
    return low, high


def _clamp(node: Node, value: Any, low: Any, high: Any) -> Any:
    if value < low:
        node.warn(f"Value {value:g} is below the minimum {low:g}: using {low:g}")
        return low
    if value > high:
        node.warn(f"Value {value:g} is above the maximum {high:g}: using {high:g}")
        return high
    return value


class NumberSlider(Node):
    """A number you drag between a minimum and a maximum.

    The value is rounded to ``decimals`` places and kept between ``min`` and ``max``:
    a value outside them (typed in a file or set with ``--set``) is clamped, with a
    warning. The slider's value is saved in the graph file.

    Example: a slider from 0 to 10 with 1 decimal set to 12.34 gives 10.0 and warns.
    """

    type_id = "params.NumberSlider"
    nickname, aliases = "Num", ("Number", "slider")
    widget = Widget.SLIDER
    outputs = (Out("Value", NUMBER, "V", "The slider's number, in model units or as a ratio."),)
    settings_spec = (
        Setting("value", float, 0.5, "The number the slider is set to."),
        Setting("min", float, 0.0, "The smallest value the slider gives."),
        Setting("max", float, 1.0, "The largest value the slider gives."),
        Setting("decimals", int, 2, "How many digits after the decimal point (0 to 15)."),
    )

    def solve(self) -> float:
        low, high = _bounds(self, NUMBER)
        decimals = self.settings.get("decimals")
        if isinstance(decimals, float) and decimals.is_integer():
            decimals = int(decimals)
        if isinstance(decimals, bool) or not isinstance(decimals, int) or not 0 <= decimals <= 15:
            raise NodeError(f"The slider's decimals must be a whole number from 0 to 15, not {decimals!r}")
        value = round(_setting(self, "value", NUMBER), decimals)
        return float(_clamp(self, value, low, high))


class IntegerSlider(Node):
    """A whole number you drag between a minimum and a maximum.

    A value outside ``min`` … ``max`` is clamped with a warning; a value with a
    fraction (2.5 typed in a file) is rounded to the nearest whole number.
    """

    type_id = "params.IntegerSlider"
    nickname, aliases = "Int", ("Integer", "count slider")
    widget = Widget.SLIDER
    outputs = (Out("Value", INTEGER, "V", "The slider's whole number, e.g. a count of segments."),)
    settings_spec = (
        Setting("value", int, 5, "The whole number the slider is set to."),
        Setting("min", int, 0, "The smallest value the slider gives."),
        Setting("max", int, 10, "The largest value the slider gives."),
    )

    def solve(self) -> int:
        low, high = _bounds(self, INTEGER)
        raw = self.settings.get("value")
        value = _setting(self, "value", INTEGER)
        if isinstance(raw, float) and not raw.is_integer():
            self.warn(f"Value {raw:g} is not a whole number: using {value}")
        return int(_clamp(self, value, low, high))


class Toggle(Node):
    """A switch: true or false, saved in the graph file.

    Use it to turn an option on or off, such as Wrap on List Item.
    """

    type_id = "params.Toggle"
    nickname, aliases = "Tgl", ("Boolean Toggle", "boolean", "switch")
    widget = Widget.TOGGLE
    outputs = (Out("Value", BOOLEAN, "B", "True when the toggle is on."),)
    settings_spec = (Setting("value", bool, False, "Whether the toggle is on."),)

    def solve(self) -> bool:
        raw = self.settings.get("value")
        if isinstance(raw, bool):
            return raw
        if isinstance(raw, str):  # e.g. --set toggle=true
            try:
                return cast(raw, BOOLEAN)
            except CastError as exc:
                raise NodeError(f"The toggle's value: {exc}") from None
        raise NodeError(f"The toggle's value must be true or false, not {raw!r}")
