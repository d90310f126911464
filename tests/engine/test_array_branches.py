"""Branches of numbers, integers, booleans, points and vectors held as numpy arrays (issue 16, item 1).

An array branch is the same data as the list of its items: nodes iterating a tree see
Python values, trees compare equal, the modifiers and the matching rules give what they
give on lists; casts, NaN checks and bounds are done on the whole array.
"""

from __future__ import annotations

import math
from typing import ClassVar

import numpy as np
import pytest

from torsal.engine.bounds import within_bounds
from torsal.engine.datatree import DataTree, Triples, apply_modifiers
from torsal.engine.graph import Graph
from torsal.engine.node import ITEM, LIST, In, Node, NodeError, NodeWarning, Out
from torsal.engine.solver import OK, Solver, cast_tree, merge_trees
from torsal.engine.types import BOOLEAN, GENERIC, INTEGER, NUMBER, POINT, TEXT, VECTOR, summarize_value
from torsal.engine.values import Point, Vector


def array_tree(*branches: list) -> DataTree:
    return DataTree({(i,): np.asarray(b) for i, b in enumerate(branches)})


def list_tree(*branches: list) -> DataTree:
    return DataTree({(i,): list(b) for i, b in enumerate(branches)})


class Numbers(Node):
    """Outputs 0, 1, ... Count - 1 as an array (as Series does)."""

    type_id = "test.ArrayNumbers"
    inputs = (In("Count", INTEGER, "C", "How many.", default=4),)
    outputs = (Out("Numbers", NUMBER, "N", "The numbers.", access=LIST),)

    def solve(self, count: int) -> np.ndarray:
        return np.arange(count, dtype=np.float64)


class Seen(Node):
    """Records what its solve was handed."""

    type_id = "test.ArraySeen"
    seen: ClassVar[list] = []

    def solve(self, value):  # replaced per test by the port set below
        Seen.seen.append(value)
        return value


def seer(access, arrays: bool = False) -> type[Node]:
    class See(Seen):
        type_id = f"test.ArraySeen{access}{arrays}"
        inputs = (In("Value", NUMBER, "V", "What comes in.", access=access, arrays=arrays),)
        outputs = (Out("Out", NUMBER, "O", "What came in.", access=access),)

    return See


def solve_into(see: type[Node], count: int = 4) -> Solver:
    Seen.seen = []
    graph = Graph()
    graph.add_node(Numbers(), "n")
    graph.set_input_value("n", "Count", count)
    graph.add_node(see(), "see")
    graph.connect("n", "Numbers", "see", "Value")
    solver = Solver(graph)
    solver.solve()
    return solver


def test_a_list_output_returned_as_an_array_is_stored_as_one():
    tree = solve_into(seer(ITEM)).result("n").output("Numbers")
    (branch,) = tree.raw_branches
    assert isinstance(branch, np.ndarray) and branch.dtype == np.float64


def test_an_array_branch_is_handed_out_as_python_floats():
    tree = array_tree([0.0, 1.5])
    assert tree.branches == [[0.0, 1.5]]
    assert [type(v) for v in tree.all_items()] == [float, float]


def test_an_array_branch_equals_the_list_of_its_items():
    assert array_tree([1.0, 2.0], [3.0]) == list_tree([1.0, 2.0], [3.0])


def test_an_item_input_receives_python_floats_from_an_array_branch():
    solve_into(seer(ITEM))
    assert Seen.seen == [0.0, 1.0, 2.0, 3.0]
    assert {type(v) for v in Seen.seen} == {float}


def test_a_list_input_receives_a_list_unless_it_takes_arrays():
    solve_into(seer(LIST))
    assert Seen.seen == [[0.0, 1.0, 2.0, 3.0]] and isinstance(Seen.seen[0], list)


def test_a_list_input_that_takes_arrays_receives_the_array_itself():
    solver = solve_into(seer(LIST, arrays=True))
    (given,) = Seen.seen
    assert given is solver.result("n").output("Numbers").raw_branches[0]


def test_a_stored_array_is_read_only():
    (branch,) = array_tree([1.0, 2.0]).raw_branches
    with pytest.raises(ValueError, match="read-only"):
        branch[0] = 5.0


def test_appending_to_an_array_branch_gives_the_list_with_the_item():
    tree = array_tree([1.0, 2.0])
    tree.append((0,), "a")
    assert tree.branches == [[1.0, 2.0, "a"]]


def test_extending_an_array_branch_with_an_array_keeps_one_array():
    tree = array_tree([1.0])
    tree.extend((0,), np.array([2.0, 3.0]))
    (branch,) = tree.raw_branches
    assert isinstance(branch, np.ndarray) and branch.tolist() == [1.0, 2.0, 3.0]


def test_two_wires_of_arrays_into_one_input_concatenate_their_branches():
    merged = merge_trees([array_tree([1.0, 2.0]), array_tree([3.0])])
    assert merged == list_tree([1.0, 2.0, 3.0])


