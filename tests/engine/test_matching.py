"""Data-tree matching through real graphs (``docs/data-trees.md``).

Every case of the table in docs/data-trees.md is built as a graph — a tree source (or a persistent
value) wired into an item-access Add, modifiers set with ``graph.set_modifiers`` — solved,
and the output tree compared path by path, in order. Then list access, tree access and
cases of our own: empty branches, three inputs, list outputs per call, master-input
ties, uneven-match remarks, modifier chains, merged wires, casts.
"""

from __future__ import annotations

from typing import Any

import pytest

from tests.support.nodekit import (
    Add,
    AddRequired,
    BranchCount,
    ListItem,
    ListLength,
    Series,
    Sum3,
    TreeSource,
)
from torsal.engine.graph import Graph
from torsal.engine.node import Level, Message, Node
from torsal.engine.solver import Solver

Tree = dict[str, list[Any]]


def solve(
    node: Node,
    trees: dict[str, Tree] | None = None,
    values: dict[str, Any] | None = None,
    modifiers: dict[str, list[str]] | None = None,
) -> tuple[Solver, Graph]:
    """Solve ``node`` (id ``n``) fed by tree sources (``trees``) and persistent ``values``."""
    graph = Graph()
    graph.add_node(node, "n")
    for port, tree in (trees or {}).items():
        graph.add_node(TreeSource({"branches": tree}), f"src_{port}")
        graph.connect(f"src_{port}", "Tree", "n", port)
    for port, value in (values or {}).items():
        graph.set_input_value("n", port, value)
    for port, names in (modifiers or {}).items():
        graph.set_modifiers("n", port, names)
    solver = Solver(graph)
    solver.solve()
    return solver, graph


def output(solver: Solver, port: str) -> list[tuple[str, list[Any]]]:
    """The output tree as an ordered list of (path, items): order is part of the result."""
    return list(solver.result("n").output(port).to_dict().items())


def texts(solver: Solver, level: Level | None = None) -> list[str]:
    return [m.text for m in solver.result("n").messages if level is None or m.level is level]


# --------------------------------------------------------------------------- the table of docs/data-trees.md

SPEC_CASES = [
    # id, A, B, modifiers on A, expected Result
    ("longest-list", {"{0}": [1, 2, 3]}, {"{0}": [10]}, [], {"{0}": [11, 12, 13]}),
    ("last-item-reused", {"{0}": [1, 2, 3]}, {"{0}": [10, 20]}, [], {"{0}": [11, 22, 23]}),
    (
        "branches-follow-master",
        {"{0}": [1, 2]},
        {"{0}": [10], "{1}": [20]},
        [],
        {"{0}": [11, 12], "{1}": [21, 22]},
    ),
    (
        "deeper-master",
        {"{0;0}": [1], "{0;1}": [2]},
        {"{0}": [10, 20]},
        [],
        {"{0;0}": [11, 21], "{0;1}": [12, 22]},
    ),
    (
        "graft",
        {"{0}": [1, 2, 3]},
        {"{0}": [10]},
        ["graft"],
        {"{0;0}": [11], "{0;1}": [12], "{0;2}": [13]},
    ),
    ("flatten", {"{0;0}": [1], "{0;1}": [2, 3]}, {"{0}": [10]}, ["flatten"], {"{0}": [11, 12, 13]}),
    (
        "simplify",
        {"{0;0;0}": [1], "{0;0;1}": [2]},
        {"{0}": [10]},
        ["simplify"],
        {"{0}": [11], "{1}": [12]},
    ),
    ("reverse", {"{0}": [1, 2, 3]}, {"{0}": [0]}, ["reverse"], {"{0}": [3, 2, 1]}),
]


@pytest.mark.parametrize("a,b,mods,expected", [c[1:] for c in SPEC_CASES], ids=[c[0] for c in SPEC_CASES])
def test_spec_case_through_wired_trees(a, b, mods, expected):
    solver, _ = solve(Add(), trees={"A": a, "B": b}, modifiers={"A": mods})
    assert solver.result("n").state == "ok", solver.result("n").messages
    assert output(solver, "Result") == list(expected.items())
    assert all(isinstance(x, float) for _, items in output(solver, "Result") for x in items)


