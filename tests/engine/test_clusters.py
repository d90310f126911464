"""Clusters (issue 12.7): make, explode, edit, solve and save a sub-graph packaged as one node.

Expected outputs come from the un-clustered graph (the graph the cluster was made from,
solved before clustering) or from closed forms, never from a cluster's own solve.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any, ClassVar

import pytest

from tests.support.nodekit import make_registry
from torsal.engine.cluster import MAX_NESTING, ClusterNode
from torsal.engine.cluster_edits import (
    add_cluster_instance,
    cluster_graph,
    cluster_instance,
    definition_of,
    explode_cluster,
    make_cluster,
    rename_cluster_port,
    reorder_cluster_ports,
    restore_cluster,
    set_cluster_graph,
)
from torsal.engine.datatree import DataTree
from torsal.engine.graph import Graph, GraphError
from torsal.engine.graphfile import GraphFileError, dumps, loads, read_graph
from torsal.engine.node import In, Node, Out
from torsal.engine.registry import Registry
from torsal.engine.solver import ERROR, OK, Solver
from torsal.engine.types import NUMBER

EXAMPLES = Path(__file__).resolve().parents[2] / "torsal" / "resources" / "examples"
FIRST_STEPS = EXAMPLES / "first-steps.graph"
INNER = ["edges", "total", "heights"]  # first-steps' three computing nodes


class Counted(Node):
    """Passes a number through and counts its solves (per node id, in ``solves``)."""

    type_id = "debug.Counted"
    inputs = (In("X", NUMBER, "X", default=0.0),)
    outputs = (Out("Y", NUMBER, "Y"),)
    solves: ClassVar[list[float]] = []

    def solve(self, x: float) -> float:
        Counted.solves.append(x)
        return x


@pytest.fixture(scope="module")
def kit() -> Registry:
    registry = make_registry()
    registry.register(Counted)
    return registry


@pytest.fixture(scope="module")
def library() -> Registry:
    from torsal.nodes.catalogue import default_registry

    return default_registry()


def solved(graph: Graph) -> Solver:
    """A new solver that has solved all of ``graph`` (another solver may have solved it before)."""
    graph.expire_all()
    solver = Solver(graph)
    solver.solve()
    return solver


def outputs_of(solver: Solver, node_id: str) -> dict[str, DataTree]:
    return dict(solver.result(node_id).outputs)


def wire_set(graph: Graph) -> set[tuple[str, str, str, str]]:
    return {(w.source, w.source_port, w.target, w.target_port) for w in graph.wires}


def slider(graph: Graph, kit: Registry, node_id: str, value: float) -> None:
    graph.add_node(kit.create("params.NumberSlider", {"value": value, "max": 100.0}), node_id)


def two_adds(kit: Registry) -> Graph:
    """a, b → sum = Add(a, b) → twice = Add(sum, sum) → shown = Add(twice, 0)."""
    graph = Graph()
    slider(graph, kit, "a", 2.0)
    slider(graph, kit, "b", 3.0)
    for node_id in ("sum", "twice", "shown"):
        graph.add_node(kit.create("maths.Add"), node_id)
    graph.connect("a", "Value", "sum", "A")
    graph.connect("b", "Value", "sum", "B")
    graph.connect("sum", "Result", "twice", "A")
    graph.connect("sum", "Result", "twice", "B")
    graph.connect("twice", "Result", "shown", "A")
    return graph


def first_steps(library: Registry) -> tuple[Graph, dict[str, dict[str, DataTree]]]:
    """The first-steps example and every node's outputs solved before any clustering."""
    graph = read_graph(FIRST_STEPS, library)
    solver = solved(graph)
    return graph, {n: outputs_of(solver, n) for n in graph.nodes}


# --------------------------------------------------------------------------- make

def test_cluster_of_first_steps_gives_the_expanded_graphs_outputs(library: Registry) -> None:
    graph, before = first_steps(library)
    cluster = make_cluster(graph, INNER, name="Panels")
    solver = solved(graph)
    assert solver.result(cluster).state == OK
    assert outputs_of(solver, "show_heights") == before["show_heights"]
    assert outputs_of(solver, "show_total") == before["show_total"]
    ports = definition_of(graph, cluster).output_names()
    assert [solver.result(cluster).output(p) for p in ports] == [
        before["heights"]["Result"], before["total"]["Result"]]


