"""The graph's incremental indexes, and its bulk edits.

The graph keeps the wires into and out of each node and a topological rank of every
node up to date edit by edit (see :mod:`torsal.engine.graph`). After any sequence of edits
they must say what a rebuild from the wire list says; the bulk edits ``add_many`` and
``remove_many`` must emit exactly the events of the single edits they stand for.
"""

from __future__ import annotations

import contextlib
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tests.support.nodekit import Add
from torsal.engine.graph import Graph, GraphError, Group, NodeRecord, Wire
from torsal.engine.node import In, Node, Out, Setting
from torsal.engine.solver import Solver
from torsal.engine.types import NUMBER


class Ports(Node):
    """Inputs named by its ``names`` setting, read afresh on every call (as Expression's)."""

    type_id = "test.Ports"
    outputs = (Out("Result", NUMBER, "R"),)
    settings_spec = (Setting("names", list, ["x", "y"]),)

    def input_ports(self) -> tuple[In, ...]:
        return tuple(In(n, NUMBER, n, default=0.0, multiple=True) for n in self.settings["names"])

    def solve(self, *values: float) -> float:
        return sum(values)


def rebuilt_into(graph: Graph) -> dict[str, list[Wire]]:
    into: dict[str, list[Wire]] = {}
    for wire in graph.wires:
        into.setdefault(wire.target, []).append(wire)
    return into


def rebuilt_from(graph: Graph) -> dict[str, list[Wire]]:
    out: dict[str, list[Wire]] = {}
    for wire in graph.wires:
        out.setdefault(wire.source, []).append(wire)
    return out


def reaches_by_search(graph: Graph, start: str, goal: str) -> bool:
    """Whether ``goal`` is downstream of ``start``, by a plain search of the wire list."""
    seen, stack = {start}, [start]
    while stack:
        current = stack.pop()
        if current == goal:
            return True
        for wire in graph.wires:
            if wire.source == current and wire.target not in seen:
                seen.add(wire.target)
                stack.append(wire.target)
    return False


def assert_indexes_match_a_rebuild(graph: Graph) -> None:
    into, out = rebuilt_into(graph), rebuilt_from(graph)
    for node_id in graph.nodes:
        assert graph.wires_into(node_id) == into.get(node_id, [])
        assert graph.wires_from(node_id) == out.get(node_id, [])
    order = graph.order()
    assert sorted(order) == sorted(graph.nodes)
    position = {n: i for i, n in enumerate(order)}
    assert all(position[w.source] < position[w.target] for w in graph.wires)
    assert graph.in_order(reversed(order)) == order
    ids = list(graph.nodes)
    for start in ids[:6]:
        for goal in ids[-6:]:
            assert graph.reaches(start, goal) == reaches_by_search(graph, start, goal)
            assert graph.upstream(goal) == {n for n in ids if n != goal and reaches_by_search(graph, n, goal)}


EDIT = st.tuples(st.sampled_from(["add", "connect", "disconnect", "remove", "rename"]), st.integers(0, 10**6))