@pytest.mark.parametrize(
    "modifiers", [["graft"], ["flatten"], ["simplify"], ["reverse"], ["graft", "flatten"]]
)
def test_modifiers_on_array_branches_give_what_they_give_on_lists(modifiers):
    arrays = DataTree({(0, 0): np.array([1.0, 2.0]), (0, 1): np.array([3.0])})
    lists = DataTree({(0, 0): [1.0, 2.0], (0, 1): [3.0]})
    assert apply_modifiers(arrays, modifiers) == apply_modifiers(lists, modifiers)


def test_flattening_arrays_of_one_dtype_keeps_an_array():
    (branch,) = array_tree([1.0], [2.0, 3.0]).flattened().raw_branches
    assert isinstance(branch, np.ndarray) and branch.tolist() == [1.0, 2.0, 3.0]


def port(value_type, name: str = "Value", **bounds) -> In:
    return In(name, value_type, name[0], "The input under test.", access=LIST, **bounds)


def test_numbers_into_an_integer_input_round_half_to_even_as_round_does():
    cast = cast_tree(array_tree([0.5, 1.5, 2.5, -0.5, 2.7]), port(INTEGER))
    assert cast.all_items() == [round(v) for v in (0.5, 1.5, 2.5, -0.5, 2.7)]
    assert cast.raw_branches[0].dtype == np.int64


def test_integers_into_a_number_input_become_floats():
    cast = cast_tree(array_tree([1, 2]), port(NUMBER))
    assert cast.all_items() == [1.0, 2.0] and cast.raw_branches[0].dtype == np.float64


def test_numbers_into_a_boolean_input_are_true_when_not_zero():
    assert cast_tree(array_tree([0.0, 2.0, -1.0]), port(BOOLEAN)).all_items() == [False, True, True]


@pytest.mark.parametrize("value_type", [INTEGER, BOOLEAN])
def test_a_nan_in_an_array_is_refused_naming_the_input(value_type):
    with pytest.raises(NodeError, match=r"^Segments is not a number \(NaN\)$"):
        cast_tree(array_tree([1.0, math.nan]), port(value_type, "Segments"))


def test_a_nan_in_an_array_into_a_number_input_stays_nan():
    (value,) = cast_tree(array_tree([math.nan]), port(NUMBER)).all_items()
    assert math.isnan(value)


def test_an_infinite_number_into_an_integer_input_says_what_a_list_says():
    messages = []
    for tree in (array_tree([1.0, math.inf]), list_tree([1.0, math.inf])):
        with pytest.raises(NodeError) as caught:
            cast_tree(tree, port(INTEGER, "Segments"))
        messages.append(str(caught.value))
    assert messages[0] == messages[1]


def test_numbers_into_a_text_input_are_cast_item_by_item():
    assert cast_tree(array_tree([1.5, 2.0]), port(TEXT)).all_items() == ["1.5", "2"]


def test_a_value_outside_the_bounds_in_an_array_is_refused_with_the_lists_sentence():
    bounded = port(INTEGER, "Segments", min=1, max=100)
    messages = []
    for tree in (array_tree([5, 0, 7]), list_tree([5, 0, 7])):
        with pytest.raises(NodeWarning) as caught:
            within_bounds(tree, bounded)
        messages.append(str(caught.value))
    assert messages == ["Segments must be at least 1, not 0"] * 2


def test_an_array_within_the_bounds_passes():
    tree = array_tree([1, 100])
    assert within_bounds(tree, port(INTEGER, "Segments", min=1, max=100)) is tree


def test_array_items_are_summarised_as_json_numbers():
    assert [summarize_value(v) for v in array_tree([1.5, 2.0]).all_items()] == [1.5, 2.0]
    assert [summarize_value(v) for v in array_tree([3]).all_items()] == [3]


def test_an_array_branch_reports_its_empty_state_and_first_item():
    assert not array_tree([2.0]).is_empty() and array_tree([]).is_empty()
    assert array_tree([2.0, 3.0]).first() == 2.0 and type(array_tree([2.0]).first()) is float


def test_longest_list_matching_repeats_an_arrays_last_item_for_an_item_input():
    class Add(Node):
        type_id = "test.ArrayAdd"
        inputs = (In("A", NUMBER, "A", "First."), In("B", NUMBER, "B", "Second."))
        outputs = (Out("Sum", NUMBER, "S", "A + B."),)

        def solve(self, a: float, b: float) -> float:
            return a + b

    graph = Graph()
    graph.add_node(Numbers(), "n")
    graph.add_node(Add(), "add")
    graph.connect("n", "Numbers", "add", "A")
    graph.set_input_value("add", "B", [10.0, 20.0])
    solver = Solver(graph)
    solver.solve()
    assert solver.result("add").state == OK
    assert solver.result("add").output("Sum").all_items() == [10.0, 21.0, 22.0, 23.0]