def test_cluster_of_first_steps_matches_the_closed_form(library: Registry) -> None:
    graph, _ = first_steps(library)
    cluster = make_cluster(graph, INNER, name="Panels")
    solver = solved(graph)
    names = ("Panel heights Result", "Total length Result")
    heights, total = (solver.result(cluster).output(p) for p in names)
    expected = [2.5 + 0.5 * math.sin(2 * math.pi * (1.2 * i) / 6) for i in range(12)]
    assert heights.branch(heights.paths[0]) == pytest.approx(expected, abs=1e-12)
    assert total.all_items() == pytest.approx([14.4], abs=1e-12)


def test_cluster_ports_are_the_wires_that_crossed_the_selection(library: Registry) -> None:
    graph, _ = first_steps(library)
    cluster = make_cluster(graph, INNER, name="Panels")
    definition = definition_of(graph, cluster)
    # width and count each feed two inner inputs: one port per outside source
    assert definition.input_names() == ["Step", "Count", "a"]
    # two inner outputs called Result: each is named after its node, as the designer labelled it
    assert definition.output_names() == ["Panel heights Result", "Total length Result"]
    assert wire_set(graph) == {
        ("width", "Value", cluster, "Step"), ("count", "Value", cluster, "Count"),
        ("wave", "Value", cluster, "a"),
        (cluster, "Panel heights Result", "show_heights", "Input"),
        (cluster, "Total length Result", "show_total", "Input"),
    }


def test_cluster_keeps_inner_settings_and_values(library: Registry) -> None:
    graph, _ = first_steps(library)
    expression = graph.nodes["heights"].node.settings["expression"]
    cluster = make_cluster(graph, INNER, name="Panels")
    inner = definition_of(graph, cluster).graph
    assert inner.nodes["heights"].node.settings["expression"] == expression
    assert inner.nodes["edges"].inputs["Start"].value == 0.0


def test_a_selection_fed_back_through_outside_nodes_is_refused(kit: Registry) -> None:
    graph = two_adds(kit)
    with pytest.raises(GraphError, match="feeds it back"):
        make_cluster(graph, ["sum", "shown"])


# --------------------------------------------------------------------------- files

def test_save_load_solve_gives_the_same_outputs(library: Registry) -> None:
    graph, before = first_steps(library)
    make_cluster(graph, INNER, name="Panels")
    text = dumps(graph)
    reopened = loads(text, library)
    solver = solved(reopened)
    assert outputs_of(solver, "show_heights") == before["show_heights"]
    assert outputs_of(solver, "show_total") == before["show_total"]
    assert dumps(reopened) == text  # load → save: the same bytes


def test_file_stores_each_definition_once(kit: Registry) -> None:
    graph = two_adds(kit)
    cluster = make_cluster(graph, ["sum", "twice"], name="Double sum")
    add_cluster_instance(graph, graph.nodes[cluster].node.definition.id, "again")
    data = json.loads(dumps(graph))
    assert [entry["id"] for entry in data["clusters"]] == ["doublesum"]
    settings = [n["settings"] for n in data["nodes"] if n["type"] == "cluster.Cluster"]
    assert settings == [{"definition": "doublesum"}, {"definition": "doublesum"}]


def test_a_file_without_clusters_is_written_without_a_clusters_section(library: Registry) -> None:
    text = FIRST_STEPS.read_text(encoding="utf-8")
    assert dumps(loads(text, library)) == text


def test_headless_run_solves_clusters(library: Registry, tmp_path: Path) -> None:
    from torsal.app.headless import run_file

    graph, before = first_steps(library)
    cluster = make_cluster(graph, INNER, name="Panels")
    path = tmp_path / "clustered.graph"
    path.write_text(dumps(graph), encoding="utf-8")
    result = run_file(path, registry=library).to_json()
    expected = [round(v, 12) for v in before["heights"]["Result"].all_items()]
    assert result["ok"]
    shown = result["nodes"][cluster]["outputs"]["Panel heights Result"]["{0}"]
    assert [round(v, 12) for v in shown] == expected


# --------------------------------------------------------------------------- explode

