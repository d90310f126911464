"""Expressions: a small, safe maths language for the ``maths.Expression`` node.

Write a formula in the node's variables (``x`` and ``y`` unless you name others).
Each variable becomes an input; give it one number or a list of numbers, and the
formula is worked out for every value at once::

    sin(x) * y + 2
    sqrt(x**2 + y**2)
    clamp(x / 10, 0, 1)
    1 if x > 0 else -1
    degrees(atan2(y, x))

Numbers
    ``3``, ``2.5``, ``.5``, ``1e-3``. All arithmetic is done in decimal (floating point)
    numbers, so ``7 / 2`` is 3.5 and ``7 // 2`` is 3.0.

Constants
    ``pi`` (3.14159…), ``tau`` (2·pi, a full turn in radians) and ``e`` (2.71828…).

Operators, from loosest to tightest binding
    ``a if condition else b``   choose, value by value
    ``or``  ``and``  ``not``    logic
    ``<  <=  >  >=  ==  !=``    comparisons; chains like ``0 <= x < 1`` work
    ``+  -``                    add, subtract
    ``*  /  //  %``             multiply, divide, divide rounding down, remainder
                                (the remainder has the sign of the divisor: ``-1 % 3`` is 2)
    ``-x  +x``                  sign
    ``**``                      power; ``2 ** 3 ** 2`` is ``2 ** 9`` and ``-2 ** 2`` is -4

    Use round brackets ``( )`` to group; inside brackets a formula may span several lines.

True and false
    Comparisons, ``and``, ``or`` and ``not`` give 1 for true and 0 for false, so
    ``(x > 0) * x`` keeps the positive values and zeroes the rest. A condition counts
    as true when its value is not 0. Both sides of ``and``/``or``/``if … else`` are
    always worked out.

Functions (angles are in radians)
    ``sin cos tan``  ``asin acos atan``  ``atan2(y, x)``  ``sinh cosh tanh``
    ``radians(deg)``  ``degrees(rad)``
    ``sqrt exp``  ``log(x)`` (natural)  ``log(x, base)``  ``log10 log2``
    ``abs sign floor ceil round``  (``round`` halves to even: ``round(2.5)`` is 2)
    ``hypot(a, b)`` (the length sqrt(a² + b²))
    ``min(a, b, …)``  ``max(a, b, …)``  value by value, at least two values
    ``clamp(x, lo, hi)``  ``x`` limited to the range lo … hi

Lists
    When an input is a list, the formula runs once per item. Two lists are paired
    item by item and must have the same length; a single number is used with every item.
    The result always has one value per item, even for a formula like ``1``.

Results out of range
    Dividing by zero, overflowing (``9 ** 9 ** 9``) or leaving a function's domain
    (``sqrt(-1)``) is not an error: the result is ``inf``, ``-inf`` or ``nan`` (not a
    number), and the node warns about it.

What is not allowed
    A formula is pure arithmetic: no text in quotes, lists, indexing (``x[0]``),
    attribute access (``x.real``), assignment, ``lambda`` or ``for``, and no functions
    beyond those above. A formula is at most 2,000 characters, 500 parts (numbers,
    names and operations) and 50 levels of nesting. Files containing formulas never
    run code: the text is checked piece by piece against the list above, and only
    the numeric operations listed here are ever performed.

For programmers: :func:`compile_expression` parses and checks the text once and
returns a :class:`CompiledExpression`, a callable that evaluates with numpy over
broadcast arrays::

    >>> f = compile_expression("sin(x) * y + 2")
    >>> f(x=0.0, y=3.0)
    2.0
    >>> f(x=np.zeros(3), y=np.arange(3.0))
    array([2., 2., 2.])
"""

from __future__ import annotations

import ast
import difflib
import keyword
import math
import unicodedata
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from operator import itemgetter
from typing import Any, Final, TypeAlias

import numpy as np

from torsal.nodes.expression_grammar import (
    _BINARY_UFUNCS,
    _COMPARE_UFUNCS,
    _FOLD_UFUNCS,
    _FUNCTIONS,
    _GRAMMAR_LEAVES,
    _REJECTED,
    _UNARY_UFUNCS,
    _UNSUPPORTED_OPERATORS,
    FUNCTION_NAMES,
)

