"""List Item and List Length."""

from __future__ import annotations

from tests.support.node_helpers import out, run, texts, tree
from torsal.nodes.lists.items import ListItem, ListLength


def test_list_item_picks_by_position_from_zero():
    assert out(run(ListItem(), List=["a", "b", "c"], Index=1)) == {(0,): ["b"]}


def test_list_item_defaults_to_the_first_item():
    assert out(run(ListItem(), List=["a", "b", "c"])) == {(0,): ["a"]}


def test_list_item_with_several_indices_picks_several_items():
    assert out(run(ListItem(), List=[10, 20, 30], Index=[2, 0])) == {(0,): [30, 10]}


def test_list_item_out_of_range_without_wrap_warns_and_gives_null():
    result = run(ListItem(), List=["a", "b", "c"], Index=5)
    assert result.state == "warning"
    assert texts(result) == [
        "Index 5 is outside the list of 3 items (0 to 2); turn on Wrap to wrap around"
    ]
    assert out(result) == {(0,): [None]}


def test_list_item_negative_index_without_wrap_is_out_of_range():
    result = run(ListItem(), List=["a", "b"], Index=-1)
    assert texts(result) == [
        "Index -1 is outside the list of 2 items (0 to 1); turn on Wrap to wrap around"
    ]


def test_list_item_with_wrap_wraps_past_the_end_and_before_the_start():
    result = run(ListItem(), List=["a", "b", "c"], Index=[4, -1], Wrap=True)
    assert out(result) == {(0,): ["b", "c"]}


def test_list_item_per_branch():
    data = tree({(0,): ["a", "b"], (1,): ["c", "d"]})
    assert out(run(ListItem(), List=data, Index=1)) == {(0,): ["b"], (1,): ["d"]}


def test_list_item_on_an_empty_branch_warns():
    result = run(ListItem(), List=tree({(0,): [], (1,): ["x"]}))
    assert texts(result) == ["The list is empty: there is no item to pick"]
    assert out(result) == {(0,): [None], (1,): ["x"]}


def test_list_length_counts_each_branch():
    result = run(ListLength(), List=tree({(0,): [1, 2, 3], (1,): [4]}))
    assert out(result) == {(0,): [3], (1,): [1]}


def test_list_length_of_an_empty_branch_is_zero():
    result = run(ListLength(), List=tree({(0,): [], (1,): ["a"]}))
    assert out(result) == {(0,): [0], (1,): [1]}


def test_list_length_with_nothing_wired_warns():
    result = run(ListLength())
    assert result.state == "warning"
    assert texts(result) == ["Input List collected no data"]