def test_explode_restores_the_wiring_and_outputs(library: Registry) -> None:
    graph, before = first_steps(library)
    wires = wire_set(graph)
    positions = {n: r.position for n, r in graph.nodes.items()}
    cluster = make_cluster(graph, INNER, name="Panels")
    restored = explode_cluster(graph, cluster)
    assert sorted(restored) == sorted(INNER)
    assert wire_set(graph) == wires
    assert {n: r.position for n, r in graph.nodes.items()} == positions
    assert graph.clusters == {}
    solver = solved(graph)
    assert {n: outputs_of(solver, n) for n in graph.nodes} == before


def test_make_then_explode_gives_back_the_same_file(library: Registry) -> None:
    graph, _ = first_steps(library)
    text = dumps(graph)
    explode_cluster(graph, make_cluster(graph, INNER, name="Panels"))
    assert dumps(graph) == text


def test_make_then_explode_gives_back_a_group_taken_inside(library: Registry) -> None:
    graph, _ = first_steps(library)
    text = dumps(graph)
    explode_cluster(graph, make_cluster(graph, ["width", "count", "wave"], name="Inputs"))  # the Inputs group
    assert dumps(graph) == text


def test_explode_keeps_the_layout_relative_to_a_moved_cluster(library: Registry) -> None:
    graph, _ = first_steps(library)
    cluster = make_cluster(graph, INNER, name="Panels")
    x, y = graph.nodes[cluster].position
    graph.move_node(cluster, (x + 100.0, y - 50.0))
    explode_cluster(graph, cluster)
    assert graph.nodes["edges"].position == (420.0, -10.0)  # was (320, 40)


def test_explode_then_restore_puts_the_cluster_back(kit: Registry) -> None:
    graph = two_adds(kit)
    cluster = make_cluster(graph, ["sum", "twice"], name="Double sum")
    wires = wire_set(graph)
    info = cluster_instance(graph, cluster)
    restored = explode_cluster(graph, cluster)
    restore_cluster(graph, info, restored)
    assert wire_set(graph) == wires
    assert isinstance(graph.nodes[cluster].node, ClusterNode)
    assert "doublesum" in graph.clusters


def test_explode_then_restore_gives_back_the_same_file(library: Registry) -> None:
    graph, _ = first_steps(library)
    cluster = make_cluster(graph, INNER, name="Panels")
    graph.move_node(cluster, (500.0, 500.0))  # explode now moves the nodes: no memory of the make
    text = dumps(graph)
    info = cluster_instance(graph, cluster)
    restore_cluster(graph, info, explode_cluster(graph, cluster))
    assert dumps(graph) == text


def test_groups_come_back_after_make_then_explode(library: Registry) -> None:
    graph, _ = first_steps(library)
    members = {g.id: list(g.nodes) for g in graph.groups}
    explode_cluster(graph, make_cluster(graph, INNER, name="Panels"))
    assert {g.id: list(g.nodes) for g in graph.groups} == members


def test_explode_keeps_a_definition_another_instance_uses(kit: Registry) -> None:
    graph = two_adds(kit)
    cluster = make_cluster(graph, ["sum", "twice"], name="Double sum")
    add_cluster_instance(graph, "doublesum", "again")
    explode_cluster(graph, cluster)
    assert "doublesum" in graph.clusters


def test_save_reload_explode_save_gives_back_the_shipped_file(library: Registry) -> None:
    graph, _ = first_steps(library)
    make_cluster(graph, INNER, name="Panels")
    reloaded = loads(dumps(graph), library)  # no memory of the make: explode works from the file
    explode_cluster(reloaded, "panels")
    assert dumps(reloaded) == FIRST_STEPS.read_text(encoding="utf-8")


def test_a_saved_cluster_stands_in_its_first_nodes_place(library: Registry) -> None:
    graph, _ = first_steps(library)
    make_cluster(graph, INNER, name="Panels")
    data = json.loads(dumps(graph))
    nodes = [n["id"] for n in data["nodes"]]
    assert nodes == ["width", "count", "wave", "panels", "show_heights", "show_total"]
    layout = next(g for g in data["groups"] if g["id"] == "layout")
    assert layout["nodes"] == ["panels", "show_heights", "show_total"]


