"""The list nodes take array branches as they are (issue 16, item 1).

Each node is given the same items once as a list branch and once as an array branch (a
numpy array of numbers, integers or booleans, or Triples of points); it must give the
same items, worked out here by hand, and keep an array branch an array.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from tests.support.node_helpers import run
from torsal.engine.datatree import DataTree, Triples, is_array
from torsal.engine.values import Point
from torsal.nodes.lists.culling import CullPattern
from torsal.nodes.lists.items import ListItem, ListLength
from torsal.nodes.lists.ordering import Reverse, Shift, Sort
from torsal.nodes.lists.trees import Merge, Partition

NUMBERS = [3.0, 1.0, 4.0, 1.5, 5.0]
POINTS = [Point(0.0, 0.0, 0.0), Point(1.0, 0.0, 0.0), Point(1.0, 2.0, 0.0), Point(0.0, 2.0, 3.0)]


def as_list(items: list[Any]) -> DataTree:
    return DataTree({(0,): list(items)})


def as_array(items: list[Any]) -> DataTree:
    if isinstance(items[0], Point):
        return DataTree({(0,): Triples(np.array(items, dtype=float), Point)})
    return DataTree({(0,): np.array(items)})


FORMS = pytest.mark.parametrize("form", [as_list, as_array], ids=["list", "array"])


def only_branch(tree: DataTree) -> Any:
    (branch,) = tree.raw_branches
    return branch


def warnings(result) -> list[str]:
    return [m.text for m in result.messages]


def assert_kept_as(form, branch) -> None:
    """An array branch in gives an array branch out; a list in gives a list out."""
    assert is_array(branch) == (form is as_array)


@FORMS
def test_list_item_picks_the_item_at_an_index(form):
    result = run(ListItem(), List=form(NUMBERS), Index=2)
    assert result.output("Item").branches == [[4.0]]
    assert type(result.output("Item").first()) is float


@FORMS
def test_list_item_wraps_a_negative_index_from_the_end(form):
    result = run(ListItem(), List=form(NUMBERS), Index=-1, Wrap=True)
    assert result.output("Item").branches == [[5.0]]


@FORMS
def test_list_item_wraps_an_index_past_the_end(form):
    result = run(ListItem(), List=form(NUMBERS), Index=7, Wrap=True)  # 7 mod 5 = 2
    assert result.output("Item").branches == [[4.0]]


@FORMS
def test_list_item_outside_the_list_without_wrap_warns(form):
    result = run(ListItem(), List=form(NUMBERS), Index=5)
    assert any("outside the list of 5 items" in w for w in warnings(result))


@FORMS
def test_list_item_of_points_gives_a_point(form):
    result = run(ListItem(), List=form(POINTS), Index=2)
    (item,) = result.output("Item").all_items()
    assert item == Point(1.0, 2.0, 0.0) and type(item) is Point


@FORMS
def test_list_length_counts_the_items(form):
    assert run(ListLength(), List=form(NUMBERS)).output("Length").branches == [[5]]


@FORMS
def test_cull_pattern_keeps_every_other_item(form):
    result = run(CullPattern(), List=form(NUMBERS), Pattern=form([True, False]))
    branch = only_branch(result.output("List"))
    assert list(branch.tolist() if is_array(branch) else branch) == [3.0, 4.0, 5.0]
    assert_kept_as(form, branch)


@FORMS
def test_cull_pattern_repeats_a_pattern_longer_than_one_item_over_points(form):
    result = run(CullPattern(), List=form(POINTS), Pattern=form([False, True, True]))
    branch = only_branch(result.output("List"))
    assert result.output("List").branches == [[POINTS[1], POINTS[2]]]
    assert_kept_as(form, branch)


def test_cull_pattern_with_a_null_in_the_pattern_warns():
    result = run(CullPattern(), List=as_array(NUMBERS), Pattern=as_list([True, None]))
    assert any("empty (null)" in w for w in warnings(result))


@FORMS
@pytest.mark.parametrize(("shift", "wrap", "expected"), [
    (1, True, [1.0, 4.0, 1.5, 5.0, 3.0]),
    (-2, True, [1.5, 5.0, 3.0, 1.0, 4.0]),
    (7, True, [4.0, 1.5, 5.0, 3.0, 1.0]),  # 7 mod 5 = 2
    (2, False, [4.0, 1.5, 5.0]),
    (-2, False, [3.0, 1.0, 4.0]),
    (0, True, NUMBERS),
])
def test_shift_moves_the_items(form, shift, wrap, expected):
    result = run(Shift(), List=form(NUMBERS), Shift=shift, Wrap=wrap)
    assert result.output("List").branches == [expected]
    assert_kept_as(form, only_branch(result.output("List")))


@FORMS
def test_shift_moves_points_and_keeps_them_points(form):
    result = run(Shift(), List=form(POINTS), Shift=1)
    assert result.output("List").branches == [POINTS[1:] + POINTS[:1]]
    assert_kept_as(form, only_branch(result.output("List")))


@FORMS
def test_reverse_puts_the_last_item_first(form):
    result = run(Reverse(), List=form(POINTS))
    assert result.output("List").branches == [POINTS[::-1]]
    assert_kept_as(form, only_branch(result.output("List")))


@FORMS
def test_sort_orders_the_keys_and_moves_the_values_alongside(form):
    result = run(Sort(), Keys=form(NUMBERS), Values=form([10, 11, 12, 13, 14]))
    assert result.output("Keys").branches == [[1.0, 1.5, 3.0, 4.0, 5.0]]
    assert result.output("Values").branches == [[11, 13, 10, 12, 14]]
    assert_kept_as(form, only_branch(result.output("Values")))


@FORMS
def test_sort_keeps_equal_keys_in_their_order(form):
    result = run(Sort(), Keys=form([2.0, 1.0, 2.0, 1.0]), Values=form(POINTS))
    assert result.output("Values").branches == [[POINTS[1], POINTS[3], POINTS[0], POINTS[2]]]


@FORMS
def test_sort_refuses_nan_keys(form):
    result = run(Sort(), Keys=form([1.0, float("nan")]))
    assert result.output("Keys").is_empty()
    assert result.state == "warning"


def test_sort_of_array_keys_without_values_gives_no_values():
    result = run(Sort(), Keys=as_array(NUMBERS))
    assert result.output("Keys").branches == [[1.0, 1.5, 3.0, 4.0, 5.0]]
    assert result.output("Values").is_empty()


@FORMS
def test_merge_puts_branches_of_one_path_end_to_end(form):
    result = run(Merge(), D1=form(NUMBERS[:2]), D2=form(NUMBERS[2:]))
    assert result.output("Result").branches == [NUMBERS]
    assert_kept_as(form, only_branch(result.output("Result")))


def test_merge_of_an_array_and_a_list_gives_the_items_of_both():
    result = run(Merge(), D1=as_array([1.0, 2.0]), D2=as_list(["a"]))
    assert result.output("Result").branches == [[1.0, 2.0, "a"]]


@FORMS
def test_partition_cuts_a_list_into_chunks(form):
    result = run(Partition(), List=form(NUMBERS), Size=2)
    tree = result.output("Chunks")
    assert tree.to_dict() == {"{0;0}": [3.0, 1.0], "{0;1}": [4.0, 1.5], "{0;2}": [5.0]}
    assert all(is_array(b) == (form is as_array) for b in tree.raw_branches)