__all__ = [
    "CONSTANTS",
    "FUNCTION_NAMES",
    "MAX_DEPTH",
    "MAX_LENGTH",
    "MAX_NODES",
    "CompiledExpression",
    "ExpressionError",
    "compile_expression",
]

MAX_LENGTH: Final = 2000
"""Longest expression text accepted, in characters; checked before parsing."""
MAX_NODES: Final = 500
"""Most parts (numbers, names, operations, calls) an expression may have."""
MAX_DEPTH: Final = 50
"""Deepest nesting accepted; a run like ``a + b - c + …`` counts as one level."""

CONSTANTS: Final[dict[str, float]] = {"pi": math.pi, "e": math.e, "tau": math.tau}

# During evaluation every value is a float64 scalar or a float64 array (bool for truths)
# of at least one dimension; never a Python int, so no power can grow without bound.
Env: TypeAlias = dict[str, Any]
Evaluator: TypeAlias = Callable[[Env], Any]


class ExpressionError(ValueError):
    """An expression that cannot be compiled or evaluated; the message is for a designer."""


# ------------------------------------------------------------------------ compiled form


@dataclass(frozen=True, slots=True)
class _Node:
    """One compiled sub-expression.

    ``fn(env)`` returns its value. ``const`` nodes hold a value worked out at compile
    time. ``fresh`` means an array ``fn`` returns is newly made by this evaluation and
    shared with nobody, so the next operation may overwrite it instead of allocating.
    """

    fn: Evaluator
    const: bool = False
    fresh: bool = False
    value: Any = None


def _constant(value: Any) -> _Node:
    return _Node(lambda env: value, const=True, value=value)


def _scalarise(value: Any) -> Any:
    """0-d arrays (from ``np.where``) become scalars, keeping the invariant on values."""
    if type(value) is np.ndarray and value.ndim == 0:
        return value[()]
    return value


def _fold(fn: Evaluator, *children: _Node) -> _Node | None:
    """Work ``fn`` out now when every child is constant (numpy only, so it is bounded)."""
    if all(child.const for child in children):
        return _constant(_scalarise(fn({})))
    return None


def _apply1(ufunc: np.ufunc, a: Any, a_fresh: bool) -> Any:
    if a_fresh and type(a) is np.ndarray:
        return ufunc(a, out=a)
    return ufunc(a)


def _apply2(ufunc: np.ufunc, a: Any, b: Any, a_fresh: bool, b_fresh: bool) -> Any:
    """``ufunc(a, b)``, writing into a fresh operand when it already has the result's shape."""
    if a_fresh and type(a) is np.ndarray and (type(b) is not np.ndarray or b.shape == a.shape):
        return ufunc(a, b, out=a)
    if b_fresh and type(b) is np.ndarray and (type(a) is not np.ndarray or a.shape == b.shape):
        return ufunc(a, b, out=b)
    return ufunc(a, b)


def _unary(ufunc: np.ufunc, operand: _Node) -> _Node:
    fn, fresh = operand.fn, operand.fresh

    def run(env: Env) -> Any:
        return _apply1(ufunc, fn(env), fresh)

    return _fold(run, operand) or _Node(run, fresh=True)


def _chain(first: _Node, steps: Sequence[tuple[np.ufunc, _Node | None]]) -> _Node:
    """``((first op1 r1) op2 r2) …`` evaluated in one loop, however long the run.

    A step with no right-hand node applies a one-argument ufunc to the running value.
    A constant prefix is worked out now, so ``2 * pi * x`` multiplies ``x`` once.
    """
    acc = first
    index = 0
    while index < len(steps) and acc.const:
        ufunc, right = steps[index]
        if right is None:
            acc = _constant(_scalarise(ufunc(acc.value)))
        elif right.const:
            acc = _constant(_scalarise(ufunc(acc.value, right.value)))
        else:
            break
        index += 1
    rest = tuple(
        (ufunc, None, False) if right is None else (ufunc, right.fn, right.fresh)
        for ufunc, right in steps[index:]
    )
    if not rest:
        return acc
    start, start_fresh = acc.fn, acc.fresh

    def run(env: Env) -> Any:
        a = start(env)
        a_fresh = start_fresh
        for ufunc, right, right_fresh in rest:
            if right is None:
                a = _apply1(ufunc, a, a_fresh)
            else:
                a = _apply2(ufunc, a, right(env), a_fresh, right_fresh)
            a_fresh = True
        return a

    return _Node(run, fresh=True)