def test_explode_of_a_loaded_cluster_puts_its_nodes_where_it_stands_in_the_file(kit: Registry) -> None:
    graph = two_adds(kit)
    make_cluster(graph, ["sum", "twice"], name="Double sum")
    data = json.loads(dumps(graph))
    data["nodes"].sort(key=lambda n: n["id"] != "doublesum")  # the cluster first in the file
    reloaded = loads(json.dumps(data), kit)
    explode_cluster(reloaded, "doublesum")
    saved = json.loads(dumps(reloaded))
    assert [n["id"] for n in saved["nodes"]] == ["sum", "twice", "a", "b", "shown"]
    assert "clusters" not in saved


# --------------------------------------------------------------------------- instances and editing

def two_instances(kit: Registry) -> tuple[Graph, str, str]:
    """a, b → cluster (sum, twice) → shown; a second instance fed by c = 10, d = 1."""
    graph = two_adds(kit)
    first = make_cluster(graph, ["sum", "twice"], name="Double sum")
    second = add_cluster_instance(graph, "doublesum", "again")
    slider(graph, kit, "c", 10.0)
    slider(graph, kit, "d", 1.0)
    graph.connect("c", "Value", second, "A")
    graph.connect("d", "Value", second, "B")
    return graph, first, second


def test_two_instances_of_one_definition_solve_their_own_inputs(kit: Registry) -> None:
    graph, first, second = two_instances(kit)
    solver = solved(graph)
    assert solver.result(first).output("Result").all_items() == [10.0]  # 2 * (2 + 3)
    assert solver.result(second).output("Result").all_items() == [22.0]  # 2 * (10 + 1)


def test_editing_the_definition_updates_every_instance(kit: Registry) -> None:
    graph, first, second = two_instances(kit)
    solver = solved(graph)
    edited = cluster_graph(graph, "doublesum")
    edited.disconnect(next(w for w in edited.wires_into("twice") if w.target_port == "B"))
    edited.set_input_value("twice", "B", 100.0)  # twice = sum + 100
    set_cluster_graph(graph, "doublesum", edited)
    solver.solve()
    assert solver.result(first).output("Result").all_items() == [105.0]
    assert solver.result(second).output("Result").all_items() == [111.0]
    assert solver.result("shown").output("Result").all_items() == [105.0]


def test_undoing_a_definition_edit_restores_the_outputs(kit: Registry) -> None:
    graph, first, _ = two_instances(kit)
    solver = Solver(graph)
    edited = cluster_graph(graph, "doublesum")
    edited.remove_node(definition_of(graph, "doublesum").outputs[0])  # the port's Output node
    change = set_cluster_graph(graph, "doublesum", edited)
    assert graph.nodes[first].node.output_ports() == ()
    assert {(w.source, w.target) for w in change.dropped} == {(first, "shown")}
    set_cluster_graph(graph, "doublesum", change.previous, change.previous_inputs, change.previous_outputs)
    for wire in change.dropped:
        graph.connect_wire(wire)
    solver.solve()
    assert solver.result("shown").output("Result").all_items() == [10.0]


def test_renaming_a_port_carries_the_outer_wires(kit: Registry) -> None:
    graph, first, second = two_instances(kit)
    rename_cluster_port(graph, "doublesum", "input", "A", "First")
    assert ("a", "Value", first, "First") in wire_set(graph)
    assert ("c", "Value", second, "First") in wire_set(graph)
    solver = solved(graph)
    assert solver.result(second).output("Result").all_items() == [22.0]


def test_a_definition_edit_that_would_contain_itself_is_refused(kit: Registry) -> None:
    graph, first, _ = two_instances(kit)
    edited = cluster_graph(graph, "doublesum")
    add_cluster_instance(edited, "doublesum", "inside")
    with pytest.raises(GraphError, match="contains itself"):
        set_cluster_graph(graph, "doublesum", edited)
    assert "inside" not in definition_of(graph, "doublesum").graph.nodes
    assert solved(graph).result(first).output("Result").all_items() == [10.0]


def test_a_cluster_made_inside_a_definition_nests(kit: Registry) -> None:
    graph, first, second = two_instances(kit)
    edited = cluster_graph(graph, "doublesum")
    make_cluster(edited, ["twice"], name="Doubler")
    set_cluster_graph(graph, "doublesum", edited)
    assert set(graph.clusters) == {"doublesum", "doubler"}
    solver = solved(graph)
    assert solver.result(first).output("Result").all_items() == [10.0]
    assert solver.result(second).output("Result").all_items() == [22.0]
    reopened = solved(loads(dumps(graph), kit))
    assert reopened.result(second).output("Result").all_items() == [22.0]