def apply_edit(graph: Graph, kind: str, seed: int, made: list[int]) -> None:
    ids = list(graph.nodes)
    if kind == "add" or not ids:
        made[0] += 1
        node = Ports() if seed % 3 == 0 else Add()
        graph.add_node(node, f"n{made[0]}")
        return
    pick = ids[seed % len(ids)]
    if kind == "connect":
        target = ids[(seed // 7) % len(ids)]
        ports = [p.name for p in graph.nodes[target].node.input_ports()]
        with contextlib.suppress(GraphError):  # a loop, an input already fed: nothing changes
            graph.connect(pick, "Result", target, ports[(seed // 49) % len(ports)] if ports else "x")
    elif kind == "disconnect" and graph.wires:
        graph.disconnect(graph.wires[seed % len(graph.wires)])
    elif kind == "remove":
        graph.remove_node(pick)
    elif kind == "rename" and isinstance(graph.nodes[pick].node, Ports):
        graph.set_setting(pick, "names", [["x", "y"], ["x"], ["y", "z"], []][seed % 4])


@settings(max_examples=60, deadline=None)
@given(st.lists(EDIT, max_size=60))
def test_after_any_edits_the_indexes_equal_a_rebuild_from_the_wire_list(edits):
    graph = Graph()
    made = [0]
    for kind, seed in edits:
        apply_edit(graph, kind, seed, made)
    assert_indexes_match_a_rebuild(graph)


def test_a_wire_running_backward_in_the_ranks_reorders_only_what_lies_between():
    graph = Graph()
    for name in ["c", "a", "b", "d"]:  # added in an order the wires then contradict
        graph.add_node(Add(), name)
    graph.connect("b", "Result", "c", "A")
    graph.connect("a", "Result", "b", "A")
    graph.connect("c", "Result", "d", "A")
    order = graph.order()
    assert order.index("a") < order.index("b") < order.index("c") < order.index("d")


def test_a_wire_that_would_close_a_loop_is_refused_and_changes_nothing():
    graph = Graph()
    for name in "abc":
        graph.add_node(Add(), name)
    graph.connect("a", "Result", "b", "A")
    graph.connect("b", "Result", "c", "A")
    with pytest.raises(GraphError, match="loop"):
        graph.connect("c", "Result", "a", "A")
    assert graph.wires_into("a") == [] and graph.order() == ["a", "b", "c"]


def test_a_setting_that_removes_a_port_unplugs_only_that_ports_wires():
    graph = Graph()
    graph.add_node(Add(), "src")
    graph.add_node(Ports(), "p")
    graph.add_node(Add(), "other")
    graph.connect("src", "Result", "p", "x")
    graph.connect("src", "Result", "p", "y")
    graph.connect("p", "Result", "other", "A")
    graph.set_setting("p", "names", ["x"])
    assert [str(w) for w in graph.wires] == ["src.Result → p.x", "p.Result → other.A"]


def test_the_solver_solves_only_the_expired_nodes_in_topological_order():
    graph = Graph()
    for name in ["d", "c", "b", "a", "side"]:
        graph.add_node(Add(), name)
    graph.connect("a", "Result", "b", "A")
    graph.connect("b", "Result", "c", "A")
    graph.connect("c", "Result", "d", "A")
    solver = Solver(graph)
    solver.solve()
    graph.set_input_value("b", "B", 2.0)
    assert solver.solve().solved == ["b", "c", "d"]
    assert solver.result("d").outputs["Result"].first() == 2.0


def test_the_solver_forgets_the_results_of_removed_nodes():
    graph = Graph()
    graph.add_node(Add(), "a")
    graph.add_node(Add(), "b")
    solver = Solver(graph)
    solver.solve()
    graph.remove_node("a")
    solver.solve()
    assert set(solver.results) == {"b"}


# --------------------------------------------------------------------------- bulk edits

def recorded(graph: Graph) -> list[tuple[str, str | None, Any]]:
    events: list[tuple[str, str | None, Any]] = []
    graph.subscribe(lambda e: events.append((e.kind, e.node_id, getattr(e, "wire", None))))
    return events


def base_graph() -> Graph:
    graph = Graph()
    for name in ["s", "t", "u"]:
        graph.add_node(Add(), name)
    graph.connect("s", "Result", "t", "A")
    graph.connect("t", "Result", "u", "A")
    graph.expired.clear()
    return graph


def pasted() -> tuple[list[NodeRecord], list[Wire]]:
    records = [NodeRecord(n, Add(), "maths.Add") for n in ["p", "q", "r"]]
    wires = [
        Wire("q", "Result", "r", "A"),
        Wire("p", "Result", "q", "A"),
        Wire("s", "Result", "p", "B"),
        Wire("r", "Result", "u", "B"),
    ]
    return records, wires


def test_add_many_emits_the_events_of_the_single_edits_and_leaves_the_same_graph():
    one_by_one, bulk = base_graph(), base_graph()
    single_events, bulk_events = recorded(one_by_one), recorded(bulk)
    records, wires = pasted()
    for record in records:
        one_by_one.add_record(record)
    for wire in wires:
        one_by_one.connect_wire(wire)
    bulk.add_many(*pasted())
    assert bulk_events == single_events
    assert bulk.wires == one_by_one.wires and list(bulk.nodes) == list(one_by_one.nodes)
    assert bulk.expired == one_by_one.expired
    assert_indexes_match_a_rebuild(bulk)


def test_add_many_with_a_bad_wire_takes_everything_out_again():
    graph = base_graph()
    records, wires = pasted()
    wires.append(Wire("u", "Result", "p", "A"))  # u is fed by r, fed by q, by p: a loop
    with pytest.raises(GraphError, match="loop"):
        graph.add_many(records, wires)
    assert list(graph.nodes) == ["s", "t", "u"]
    assert [str(w) for w in graph.wires] == ["s.Result → t.A", "t.Result → u.A"]
    assert_indexes_match_a_rebuild(graph)


def test_remove_many_emits_the_events_of_removing_each_node_in_turn():
    one_by_one, bulk = base_graph(), base_graph()
    for graph in (one_by_one, bulk):
        graph.add_many(*pasted())
        graph.groups.append(Group("g", nodes=["p", "s", "q"]))
    single_events, bulk_events = recorded(one_by_one), recorded(bulk)
    for node_id in ["q", "t", "p"]:
        one_by_one.remove_node(node_id)
    removed = bulk.remove_many(["q", "t", "p"])
    assert bulk_events == single_events
    assert [r.id for r in removed] == ["q", "t", "p"]
    assert bulk.groups[0].nodes == ["s"] == one_by_one.groups[0].nodes
    assert bulk.wires == one_by_one.wires and bulk.expired == one_by_one.expired
    assert_indexes_match_a_rebuild(bulk)


def test_remove_many_with_an_unknown_id_removes_nothing():
    graph = base_graph()
    with pytest.raises(GraphError, match="no node"):
        graph.remove_many(["s", "missing"])
    assert list(graph.nodes) == ["s", "t", "u"]


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.booleans(), st.integers(0, 50)), max_size=40))
def test_new_id_is_always_the_smallest_free_number(steps):
    graph = Graph()
    for add, seed in steps:
        ids = list(graph.nodes)
        if add or not ids:
            expected = "add" if "add" not in graph.nodes else next(
                f"add{n}" for n in range(2, 10**6) if f"add{n}" not in graph.nodes
            )
            assert graph.new_id("Add") == expected
            graph.add_node(Add())
        else:
            graph.remove_node(ids[seed % len(ids)])


def test_an_expired_id_that_is_not_a_node_is_left_out_of_the_solve():
    graph = base_graph()
    graph.expire("ghost")
    graph.expire("t")
    assert Solver(graph).solve().solved == ["t", "u"]
