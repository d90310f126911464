"""The expression language of ``maths.Expression``: values, vectorisation and safety."""

from __future__ import annotations

import ast
import builtins
import math
import os
import pickle
import subprocess
import sys
import warnings
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import nodes.expressions as expressions_module
from nodes.expressions import (
    MAX_DEPTH,
    MAX_LENGTH,
    MAX_NODES,
    CompiledExpression,
    ExpressionError,
    compile_expression,
)

SAMPLE = np.array([-3.5, -1.0, -0.25, 0.0, 0.3, 0.5, 1.0, 2.5, 7.0, 1e5])
UNIT = np.linspace(-0.95, 0.95, 9)  # inside the domain of asin, acos


def evaluate(text: str, **values: Any) -> Any:
    return compile_expression(text, variables=tuple(values) or ("x", "y"))(**values)


# ----------------------------------------------------------------------------- arithmetic


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("1 + 2", 3.0),
        ("7 - 10", -3.0),
        ("6 * 7", 42.0),
        ("7 / 2", 3.5),
        ("7 // 2", 3.0),
        ("-7 // 2", -4.0),
        ("7 % 3", 1.0),
        ("-1 % 3", 2.0),
        ("7.5 % -2", -0.5),
        ("2 ** 10", 1024.0),
        ("2 ** 0.5", math.sqrt(2)),
        ("2 ** -1", 0.5),
        ("1e-3 * 1000", 1.0),
        (".5 + 0.25", 0.75),
    ],
)
def test_arithmetic_on_numbers(text: str, expected: float) -> None:
    assert evaluate(text) == pytest.approx(expected, rel=1e-15)


def test_integer_arithmetic_is_done_in_floats() -> None:
    result = evaluate("7 // 2")
    assert type(result) is float
    assert result == 3.0


def test_huge_integer_literal_is_inf_not_an_error() -> None:
    assert evaluate("1" + "0" * 400) == math.inf


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("2 + 3 * 4", 14.0),
        ("(2 + 3) * 4", 20.0),
        ("10 - 4 - 3", 3.0),
        ("64 / 4 / 2", 8.0),
        ("2 ** 3 ** 2", 512.0),
        ("(2 ** 3) ** 2", 64.0),
        ("-2 ** 2", -4.0),
        ("2 * 3 ** 2", 18.0),
        ("-3 % 5 * 2", 4.0),
        ("1 + 2 < 4", 1.0),
        ("not 1 + 1 == 3", 1.0),
        ("1 or 0 and 0", 1.0),
        ("5 if 0 else 2 + 1", 3.0),
        ("- - 4", 4.0),
        ("+4", 4.0),
    ],
)
def test_precedence_follows_python(text: str, expected: float) -> None:
    assert evaluate(text) == expected


def test_formula_in_brackets_may_span_lines() -> None:
    assert evaluate("(1 +\n 2)") == 3.0


def test_surrounding_whitespace_is_ignored() -> None:
    assert evaluate("  1 + 1\n") == 2.0


# ------------------------------------------------------------------------------ functions


@pytest.mark.parametrize(
    ("name", "reference", "sample"),
    [
        ("sin", np.sin, SAMPLE),
        ("cos", np.cos, SAMPLE),
        ("tan", np.tan, SAMPLE),
        ("asin", np.arcsin, UNIT),
        ("acos", np.arccos, UNIT),
        ("atan", np.arctan, SAMPLE),
        ("sinh", np.sinh, UNIT),
        ("cosh", np.cosh, UNIT),
        ("tanh", np.tanh, SAMPLE),
        ("sqrt", np.sqrt, np.abs(SAMPLE)),
        ("exp", np.exp, UNIT),
        ("log", np.log, np.abs(SAMPLE) + 0.1),
        ("log10", np.log10, np.abs(SAMPLE) + 0.1),
        ("log2", np.log2, np.abs(SAMPLE) + 0.1),
        ("abs", np.abs, SAMPLE),
        ("floor", np.floor, SAMPLE),
        ("ceil", np.ceil, SAMPLE),
        ("round", np.round, SAMPLE),
        ("sign", np.sign, SAMPLE),
        ("radians", np.radians, SAMPLE),
        ("degrees", np.degrees, SAMPLE),
    ],
)
def test_one_argument_functions_match_numpy(
    name: str, reference: Callable[[np.ndarray], np.ndarray], sample: np.ndarray
) -> None:
    np.testing.assert_array_equal(evaluate(f"{name}(x)", x=sample), reference(sample))


