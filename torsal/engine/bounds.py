"""Port bounds: the least and the greatest value an input takes, declared on the port.

A node says ``In("Segments", INTEGER, "S", "Rulings minus one.", default=24, min=1,
max=MAX_SEGMENTS)`` and the solver refuses a value outside the bounds before ``solve``
is called, with one sentence naming the input (Segments 0: "Segments must be at least
1, not 0"; Segments 1e12: "Segments is 1,000,000,000,000; at most 100,000 can be made at
once"). The node is put in warning and makes nothing, as for any input a check refuses.
The same declaration is what a front-end shows: the inspector lists the bounds of each
input and a slider wired into a bounded input is kept within them.

An input that is a value list declares ``choices`` (its numbers and their names): any
other value is refused with the choices ("Placement is 5, not one of its choices: 0
Beside model, 1 Origin, 2 On plane"), not with a count's wording.
"""

from __future__ import annotations

from decimal import Decimal
from itertools import chain
from typing import TYPE_CHECKING

import numpy as np

from torsal.engine.datatree import is_array
from torsal.engine.node import NodeWarning

if TYPE_CHECKING:
    from torsal.engine.datatree import DataTree
    from torsal.engine.node import In


def shown(count: int) -> str:
    """A count as a message shows it: in full with separators up to 10^15 (1,000,000),
    beyond that in three figures (Segments 1e308 arrives as a 309-digit integer)."""
    if abs(count) < 10**15:
        return f"{count:,}"
    return f"{Decimal(count):.2e}"  # exact for any integer (a float would overflow past 1e308)


def _text(value: float) -> str:
    return shown(value) if isinstance(value, int) else f"{value:g}"


def choices_text(port: In) -> str:
    """A value list's choices as messages show them: "0 Beside model, 1 Origin"."""
    return ", ".join(f"{value} {name}" for value, name in port.choices)


def bounds_text(port: In) -> str:
    """The bounds as the inspector shows them ("1 to 100,000", "0 or more", a value
    list's "0 Beside model, 1 Origin"), or ""."""
    if port.choices:
        return choices_text(port)
    low, high = port.min, port.max
    if low is not None and high is not None:
        return f"{_text(low)} to {_text(high)}"
    if low is not None:
        return f"{_text(low)} or more"
    if high is not None:
        return f"at most {_text(high)}"
    return ""


def refusal(port: In, value: float) -> str | None:
    """The sentence refusing ``value`` for ``port``, or None when it is within the bounds."""
    if port.choices:
        if any(value == choice for choice, _ in port.choices):
            return None
        return f"{port.name} is {_text(value)}, not one of its choices: {choices_text(port)}"
    if port.min is not None and value < port.min:
        return f"{port.name} must be at least {_text(port.min)}, not {_text(value)}"
    if port.max is not None and value > port.max:
        if isinstance(value, int):
            return f"{port.name} is {shown(value)}; at most {_text(port.max)} can be made at once"
        return f"{port.name} must be at most {_text(port.max)}, not {_text(value)}"
    return None


def within_bounds(tree: DataTree, port: In) -> DataTree:
    """``tree`` unchanged when every number in it lies within ``port``'s bounds; otherwise a
    :class:`~torsal.engine.node.NodeWarning` naming the input and the smallest (or the largest)
    value outside them. One pass over the items, however many branches they are in."""
    if port.min is None and port.max is None and not port.choices:
        return tree
    lists = [b for b in tree.raw_branches if not is_array(b)]
    numbers = [v for v in chain.from_iterable(lists) if type(v) is int or type(v) is float]
    for array in tree.raw_branches:  # an array branch by its least and greatest value
        if isinstance(array, np.ndarray) and array.dtype.kind in "if" and len(array):
            if array.dtype.kind == "f" and np.isnan(array).any():
                array = array[~np.isnan(array)]
                if not len(array):
                    continue
            numbers += [array.min().item(), array.max().item()]
    if numbers:
        for value in (min(numbers), max(numbers)):
            message = refusal(port, value)
            if message is not None:
                raise NodeWarning(message)
    if port.choices:  # between the least and the greatest there may be values that are no choice
        allowed = np.array([value for value, _ in port.choices], dtype=float)
        values = np.asarray(numbers, dtype=float)
        for array in tree.raw_branches:
            if isinstance(array, np.ndarray) and array.dtype.kind in "if" and len(array):
                kept = array[~np.isnan(array)] if array.dtype.kind == "f" else array
                values = np.concatenate([values, kept])
        outside = values[~np.isin(values, allowed)]
        if len(outside):
            raise NodeWarning(refusal(port, outside[0].item()) or "")
    return tree
