"""A NaN reaching an input that needs a cast says "X is not a number (NaN)" (issue 11, item 6).

It is never read as empty, as 0, or — through ``bool`` — as true.
"""

from __future__ import annotations

import math

import pytest

from torsal.engine.graph import Graph
from torsal.engine.node import In, Node, Out, Setting
from torsal.engine.solver import ERROR, OK, Solver
from torsal.engine.types import BOOLEAN, DOMAIN, INTEGER, NUMBER, POINT, TEXT, CastError, cast


class Constant(Node):
    type_id = "test.NanConstant"
    outputs = (Out("Value", NUMBER, "V", "The value."),)
    settings_spec = (Setting("value", float, 1.0),)

    def solve(self) -> float:
        return float(self.settings["value"])


def taker(value_type, port: str) -> type[Node]:
    class Take(Node):
        type_id = f"test.Take{value_type.name}"
        inputs = (In(port, value_type, port[0], "The input under test."),)
        outputs = (Out("Out", value_type, "O", "What came in."),)

        def solve(self, value):
            return value

    return Take


def solve_with_nan(value_type, port: str, wired: bool = True):
    """A NaN into ``port`` from a wire (a node's output) or as the input's own value (``--set``)."""
    graph = Graph()
    graph.add_node(taker(value_type, port)(), "taker")
    if wired:
        graph.add_node(Constant({"value": math.nan}), "source")
        graph.connect("source", "Value", "taker", port)
    else:
        graph.set_input_value("taker", port, math.nan)
    solver = Solver(graph)
    solver.solve()
    return solver.result("taker")


@pytest.mark.parametrize(
    ("value_type", "port", "wired"),
    [
        (INTEGER, "Segments", True),
        (BOOLEAN, "Closed", True),
        (DOMAIN, "Range", True),
        (INTEGER, "Segments", False),
        (POINT, "Centre", False),
    ],
    ids=["wired Integer", "wired Boolean", "wired Domain", "set Integer", "set Point"],
)
def test_a_nan_is_reported_as_not_a_number_naming_the_input(value_type, port, wired):
    result = solve_with_nan(value_type, port, wired)
    assert result.state == ERROR
    assert [m.text for m in result.messages] == [f"{port} is not a number (NaN)"]


def test_a_nan_into_text_is_shown_as_nan():
    result = solve_with_nan(TEXT, "Note")
    assert result.state == OK
    assert result.outputs["Out"].to_dict() == {"{0}": ["nan"]}


@pytest.mark.parametrize(
    ("target", "name"), [(INTEGER, "an Integer"), (BOOLEAN, "a Boolean"), (DOMAIN, "a Domain")]
)
def test_casting_nan_says_it_is_not_a_number(target, name):
    with pytest.raises(CastError, match=f"NaN is not a number, so it cannot be used as {name}"):
        cast(math.nan, target)


def test_ordinary_numbers_still_cast():
    assert cast(2.6, INTEGER) == 3
    assert cast(0.0, BOOLEAN) is False
    assert cast(4.0, DOMAIN).max == 4.0