def test_atan2_takes_y_then_x() -> None:
    np.testing.assert_array_equal(
        evaluate("atan2(y, x)", x=SAMPLE, y=SAMPLE[::-1]), np.arctan2(SAMPLE[::-1], SAMPLE)
    )


def test_hypot_is_length_of_the_vector() -> None:
    assert evaluate("hypot(3, 4)") == 5.0


def test_min_and_max_are_elementwise_over_their_arguments() -> None:
    x, y = np.array([1.0, 5.0, 3.0]), np.array([4.0, 2.0, 3.5])
    np.testing.assert_array_equal(evaluate("min(x, y, 3)", x=x, y=y), [1.0, 2.0, 3.0])
    np.testing.assert_array_equal(evaluate("max(x, y, 3)", x=x, y=y), [4.0, 5.0, 3.5])


def test_clamp_limits_to_the_range() -> None:
    np.testing.assert_array_equal(
        evaluate("clamp(x, 0, 1)", x=np.array([-2.0, 0.25, 3.0])), [0.0, 0.25, 1.0]
    )


def test_log_with_a_base() -> None:
    assert evaluate("log(8, 2)") == pytest.approx(3.0, rel=1e-15)


def test_round_halves_to_even() -> None:
    np.testing.assert_array_equal(
        evaluate("round(x)", x=np.array([0.5, 1.5, 2.5, -2.5])), [0.0, 2.0, 2.0, -2.0]
    )


def test_degrees_of_atan2_gives_compass_angle() -> None:
    assert evaluate("degrees(atan2(1, 1))") == pytest.approx(45.0, rel=1e-15)


# ------------------------------------------------------------------------------ constants


@pytest.mark.parametrize(("text", "expected"), [("pi", math.pi), ("e", math.e), ("tau", math.tau)])
def test_constants(text: str, expected: float) -> None:
    assert evaluate(text) == expected


def test_true_and_false_are_one_and_zero() -> None:
    assert (evaluate("True"), evaluate("False")) == (1.0, 0.0)


def test_constant_parts_are_worked_out_once_with_the_same_values() -> None:
    x = np.linspace(0, 1, 5)
    np.testing.assert_array_equal(evaluate("2 * pi * x", x=x), 2 * np.pi * x)


# -------------------------------------------------------------------------- vectorisation


def test_numbers_in_give_a_float_out() -> None:
    result = compile_expression("sin(x) * y + 2")(x=0.0, y=3.0)
    assert type(result) is float
    assert result == 2.0


def test_arrays_are_evaluated_elementwise() -> None:
    x, y = np.linspace(0, 3, 7), np.linspace(1, 2, 7)
    np.testing.assert_array_equal(compile_expression("sin(x) * y + 2")(x=x, y=y), np.sin(x) * y + 2)


def test_lists_are_accepted_as_arrays() -> None:
    np.testing.assert_array_equal(evaluate("x * 2", x=[1, 2, 3]), [2.0, 4.0, 6.0])


def test_a_number_is_paired_with_every_item() -> None:
    np.testing.assert_array_equal(evaluate("x + y", x=[1.0, 2.0], y=10), [11.0, 12.0])


def test_arrays_broadcast_like_numpy() -> None:
    x, y = np.arange(3.0).reshape(3, 1), np.arange(4.0)
    result = compile_expression("x * 10 + y")(x=x, y=y)
    assert result.shape == (3, 4)
    np.testing.assert_array_equal(result, x * 10 + y)


def test_result_has_one_value_per_item_even_when_constant() -> None:
    np.testing.assert_array_equal(compile_expression("1")(x=[5.0, 6.0, 7.0]), [1.0, 1.0, 1.0])


def test_result_takes_the_shape_of_all_inputs_given() -> None:
    result = compile_expression("x + 1")(x=2.0, y=np.zeros(3))
    np.testing.assert_array_equal(result, [3.0, 3.0, 3.0])