@pytest.mark.parametrize(
    "a,b,mods,expected",
    [c[1:] for c in SPEC_CASES if set(c[1]) == {"{0}"} and set(c[2]) == {"{0}"}],
    ids=[c[0] for c in SPEC_CASES if set(c[1]) == {"{0}"} and set(c[2]) == {"{0}"}],
)
def test_spec_case_through_persistent_values(a, b, mods, expected):
    """One-branch cases again, with the inputs' own values instead of wires."""
    solver, _ = solve(Add(), values={"A": a["{0}"], "B": b["{0}"]}, modifiers={"A": mods})
    assert output(solver, "Result") == list(expected.items())


def test_spec_list_access_list_length():
    solver, _ = solve(ListLength(), trees={"List": {"{0}": [1, 2, 3], "{1}": [4]}})
    assert output(solver, "Length") == [("{0}", [3]), ("{1}", [1])]


def test_modifiers_on_the_other_input_and_both_inputs():
    solver, _ = solve(
        Add(),
        trees={"A": {"{0}": [10]}, "B": {"{0}": [1, 2, 3]}},
        modifiers={"B": ["graft"]},
    )
    # B has three branches, so B is the master and its paths are used
    assert output(solver, "Result") == [("{0;0}", [11]), ("{0;1}", [12]), ("{0;2}", [13])]
    solver, _ = solve(
        Add(),
        trees={"A": {"{0}": [1, 2]}, "B": {"{0}": [10, 20]}},
        modifiers={"A": ["reverse"], "B": ["graft"]},
    )
    # A reversed: [2, 1]; B grafted: {0;0}: [10], {0;1}: [20] → master B, A's branch reused
    assert output(solver, "Result") == [("{0;0}", [12, 11]), ("{0;1}", [22, 21])]


# --------------------------------------------------------------------------- cases of our own


def test_empty_branch_makes_no_calls_and_no_items():
    solver, _ = solve(Add(), trees={"A": {"{0}": [1, 2], "{1}": []}}, values={"B": 10})
    result = solver.result("n").output("Result").to_dict()
    assert result["{0}"] == [11, 12]
    assert result.get("{1}", []) == []
    assert solver.result("n").state == "ok"


def test_empty_branch_of_the_other_input_is_reused_as_empty():
    solver, _ = solve(Add(), trees={"A": {"{0}": [1], "{1}": [2]}, "B": {"{0}": [10], "{1}": []}})
    result = solver.result("n").output("Result").to_dict()
    assert result["{0}"] == [11]
    assert result.get("{1}", []) == []


def test_three_inputs_longest_list():
    solver, _ = solve(Sum3(), trees={"A": {"{0}": [1, 2, 3]}, "B": {"{0}": [10]}, "C": {"{0}": [100, 200]}})
    assert output(solver, "Result") == [("{0}", [111, 212, 213])]


def test_three_inputs_with_uneven_branches_follow_the_master_and_say_so():
    solver, _ = solve(
        Sum3(),
        trees={
            "A": {"{0}": [1]},
            "B": {"{0}": [10], "{1}": [20], "{2}": [30]},
            "C": {"{0}": [100], "{1}": [200]},
        },
    )
    assert output(solver, "Result") == [("{0}", [111]), ("{1}", [221]), ("{2}", [231])]
    assert texts(solver, Level.REMARK) == ["B has 3 branches, C has 2: C's last branch is reused"]
    assert solver.result("n").state == "ok"  # a remark is not a warning


def test_uneven_branches_remark_in_plain_words():
    solver, _ = solve(
        Add(), trees={"A": {"{0}": [1], "{1}": [2], "{2}": [3]}, "B": {"{0}": [10], "{1}": [20]}}
    )
    assert output(solver, "Result") == [("{0}", [11]), ("{1}", [22]), ("{2}", [23])]
    assert Message(Level.REMARK, "A has 3 branches, B has 2: B's last branch is reused") in (
        solver.result("n").messages
    )
    assert solver.result("n").state == "ok"


def test_uneven_items_remark_names_the_branch():
    solver, _ = solve(Add(), trees={"A": {"{0}": [1, 2, 3]}, "B": {"{0}": [10, 20]}})
    assert texts(solver, Level.REMARK) == ["A has 3 items, B has 2 in branch {0}: B's last item is reused"]


@pytest.mark.parametrize(
    "a,b",
    [
        ({"{0}": [1, 2, 3]}, {"{0}": [10]}),  # one value against a list: the usual case
        ({"{0}": [1, 2]}, {"{0}": [10, 20]}),  # even
        ({"{0}": [1, 2]}, {"{0}": [10], "{1}": [20]}),  # one branch against many
    ],
)
def test_even_or_single_value_matching_makes_no_remark(a, b):
    solver, _ = solve(Add(), trees={"A": a, "B": b})
    assert solver.result("n").messages == []