def test_reordering_ports_changes_only_their_order(kit: Registry) -> None:
    graph, first, _ = two_instances(kit)
    old = reorder_cluster_ports(graph, "doublesum", "input", ["B", "A"])
    assert old == ["A", "B"]
    assert [p.name for p in graph.nodes[first].node.input_ports()] == ["B", "A"]
    assert ("a", "Value", first, "A") in wire_set(graph)


# --------------------------------------------------------------------------- incremental solving

def counted_cluster(kit: Registry) -> tuple[Graph, str]:
    """x → p, y → q (two Counted nodes) in one cluster; an inner slider k → r (Counted)."""
    graph = Graph()
    slider(graph, kit, "x", 1.0)
    slider(graph, kit, "y", 2.0)
    slider(graph, kit, "k", 5.0)
    for node_id in ("p", "q", "r"):
        graph.add_node(Counted(), node_id)
    graph.connect("x", "Value", "p", "X")
    graph.connect("y", "Value", "q", "X")
    graph.connect("k", "Value", "r", "X")
    graph.add_node(kit.create("maths.Add"), "after")
    graph.connect("p", "Y", "after", "A")
    graph.add_node(kit.create("maths.Add"), "after_r")
    graph.connect("r", "Y", "after_r", "A")
    cluster = make_cluster(graph, ["p", "q", "k", "r"], name="Counting")
    return graph, cluster


def test_a_changed_cluster_input_re_solves_only_what_depends_on_it(kit: Registry) -> None:
    graph, cluster = counted_cluster(kit)
    solver = solved(graph)
    Counted.solves.clear()
    graph.set_setting("y", "value", 7.0)
    solver.solve()
    assert Counted.solves == [7.0]  # q only; p and r kept their results
    assert solver.cluster_solver(cluster).graph.nodes  # the instance's own inner graph


def test_an_unchanged_input_re_solves_nothing_inside(kit: Registry) -> None:
    graph, _ = counted_cluster(kit)
    solver = solved(graph)
    Counted.solves.clear()
    graph.set_setting("y", "value", 2.0)  # the same value: the cluster is expired, its input is not new
    solver.solve()
    assert Counted.solves == []


def test_a_slider_changed_inside_the_definition_re_solves_the_instance(kit: Registry) -> None:
    graph, _ = counted_cluster(kit)
    solver = solved(graph)
    edited = cluster_graph(graph, "counting")
    edited.set_setting("k", "value", 9.0)
    set_cluster_graph(graph, "counting", edited)
    Counted.solves.clear()
    solver.solve()
    assert 9.0 in Counted.solves
    assert solver.result("after_r").output("Result").all_items() == [9.0]


# --------------------------------------------------------------------------- trees and messages

def test_graft_on_a_cluster_port_matches_graft_on_the_inner_input(kit: Registry) -> None:
    def build() -> Graph:
        graph = Graph()
        graph.add_node(kit.create("params.Tree", {"branches": {"{0}": [1, 2, 3], "{1}": [4]}}), "tree")
        graph.add_node(kit.create("lists.ListLength"), "length")
        graph.connect("tree", "Tree", "length", "List")
        graph.add_node(kit.create("trees.BranchCount"), "branches")
        graph.connect("length", "Length", "branches", "Tree")
        return graph

    expanded = build()
    expanded.set_modifiers("length", "List", ["graft"])
    plain = solved(expanded)
    clustered = build()
    cluster = make_cluster(clustered, ["length"], name="Lengths")
    clustered.set_modifiers(cluster, "List", ["graft"])
    solver = solved(clustered)
    assert solver.result(cluster).output("Length") == plain.result("length").output("Length")
    # grafted: one branch per item, each of length 1
    assert solver.result(cluster).output("Length").to_dict() == {
        "{0;0}": [1], "{0;1}": [1], "{0;2}": [1], "{1;0}": [1]}


