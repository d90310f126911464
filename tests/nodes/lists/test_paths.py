"""Simplify Tree, Tree Branch, Trim Tree and Path Mapper, on trees written out by hand."""

from __future__ import annotations

from tests.support.node_helpers import out, run, texts, tree
from torsal.nodes.lists.paths import PathMapper, SimplifyTree, TreeBranch, TrimTree

GRID = tree({(0, 0): ["a", "b", "c"], (0, 1): ["d", "e", "f"]})  # two rows of three


def test_simplify_removes_the_levels_every_path_shares():
    result = run(SimplifyTree(), Tree=tree({(0, 0, 1): ["a"], (0, 0, 2): ["b"]}))
    assert out(result) == {(1,): ["a"], (2,): ["b"]}


def test_tree_branch_picks_the_branch_at_a_typed_path():
    assert out(run(TreeBranch(), Tree=GRID, Path="{0;1}")) == {(0,): ["d", "e", "f"]}


def test_tree_branch_names_the_missing_path_and_the_ones_there_are():
    result = run(TreeBranch(), Tree=GRID, Path="{3}")
    assert result.state == "warning"
    assert texts(result) == ["The tree has no branch {3}; it has {0;0}, {0;1}"]


def test_trim_tree_gathers_the_branches_of_each_parent():
    result = run(TrimTree(), Tree=tree({(0, 0): ["a"], (0, 1): ["b"], (1, 0): ["c"]}), Depth=1)
    assert out(result) == {(0,): ["a", "b"], (1,): ["c"]}


def test_path_mapper_swaps_levels():
    result = run(PathMapper(), Tree=tree({(0, 1): ["x"], (2, 3): ["y"]}), Source="{a;b}", Target="{b;a}")
    assert out(result) == {(1, 0): ["x"], (3, 2): ["y"]}


def test_path_mapper_with_item_indices_transposes_rows_into_columns():
    result = run(PathMapper(), Tree=GRID, Source="{a;b}(i)", Target="{i}")
    assert out(result) == {(0,): ["a", "d"], (1,): ["b", "e"], (2,): ["c", "f"]}


def test_path_mapper_refuses_a_target_naming_what_source_does_not():
    result = run(PathMapper(), Tree=GRID, Source="{a;b}", Target="{c}")
    assert result.state == "warning"
    assert texts(result)[0].startswith("Target '{c}' uses 'c', which Source does not name")
