"""Explode Tree: one output per branch, a settable number of outputs kept in the file."""

from __future__ import annotations

import math

import pytest

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.datatree import DataTree
from torsal.engine.graph import Graph
from torsal.engine.graphfile import dumps, loads
from torsal.engine.solver import Solver
from torsal.nodes.catalogue import default_registry
from torsal.nodes.lists.explode import MAX_OUTPUTS, ExplodeTree
from torsal.nodes.lists.trees import Partition
from torsal.nodes.params.panel import Panel

THREE = {(0, 0): ["a", "b"], (0, 1): [3.5], (2,): ["c"]}


def test_each_branch_goes_to_its_own_output_in_path_order():
    result = run(ExplodeTree({"outputs": 3}), Data=tree(THREE))
    assert result.state == "ok"
    assert [out(result, f"Branch{i}") for i in range(3)] == [{(0,): ["a", "b"]}, {(0,): [3.5]}, {(0,): ["c"]}]


def test_a_new_node_has_two_outputs_and_warns_about_the_branches_it_drops():
    node = ExplodeTree()
    assert [p.name for p in node.output_ports()] == ["Branch0", "Branch1"]
    result = run(node, Data=tree(THREE))
    assert result.state == "warning"
    assert texts(result) == [
        "The tree has 3 branches and the node 2 outputs: its last branch, {2}, is not passed on. "
        "Right-click the node → Match outputs."
    ]
    assert out(result, "Branch1") == {(0,): [3.5]}


def test_outputs_past_the_last_branch_are_empty():
    result = run(ExplodeTree({"outputs": 5}), Data=tree(THREE))
    assert result.state == "ok"
    assert [out(result, f"Branch{i}") for i in (3, 4)] == [{}, {}]


@pytest.mark.parametrize(("asked", "ports", "said"), [
    (0, 1, "The Outputs setting must be at least 1, not 0: 1 used"),
    (1e12, MAX_OUTPUTS,
     f"The Outputs setting is at most {MAX_OUTPUTS}, not 1000000000000: {MAX_OUTPUTS} used"),
    (math.nan, 2, "The Outputs setting must be a whole number, not nan: 2 used"),
    ("three", 2, "The Outputs setting must be a whole number, not 'three': 2 used"),
])
def test_a_count_out_of_range_is_kept_in_range_and_named(asked, ports, said):
    node = ExplodeTree({"outputs": asked})
    assert len(node.output_ports()) == ports
    result = run(node, Data=tree({(0,): [1]}))
    assert said in texts(result)
    assert out(result, "Branch0") == {(0,): [1]}


def test_match_outputs_gives_one_output_per_branch_of_the_tree_it_receives():
    graph = Graph()
    graph.add_node(Panel({"text": "1\n2\n3\n4\n5\n6\n7"}), "numbers")
    graph.add_node(Partition(), "chunks")
    graph.set_input_value("chunks", "Size", 2)
    graph.add_node(ExplodeTree(), "bang")
    graph.connect("numbers", "Output", "chunks", "List")
    graph.connect("chunks", "Chunks", "bang", "Data")
    solver = Solver(graph)
    solver.solve()
    record = graph.nodes["bang"]
    assert record.node.match_outputs(solver.inputs_of("bang")) == {"outputs": 4}  # 7 items in 2s: 4 chunks
    assert record.node.match_outputs([DataTree()]) is None  # nothing received: nothing to match
    graph.set_setting("bang", "outputs", 4)
    solver.solve()
    assert solver.result("bang").state == "ok"
    assert [len(solver.result("bang").output(f"Branch{i}").all_items()) for i in range(4)] == [2, 2, 2, 1]


def test_the_outputs_and_their_wires_are_kept_in_the_file_and_fewer_outputs_unplug_wires():
    registry = default_registry()
    graph = Graph()
    graph.add_node(ExplodeTree({"outputs": 4}), "bang")
    graph.add_node(Panel(), "shown")
    graph.connect("bang", "Branch3", "shown", "Input")
    again = loads(dumps(graph), registry)
    assert [p.name for p in again.nodes["bang"].node.output_ports()] == [f"Branch{i}" for i in range(4)]
    assert [(w.source_port, w.target) for w in again.wires_from("bang")] == [("Branch3", "shown")]
    again.set_setting("bang", "outputs", 3)
    assert again.wires_from("bang") == []