def test_lists_of_different_lengths_are_a_clear_error() -> None:
    with pytest.raises(ExpressionError, match="x has 3 values, y has 4 values"):
        compile_expression("x + y")(x=np.zeros(3), y=np.zeros(4))


def test_result_is_never_the_callers_array() -> None:
    x = np.arange(3.0)
    result = compile_expression("x")(x=x)
    assert result is not x
    result[0] = 99.0
    assert x[0] == 0.0


@pytest.mark.parametrize(
    "text",
    [
        "-x * 2 + y",
        "sin(x) ** 2 + y",
        "min(x, y) - max(x, y)",
        "(x if x > y else y) + 1",
        "clamp(x, 0, 1) * 3",
        "abs(-sqrt(x * x))",
    ],
)
def test_inputs_are_never_modified(text: str) -> None:
    x, y = np.linspace(-1, 1, 5), np.linspace(1, 0, 5)
    x_before, y_before = x.copy(), y.copy()
    compile_expression(text)(x=x, y=y)
    np.testing.assert_array_equal(x, x_before)
    np.testing.assert_array_equal(y, y_before)


def test_evaluating_twice_gives_the_same_result() -> None:
    f = compile_expression("sqrt(x ** 2 + y ** 2) * 2")
    x, y = np.arange(4.0), np.ones(4)
    np.testing.assert_array_equal(f(x=x, y=y), f(x=x, y=y))


def test_vectorised_evaluation_gives_numpys_values_on_a_million_points() -> None:
    """Its speed, against numpy's in the same run, is benchmarked in bench_expressions.py."""
    rng = np.random.default_rng(0)
    x, y = rng.random(10**6), rng.random(10**6)
    f = compile_expression("sin(x) * y + 2")
    np.testing.assert_array_equal(f(x=x, y=y), np.sin(x) * y + 2)


# ------------------------------------------------------------------ conditions and logic


def test_if_expression_chooses_value_by_value() -> None:
    x = np.array([-2.0, 0.0, 3.0])
    np.testing.assert_array_equal(evaluate("1 if x > 0 else -1", x=x), [-1.0, -1.0, 1.0])


def test_if_expression_branches_may_be_arrays() -> None:
    x, y = np.array([1.0, 5.0, 3.0]), np.array([4.0, 2.0, 3.0])
    np.testing.assert_array_equal(evaluate("x if x < y else y", x=x, y=y), [1.0, 2.0, 3.0])


def test_nested_if_expressions_work_like_else_if() -> None:
    x = np.array([-5.0, 0.0, 5.0])
    np.testing.assert_array_equal(
        evaluate("-1 if x < 0 else 0 if x == 0 else 1", x=x), [-1.0, 0.0, 1.0]
    )


def test_condition_is_true_when_not_zero() -> None:
    np.testing.assert_array_equal(
        evaluate("10 if x else 20", x=np.array([0.0, 2.0, -0.5])), [20.0, 10.0, 10.0]
    )


@pytest.mark.parametrize(
    ("op", "expected"),
    [
        ("<", [1.0, 0.0, 0.0]),
        ("<=", [1.0, 1.0, 0.0]),
        (">", [0.0, 0.0, 1.0]),
        (">=", [0.0, 1.0, 1.0]),
        ("==", [0.0, 1.0, 0.0]),
        ("!=", [1.0, 0.0, 1.0]),
    ],
)
def test_comparisons_give_one_or_zero(op: str, expected: list[float]) -> None:
    np.testing.assert_array_equal(evaluate(f"x {op} 2", x=np.array([1.0, 2.0, 3.0])), expected)


def test_chained_comparison_means_both() -> None:
    x = np.array([-0.5, 0.0, 0.5, 1.0])
    np.testing.assert_array_equal(evaluate("0 <= x < 1", x=x), [0.0, 1.0, 1.0, 0.0])


def test_comparison_result_is_a_number() -> None:
    np.testing.assert_array_equal(evaluate("(x > 0) * x", x=np.array([-2.0, 3.0])), [0.0, 3.0])


