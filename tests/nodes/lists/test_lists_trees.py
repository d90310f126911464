"""Flatten, Graft, Merge and Partition."""

from __future__ import annotations

from tests.support.node_helpers import out, run, texts, tree
from torsal.nodes.lists.trees import Flatten, Graft, Merge, Partition


def test_flatten_puts_all_items_in_branch_zero_in_path_order():
    result = run(Flatten(), Tree=tree({(0, 1): ["b", "c"], (0, 0): ["a"], (2,): ["d"]}))
    assert out(result) == {(0,): ["a", "b", "c", "d"]}


def test_graft_gives_each_item_its_own_branch():
    result = run(Graft(), Tree=tree({(0,): ["a", "b"], (1,): ["c"]}))
    assert out(result) == {(0, 0): ["a"], (0, 1): ["b"], (1, 0): ["c"]}


def test_merge_joins_branches_with_the_same_path_end_to_end():
    result = run(Merge(), D1=tree({(0,): [1, 2]}), D2=tree({(0,): [3], (1,): [4]}))
    assert out(result) == {(0,): [1, 2, 3], (1,): [4]}


def test_merge_with_one_input_left_empty_passes_the_other():
    result = run(Merge(), D2=tree({(0,): ["x"]}))
    assert result.state == "ok"
    assert out(result) == {(0,): ["x"]}


def test_partition_cuts_a_list_into_chunks_in_sub_branches():
    result = run(Partition(), List=["a", "b", "c", "d", "e"], Size=2)
    assert out(result) == {(0, 0): ["a", "b"], (0, 1): ["c", "d"], (0, 2): ["e"]}


def test_partition_uses_several_sizes_in_turn():
    result = run(Partition(), List=[1, 2, 3, 4, 5, 6], Size=[1, 2])
    assert out(result) == {(0, 0): [1], (0, 1): [2, 3], (0, 2): [4], (0, 3): [5, 6]}


def test_partition_keeps_each_branch_under_its_own_path():
    result = run(Partition(), List=tree({(0,): [1, 2, 3], (1,): [4, 5]}), Size=2)
    assert out(result) == {(0, 0): [1, 2], (0, 1): [3], (1, 0): [4, 5]}


def test_partition_with_size_zero_warns_and_leaves_the_list_uncut():
    result = run(Partition(), List=[1, 2, 3], Size=0)
    assert result.state == "warning"
    assert texts(result) == ["Size must be at least 1, not 0: the list it cuts gets no chunks"]
    assert out(result) == {(0, 0): []}
