"""The matching plan (engine/matching.py) read directly, rule by rule of docs/data-trees.md.

Expected values are Grasshopper's documented behaviour for item and list access: longest
list (the last item reused), the input with most branches leading (its last branch reused
by the others), output paths from that master input, one call per item, and a list output
per call in its own branch {p;i} when a branch makes several calls. Each case builds the
input trees by hand and reads which calls the plan makes, with which arguments, for which path.
"""

from __future__ import annotations

from typing import Any

from tests.support.nodekit import Add, AddRequired, ListItem, ListLength, Series
from torsal.engine.datatree import DataTree
from torsal.engine.matching import plan
from torsal.engine.node import ITEM, In, Node, Out
from torsal.engine.types import NUMBER


def calls(node: Node, *trees: dict[tuple[int, ...], list[Any]], wired: list[bool] | None = None
          ) -> list[tuple[tuple[int, ...], list[tuple[Any, ...]]]]:
    """Each group's path and its calls' arguments, in order."""
    made = plan(node, [DataTree(t) for t in trees], wired)
    return [(group.path, [tuple(row) for row in group.rows]) for group in made.groups]


def test_rule_1_a_required_input_without_data_stops_the_node_before_any_call():
    made = plan(AddRequired(), [DataTree({(0,): [1.0]}), DataTree()])
    assert made.missing == "Input B collected no data" and not made.groups


def test_rule_1_a_wired_input_that_received_nothing_is_missing_even_with_a_default():
    made = plan(Add(), [DataTree({(0,): [1.0]}), DataTree()], [True, True])
    assert made.missing == "Input B collected no data"


def test_rule_1_an_unwired_empty_input_uses_its_default_as_one_call():
    made = plan(Add(), [DataTree({(0,): [1.0]}), DataTree({(0,): [0.0]})])
    assert made.missing is None and made.calls == 1


def test_rule_2_the_input_with_most_branches_leads_and_a_shorter_tree_reuses_its_last_branch():
    assert calls(Add(), {(0,): [1.0, 2.0]}, {(0,): [10.0], (1,): [20.0]}) == [
        ((0,), [(1.0, 10.0), (2.0, 10.0)]),
        ((1,), [(1.0, 20.0), (2.0, 20.0)]),
    ]


def test_rule_3_longest_list_reuses_the_last_item_of_the_shorter_list():
    assert calls(Add(), {(0,): [1.0, 2.0, 3.0]}, {(0,): [10.0, 20.0]}) == [
        ((0,), [(1.0, 10.0), (2.0, 20.0), (3.0, 20.0)]),
    ]


def test_rule_3_a_branch_with_an_empty_item_list_makes_no_call():
    assert calls(Add(), {(0,): [1.0], (1,): []}, {(0,): [10.0]}) == [((0,), [(1.0, 10.0)])]


def test_rule_4_paths_come_from_the_master_input_the_first_with_most_branches():
    assert [path for path, _ in calls(Add(), {(0, 0): [1.0], (0, 1): [2.0]}, {(5,): [10.0, 20.0]})] == [
        (0, 0), (0, 1),
    ]
    assert [path for path, _ in calls(Add(), {(7,): [1.0], (8,): [2.0]}, {(3,): [1.0], (4,): [2.0]})] == [
        (7,), (8,),
    ]


def test_rule_5_list_outputs_go_to_p_i_only_when_a_branch_makes_several_calls():
    series = Series()  # item inputs, a list output
    one = plan(series, [DataTree({(0,): [0.0]}), DataTree({(0,): [1.0]}), DataTree({(0,): [3]})])
    several = plan(series, [DataTree({(0,): [0.0, 5.0]}), DataTree({(0,): [1.0]}), DataTree({(0,): [3]})])
    assert not one.sub_branches and several.sub_branches


def test_list_access_passes_a_whole_branch_per_call_and_is_repeated_for_every_item_call():
    assert calls(ListLength(), {(0,): [1, 2, 3], (1,): [4]}) == [((0,), [([1, 2, 3],)]), ((1,), [([4],)])]
    assert calls(ListItem(), {(0,): ["a", "b", "c"]}, {(0,): [0, 2]}) == [
        ((0,), [(["a", "b", "c"], 0), (["a", "b", "c"], 2)]),
    ]


def test_rule_6_one_item_on_every_input_is_one_call_at_path_0():
    made = plan(Add(), [DataTree({(0,): [1.0]}), DataTree({(0,): [2.0]})])
    assert [(g.path, list(g.rows)) for g in made.groups] == [((0,), [[1.0, 2.0]])] and made.calls == 1


def test_uneven_trees_are_remarked_in_words():
    a = DataTree({(0,): [1.0], (1,): [2.0], (2,): [3.0]})
    made = plan(Add(), [a, DataTree({(0,): [1.0], (1,): [2.0]})])
    assert made.remarks == ["A has 3 branches, B has 2: B's last branch is reused"]


def test_a_solve_over_the_call_budget_is_refused_before_any_call_naming_the_input():
    class Tight(Add):
        max_calls = 3

    made = plan(Tight(), [DataTree({(0,): [1.0, 2.0, 3.0, 4.0]}), DataTree({(0,): [1.0]})])
    assert made.refusal == f"A has 4 values: {Tight().name()} would run 4 times; at most 3 at once"


def test_the_plan_counts_its_calls_without_making_them():
    class Counting(Node):
        type_id = "test.Counting"
        inputs = (In("X", NUMBER, "X", access=ITEM),)
        outputs = (Out("Y", NUMBER, "Y"),)
        made = 0

        def solve(self, x: float) -> float:
            Counting.made += 1
            return x

    result = plan(Counting(), [DataTree({(0,): [1.0] * 5, (1,): [2.0] * 3})])
    assert result.calls == 8 and Counting.made == 0