def test_an_error_inside_shows_on_the_cluster_naming_the_inner_node(kit: Registry) -> None:
    graph = Graph()
    slider(graph, kit, "x", 1.0)
    graph.add_node(kit.create("debug.Fail"), "broken", label="Broken step")
    graph.add_node(kit.create("maths.Add"), "fine")
    graph.connect("x", "Value", "broken", "X")
    graph.connect("x", "Value", "fine", "A")
    graph.add_node(kit.create("maths.Add"), "out1")
    graph.add_node(kit.create("maths.Add"), "out2")
    graph.connect("broken", "Y", "out1", "A")
    graph.connect("fine", "Result", "out2", "A")
    cluster = make_cluster(graph, ["broken", "fine"], name="Mixed")
    solver = solved(graph)
    result = solver.result(cluster)
    assert result.state == ERROR
    assert result.messages[0].text.startswith("Broken step: RuntimeError")
    assert result.output("Result").all_items() == [1.0]  # the healthy branch still gives its output


# --------------------------------------------------------------------------- bad files

def clustered_data(kit: Registry) -> dict[str, Any]:
    graph = two_adds(kit)
    make_cluster(graph, ["sum", "twice"], name="Double sum")
    return json.loads(dumps(graph))


def refusal(kit: Registry, data: dict[str, Any]) -> str:
    with pytest.raises(GraphFileError) as caught:
        loads(json.dumps(data), kit)
    return str(caught.value)


def test_a_missing_definition_is_refused_by_name(kit: Registry) -> None:
    data = clustered_data(kit)
    data["clusters"] = []
    assert "'doublesum', which is not in the file" in refusal(kit, data)


def test_a_definition_containing_itself_is_refused(kit: Registry) -> None:
    data = clustered_data(kit)
    definition = data["clusters"][0]
    definition["nodes"].append(
        {"id": "me", "type": "cluster.Cluster", "settings": {"definition": "doublesum"}})
    assert "cluster definition 'doublesum' contains itself (doublesum → doublesum)" in refusal(kit, data)


def test_definitions_containing_each_other_are_refused(kit: Registry) -> None:
    data = clustered_data(kit)
    other = {"id": "other", "name": "Other", "nodes": [
        {"id": "inner", "type": "cluster.Cluster", "settings": {"definition": "doublesum"}}]}
    data["clusters"][0]["nodes"].append(
        {"id": "loop", "type": "cluster.Cluster", "settings": {"definition": "other"}})
    data["clusters"].append(other)
    assert "contains itself (doublesum → other → doublesum)" in refusal(kit, data)


def test_a_wire_to_a_missing_cluster_port_is_refused(kit: Registry) -> None:
    data = clustered_data(kit)
    wire = next(w for w in data["wires"] if w["to"][1] == "A")
    wire["to"][1] = "Nowhere"
    assert "Double sum has no input called 'Nowhere'" in refusal(kit, data)


def test_a_port_list_naming_a_missing_node_is_refused(kit: Registry) -> None:
    data = clustered_data(kit)
    data["clusters"][0]["inputs"].append("ghost")
    assert "its inputs list names 'ghost'" in refusal(kit, data)


def test_clusters_nested_too_deep_are_refused(kit: Registry) -> None:
    data = clustered_data(kit)
    chain = [{"id": f"level{i}", "nodes": [
        {"id": "down", "type": "cluster.Cluster", "settings": {"definition": f"level{i + 1}"}}]}
        for i in range(MAX_NESTING + 1)]
    chain.append({"id": f"level{MAX_NESTING + 1}", "nodes": []})
    data["clusters"].extend(chain)
    assert f"nested more than {MAX_NESTING} deep" in refusal(kit, data)


def test_a_malformed_clusters_section_is_refused_without_a_traceback(kit: Registry) -> None:
    data = clustered_data(kit)
    data["clusters"][0]["inputs"] = "not a list"
    assert "not a valid graph" in refusal(kit, data)


# --------------------------------------------------------------------------- copy and paste

def fragment_of(graph: Graph, node_ids: list[str]) -> str:
    from torsal.engine.graphfile import FORMAT, VERSION, encode, fragment_clusters, node_data

    nodes = [node_data(graph.nodes[n]) for n in node_ids]
    return encode({"format": FORMAT, "version": VERSION, "nodes": nodes,
                   "clusters": fragment_clusters(graph, node_ids)})


