"""A value-list input (``In(..., choices=...)``): a value that is no choice is refused with
a sentence naming the input and its choices, never with a count's "can be made" wording."""

from __future__ import annotations

import numpy as np

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.bounds import bounds_text
from torsal.engine.node import In, Node, Out
from torsal.engine.types import INTEGER

PLACES = ((0, "Beside model"), (1, "Origin"), (2, "On plane"))
PLACES_TEXT = "0 Beside model, 1 Origin, 2 On plane"


class Place(Node):
    """Test-only node: passes a choice on."""

    type_id = "test.Place"
    inputs = (In("Placement", INTEGER, "Pl", "Where.", default=0, min=0, max=2, choices=PLACES),)
    outputs = (Out("Choice", INTEGER, "C", "The choice."),)

    def solve(self, placement: int) -> int:
        return placement


class Sparse(Node):
    """Test-only node: a value list whose numbers have a gap."""

    type_id = "test.Sparse"
    inputs = (In("Mode", INTEGER, "M", "Mode.", default=1, min=1, max=5,
                 choices=((1, "Fast"), (5, "Exact"))),)
    outputs = (Out("Same", INTEGER, "S", "The mode."),)

    def solve(self, mode: int) -> int:
        return mode


def test_a_choice_reaches_solve():
    result = run(Place(), Placement=2)
    assert result.state == "ok" and out(result, "Choice") == {(0,): [2]}


def test_a_value_past_the_last_choice_names_the_input_and_its_choices():
    result = run(Place(), Placement=5)
    assert result.state == "warning"
    assert texts(result) == [f"Placement is 5, not one of its choices: {PLACES_TEXT}"]
    assert out(result, "Choice") == {}


def test_a_value_below_the_first_choice_names_the_choices_too():
    assert texts(run(Place(), Placement=-1)) == [f"Placement is -1, not one of its choices: {PLACES_TEXT}"]


def test_a_value_between_two_choices_that_is_none_of_them_is_refused():
    assert texts(run(Sparse(), Mode=3)) == ["Mode is 3, not one of its choices: 1 Fast, 5 Exact"]


def test_an_array_branch_with_a_value_that_is_no_choice_is_refused():
    result = run(Sparse(), Mode=tree({(0,): np.array([1, 5, 4, 5])}))
    assert texts(result) == ["Mode is 4, not one of its choices: 1 Fast, 5 Exact"]


def test_a_list_of_choices_reaches_solve():
    result = run(Sparse(), Mode=tree({(0,): [1, 5, 5]}))
    assert result.state == "ok" and out(result, "Same") == {(0,): [1, 5, 5]}


def test_the_inspector_shows_a_value_lists_choices_as_its_bounds():
    assert bounds_text(Place.inputs[0]) == PLACES_TEXT
