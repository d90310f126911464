"""Input trees made ready for a port: several wires merged, items cast to the port's type.

An array branch is checked by its dtype and cast as a whole where the cast is plain; a list
branch item by item. The solver (:mod:`torsal.engine.solver`) calls these for every input it gathers.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsal.engine.datatree import DataTree, Path, Triples, as_list, is_array
from torsal.engine.node import In, NodeError
from torsal.engine.types import BOOLEAN, GENERIC, INTEGER, NUMBER, POINT, TEXT, VECTOR, CastError, cast
from torsal.engine.values import Point, Vector


def merge_trees(trees: list[DataTree]) -> DataTree:
    """Several wires into one input: branches with the same path are concatenated."""
    if len(trees) == 1:
        return trees[0]
    merged = DataTree()
    for tree in trees:
        for path, branch in tree.raw_items():
            merged.extend(path, branch)
    return DataTree(dict(merged.raw_items()))


def cast_tree(tree: DataTree, port: In) -> DataTree:
    """Cast every item of ``tree`` to ``port``'s type (items already right are kept).

    An array branch is checked by its dtype, and cast as a whole array where the cast is
    plain (Integer to Number, Number to Integer, ...); list branches item by item.
    """
    if port.type is GENERIC:
        return tree
    classes = port.type.classes
    needs_cast = False
    for branch in tree.raw_branches:
        if is_array(branch):
            if not array_fits(branch, port):
                needs_cast = True
                break
            continue
        for item in branch:
            if type(item) not in classes and not _kept(item, classes):
                needs_cast = True
                break
        if needs_cast:
            break
    if not needs_cast:
        return tree

    def convert(item: Any) -> Any:
        if item is None:
            return None
        if isinstance(item, float) and math.isnan(item) and port.type is not TEXT:
            raise NodeError(f"{port.name} is not a number (NaN)")  # not "empty", and never 0 or True
        try:
            return cast(item, port.type)
        except CastError as exc:
            raise NodeError(f"input {port.name}: {exc}") from None

    out: dict[Path, Any] = {}
    for path, branch in tree.raw_items():
        cast_array = cast_array_branch(branch, port) if is_array(branch) else None
        if cast_array is not None:
            out[path] = cast_array
        else:
            out[path] = [convert(item) for item in as_list(branch)]
    return DataTree(out)


def _kept(item: Any, classes: tuple[type, ...]) -> bool:
    """Whether the cast would hand ``item`` back as it is although its class is not one of
    ``classes`` but a subclass (a NurbsCurve into a Curve input): then the tree needs no copy.
    Not a bool (True is an int, yet a Boolean into an Integer input is converted) nor a float
    (a numpy float is a float, and the cast refuses it when it is NaN)."""
    return isinstance(item, classes) and not isinstance(item, bool | float)


#: the dtype an array branch has when its items are of a port's type
_DTYPE_OF = {
    NUMBER.name: np.dtype(np.float64), INTEGER.name: np.dtype(np.int64), BOOLEAN.name: np.dtype(np.bool_),
}
#: the kind of item an (n, 3) array branch holds for a Point or Vector port
TRIPLE_OF = {POINT.name: Point, VECTOR.name: Vector}
_INT_LIMIT = 2.0**62  # floats below this round to an int64 exactly


def array_fits(array: np.ndarray | Triples, port: In) -> bool:
    """Whether an array branch's items are already of ``port``'s type (as a list's would be)."""
    if isinstance(array, Triples):
        return TRIPLE_OF.get(port.type.name) is array.item_class
    dtype = _DTYPE_OF.get(port.type.name)
    return dtype is not None and array.dtype == dtype


def cast_array_branch(array: np.ndarray | Triples, port: In) -> np.ndarray | Triples | None:
    """An array branch cast to ``port``'s type as one array, or None to cast item by item
    (a cast that is not plain, or a value whose message must name it). A NaN is refused
    as for a list ("... is not a number (NaN)"), never read as 0 or true. Points into a
    Vector input (and vectors into a Point input) keep their numbers."""
    if isinstance(array, Triples):
        item_class = TRIPLE_OF.get(port.type.name)
        return None if item_class is None else Triples(array.array, item_class)
    target = _DTYPE_OF.get(port.type.name)
    if target is None:
        return None
    if array.dtype == target:
        return array
    kind = array.dtype.kind
    if kind == "f":
        if np.isnan(array).any():
            raise NodeError(f"{port.name} is not a number (NaN)")
        if target.kind == "b":
            return array != 0
        if not (np.abs(array) < _INT_LIMIT).all():  # inf or huge: the item's own message
            return None
        return np.rint(array).astype(np.int64)  # round half to even, as round() does
    if target.kind == "b":
        return array != 0
    return array.astype(target)
