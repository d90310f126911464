"""The expression language's vocabulary: its functions and operators, and the Python
syntax it refuses with a sentence each (used by :mod:`torsal.nodes.expressions`)."""

from __future__ import annotations

import ast
from typing import Final, NamedTuple

import numpy as np

# --------------------------------------------------------------------------- functions


class _Function(NamedTuple):
    min_args: int
    max_args: int | None  # None: any number from min_args up
    help: str


_UNARY_UFUNCS: Final[dict[str, np.ufunc]] = {
    "sin": np.sin,
    "cos": np.cos,
    "tan": np.tan,
    "asin": np.arcsin,
    "acos": np.arccos,
    "atan": np.arctan,
    "sinh": np.sinh,
    "cosh": np.cosh,
    "tanh": np.tanh,
    "sqrt": np.sqrt,
    "exp": np.exp,
    "log10": np.log10,
    "log2": np.log2,
    "abs": np.absolute,
    "floor": np.floor,
    "ceil": np.ceil,
    "round": np.rint,  # same as np.round(x): halves go to the even neighbour
    "sign": np.sign,
    "radians": np.radians,
    "degrees": np.degrees,
}
_FOLD_UFUNCS: Final[dict[str, np.ufunc]] = {
    "atan2": np.arctan2,
    "hypot": np.hypot,
    "min": np.minimum,
    "max": np.maximum,
}
_FUNCTIONS: Final[dict[str, _Function]] = {
    **{name: _Function(1, 1, f"{name}(x)") for name in _UNARY_UFUNCS},
    "atan2": _Function(2, 2, "atan2(y, x)"),
    "hypot": _Function(2, 2, "hypot(a, b)"),
    "min": _Function(2, None, "min(a, b, ...)"),
    "max": _Function(2, None, "max(a, b, ...)"),
    "log": _Function(1, 2, "log(x) or log(x, base)"),
    "clamp": _Function(3, 3, "clamp(x, lo, hi)"),
}
FUNCTION_NAMES: Final[tuple[str, ...]] = tuple(sorted(_FUNCTIONS))

# ---------------------------------------------------------------------------- operators

_BINARY_UFUNCS: Final[dict[type[ast.operator], np.ufunc]] = {
    ast.Add: np.add,
    ast.Sub: np.subtract,
    ast.Mult: np.multiply,
    ast.Div: np.true_divide,
    ast.FloorDiv: np.floor_divide,
    ast.Mod: np.remainder,  # Python's sign convention
    ast.Pow: np.power,  # on float64: 9 ** 9 ** 9 is inf, not a huge integer
}
_COMPARE_UFUNCS: Final[dict[type[ast.cmpop], np.ufunc]] = {
    ast.Lt: np.less,
    ast.LtE: np.less_equal,
    ast.Gt: np.greater,
    ast.GtE: np.greater_equal,
    ast.Eq: np.equal,
    ast.NotEq: np.not_equal,
}
_UNSUPPORTED_OPERATORS: Final[dict[type[ast.AST], str]] = {
    ast.MatMult: "The operator '@' is not supported",
    ast.BitAnd: "The operator '&' is not supported; use 'and'",
    ast.BitOr: "The operator '|' is not supported; use 'or'",
    ast.BitXor: "The operator '^' is not supported; for powers use '**'",
    ast.LShift: "The operator '<<' is not supported",
    ast.RShift: "The operator '>>' is not supported",
    ast.Invert: "The operator '~' is not supported; use 'not'",
    ast.Is: "'is' is not supported; compare numbers with == or !=",
    ast.IsNot: "'is not' is not supported; compare numbers with == or !=",
    ast.In: "'in' is not supported",
    ast.NotIn: "'not in' is not supported",
}
_REJECTED: Final[dict[type[ast.AST], str]] = {
    ast.Subscript: "Indexing with [ ] is not allowed",
    ast.Slice: "Slices are not allowed",
    ast.Lambda: "'lambda' (defining a function) is not allowed",
    ast.ListComp: "Comprehensions ('for ... in ...') are not allowed",
    ast.SetComp: "Comprehensions ('for ... in ...') are not allowed",
    ast.DictComp: "Comprehensions ('for ... in ...') are not allowed",
    ast.GeneratorExp: "Comprehensions ('for ... in ...') are not allowed",
    ast.JoinedStr: "f-strings are not allowed: expressions work on numbers only",
    ast.FormattedValue: "f-strings are not allowed: expressions work on numbers only",
    ast.NamedExpr: "Assignment with ':=' is not allowed",
    ast.Starred: "Unpacking with '*' is not allowed",
    ast.List: "Lists [ ] are not allowed: write a single formula",
    ast.Tuple: "Tuples like (a, b) are not allowed: write a single formula",
    ast.Set: "Sets { } are not allowed",
    ast.Dict: "Dictionaries { : } are not allowed",
    ast.Await: "'await' is not allowed",
    ast.Yield: "'yield' is not allowed",
    ast.YieldFrom: "'yield' is not allowed",
}
_GRAMMAR_LEAVES: Final = (ast.expr_context, ast.operator, ast.unaryop, ast.cmpop, ast.boolop)