def test_and_or_not_are_elementwise_and_give_one_or_zero() -> None:
    x, y = np.array([0.0, 0.0, 2.0, 2.0]), np.array([0.0, 3.0, 0.0, 3.0])
    np.testing.assert_array_equal(evaluate("x and y", x=x, y=y), [0.0, 0.0, 0.0, 1.0])
    np.testing.assert_array_equal(evaluate("x or y", x=x, y=y), [0.0, 1.0, 1.0, 1.0])
    np.testing.assert_array_equal(evaluate("not x", x=x), [1.0, 1.0, 0.0, 0.0])


# ------------------------------------------------------------------------ out of range


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("1 / 0", math.inf),
        ("-1 / 0", -math.inf),
        ("0 / 0", math.nan),
        ("1 // 0", math.inf),
        ("1 % 0", math.nan),
        ("sqrt(-1)", math.nan),
        ("log(0)", -math.inf),
        ("exp(1000)", math.inf),
        ("10.0 ** 400", math.inf),
        ("(-8) ** (1 / 3)", math.nan),
    ],
)
def test_out_of_range_gives_inf_or_nan_without_warnings(text: str, expected: float) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        result = compile_expression(text, ["x"])(x=np.ones(2))
    np.testing.assert_array_equal(result, [expected, expected])


def float64_powers(monkeypatch: pytest.MonkeyPatch) -> list[tuple[Any, Any]]:
    """Watch every power the expression language works out; the operands are recorded.

    An operand that is not float64 fails at once, before the power is computed: a
    Python int there would make ``9**9**9`` a 370-million-digit integer (minutes of
    work) instead of inf.
    """
    powers: list[tuple[Any, Any]] = []
    power = expressions_module._BINARY_UFUNCS[ast.Pow]

    def float64_only(a: Any, b: Any, **kwargs: Any) -> Any:
        for operand in (a, b):
            assert type(operand) in (np.float64, np.ndarray), f"power of a {type(operand).__name__}"
            assert np.asarray(operand).dtype == np.float64
        powers.append((a, b))
        return power(a, b, **kwargs)

    monkeypatch.setitem(expressions_module._BINARY_UFUNCS, ast.Pow, float64_only)
    return powers


def test_power_tower_is_inf_worked_out_once_in_floats(monkeypatch: pytest.MonkeyPatch) -> None:
    powers = float64_powers(monkeypatch)
    f = compile_expression("9**9**9")
    assert powers == [(9.0, 9.0), (9.0, 9.0**9)]  # folded when compiled: 9 ** 387420489.0
    assert f() == math.inf
    assert len(powers) == 2  # evaluating it computes nothing more


def test_power_tower_of_a_variable_is_inf_in_three_float_powers(monkeypatch: pytest.MonkeyPatch) -> None:
    powers = float64_powers(monkeypatch)
    result = compile_expression("x**x**x**x", ["x"])(x=np.full(1000, 9.0))
    assert len(powers) == 3  # one vectorised power per '**'
    assert np.all(result == math.inf)


# ------------------------------------------------------------------------------ variables


def test_variables_can_be_named() -> None:
    f = compile_expression("width * height", variables=["width", "height"])
    assert f.variables == ("width", "height")
    assert f(width=2.0, height=3.0) == 6.0


def test_unused_variables_need_no_value() -> None:
    assert compile_expression("x + 1")(x=1.0) == 2.0


def test_missing_value_is_a_clear_error() -> None:
    with pytest.raises(ExpressionError, match="No value given for y"):
        compile_expression("x + y")(x=1.0)


def test_value_for_an_undeclared_variable_is_a_clear_error() -> None:
    with pytest.raises(ExpressionError, match=r"Unknown variable 'z' \(variables are x, y\)"):
        compile_expression("x")(x=1.0, z=2.0)


@pytest.mark.parametrize("value", ["abc", ["1", "2"], [1, [2, 3]], 1 + 2j, None])
def test_values_that_are_not_numbers_are_a_clear_error(value: object) -> None:
    with pytest.raises(ExpressionError, match="'x' must be numbers"):
        compile_expression("x")(x=value)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    ("variables", "message"),
    [
        (["2x"], "can't be a variable name"),
        (["x y"], "can't be a variable name"),
        (["_x"], "may not start with _"),
        (["__class__"], "may not start with _"),
        (["pi"], "name of a constant"),
        (["sin"], "name of a function"),
        (["if"], "reserved word"),
        (["ﬁ"], "can't be a variable name"),
        (["x", "x"], "listed more than once"),
        ("xy", "list of names"),
    ],
)
def test_bad_variable_names_are_refused(variables: Any, message: str) -> None:
    with pytest.raises(ExpressionError, match=message):
        compile_expression("1", variables=variables)