def test_master_input_on_a_tie_is_the_first():
    solver, _ = solve(Add(), trees={"A": {"{0;0}": [1], "{0;1}": [2]}, "B": {"{5}": [10], "{7}": [20]}})
    assert output(solver, "Result") == [("{0;0}", [11]), ("{0;1}", [22])]
    solver, _ = solve(Add(), trees={"A": {"{5}": [1], "{7}": [2]}, "B": {"{0;0}": [10], "{0;1}": [20]}})
    assert output(solver, "Result") == [("{5}", [11]), ("{7}", [22])]


def test_master_input_is_the_one_with_most_branches_even_when_second():
    solver, _ = solve(Add(), trees={"A": {"{3}": [1]}, "B": {"{0;0}": [10], "{0;1}": [20]}})
    assert output(solver, "Result") == [("{0;0}", [11]), ("{0;1}", [21])]


def test_list_output_per_call_goes_to_p_i_branches():
    solver, _ = solve(Series(), trees={"Start": {"{0}": [0, 10]}}, values={"Count": 3})
    assert output(solver, "Series") == [("{0;0}", [0, 1, 2]), ("{0;1}", [10, 11, 12])]


def test_list_output_per_call_under_a_deeper_master_path():
    solver, _ = solve(Series(), trees={"Start": {"{2;1}": [0, 5]}}, values={"Count": 2})
    assert output(solver, "Series") == [("{2;1;0}", [0, 1]), ("{2;1;1}", [5, 6])]


def test_list_output_depths_never_mix_across_branches():
    """Branch {0} makes one call and {1} two: every list still gets its own {p;i}."""
    solver, _ = solve(Series(), trees={"Start": {"{0}": [0], "{1}": [5, 6]}}, values={"Count": 2})
    assert output(solver, "Series") == [("{0;0}", [0, 1]), ("{1;0}", [5, 6]), ("{1;1}", [6, 7])]


def test_list_output_of_a_single_call_keeps_the_path():
    """Engine choice (as Grasshopper dividing one curve): one call keeps ``{0}``. The spec's
    rule 4 reads ``{p;i}`` for every call; see the report to the lead."""
    solver, _ = solve(Series(), values={"Start": 1, "Count": 3})
    assert output(solver, "Series") == [("{0}", [1, 2, 3])]


def test_list_access_input_is_repeated_for_every_item_call():
    solver, _ = solve(ListItem(), trees={"List": {"{0}": ["a", "b", "c"]}, "Index": {"{0}": [0, 2, 5]}})
    assert output(solver, "Item") == [("{0}", ["a", "c", "c"])]


def test_list_access_with_branches_on_the_list_input():
    solver, _ = solve(
        ListItem(), trees={"List": {"{0}": ["a", "b"], "{1}": ["c", "d", "e"]}}, values={"Index": 1}
    )
    assert output(solver, "Item") == [("{0}", ["b"]), ("{1}", ["d"])]


def test_tree_access_gets_the_whole_tree_once():
    solver, _ = solve(BranchCount(), trees={"Tree": {"{0}": [1], "{1}": [2, 3], "{4;1}": []}})
    assert output(solver, "Count") == [("{0}", [3])]


@pytest.mark.parametrize(
    "mods,expected",
    [
        (["flatten", "graft"], [("{0;0}", [11]), ("{0;1}", [12]), ("{0;2}", [13])]),
        (["graft", "flatten"], [("{0}", [11, 12, 13])]),
        (["flatten", "reverse"], [("{0}", [13, 12, 11])]),
        (["reverse"], [("{0;0}", [11]), ("{0;1}", [13, 12])]),
        (["simplify"], [("{0}", [11]), ("{1}", [12, 13])]),
        (["graft", "simplify"], [("{0;0}", [11]), ("{1;0}", [12]), ("{1;1}", [13])]),
    ],
    ids=lambda v: "+".join(v) if isinstance(v, list) and v and isinstance(v[0], str) else None,
)
def test_modifiers_apply_in_order(mods, expected):
    solver, _ = solve(
        Add(), trees={"A": {"{0;0}": [1], "{0;1}": [2, 3]}}, values={"B": 10}, modifiers={"A": mods}
    )
    assert output(solver, "Result") == expected


