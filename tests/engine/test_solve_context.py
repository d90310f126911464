"""A solve's run state (messages, token, progress, scratch) lives in a per-solve context,
not on the node object: one node object solved by two solvers at once keeps them apart."""

from __future__ import annotations

import threading

from tests.engine.test_solver import Constant
from torsal.engine.errors import NodeWarning
from torsal.engine.graph import Graph
from torsal.engine.node import In, Level, Message, Node, Out
from torsal.engine.solve_context import SolveContext
from torsal.engine.solver import WARNING, Solver
from torsal.engine.types import NUMBER


class Shared(Node):
    """Warns with its input, waiting in between for the other solve to get as far."""

    type_id = "test.Shared"
    inputs = (In("A", NUMBER, "A", "Anything."),)
    outputs = (Out("Result", NUMBER, "R", "A."),)
    both_inside = threading.Barrier(2, timeout=10)

    def before_solve(self) -> None:
        self.run_state["calls"] = 0

    def solve(self, a: float) -> float:
        self.run_state["calls"] += 1
        Shared.both_inside.wait()
        self.warn(f"saw {a:g}")
        Shared.both_inside.wait()
        return a

    def after_solve(self) -> None:
        self.remark(f"{self.run_state['calls']} call")


def graph_with(node: Node, value: float) -> Graph:
    graph = Graph()
    graph.add_node(Constant({"value": value}), "c")
    graph.add_node(node, "shared")
    graph.connect("c", "Value", "shared", "A")
    return graph


def test_one_node_object_solved_by_two_solvers_at_once_keeps_each_solves_messages():
    node = Shared()
    solvers = [Solver(graph_with(node, 1.0)), Solver(graph_with(node, 2.0))]
    threads = [threading.Thread(target=s.solve) for s in solvers]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(timeout=20)
    texts = [[m.text for m in s.result("shared").messages] for s in solvers]
    assert texts == [["saw 1", "1 call"], ["saw 2", "1 call"]]
    assert all(s.result("shared").state == WARNING for s in solvers)


def test_a_solve_leaves_no_messages_on_the_node():
    class Warns(Node):
        type_id = "test.Warns"
        outputs = (Out("Result", NUMBER, "R", "One."),)

        def solve(self) -> float:
            self.warn("careful")
            return 1.0

    node = Warns()
    graph = Graph()
    graph.add_node(node, "w")
    solver = Solver(graph)
    solver.solve()
    assert [m.text for m in solver.result("w").messages] == ["careful"]
    assert node.messages == []  # the node's own run state (used on its own) is untouched


def test_a_node_used_on_its_own_hears_its_own_progress_listener():
    class Halfway(Node):
        type_id = "test.Halfway"
        outputs = (Out("Result", NUMBER, "R", "One."),)

        def solve(self) -> float:
            self.progress(0.5)
            return 1.0

    node, heard = Halfway(), []
    node.on_progress = heard.append
    node.solve()
    graph = Graph()
    graph.add_node(node, "h")
    from_solver: list[tuple[str, float]] = []
    Solver(graph).solve(node_progress=lambda node_id, f: from_solver.append((node_id, f)))
    assert heard == [0.5] and from_solver == [("h", 0.5)]


def test_a_message_said_again_in_one_solve_is_kept_once_in_the_order_first_said():
    context = SolveContext(object())
    a, b, warned_b = Message(Level.WARNING, "a"), Message(Level.REMARK, "b"), Message(Level.WARNING, "b")
    for message in (a, b, Message(Level.WARNING, "a"), warned_b):
        context.say(message)
    assert context.messages == [a, b, warned_b]


def test_messages_forgotten_are_said_anew():
    context = SolveContext(object())
    context.say(Message(Level.WARNING, "a"))
    context.say(Message(Level.WARNING, "b"))
    context.forget_since(1)
    context.say(Message(Level.WARNING, "b"))  # forgotten: said anew
    context.say(Message(Level.WARNING, "a"))  # kept: not repeated
    assert [m.text for m in context.messages] == ["a", "b"]


def test_a_node_that_raises_after_saying_the_same_warning_shows_it_once():
    class Twice(Node):
        type_id = "test.Twice"
        outputs = (Out("Value", NUMBER, "V", "The value."),)

        def solve(self) -> float:
            self.warn("too narrow")
            raise NodeWarning("too narrow")

    graph = Graph()
    graph.add_node(Twice(), "t")
    solver = Solver(graph)
    solver.solve()
    result = solver.result("t")
    assert [(m.level, m.text) for m in result.messages] == [(Level.WARNING, "too narrow")]