def test_compiled_expressions_compare_by_text_and_variables() -> None:
    assert compile_expression("x + 1") == compile_expression("x + 1")
    assert hash(compile_expression("x + 1")) == hash(compile_expression("x + 1"))
    assert compile_expression("x + 1") != compile_expression("x + 1", ["x"])


def test_compiled_expression_survives_pickling() -> None:
    f = pickle.loads(pickle.dumps(compile_expression("x * 2", ["x"])))
    assert isinstance(f, CompiledExpression)
    assert f(x=4.0) == 8.0


def test_compiled_expression_can_be_made_directly() -> None:
    assert CompiledExpression("x + y", ("x", "y"))(x=1.0, y=2.0) == 3.0


# ------------------------------------------------------------------- messages for designers


def test_unknown_name_lists_the_variables() -> None:
    with pytest.raises(ExpressionError) as error:
        compile_expression("foo + 1")
    assert str(error.value) == "Unknown name 'foo' (variables are x, y)"


def test_misspelt_function_gets_a_suggestion() -> None:
    with pytest.raises(ExpressionError, match="Unknown function 'sine'; did you mean 'sin'"):
        compile_expression("sine(x)")


def test_wrong_number_of_values_names_the_function() -> None:
    with pytest.raises(ExpressionError, match=r"atan2 is written atan2\(y, x\), but was given 1"):
        compile_expression("atan2(x)")


def test_syntax_error_says_where() -> None:
    with pytest.raises(
        ExpressionError, match=r"Could not read the expression: .* \(at character 4\)"
    ):
        compile_expression("x +* 2")


def test_function_name_without_brackets_is_explained() -> None:
    with pytest.raises(ExpressionError, match="'sin' is a function"):
        compile_expression("sin + 1")


def test_calling_a_variable_is_explained() -> None:
    with pytest.raises(ExpressionError, match="'x' is a value, not a function"):
        compile_expression("x(2)")


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("x & y", "use 'and'"),
        ("x | y", "use 'or'"),
        ("x ^ 2", "for powers use"),
        ("~x", "use 'not'"),
        ("x @ y", "'@'"),
        ("x << 1", "'<<'"),
        ("x is 1", "'is' is not supported"),
        ("x in y", "'in' is not supported"),
    ],
)
def test_unsupported_operators_are_named(text: str, message: str) -> None:
    with pytest.raises(ExpressionError, match=message):
        compile_expression(text)


def test_empty_expression_is_refused() -> None:
    with pytest.raises(ExpressionError, match="empty"):
        compile_expression("   ")


def test_expression_that_is_not_text_is_refused() -> None:
    with pytest.raises(ExpressionError, match="must be text"):
        compile_expression(42)  # type: ignore[arg-type]


# ------------------------------------------------------------------------------- limits


def test_expression_at_the_length_limit_is_accepted() -> None:
    text = "x" + " " * (MAX_LENGTH - 1)
    assert compile_expression(text)(x=1.0) == 1.0


