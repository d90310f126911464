"""The Expression node: a formula in named variables, worked out over whole lists at once."""

from __future__ import annotations

import ast
from collections.abc import Sequence
from functools import lru_cache
from typing import Any

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeError, Out, Setting
from torsal.engine.types import NUMBER
from torsal.engine.widgets import Widget
from torsal.nodes.expressions import CompiledExpression, ExpressionError, compile_expression


@lru_cache(maxsize=256)
def _compiled(text: str, variables: tuple[str, ...]) -> tuple[CompiledExpression | None, str, frozenset[str]]:
    """The compiled expression (or None and the reason) and the variables it uses."""
    try:
        compiled = compile_expression(text, variables)
    except ExpressionError as exc:
        return None, str(exc), frozenset(variables)
    # The text has been checked and parsed once already; walk it again (no evaluation)
    # only to learn which variables it really uses.
    names = {n.id for n in ast.walk(ast.parse(text.strip(), mode="eval")) if isinstance(n, ast.Name)}
    return compiled, "", frozenset(names & set(variables))


def _port(name: str, used: bool) -> In:
    return In(
        name, NUMBER, name,
        f"The values of {name} in the expression: one number or a list, one result per item."
        + ("" if used else " Not used by the expression."),
        access=LIST, optional=not used, arrays=True,
    )


def _as_array(name: str, values: Sequence[Any]) -> np.ndarray:
    if isinstance(values, np.ndarray) and values.dtype == np.float64:
        return values  # an array branch: used as it is
    try:
        return np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):  # empty (null) items, from a node that skipped a call
        return np.asarray([np.nan if v is None else v for v in values], dtype=np.float64)


class Expression(Node):
    """Work out a formula for every item of its inputs, such as ``sqrt(x**2 + y**2)``.

    Each name in ``variables`` becomes an input. Give each one number or a list: the
    formula runs once per item, pairing the lists item by item; a shorter list
    repeats its last value (x = [1, 2, 3] with y = 10 gives x + y = [11, 12, 13]).
    Branches of a data tree are matched as for any node.

    The formula may use ``+ - * / // % **``, comparisons (which give 1 for true and
    0 for false), ``a if condition else b``, ``pi``, ``e`` and the functions
    ``sin cos tan asin acos atan atan2 sqrt exp log abs min max floor ceil round``
    and a few more (see the expression help). Angles are in radians.

    Results that are not finite numbers (dividing by zero, ``sqrt(-1)``) are kept as
    ``inf`` or ``nan`` and the node warns how many there are.
    """

    type_id = "maths.Expression"
    nickname, aliases = "Expr", ("formula", "Addition", "Multiplication", "Division", "Subtraction")
    widget = Widget.EXPRESSION
    inputs = (_port("x", True), _port("y", True))
    outputs = (
        Out("Result", NUMBER, "R", "The formula's value for each matched item.", access=LIST),
    )
    settings_spec = (
        Setting("expression", str, "x + y", "The formula, e.g. 'x * 2 + y'."),
        Setting("variables", list, ["x", "y"], "The names used in the formula; one input each."),
    )

    def __init__(self, settings: dict[str, Any] | None = None) -> None:
        super().__init__(settings)
        if isinstance(self.settings["variables"], list):  # never share the mutable default
            self.settings["variables"] = list(self.settings["variables"])

    # -- ports follow the variables -----------------------------------------------------
    def _variables(self) -> tuple[str, ...]:
        names = self.settings.get("variables")
        if not isinstance(names, list | tuple):
            return ()
        return tuple(dict.fromkeys(n for n in names if isinstance(n, str) and n))

    def _compile(self) -> tuple[CompiledExpression | None, str, frozenset[str]]:
        text = self.settings.get("expression")
        names = self.settings.get("variables")
        if not isinstance(text, str):
            return None, f"The expression must be text, not {text!r}", frozenset()
        if not isinstance(names, list | tuple) or not all(isinstance(n, str) for n in names):
            return None, f"Variables must be a list of names, like ['x', 'y'], not {names!r}", frozenset()
        return _compiled(text, tuple(names))

    def input_ports(self) -> tuple[In, ...]:
        compiled, _, used = self._compile()
        names = self._variables()
        if compiled is None:
            used = frozenset(names)
        if names == ("x", "y") and used == {"x", "y"}:
            return self.inputs
        return tuple(_port(name, name in used) for name in names)

    # -- solving -----------------------------------------------------------------------
    def before_solve(self) -> None:
        self.run_state["not_finite"] = 0

    def after_solve(self) -> None:
        n = self.run_state.get("not_finite", 0)
        if n:
            self.warn(
                f"{n} result is not a finite number (division by zero?)" if n == 1
                else f"{n} results are not finite numbers (division by zero?)"
            )

    def solve(self, *columns: Sequence[Any]) -> np.ndarray:
        compiled, problem, used = self._compile()
        if compiled is None:
            raise NodeError(problem)
        lists = {n: c for n, c in zip(self._variables(), columns, strict=True) if n in used}
        if any(len(values) == 0 for values in lists.values()):
            return []  # a used variable has no items in this branch: nothing to pair
        count = max((len(values) for values in lists.values()), default=1)
        self._remark_uneven(lists, count)
        arrays = {}
        for name, values in lists.items():
            array = _as_array(name, values)
            if len(array) == 1:
                arrays[name] = array[0]  # one value is used with every item
            elif len(array) < count:  # longest list: repeat the last value
                arrays[name] = np.concatenate([array, np.full(count - len(array), array[-1])])
            else:
                arrays[name] = array
        try:
            result = compiled(**arrays)
        except ExpressionError as exc:
            raise NodeError(str(exc)) from None
        result = np.asarray(result, dtype=np.float64)
        if result.shape != (count,):  # a formula like '1': one value per item all the same
            result = np.ascontiguousarray(np.broadcast_to(result, (count,)))
        state = self.run_state
        state["not_finite"] = state.get("not_finite", 0) + int(np.count_nonzero(~np.isfinite(result)))
        return result  # an array branch: the tree keeps it as it is

    def _remark_uneven(self, lists: dict[str, Sequence[Any]], count: int) -> None:
        longest = next((n for n, v in lists.items() if len(v) == count), "")
        for name, values in lists.items():
            if 1 < len(values) < count:
                self.remark(
                    f"{longest} has {count} items, {name} has {len(values)}: "
                    f"{name}'s last value is reused"
                )