def _as_float(truth: Any) -> Any:
    if type(truth) is np.ndarray:
        return truth.astype(np.float64)
    return np.float64(truth)


# ---------------------------------------------------------------------------- compiler


def _describe(names: Sequence[str]) -> str:
    return ", ".join(names) if names else "none"


def _suggest(name: str, candidates: Sequence[str]) -> str:
    close = difflib.get_close_matches(name, candidates, n=1)
    return f"; did you mean '{close[0]}'?" if close else ""


def _short(value: object) -> str:
    text = repr(value)
    return text if len(text) <= 24 else text[:20] + "…" + text[-3:]


def _check_size(tree: ast.AST) -> None:
    """Count parts and measure nesting without recursion, so any tree is safe to check.

    A run of operators such as ``a + b - c * d + …`` is evaluated in a loop, so the
    left-hand chain of binary operations does not deepen the nesting.
    """
    count = 0
    stack: list[tuple[ast.AST, int]] = [(tree, 1)]
    while stack:
        node, depth = stack.pop()
        if isinstance(node, _GRAMMAR_LEAVES):
            continue
        count += 1
        if count > MAX_NODES:
            raise ExpressionError(
                f"The expression is too big: more than {MAX_NODES} parts "
                "(numbers, names and operations). Split it over several Expression nodes."
            )
        if depth > MAX_DEPTH:
            raise ExpressionError(
                f"The expression is nested too deeply: more than {MAX_DEPTH} levels "
                "of brackets, functions or operators."
            )
        for child in ast.iter_child_nodes(node):
            same_run = isinstance(node, ast.BinOp) and child is node.left
            stack.append((child, depth if same_run else depth + 1))


