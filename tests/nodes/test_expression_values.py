"""The expression language of ``maths.Expression``: the values it gives — arithmetic,
functions, constants, vectorisation, conditions and logic, and out-of-range results.
Variables and messages, limits, safety and the property test against numpy are in the
other ``test_expression_*.py`` files."""

from __future__ import annotations

import ast
import math
import warnings
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

import torsal.nodes.expressions as expressions_module
from torsal.nodes.expressions import (
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