def test_a_pasted_cluster_shares_the_same_definition(kit: Registry) -> None:
    from torsal.engine.graphfile import adopt_clusters

    graph = two_adds(kit)
    cluster = make_cluster(graph, ["sum", "twice"], name="Double sum")
    pasted = loads(fragment_of(graph, [cluster]), kit).nodes[cluster]
    pasted.id = "pasted"
    adopt_clusters(graph, [pasted])
    graph.add_record(pasted)
    assert pasted.node.definition is graph.nodes[cluster].node.definition


def test_a_pasted_cluster_whose_definition_differs_gets_its_own(kit: Registry) -> None:
    from torsal.engine.graphfile import adopt_clusters

    graph = two_adds(kit)
    cluster = make_cluster(graph, ["sum", "twice"], name="Double sum")
    text = fragment_of(graph, [cluster])
    rename_cluster_port(graph, "doublesum", "input", "A", "First")
    pasted = loads(text, kit).nodes[cluster]
    pasted.id = "pasted"
    adopt_clusters(graph, [pasted])
    assert pasted.node.definition.id == "doublesum2"
    assert graph.clusters["doublesum2"] is pasted.node.definition


# --------------------------------------------------------------------------- the format document

def test_the_format_documents_example_solves_as_it_says(library: Registry) -> None:
    doc = (Path(__file__).resolve().parents[2] / "docs" / "graph-format-clusters.md").read_text("utf-8")
    example = doc.split("```json\n", 1)[1].split("```", 1)[0]
    solver = solved(loads(example, library))
    assert solver.result("double").output("Result").to_dict() == {"{0}": [10.0]}  # 2 × (2 + 3)


def test_instances_multiplying_past_the_node_limit_are_refused(kit: Registry) -> None:
    data = clustered_data(kit)  # "doublesum": 5 nodes; each level holds 20 of the one below
    for level in range(1, 5):
        below = "doublesum" if level == 1 else f"many{level - 1}"
        nodes = [{"id": f"n{i}", "type": "cluster.Cluster", "settings": {"definition": below}}
                 for i in range(20)]
        data["clusters"].append({"id": f"many{level}", "nodes": nodes})
    data["nodes"].append({"id": "top", "type": "cluster.Cluster", "settings": {"definition": "many4"}})
    assert "expand to more than 200,000 nodes" in refusal(kit, data)  # 5 × 20⁴ = 800,000


def test_explode_carries_a_cluster_ports_graft_onto_the_inner_input(kit: Registry) -> None:
    graph = Graph()
    graph.add_node(kit.create("params.Tree", {"branches": {"{0}": [1, 2, 3]}}), "tree")
    graph.add_node(kit.create("lists.ListLength"), "length")
    graph.add_node(kit.create("trees.BranchCount"), "branches")
    graph.connect("tree", "Tree", "length", "List")
    graph.connect("length", "Length", "branches", "Tree")
    cluster = make_cluster(graph, ["length"], name="Lengths")
    graph.set_modifiers(cluster, "List", ["graft"])
    explode_cluster(graph, cluster)
    assert graph.nodes["length"].inputs["List"].modifiers == ["graft"]
    assert solved(graph).result("branches").output("Count").all_items() == [3]


def test_nodes_after_a_cluster_output_that_did_not_change_are_not_solved_again(kit: Registry) -> None:
    graph, _ = counted_cluster(kit)
    graph.add_node(Counted(), "p_after")
    graph.connect("after", "Result", "p_after", "X")  # after ← the cluster's p output, unchanged below
    solver = solved(graph)
    Counted.solves.clear()
    graph.set_setting("y", "value", 7.0)  # reaches q inside, which feeds no output
    report = solver.solve()
    assert Counted.solves == [7.0]
    assert "after" not in report.solved and "p_after" not in report.solved
    assert solver.result("p_after").output("Y").all_items() == [1.0]


def test_a_cluster_output_that_changed_re_solves_what_it_feeds(kit: Registry) -> None:
    graph, _ = counted_cluster(kit)
    solver = solved(graph)
    graph.set_setting("x", "value", 4.0)
    report = solver.solve()
    assert "after" in report.solved
    assert solver.result("after").output("Result").all_items() == [4.0]