class _Compiler:
    """Turns a size-checked ``ast`` tree into a tree of small numpy closures.

    Every node type is matched against the whitelist; anything else raises
    :class:`ExpressionError`. Recursion is bounded by :data:`MAX_DEPTH`.
    """

    def __init__(self, variables: tuple[str, ...]) -> None:
        self.variables = variables
        self.used: set[str] = set()

    # values ---------------------------------------------------------------------------

    def value(self, node: ast.AST) -> _Node:
        """Compile ``node`` to a closure returning float64 values."""
        if isinstance(node, ast.Constant):
            return _constant(self._number(node.value))
        if isinstance(node, ast.Name):
            return self._name(node.id)
        if isinstance(node, ast.BinOp):
            return self._binary_run(node)
        if isinstance(node, ast.UnaryOp):
            if isinstance(node.op, ast.USub):
                return _unary(np.negative, self.value(node.operand))
            if isinstance(node.op, ast.UAdd):
                return self.value(node.operand)
            if isinstance(node.op, ast.Not):
                return self._truth_as_value(node)
            raise ExpressionError(_UNSUPPORTED_OPERATORS[type(node.op)])
        if isinstance(node, ast.Compare | ast.BoolOp):
            return self._truth_as_value(node)
        if isinstance(node, ast.IfExp):
            return self._if(node)
        if isinstance(node, ast.Call):
            return self._call(node)
        raise self._rejection(node)

    def _number(self, value: object) -> np.float64:
        if isinstance(value, bool | int | float):
            try:
                return np.float64(value)
            except OverflowError:  # an integer literal beyond float range
                return np.float64(math.inf)
        if isinstance(value, complex):
            raise ExpressionError(f"Complex numbers ({_short(value)}) are not supported")
        if isinstance(value, str | bytes):
            raise ExpressionError(
                f"Text ({_short(value)}) is not allowed: expressions work on numbers only"
            )
        raise ExpressionError(f"{_short(value)} is not allowed: expressions work on numbers only")

    def _name(self, name: str) -> _Node:
        if name in self.variables:
            self.used.add(name)
            return _Node(itemgetter(name))
        if name in CONSTANTS:
            return _constant(np.float64(CONSTANTS[name]))
        if name in _FUNCTIONS:
            raise ExpressionError(
                f"'{name}' is a function: give it values in brackets, like {_FUNCTIONS[name].help}"
            )
        hint = _suggest(name, [*self.variables, *CONSTANTS])
        raise ExpressionError(
            f"Unknown name '{name}' (variables are {_describe(self.variables)}){hint}"
        )

    def _binary_run(self, node: ast.BinOp) -> _Node:
        steps: list[tuple[ast.operator, ast.expr]] = []
        left: ast.expr = node
        while isinstance(left, ast.BinOp):
            steps.append((left.op, left.right))
            left = left.left
        first = self.value(left)
        compiled: list[tuple[np.ufunc, _Node | None]] = []
        for op, right in reversed(steps):
            ufunc = _BINARY_UFUNCS.get(type(op))
            if ufunc is None:
                raise ExpressionError(_UNSUPPORTED_OPERATORS[type(op)])
            operand = self.value(right)
            if ufunc is np.power and operand.const and operand.value == 2.0:
                compiled.append((np.square, None))  # same values, twice as fast
            else:
                compiled.append((ufunc, operand))
        return _chain(first, compiled)

    def _truth_as_value(self, node: ast.expr) -> _Node:
        truth = self.truth(node)
        fn = truth.fn

        def run(env: Env) -> Any:
            return _as_float(fn(env))

        return _fold(run, truth) or _Node(run, fresh=True)

    def _if(self, node: ast.IfExp) -> _Node:
        test, body, orelse = self.truth(node.test), self.value(node.body), self.value(node.orelse)
        test_fn, body_fn, orelse_fn = test.fn, body.fn, orelse.fn

        def run(env: Env) -> Any:
            return _scalarise(np.where(test_fn(env), body_fn(env), orelse_fn(env)))

        return _fold(run, test, body, orelse) or _Node(run, fresh=True)

    def _call(self, node: ast.Call) -> _Node:
        func = node.func
        if not isinstance(func, ast.Name):
            if isinstance(func, ast.Attribute | ast.Subscript | ast.Lambda):
                raise self._rejection(func)
            raise ExpressionError("Only the listed functions can be called, like sin(x)")
        name = func.id
        spec = _FUNCTIONS.get(name)
        if spec is None:
            if name in self.variables or name in CONSTANTS:
                raise ExpressionError(f"'{name}' is a value, not a function")
            raise ExpressionError(
                f"Unknown function '{name}'{_suggest(name, FUNCTION_NAMES)} "
                f"(functions are {', '.join(FUNCTION_NAMES)})"
            )
        for kw in node.keywords:
            if kw.arg is None:
                raise ExpressionError(f"Unpacking with '**' is not allowed in {name}(...)")
            raise ExpressionError(
                f"Values can't be named in a function call: "
                f"write {spec.help}, not {name}({kw.arg}=...)"
            )
        if any(isinstance(arg, ast.Starred) for arg in node.args):
            raise ExpressionError(f"Unpacking with '*' is not allowed in {name}(...)")
        count = len(node.args)
        if count < spec.min_args or (spec.max_args is not None and count > spec.max_args):
            given = f"{count} value" + ("" if count == 1 else "s")
            raise ExpressionError(f"{name} is written {spec.help}, but was given {given}")
        args = [self.value(arg) for arg in node.args]
        if name in _UNARY_UFUNCS:
            return _unary(_UNARY_UFUNCS[name], args[0])
        if name in _FOLD_UFUNCS:
            ufunc = _FOLD_UFUNCS[name]
            return _chain(args[0], [(ufunc, arg) for arg in args[1:]])
        if name == "clamp":
            return _chain(args[0], [(np.maximum, args[1]), (np.minimum, args[2])])
        # log, with an optional base
        if len(args) == 1:
            return _unary(np.log, args[0])
        return _chain(_unary(np.log, args[0]), [(np.true_divide, _unary(np.log, args[1]))])

    # truths ---------------------------------------------------------------------------

    def truth(self, node: ast.AST) -> _Node:
        """Compile ``node`` to a closure returning bools (a value is true when not 0)."""
        if isinstance(node, ast.Compare):
            return self._compare(node)
        if isinstance(node, ast.BoolOp):
            ufunc = np.logical_and if isinstance(node.op, ast.And) else np.logical_or
            parts = [self.truth(part) for part in node.values]
            return _chain(parts[0], [(ufunc, part) for part in parts[1:]])
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not):
            return _unary(np.logical_not, self.truth(node.operand))
        value = self.value(node)
        fn = value.fn

        def run(env: Env) -> Any:
            return np.not_equal(fn(env), 0.0)

        return _fold(run, value) or _Node(run, fresh=True)

    def _compare(self, node: ast.Compare) -> _Node:
        ufuncs = []
        for op in node.ops:
            ufunc = _COMPARE_UFUNCS.get(type(op))
            if ufunc is None:
                raise ExpressionError(_UNSUPPORTED_OPERATORS[type(op)])
            ufuncs.append(ufunc)
        operands = [self.value(node.left), *(self.value(c) for c in node.comparators)]
        first = operands[0].fn
        pairs = tuple(zip(ufuncs, (operand.fn for operand in operands[1:]), strict=True))

        def run(env: Env) -> Any:
            a = first(env)
            result = None
            for ufunc, right in pairs:
                b = right(env)
                this = ufunc(a, b)
                result = this if result is None else np.logical_and(result, this)
                a = b
            return result

        return _fold(run, *operands) or _Node(run, fresh=True)

    # rejections -----------------------------------------------------------------------

    def _rejection(self, node: ast.AST) -> ExpressionError:
        if isinstance(node, ast.Attribute):
            return ExpressionError(f"Attribute access ('.{node.attr}') is not allowed")
        message = _REJECTED.get(type(node))
        if message is None:
            message = f"'{type(node).__name__}' is not allowed in an expression"
        return ExpressionError(message)