def test_an_array_of_numbers_into_an_integer_list_input_arrives_as_integers():
    class Take(Node):
        type_id = "test.ArrayTakeInteger"
        inputs = (In("Segments", INTEGER, "S", "Rulings minus one.", access=LIST),)
        outputs = (Out("Out", INTEGER, "O", "What came in.", access=LIST),)

        def solve(self, values):
            return values

    graph = Graph()
    graph.add_node(Numbers(), "n")
    graph.add_node(Take(), "take")
    graph.connect("n", "Numbers", "take", "Segments")
    graph.set_input_value("n", "Count", 3)
    solver = Solver(graph)
    solver.solve()
    assert solver.result("take").state == OK
    assert solver.result("take").output("Out").all_items() == [0, 1, 2]
    assert [type(v) for v in solver.result("take").output("Out").all_items()] == [int] * 3


# --------------------------------------------------------------------------- points and vectors

class Grid(Node):
    """Outputs Count points (i, 2i, 3i) as one (n, 3) array."""

    type_id = "test.ArrayPoints"
    inputs = (In("Count", INTEGER, "C", "How many.", default=3),)
    outputs = (Out("Points", POINT, "P", "The points.", access=LIST),)

    def solve(self, count: int) -> np.ndarray:
        return np.arange(count, dtype=np.float64)[:, None] * np.array([1.0, 2.0, 3.0])


def points_into(value_type, access=LIST, arrays: bool = False) -> Solver:
    class Take(Node):
        type_id = f"test.ArrayTake{value_type.name}{access}{arrays}"
        inputs = (In("Value", value_type, "V", "What comes in.", access=access, arrays=arrays),)
        outputs = (Out("Out", GENERIC, "O", "What came in.", access=access),)

        def solve(self, value):
            Seen.seen.append(value)
            return value

    Seen.seen = []
    graph = Graph()
    graph.add_node(Grid(), "grid")
    graph.add_node(Take(), "take")
    graph.connect("grid", "Points", "take", "Value")
    solver = Solver(graph)
    solver.solve()
    return solver


def test_an_n_by_3_array_from_a_point_list_output_is_held_as_one_array():
    (branch,) = points_into(POINT).result("grid").output("Points").raw_branches
    assert isinstance(branch, Triples) and branch.array.shape == (3, 3)


def test_a_point_array_branch_is_read_as_points():
    items = points_into(POINT).result("grid").output("Points").all_items()
    assert items == [Point(0, 0, 0), Point(1, 2, 3), Point(2, 4, 6)]
    assert {type(p) for p in items} == {Point}


def test_a_point_list_input_receives_points():
    points_into(POINT)
    assert Seen.seen == [[Point(0, 0, 0), Point(1, 2, 3), Point(2, 4, 6)]]


def test_a_point_input_that_takes_arrays_receives_the_n_by_3_array():
    points_into(POINT, arrays=True)
    (given,) = Seen.seen
    assert isinstance(given, np.ndarray) and given.tolist() == [[0, 0, 0], [1, 2, 3], [2, 4, 6]]


def test_points_into_a_vector_input_become_vectors_with_the_same_numbers():
    points_into(VECTOR)
    assert Seen.seen == [[Vector(0, 0, 0), Vector(1, 2, 3), Vector(2, 4, 6)]]
    assert {type(v) for v in Seen.seen[0]} == {Vector}


def test_points_into_a_text_input_are_written_item_by_item():
    points_into(TEXT, access=ITEM)
    assert Seen.seen == ["{0, 0, 0}", "{1, 2, 3}", "{2, 4, 6}"]


def test_points_into_a_number_input_are_refused_as_a_list_of_points_is():
    messages = []
    for tree in (DataTree({(0,): Triples(np.zeros((1, 3)), Point)}), DataTree({(0,): [Point(0, 0, 0)]})):
        with pytest.raises(NodeError) as caught:
            cast_tree(tree, port(NUMBER))
        messages.append(str(caught.value))
    assert messages[0] == messages[1]


@pytest.mark.parametrize(
    "modifiers", [["graft"], ["flatten"], ["simplify"], ["reverse"], ["graft", "flatten"]]
)
def test_modifiers_on_point_arrays_give_what_they_give_on_lists(modifiers):
    rows = np.array([[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]])
    arrays = DataTree({(0, 0): Triples(rows, Point), (0, 1): Triples(rows[:1], Point)})
    lists = DataTree({(0, 0): [Point(1, 2, 3), Point(4, 5, 6)], (0, 1): [Point(1, 2, 3)]})
    assert apply_modifiers(arrays, modifiers) == apply_modifiers(lists, modifiers)


def test_point_items_are_summarised_as_before():
    (point,) = DataTree({(0,): Triples(np.array([[1.0, 2.5, 3.0]]), Point)}).all_items()
    assert summarize_value(point) == {"type": "Point", "xyz": [1.0, 2.5, 3.0]}