def test_one_megabyte_expression_is_refused_by_its_length_before_parsing(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    parsed: list[str] = []
    parse = ast.parse

    def watched_parse(source: str, *args: Any, **kwargs: Any) -> ast.AST:
        parsed.append(source)
        return parse(source, *args, **kwargs)

    monkeypatch.setattr(ast, "parse", watched_parse)
    text = "x+" * 500_000 + "x"
    with pytest.raises(ExpressionError, match="too long"):
        compile_expression(text)
    assert parsed == []
    compile_expression("x+x")  # the watch works: a short text is parsed
    assert parsed == ["x+x"]


def test_ten_thousand_nested_brackets_are_refused_without_recursion_error() -> None:
    text = "(" * 10_000 + "x" + ")" * 10_000
    with pytest.raises(ExpressionError):
        compile_expression(text)


def test_brackets_nested_past_the_parser_limit_are_refused() -> None:
    with pytest.raises(ExpressionError, match="too many nested parentheses"):
        compile_expression("(" * 900 + "x" + ")" * 900)


def test_long_run_of_unary_minus_is_refused_as_too_deep() -> None:
    with pytest.raises(ExpressionError, match="nested too deeply"):
        compile_expression("-" * (MAX_LENGTH - 1) + "x")


def test_deeply_nested_functions_are_refused() -> None:
    with pytest.raises(ExpressionError, match="nested too deeply"):
        compile_expression("sin(" * MAX_DEPTH + "x" + ")" * MAX_DEPTH)


def test_moderately_nested_functions_are_accepted() -> None:
    assert compile_expression("abs(" * 20 + "x" + ")" * 20)(x=-2.0) == 2.0


def test_x_plus_600_terms_is_refused_as_too_big() -> None:
    with pytest.raises(ExpressionError, match=f"more than {MAX_NODES} parts"):
        compile_expression("x" + "+1" * 600)


def test_long_sum_within_the_part_limit_is_one_level_deep() -> None:
    text = "x" + "+1" * 200
    assert compile_expression(text)(x=0.5) == 200.5


# ---------------------------------------------------------------------- hostile corpus

HOSTILE = [
    "__import__('os').system('touch /tmp/pwned')",
    "().__class__.__bases__[0].__subclasses__()",
    "lambda: 1",
    "(lambda: 1)()",
    "f'{x}'",
    "'abc'",
    "b'abc'",
    "[x for x in y]",
    "(x for x in y)",
    "{x for x in y}",
    "{x: 1 for x in y}",
    "x.real",
    "x.__class__.__mro__",
    "x[0]",
    "x[0:1]",
    "open('f')",
    "exec('1')",
    "eval('1')",
    "compile('1', 'f', 'eval')",
    "globals()",
    "locals()",
    "vars()",
    "getattr(x, 'real')",
    "__builtins__",
    "(y:=1)",
    "{1:2}",
    "{1, 2}",
    "[1, 2]",
    "(1, 2)",
    "*x",
    "sin(*x)",
    "sin(**x)",
    "sin(x=1)",
    "max(x, y, key=abs)",
    "await x",
    "1j",
    "None",
    "...",
    "x if x else __import__('os')",
    "sin(x).__class__",
    "x; y",
    "import os",
    "x = 1",
]


@pytest.mark.parametrize("payload", HOSTILE)
def test_hostile_payload_is_refused(payload: str) -> None:
    with pytest.raises(ExpressionError):
        compile_expression(payload)


@pytest.mark.parametrize(
    ("payload", "named"),
    [
        ("__import__('os').system('ls')", ".system"),
        ("().__class__.__bases__[0].__subclasses__()", ".__subclasses__"),
        ("lambda: 1", "lambda"),
        ("f'{x}'", "f-strings"),
        ("'abc'", "Text"),
        ("[x for x in y]", "Comprehensions"),
        ("x.real", ".real"),
        ("x[0]", "Indexing"),
        ("open('f')", "Unknown function 'open'"),
        ("(y:=1)", ":="),
        ("{1:2}", "Dictionaries"),
        ("sin(x=1)", "can't be named"),
    ],
)
def test_refusal_names_the_construct(payload: str, named: str) -> None:
    with pytest.raises(ExpressionError) as error:
        compile_expression(payload)
    assert named in str(error.value)


def hostile_payloads_writing_to(folder: Path) -> list[str]:
    target = folder / "pwned"
    return [
        f"__import__('os').system('touch {target}')",
        f"__import__('subprocess').Popen(['touch', '{target}'])",
        f"open('{target}', 'w').write('x')",
        f"exec(\"open('{target}', 'w')\")",
        f"eval(\"__import__('os').system('touch {target}')\")",
        f"(lambda: __import__('os').system('touch {target}'))()",
        f"f\"{{__import__('os').system('touch {target}')}}\"",
        f"[c for c in ().__class__.__bases__[0].__subclasses__()"
        f" if c.__name__ == 'Popen'][0](['touch', '{target}'])",
        f"__builtins__['open']('{target}', 'w')",
        f"globals()['__builtins__'].open('{target}', 'w')",
        f"x if x else __import__('os').system('touch {target}')",
        f"sin(x) + __import__('os').system('touch {target}')",
        "__import__('os').fork()",
        f"__import__('os').execv('/bin/touch', ['touch', '{target}'])",
        f"(y := __import__('os').system('touch {target}'))",
    ]


_AUDITED = (
    "exec",
    "open",
    "import",
    "os.system",
    "os.exec",
    "os.fork",
    "os.forkpty",
    "os.posix_spawn",
    "os.spawn",
    "os.startfile",
    "os.remove",
    "os.rename",
    "os.mkdir",
    "subprocess.Popen",
    "socket.connect",
    "ctypes.dlopen",
)
_audit_log: list[str] | None = None


def _audit(event: str, args: tuple[object, ...]) -> None:
    if _audit_log is not None and event.startswith(_AUDITED):
        _audit_log.append(event)


sys.addaudithook(_audit)  # hooks cannot be removed; it records only inside watching()


#: Standard-library modules that Python itself imports lazily while it shows a warning (a
#: SyntaxWarning from ast.parse of a hostile payload, under pytest's warning capture): not
#: the expression's doing, and no code of the payload's.
BENIGN_LAZY_IMPORTS = frozenset({"linecache", "tokenize", "traceback", "tracemalloc", "_colorize"})


@contextmanager
def watching() -> Iterator[list[str]]:
    """Record process spawns, file opens, imports and code execution, by patch and audit.

    Used around just the code under test, so pytest's own work is not recorded.
    """
    global _audit_log
    calls: list[str] = []

    def recorder(name: str, original: Callable[..., Any]) -> Callable[..., Any]:
        def record(*args: Any, **kwargs: Any) -> Any:
            if name == "__import__" and args and args[0] in BENIGN_LAZY_IMPORTS:
                return original(*args, **kwargs)  # the warnings machinery formatting a warning
            calls.append(f"__import__ {args[0]}" if name == "__import__" and args else name)
            return original(*args, **kwargs)

        return record

    real_compile = builtins.compile

    def compile_only_to_ast(*args: Any, **kwargs: Any) -> Any:
        flags = kwargs.get("flags", args[3] if len(args) > 3 else 0)
        if not flags & ast.PyCF_ONLY_AST:
            calls.append("compile to code")
        return real_compile(*args, **kwargs)

    with pytest.MonkeyPatch.context() as patch:  # __import__ last: setattr itself imports
        patch.setattr(builtins, "compile", compile_only_to_ast)
        for module, names in [
            (os, ["system", "popen", "fork", "execv", "execve", "execvp", "spawnv", "posix_spawn"]),
            (subprocess, ["Popen", "run", "call", "check_call", "check_output"]),
            (builtins, ["open", "exec", "eval", "__import__"]),
        ]:
            for name in names:
                if hasattr(module, name):
                    patch.setattr(module, name, recorder(name, getattr(module, name)))
        _audit_log = calls
        try:
            yield calls
        finally:
            _audit_log = None


def test_watching_sees_a_spawn() -> None:
    with watching() as calls:
        os.system("true")
    assert "system" in calls
    assert "os.system" in calls


def test_hostile_corpus_creates_no_file_and_spawns_nothing(tmp_path: Path) -> None:
    payloads = [*HOSTILE, *hostile_payloads_writing_to(tmp_path)]
    accepted = []
    with watching() as calls:
        for payload in payloads:
            try:
                compile_expression(payload)
            except ExpressionError:
                continue
            accepted.append(payload)
    assert accepted == []
    assert calls == []
    assert list(tmp_path.iterdir()) == []


def test_evaluation_creates_no_file_and_spawns_nothing() -> None:
    with watching() as calls:
        f = compile_expression("sqrt(x**2 + y**2) if x > y else clamp(x * 2 * pi, 0, 1)")
        f(x=np.linspace(0, 1, 50), y=0.5)
    assert calls == []


def test_module_never_names_eval_exec_or_compile() -> None:
    source = Path(expressions_module.__file__).read_text(encoding="utf-8")
    names = {node.id for node in ast.walk(ast.parse(source)) if isinstance(node, ast.Name)} | {
        node.attr for node in ast.walk(ast.parse(source)) if isinstance(node, ast.Attribute)
    }
    assert names.isdisjoint({"eval", "exec", "compile", "__import__", "getattr", "__builtins__"})


# ------------------------------------------------------------------ property: vs numpy

X = np.array([-7.5, -2.0, -0.5, 0.0, 0.25, 1.0, 3.0, 1e3])
Y = np.array([2.0, -3.0, 0.5, 0.0, -0.25, 4.0, 3.0, -1e-3])
Reference = Callable[[], Any]
Term = tuple[str, Reference]

_BINARY = [
    ("+", np.add),
    ("-", np.subtract),
    ("*", np.multiply),
    ("/", np.true_divide),
    ("//", np.floor_divide),
    ("%", np.remainder),
    ("**", np.power),
]
_UNARY = [
    ("sin", np.sin),
    ("cos", np.cos),
    ("atan", np.arctan),
    ("sqrt", np.sqrt),
    ("exp", np.exp),
    ("log", np.log),
    ("abs", np.abs),
    ("floor", np.floor),
    ("round", np.round),
    ("tanh", np.tanh),
]
_COMPARE = [("<", np.less), ("<=", np.less_equal), (">", np.greater), ("==", np.equal)]


def _literal(value: float) -> Term:
    return repr(value), lambda: np.float64(value)


_leaves: st.SearchStrategy[Term] = st.one_of(
    st.just(("x", lambda: X)),
    st.just(("y", lambda: Y)),
    st.sampled_from([("pi", lambda: np.float64(np.pi)), ("e", lambda: np.float64(np.e))]),
    st.integers(0, 100).map(lambda i: (str(i), lambda: np.float64(i))),
    st.floats(0, 1e6, allow_nan=False, allow_infinity=False).map(_literal),
)


def _binary(a: Term, op: tuple[str, np.ufunc], b: Term) -> Term:
    return f"({a[0]} {op[0]} {b[0]})", lambda: op[1](a[1](), b[1]())


def _function(f: tuple[str, np.ufunc], a: Term) -> Term:
    return f"{f[0]}({a[0]})", lambda: f[1](a[1]())


def _negate(a: Term) -> Term:
    return f"(-{a[0]})", lambda: np.negative(a[1]())


def _choose(a: Term, c1: Term, op: tuple[str, np.ufunc], c2: Term, b: Term) -> Term:
    return (
        f"({a[0]} if {c1[0]} {op[0]} {c2[0]} else {b[0]})",
        lambda: np.where(op[1](c1[1](), c2[1]()), a[1](), b[1]()),
    )


def _extremum(name: str, a: Term, b: Term) -> Term:
    ufunc = np.minimum if name == "min" else np.maximum
    return f"{name}({a[0]}, {b[0]})", lambda: ufunc(a[1](), b[1]())


def _logic(a: Term, op: str, b: Term) -> Term:
    ufunc = np.logical_and if op == "and" else np.logical_or
    return (
        f"(({a[0]}) {op} ({b[0]}))",
        lambda: ufunc(np.not_equal(a[1](), 0), np.not_equal(b[1](), 0)).astype(np.float64),
    )


def _extend(terms: st.SearchStrategy[Term]) -> st.SearchStrategy[Term]:
    return st.one_of(
        st.builds(_binary, terms, st.sampled_from(_BINARY), terms),
        st.builds(_function, st.sampled_from(_UNARY), terms),
        st.builds(_negate, terms),
        st.builds(_choose, terms, terms, st.sampled_from(_COMPARE), terms, terms),
        st.builds(_extremum, st.sampled_from(["min", "max"]), terms, terms),
        st.builds(_logic, terms, st.sampled_from(["and", "or"]), terms),
    )


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.recursive(_leaves, _extend, max_leaves=16))
def test_random_expressions_match_numpy(term: Term) -> None:
    text, reference = term
    try:
        f = compile_expression(text)
    except ExpressionError as error:  # a rare draw beyond the size limits
        assume("too deeply" not in str(error) and "too big" not in str(error))
        raise
    with np.errstate(all="ignore"):
        expected = np.broadcast_to(reference(), X.shape)
    np.testing.assert_array_equal(f(x=X, y=Y), expected)