# -------------------------------------------------------------------------- public API


def _check_variables(variables: Sequence[str]) -> tuple[str, ...]:
    if isinstance(variables, str):
        raise ExpressionError("Variables must be a list of names, like ['x', 'y']")
    names = tuple(variables)
    for name in names:
        if not isinstance(name, str):
            raise ExpressionError(f"Variable names must be text, not {_short(name)}")
        problem = None
        if not name.isidentifier() or unicodedata.normalize("NFKC", name) != name:
            problem = "use letters, digits and _, starting with a letter"
        elif keyword.iskeyword(name):
            problem = "it is a reserved word"
        elif name.startswith("_"):
            problem = "names may not start with _"
        elif name in CONSTANTS:
            problem = "it is the name of a constant"
        elif name in _FUNCTIONS:
            problem = "it is the name of a function"
        if problem:
            raise ExpressionError(f"'{_short(name)[1:-1]}' can't be a variable name: {problem}")
    duplicates = sorted({name for name in names if names.count(name) > 1})
    if duplicates:
        raise ExpressionError(f"Variable '{duplicates[0]}' is listed more than once")
    return names


def _parse(text: str) -> ast.Expression:
    if not isinstance(text, str):
        raise ExpressionError(f"The expression must be text, not {type(text).__name__}")
    if len(text) > MAX_LENGTH:
        raise ExpressionError(
            f"The expression is too long: {len(text):,} characters, the limit is {MAX_LENGTH:,}"
        )
    source = text.strip()
    if not source:
        raise ExpressionError("The expression is empty")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # e.g. SyntaxWarning, shown as plain errors below
            return ast.parse(source, mode="eval")
    except SyntaxError as exc:
        where = ""
        if exc.offset and exc.lineno and exc.lineno > 1:
            where = f" (line {exc.lineno}, character {exc.offset})"
        elif exc.offset:
            where = f" (at character {exc.offset})"
        hint = ""
        if "\n" in source:
            hint = "; to spread a formula over several lines, wrap it in brackets ( )"
        raise ExpressionError(f"Could not read the expression: {exc.msg}{where}{hint}") from None
    except (ValueError, RecursionError, MemoryError) as exc:
        raise ExpressionError(f"Could not read the expression: {exc}") from None


