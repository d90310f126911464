"""The expression language of ``maths.Expression``: its variables, the messages a designer
gets for a wrong expression, and the limits on its length, depth and size."""

from __future__ import annotations

import ast
import pickle
from typing import Any

import pytest

from torsal.nodes.expressions import (
    MAX_DEPTH,
    MAX_LENGTH,
    MAX_NODES,
    CompiledExpression,
    ExpressionError,
    compile_expression,
)

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
