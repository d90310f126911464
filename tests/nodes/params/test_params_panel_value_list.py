"""Panel and Value List: hand-written data in the graph."""

from __future__ import annotations

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.values import Point
from torsal.nodes.maths.expression import Expression
from torsal.nodes.params.panel import Panel
from torsal.nodes.params.value_list import ValueList


def test_unwired_panel_gives_one_text_item_per_line():
    result = run(Panel({"text": "3.5\n4.0\nfour and a half"}))
    assert out(result) == {(0,): ["3.5", "4.0", "four and a half"]}


def test_empty_unwired_panel_gives_nothing():
    result = run(Panel())
    assert result.state == "ok"
    assert out(result) == {}


def test_wired_panel_passes_the_tree_unchanged():
    data = tree({(0, 0): [1.0, 2.0], (0, 1): ["a"], (3,): []})
    result = run(Panel({"text": "ignored"}), Input=data)
    assert out(result) == {(0, 0): [1.0, 2.0], (0, 1): ["a"], (3,): []}


def test_panel_lines_feed_a_number_input():
    from torsal.engine.graph import Graph
    from torsal.engine.solver import Solver

    graph = Graph()
    graph.add_node(Panel({"text": "1\n2\n3"}), "panel")
    graph.add_node(Expression({"expression": "x * 2", "variables": ["x"]}), "expr")
    graph.connect("panel", "Output", "expr", "x")
    solver = Solver(graph)
    solver.solve()
    assert out(solver.result("expr")) == {(0,): [2.0, 4.0, 6.0]}


def test_value_list_gives_the_selected_value():
    items = [{"name": "4 mm", "value": 0.004}, {"name": "6 mm", "value": 0.006}]
    assert out(run(ValueList({"items": items, "selected": 1}))) == {(0,): [0.006]}


def test_value_list_default_is_one_to_four_with_the_first_selected():
    node = ValueList()
    assert [i["name"] for i in node.settings["items"]] == ["One", "Two", "Three", "Four"]
    assert out(run(node)) == {(0,): [1]}


def test_value_list_decodes_a_point_value():
    items = [{"name": "up", "value": {"type": "Point", "xyz": [0, 0, 1]}}]
    assert out(run(ValueList({"items": items, "selected": 0}))) == {(0,): [Point(0, 0, 1)]}


def test_value_list_with_selection_out_of_range_is_an_error():
    result = run(ValueList({"selected": 4}))
    assert result.state == "error"
    assert texts(result) == ["Item 4 is selected but the list has 4 items (0 to 3)"]


def test_value_list_with_no_items_is_an_error():
    result = run(ValueList({"items": []}))
    assert texts(result) == ["The value list has no items: add at least one {name, value}"]


def test_value_list_instances_do_not_share_their_items():
    first, second = ValueList(), ValueList()
    first.settings["items"].append({"name": "Five", "value": 5})
    assert len(second.settings["items"]) == 4