def test_graft_of_several_branches():
    solver, _ = solve(
        Add(), trees={"A": {"{0}": [1, 2], "{1}": [3]}}, values={"B": 0}, modifiers={"A": ["graft"]}
    )
    assert output(solver, "Result") == [("{0;0}", [1]), ("{0;1}", [2]), ("{1;0}", [3])]


def test_simplify_keeps_one_index_of_a_single_path():
    solver, _ = solve(Add(), trees={"A": {"{0;0;3}": [1, 2]}}, values={"B": 0}, modifiers={"A": ["simplify"]})
    assert output(solver, "Result") == [("{3}", [1, 2])]


def test_simplify_only_removes_shared_leading_indices():
    solver, _ = solve(
        Add(), trees={"A": {"{1;0}": [1], "{2;0}": [2]}}, values={"B": 0}, modifiers={"A": ["simplify"]}
    )
    assert output(solver, "Result") == [("{1;0}", [1]), ("{2;0}", [2])]


def test_reverse_reverses_every_branch():
    solver, _ = solve(
        Add(), trees={"A": {"{0}": [1, 2], "{1}": [3, 4, 5]}}, values={"B": 0}, modifiers={"A": ["reverse"]}
    )
    assert output(solver, "Result") == [("{0}", [2, 1]), ("{1}", [5, 4, 3])]


def test_several_wires_into_a_list_input_merge_by_path():
    graph = Graph()
    graph.add_node(TreeSource({"branches": {"{0}": [1, 2]}}), "first")
    graph.add_node(TreeSource({"branches": {"{0}": [3], "{1}": [4]}}), "second")
    graph.add_node(ListLength(), "n")
    graph.connect("first", "Tree", "n", "List")
    graph.connect("second", "Tree", "n", "List")
    solver = Solver(graph)
    solver.solve()
    assert output(solver, "Length") == [("{0}", [3]), ("{1}", [1])]


def test_output_paths_are_in_path_order_whatever_the_source_order():
    solver, _ = solve(Add(), trees={"A": {"{1}": [2], "{0;5}": [1], "{0}": [0]}}, values={"B": 0})
    assert [path for path, _ in output(solver, "Result")] == ["{0}", "{0;5}", "{1}"]


def test_required_input_without_data_warns_and_produces_nothing():
    solver, _ = solve(AddRequired(), trees={"A": {"{0}": [1, 2]}})
    result = solver.result("n")
    assert result.state == "warning"
    assert texts(solver, Level.WARNING) == ["Input B collected no data"]
    assert result.output("Result").to_dict() == {}


def test_required_input_wired_to_an_empty_tree_warns():
    solver, _ = solve(AddRequired(), trees={"A": {"{0}": [1]}, "B": {"{0}": []}})
    assert texts(solver, Level.WARNING) == ["Input B collected no data"]


def test_optional_input_uses_its_default():
    solver, _ = solve(Add(), trees={"A": {"{0}": [1, 2], "{1}": [3]}})
    assert output(solver, "Result") == [("{0}", [1, 2]), ("{1}", [3])]
    assert solver.result("n").messages == []


def test_items_are_cast_to_the_port_type():
    solver, _ = solve(Add(), trees={"A": {"{0}": ["5", 2, True]}}, values={"B": 0.5})
    assert output(solver, "Result") == [("{0}", [5.5, 2.5, 1.5])]
    solver, _ = solve(Series(), values={"Start": 0, "Count": 2.6})
    assert output(solver, "Series") == [("{0}", [0, 1, 2])]


def test_an_item_that_cannot_be_cast_puts_the_node_in_error_with_a_message():
    solver, _ = solve(Add(), trees={"A": {"{0}": [1, "abc"]}}, values={"B": 0})
    result = solver.result("n")
    assert result.state == "error"
    assert any("'abc'" in m.text and "Number" in m.text for m in result.messages)
    assert result.output("Result").to_dict() == {}


def test_matching_downstream_of_a_matched_node():
    """A chain: the first Add's output tree is the second's input, paths carried through."""
    graph = Graph()
    graph.add_node(TreeSource({"branches": {"{0}": [1, 2], "{1}": [3]}}), "src")
    graph.add_node(Add(), "first")
    graph.add_node(Add(), "n")
    graph.connect("src", "Tree", "first", "A")
    graph.set_input_value("first", "B", 10)
    graph.connect("first", "Result", "n", "A")
    graph.set_input_value("n", "B", [100, 200])
    solver = Solver(graph)
    solver.solve()
    assert output(solver, "Result") == [("{0}", [111, 212]), ("{1}", [113, 213])]
