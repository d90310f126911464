"""Input checks shared by the first nodes: each failure is one sentence a designer can act on.

Checks for one item raise :class:`~engine.node.NodeWarning`, so that call is skipped with
a warning and the other items still solve.
"""

from __future__ import annotations

import math
from typing import Any

from engine.node import NodeWarning
from nodes.limits import MAX_NUMBERS as MAX_COUNT
from nodes.limits import shown


def finite(name: str, value: Any) -> float:
    """``value`` as a float, or a warning saying it is empty, not a number or infinite."""
    if value is None:
        raise NodeWarning(f"{name} is empty (null)")
    number = float(value)
    if math.isnan(number):
        raise NodeWarning(f"{name} is not a number (NaN)")
    if math.isinf(number):
        raise NodeWarning(f"{name} is infinite")
    return number


def whole(name: str, value: Any) -> int:
    """``value`` as an int, or a warning saying it is empty."""
    if value is None:
        raise NodeWarning(f"{name} is empty (null)")
    return int(value)


def count(name: str, value: Any, least: int = 0, limit: int = MAX_COUNT) -> int:
    """A count of things to make: a whole number from ``least`` to ``limit``."""
    number = whole(name, value)
    if number < least:
        raise NodeWarning(f"{name} must be at least {least}, not {shown(number)}")
    if number > limit:
        raise NodeWarning(f"{name} is {shown(number)}; at most {limit:,} can be made at once")
    return number
