"""maths.Expression: a formula over whole lists, matched like any node."""

from __future__ import annotations

import math

import numpy as np

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine import graphfile
from torsal.engine.graph import Graph
from torsal.engine.registry import Registry
from torsal.engine.solver import Solver
from torsal.nodes.expressions import CompiledExpression
from torsal.nodes.maths.expression import Expression
from torsal.nodes.maths.sequences import Series


def expression(text: str, variables: list[str] | None = None) -> Expression:
    return Expression({"expression": text, "variables": variables or ["x", "y"]})


def test_default_expression_adds_x_and_y():
    node = Expression()
    assert node.settings == {"expression": "x + y", "variables": ["x", "y"]}
    assert out(run(node, x=2, y=3)) == {(0,): [5.0]}


def test_list_with_single_value_repeats_the_single_value():
    result = run(Expression(), x=tree({(0,): [1, 2, 3]}), y=tree({(0,): [10]}))
    assert out(result) == {(0,): [11.0, 12.0, 13.0]}
    assert result.state == "ok"


def test_shorter_list_repeats_its_last_item_with_a_remark():
    result = run(Expression(), x=tree({(0,): [1, 2, 3]}), y=tree({(0,): [10, 20]}))
    assert out(result) == {(0,): [11.0, 22.0, 23.0]}
    assert texts(result) == ["x has 3 items, y has 2: y's last value is reused"]


def test_two_branches_each_get_their_own_results():
    result = run(Expression(), x=tree({(0,): [1, 2]}), y=tree({(0,): [10], (1,): [20]}))
    assert out(result) == {(0,): [11.0, 12.0], (1,): [21.0, 22.0]}


def test_output_follows_the_paths_of_the_input_with_most_branches():
    result = run(Expression(), x=tree({(0, 0): [1], (0, 1): [2]}), y=tree({(0,): [10, 20]}))
    assert out(result) == {(0, 0): [11.0, 21.0], (0, 1): [12.0, 22.0]}


def test_grafted_input_gives_one_branch_per_item():
    result = run(Expression(), modifiers={"x": ["graft"]}, x=[1, 2, 3], y=10)
    assert out(result) == {(0, 0): [11.0], (0, 1): [12.0], (0, 2): [13.0]}


def test_comparisons_give_one_and_zero():
    result = run(expression("x > 1", ["x"]), x=[0, 1, 2, 3])
    assert out(result) == {(0,): [0.0, 0.0, 1.0, 1.0]}


def test_if_expression_and_functions():
    result = run(expression("sqrt(x) if x >= 0 else -1", ["x"]), x=[4, -9])
    assert out(result) == {(0,): [2.0, -1.0]}


def test_variables_become_the_inputs_in_order():
    node = expression("a * b + c", ["a", "b", "c"])
    assert [p.name for p in node.input_ports()] == ["a", "b", "c"]
    assert out(run(node, a=2, b=3, c=[1, 2])) == {(0,): [7.0, 8.0]}


def test_a_variable_the_formula_does_not_use_may_stay_unwired():
    result = run(expression("x * 2"), x=[1, 2])
    assert result.state == "ok"
    assert out(result) == {(0,): [2.0, 4.0]}


def test_a_used_variable_left_unwired_warns_and_gives_nothing():
    result = run(Expression(), x=[1, 2])
    assert result.state == "warning"
    assert texts(result) == ["Input y collected no data"]
    assert out(result) == {}


def test_expression_without_variables_gives_one_value():
    assert out(run(expression("2 * pi", []))) == {(0,): [6.283185307179586]}


def test_division_by_zero_warns_how_many_results_are_not_finite():
    result = run(expression("1 / x", ["x"]), x=[0, 2, 0, 0])
    assert result.state == "warning"
    assert texts(result) == ["3 results are not finite numbers (division by zero?)"]
    assert out(result)[(0,)][1] == 0.5


def test_non_finite_count_adds_up_over_branches():
    result = run(expression("1 / x", ["x"]), x=tree({(0,): [0.0], (1,): [1.0, 0.0]}))
    assert texts(result) == ["2 results are not finite numbers (division by zero?)"]


def test_one_non_finite_result_is_worded_in_the_singular():
    result = run(expression("sqrt(x)", ["x"]), x=[-1, 4])
    assert texts(result) == ["1 result is not a finite number (division by zero?)"]


def test_syntax_error_is_a_node_error_with_a_plain_message():
    result = run(expression("x +", ["x"]), x=1)
    assert result.state == "error"
    assert texts(result)[0].startswith("Could not read the expression")
    assert "Traceback" not in texts(result)[0]


def test_unknown_function_is_an_error_and_runs_nothing():
    result = run(expression("__import__('os').system('touch /tmp/pwned')", ["x"]), x=1)
    assert result.state == "error"
    assert out(result) == {}


def test_variables_that_are_not_names_are_an_error():
    result = run(Expression({"expression": "x", "variables": "x"}))
    assert result.state == "error"
    assert texts(result) == ["Variables must be a list of names, like ['x', 'y'], not 'x'"]


def test_compiled_expression_is_cached_per_text_and_variables():
    first, second = expression("x * 3", ["x"]), expression("x * 3", ["x"])
    assert first._compile()[0] is second._compile()[0]
    assert expression("x * 4", ["x"])._compile()[0] is not first._compile()[0]


def test_changing_the_expression_setting_resolves_with_the_new_formula():
    graph = Graph()
    graph.add_node(expression("x + 1", ["x"]), "e")
    graph.set_input_value("e", "x", [1, 2])
    solver = Solver(graph)
    solver.solve()
    graph.set_setting("e", "expression", "x * 10")
    solver.solve()
    assert out(solver.result("e")) == {(0,): [10.0, 20.0]}


def test_million_items_are_solved_in_one_vectorised_call(monkeypatch):
    """How fast, against numpy in the same run: bench_expressions.py."""
    calls = []
    evaluate = CompiledExpression.__call__

    def counted(self, **values):
        calls.append({name: np.shape(value) for name, value in values.items()})
        return evaluate(self, **values)

    monkeypatch.setattr(CompiledExpression, "__call__", counted)
    graph = Graph()
    graph.add_node(Series(), "s")
    graph.set_input_value("s", "Count", 1_000_000)
    graph.add_node(expression("sin(x) * y + x ** 2 / (1 + y)"), "e")
    graph.set_input_value("e", "y", 0.5)
    graph.connect("s", "Series", "e", "x")
    solver = Solver(graph)
    solver.solve()
    graph.expire("e")
    calls.clear()
    solver.solve()
    assert calls == [{"x": (1_000_000,), "y": ()}]
    result = solver.result("e")
    assert result.state == "ok"
    values = result.output("Result").all_items()
    assert len(values) == 1_000_000
    assert values[2] == math.sin(2.0) * 0.5 + 2.0 ** 2 / 1.5


def test_expression_round_trips_through_a_graph_file():
    registry = Registry()
    registry.register(Expression)
    graph = Graph()
    graph.add_node(expression("a - b", ["a", "b"]), "e")
    text = graphfile.dumps(graph)
    loaded = graphfile.loads(text, registry)
    assert [p.name for p in loaded.nodes["e"].node.input_ports()] == ["a", "b"]
    assert graphfile.dumps(loaded) == text


def test_empty_null_items_become_nan_and_are_counted_as_not_finite():
    result = run(expression("x + 1", ["x"]), x=tree({(0,): [1.0, None, 3.0]}))
    values = out(result)[(0,)]
    assert values[0] == 2.0 and values[2] == 4.0
    assert math.isnan(values[1])
    assert texts(result) == ["1 result is not a finite number (division by zero?)"]
