"""Shift, Reverse, Sort and Cull Pattern."""

from __future__ import annotations

from tests.support.node_helpers import out, run, texts, tree
from torsal.nodes.lists.culling import CullPattern
from torsal.nodes.lists.ordering import Reverse, Shift, Sort


def items(result, port=None) -> list:
    return [x for branch in out(result, port).values() for x in branch]


def test_shift_by_one_with_wrap_moves_the_first_item_to_the_end():
    assert items(run(Shift(), List=["a", "b", "c"])) == ["b", "c", "a"]


def test_shift_by_minus_one_with_wrap_moves_the_last_item_to_the_front():
    assert items(run(Shift(), List=["a", "b", "c"], Shift=-1)) == ["c", "a", "b"]


def test_shift_more_than_the_length_wraps_around():
    assert items(run(Shift(), List=["a", "b", "c"], Shift=4)) == ["b", "c", "a"]


def test_shift_without_wrap_drops_the_shifted_out_items():
    assert items(run(Shift(), List=[1, 2, 3, 4], Shift=1, Wrap=False)) == [2, 3, 4]
    assert items(run(Shift(), List=[1, 2, 3, 4], Shift=-2, Wrap=False)) == [1, 2]
    assert items(run(Shift(), List=[1, 2], Shift=5, Wrap=False)) == []


def test_shift_keeps_each_branch_apart():
    result = run(Shift(), List=tree({(0,): [1, 2], (1,): [3, 4, 5]}))
    assert list(out(result).values()) == [[2, 1], [4, 5, 3]]


def test_reverse_reverses_each_branch():
    result = run(Reverse(), List=tree({(0,): [1, 2, 3], (1,): ["a", "b"]}))
    assert out(result) == {(0,): [3, 2, 1], (1,): ["b", "a"]}


def test_sort_orders_keys_and_moves_values_alongside():
    result = run(Sort(), Keys=[3.0, 1.0, 2.0], Values=["c", "a", "b"])
    assert out(result, "Keys") == {(0,): [1.0, 2.0, 3.0]}
    assert out(result, "Values") == {(0,): ["a", "b", "c"]}


def test_sort_keeps_equal_keys_in_their_original_order():
    result = run(Sort(), Keys=[2, 1, 2, 1], Values=["w", "x", "y", "z"])
    assert items(result, "Values") == ["x", "z", "w", "y"]


def test_sort_without_values_sorts_the_keys_alone():
    result = run(Sort(), Keys=[5, -1, 0])
    assert result.state == "ok"
    assert items(result, "Keys") == [-1.0, 0.0, 5.0]
    assert items(result, "Values") == []


def test_sort_with_mismatched_values_warns():
    result = run(Sort(), Keys=[1, 2, 3], Values=["a", "b"])
    assert texts(result) == ["There are 3 keys but 2 values: give one value per key"]
    assert items(result, "Keys") == []


def test_sort_with_nan_key_warns():
    result = run(Sort(), Keys=tree({(0,): [1.0, float("nan")]}))
    assert texts(result) == ["Keys contain NaN (not a number), which cannot be sorted"]


def test_sort_per_branch():
    result = run(Sort(), Keys=tree({(0,): [2, 1], (1,): [9, 8, 7]}))
    assert out(result, "Keys") == {(0,): [1.0, 2.0], (1,): [7.0, 8.0, 9.0]}


def test_cull_pattern_true_false_keeps_every_other_item():
    result = run(CullPattern(), List=[0, 1, 2, 3, 4], Pattern=[True, False])
    assert out(result) == {(0,): [0, 2, 4]}


def test_cull_pattern_longer_than_the_list_uses_only_its_start():
    result = run(CullPattern(), List=["a", "b"], Pattern=[False, True, True, True])
    assert out(result) == {(0,): ["b"]}


def test_cull_pattern_reads_numbers_as_true_when_not_zero():
    result = run(CullPattern(), List=["a", "b", "c"], Pattern=[1, 0, 0])
    assert out(result) == {(0,): ["a"]}


def test_cull_pattern_with_an_empty_pattern_branch_warns():
    data = tree({(0,): [1, 2], (1,): [3]})
    result = run(CullPattern(), List=data, Pattern=tree({(0,): [True], (1,): []}))
    assert result.state == "warning"
    assert texts(result) == ["The pattern is empty: give at least one true or false"]
    assert out(result)[(0,)] == [1, 2]