def test_an_unwired_cluster_input_leaves_the_inner_inputs_to_their_defaults(kit: Registry) -> None:
    graph = two_adds(kit)
    cluster = make_cluster(graph, ["sum", "twice"], name="Double sum")
    solver = solved(graph)
    graph.disconnect(next(w for w in graph.wires_into(cluster) if w.target_port == "B"))
    solver.solve()
    assert solver.result(cluster).state == OK
    assert solver.result(cluster).output("Result").all_items() == [4.0]  # 2 × (2 + B's default 0)
    graph.connect("b", "Value", cluster, "B")
    solver.solve()
    assert solver.result(cluster).output("Result").all_items() == [10.0]


def test_clustering_a_cluster_past_the_nesting_limit_is_refused(kit: Registry) -> None:
    graph = two_adds(kit)
    node = make_cluster(graph, ["sum"], name="Level")
    for _ in range(MAX_NESTING - 1):
        node = make_cluster(graph, [node], name="Level")
    with pytest.raises(GraphError, match=f"nest {MAX_NESTING} deep"):
        make_cluster(graph, [node], name="Level")
    assert solved(graph).result("shown").output("Result").all_items() == [10.0]


def test_an_instance_that_would_expand_the_graph_past_the_limit_is_refused(kit: Registry) -> None:
    graph = two_adds(kit)
    cluster = make_cluster(graph, ["sum", "twice"], name="Double sum")  # 5 nodes inside
    edited = cluster_graph(graph, "doublesum")
    for i in range(1000):
        edited.add_node(kit.create("maths.Add"), f"pad{i}")
    set_cluster_graph(graph, "doublesum", edited)
    block = make_cluster(graph, [cluster], name="Block")
    for i in range(197):  # 198 blocks of 1,008 nodes (1,005 inside Double sum) and a, b, shown: 199,587
        add_cluster_instance(graph, "block", f"b{i}")
    with pytest.raises(GraphError, match="more than 200,000 nodes"):
        add_cluster_instance(graph, "block", "one_too_many")
    assert "one_too_many" not in graph.nodes and block in graph.nodes


# --------------------------------------------------------------------------- examples

def summaries(solver: Solver, node_id: str) -> str:
    """A node's outputs as the JSON ``torsal run`` prints (geometry compared by its summary)."""
    from torsal.engine.types import summarize_value

    outputs = solver.result(node_id).outputs
    data = {port: {path: [summarize_value(v) for v in items] for path, items in tree.to_dict().items()}
            for port, tree in outputs.items()}
    return json.dumps(data, sort_keys=True, default=str)


@pytest.mark.parametrize("example", ["guggenheim-ny", "zve-roof-edge"])
def test_clustering_the_middle_of_an_example_leaves_every_other_output_as_it_was(
        library: Registry, example: str) -> None:
    graph = read_graph(EXAMPLES / f"{example}.graph", library)
    solver = solved(graph)
    before = {n: summaries(solver, n) for n in graph.nodes}
    order = graph.order()
    third = len(order) // 3
    cluster = make_cluster(graph, order[third:2 * third + 1], name="Middle")
    definition = definition_of(graph, cluster)
    assert definition.inputs and definition.outputs
    reopened = solved(loads(dumps(graph), library))
    outside = [n for n in reopened.graph.nodes if n != cluster]
    assert {n: summaries(reopened, n) for n in outside} == {n: before[n] for n in outside}


def test_a_wire_inside_a_definition_to_a_missing_node_is_refused_naming_the_definition(kit: Registry) -> None:
    data = clustered_data(kit)
    data["clusters"][0]["wires"][0]["to"][0] = "ghost"
    assert refusal(kit, data).startswith(
        "cluster definition 'doublesum': wire input_a.Value → ghost.A refers to a node 'ghost' "
        "that is not in the definition")


def test_exploding_a_second_instance_gives_its_nodes_fresh_ids(kit: Registry) -> None:
    graph, first, second = two_instances(kit)
    explode_cluster(graph, first)
    restored = explode_cluster(graph, second)
    assert restored == ["sum2", "twice2"]
    assert {("c", "Value", "sum2", "A"), ("d", "Value", "sum2", "B"), ("sum2", "Result", "twice2", "A"),
            ("sum2", "Result", "twice2", "B")} <= wire_set(graph)
    assert solved(graph).result("twice2").output("Result").all_items() == [22.0]
    assert graph.clusters == {}
