"""Coordinates matched item by item, as whole arrays when they come as arrays.

Point, Vector and the unit vectors take their numbers as lists (``In(..., access=LIST,
arrays=True)``) so that a branch of 10⁶ coordinates (from Series, Range, an Expression)
makes one ``(n, 3)`` array of points, held as :class:`~torsal.engine.datatree.Triples`, instead
of 10⁶ calls. Within a branch the lists pair up item by item as an item input's would:
the longest list sets the count, a shorter one repeats its last value, and an empty list
gives no items. Lists of Python numbers (a value typed in, a slider) are made item by item
exactly as before, so they give the same points, warnings and empty items as ever.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from torsal.engine.datatree import Branch
from torsal.engine.node import LIST, In, Node, NodeWarning
from torsal.engine.types import NUMBER
from torsal.nodes.common.checks import finite


def paired_count(node: Node, columns: dict[str, Branch]) -> int:
    """How many items the columns pair into (0 when one is empty), remarking when one is
    shorter than the longest and not a single value (its last value is reused)."""
    lengths = {name: len(values) for name, values in columns.items()}
    if min(lengths.values()) == 0:
        return 0
    count = max(lengths.values())
    longest = next(name for name, n in lengths.items() if n == count)
    for name, n in lengths.items():
        if 1 < n < count:
            node.remark(f"{longest} has {count} items, {name} has {n}: {name}'s last item is reused")
    return count


def as_float_columns(columns: dict[str, Branch], count: int) -> np.ndarray | None:
    """The columns as a ``(count, k)`` float array, each repeating its last value to
    ``count``; None unless some column is an array and every value is a finite number
    (then :func:`each_row` makes the items one by one, with their warnings)."""
    if not any(isinstance(values, np.ndarray) for values in columns.values()):
        return None
    out = np.empty((count, len(columns)))
    for j, values in enumerate(columns.values()):
        if not isinstance(values, np.ndarray):
            if any(v is None for v in values):
                return None
            values = np.asarray(values, dtype=np.float64)
        out[:len(values), j] = values
        out[len(values):, j] = values[-1]
    if not np.isfinite(out).all():
        return None
    return out


def each_row(node: Node, columns: dict[str, Branch], count: int, make: Callable[..., Any]) -> list[Any]:
    """``make(*numbers)`` for every row, each number checked finite by its input's name; a
    refused row gives an empty item and the node's warning, as an item input's call would."""
    named = [(name, values.tolist() if isinstance(values, np.ndarray) else values)
             for name, values in columns.items()]
    results: list[Any] = []
    for i in range(count):
        try:
            results.append(make(*(finite(name, values[min(i, len(values) - 1)]) for name, values in named)))
        except NodeWarning as exc:
            node.warn(str(exc))
            results.append(None)
        if not i & 4095:
            node.check_cancelled()
    return results


def xyz_inputs(x: str, y: str, z: str) -> tuple[In, In, In]:
    """The X, Y and Z inputs of a node that builds points or vectors, each a list (whole
    arrays when they come as arrays), 0 by default; ``x``, ``y``, ``z`` are their help."""
    def port(name: str, help: str) -> In:
        return In(name, NUMBER, name, help, default=0.0, access=LIST, arrays=True)

    return port("X", x), port("Y", y), port("Z", z)


def xyz_rows(
    node: Node, x: Branch, y: Branch, z: Branch, make: Callable[..., Any]
) -> np.ndarray | list[Any]:
    """The X, Y and Z lists paired item by item: an ``(n, 3)`` array when they come as
    arrays of finite numbers (the tree holds it as Triples), else ``make(x, y, z)`` row by
    row with each refused row's warning; ``[]`` when a list is empty."""
    columns = {"X": x, "Y": y, "Z": z}
    count = paired_count(node, columns)
    if count == 0:
        return []
    xyz = as_float_columns(columns, count)
    return xyz if xyz is not None else each_row(node, columns, count, make)