def _describe_shape(name: str, value: Any) -> str:
    shape = np.shape(value)
    if len(shape) == 1:
        return f"{name} has {shape[0]} value" + ("" if shape[0] == 1 else "s")
    return f"{name} has shape {shape}"


def _input(name: str, raw: object) -> Any:
    """A variable's value as a float64 scalar or an array of at least one dimension."""
    if isinstance(raw, float | int):
        try:
            return np.float64(raw)
        except OverflowError:
            return np.float64(math.copysign(math.inf, raw))
    try:
        array = np.asarray(raw)
    except (TypeError, ValueError):
        raise ExpressionError(f"The values of '{name}' must be numbers") from None
    if array.dtype.kind not in "biuf":
        raise ExpressionError(f"The values of '{name}' must be numbers")
    array = array.astype(np.float64, copy=False)
    return array[()] if array.ndim == 0 else array


@dataclass(frozen=True)
class CompiledExpression:
    """An expression parsed and checked once, ready to evaluate many times.

    Call it with one keyword per variable the text uses, each a number or an array;
    arrays broadcast as in numpy. The result is a float when every value given is a
    number, otherwise a new float64 array of the broadcast shape of all values given.

    >>> f = compile_expression("hypot(x, y)")
    >>> f(x=np.array([3.0, 5.0]), y=4.0)
    array([5.        , 6.40312424])
    """

    text: str
    variables: tuple[str, ...] = ("x", "y")
    _evaluate: Evaluator = field(init=False, repr=False, compare=False)
    _used: frozenset[str] = field(init=False, repr=False, compare=False)
    _fresh: bool = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        variables = _check_variables(self.variables)
        tree = _parse(self.text)
        _check_size(tree)
        compiler = _Compiler(variables)
        with np.errstate(all="ignore"):
            root = compiler.value(tree.body)
        object.__setattr__(self, "variables", variables)
        object.__setattr__(self, "_evaluate", root.fn)
        object.__setattr__(self, "_used", frozenset(compiler.used))
        object.__setattr__(self, "_fresh", root.fresh)

    def __reduce__(self) -> tuple[type[CompiledExpression], tuple[str, tuple[str, ...]]]:
        return (CompiledExpression, (self.text, self.variables))

    def __call__(self, **values: float | np.ndarray) -> np.ndarray | float:
        env: Env = {}
        for name, raw in values.items():
            if name not in self.variables:
                raise ExpressionError(
                    f"Unknown variable '{name}' (variables are {_describe(self.variables)})"
                )
            env[name] = _input(name, raw)
        missing = [name for name in self.variables if name in self._used and name not in env]
        if missing:
            raise ExpressionError(f"No value given for {', '.join(missing)}")
        try:
            shape = np.broadcast_shapes(*(np.shape(value) for value in env.values()))
        except ValueError:
            details = ", ".join(_describe_shape(n, v) for n, v in env.items() if np.ndim(v))
            raise ExpressionError(
                f"The inputs can't be paired up item by item: {details}"
            ) from None
        with np.errstate(all="ignore"):
            result = self._evaluate(env)
        if type(result) is not np.ndarray:
            if not shape:
                return float(result)
            return np.full(shape, result, dtype=np.float64)
        if result.shape != shape:
            return np.broadcast_to(result, shape).copy()
        if not self._fresh:  # e.g. the expression "x": never hand back the caller's array
            return result.copy()
        return result


def compile_expression(text: str, variables: Sequence[str] = ("x", "y")) -> CompiledExpression:
    """Parse and check ``text`` once; raise :class:`ExpressionError` if it is not allowed.

    >>> compile_expression("2 * pi * r", variables=["r"])(r=1.0)
    6.283185307179586

    ``compile_expression("open('f')")`` raises ``ExpressionError("Unknown function 'open'
    (functions are abs, acos, ...)")``.
    """
    names = variables if isinstance(variables, str) else tuple(variables)  # str: rejected
    return CompiledExpression(text, names)  # type: ignore[arg-type]
