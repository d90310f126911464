"""Node results that improve after the solve (torsal/engine/improve.py)."""

from __future__ import annotations

from torsal.engine.graph import Graph
from torsal.engine.improve import run_improvements
from torsal.engine.node import CancelToken, In, Node, Out, Setting
from torsal.engine.solver import OK, Solver
from torsal.engine.types import NUMBER


class Search(Node):
    """Answers ``start`` at once; in an anytime host, improves it to start + 1, + 2 … + steps."""

    type_id = "test.Search"
    outputs = (Out("Value", NUMBER, "V"),)
    settings_spec = (Setting("start", float, 1.0), Setting("steps", int, 3))

    def solve(self) -> float:
        start, steps = float(self.settings["start"]), int(self.settings["steps"])
        if self.anytime:
            def improve(stop, publish, progress):  # type: ignore[no-untyped-def]
                for k in range(1, steps + 1):
                    if stop():
                        return
                    publish(start + k, [f"found {start + k:g}"])
                    progress(k / steps)

            self.improve_later(improve)
        self.remark("quick answer")
        return start


class AddTen(Node):
    type_id = "test.AddTen"
    inputs = (In("A", NUMBER, "A"),)
    outputs = (Out("Result", NUMBER, "R"),)

    def solve(self, a: float) -> float:
        return a + 10.0


def _graph(start: float = 1.0) -> Graph:
    graph = Graph()
    graph.add_node(Search({"start": start, "steps": 3}), "search")
    graph.add_node(AddTen(), "plus")
    graph.connect("search", "Value", "plus", "A")
    return graph


def test_without_an_anytime_host_a_node_answers_in_full_and_has_no_improver():
    solver = Solver(_graph())
    solver.solve()
    assert solver.result("plus").output("Result").all_items() == [11.0]
    assert solver.improvers() == {}


def test_an_improvement_replaces_the_result_and_solves_only_what_is_downstream():
    solver = Solver(_graph(), anytime=True)
    solver.solve()
    assert solver.result("plus").output("Result").all_items() == [11.0]  # the quick answer at once
    assert list(solver.improvers()) == ["search"]
    heard: list[tuple[str, float]] = []
    assert run_improvements(solver, node_progress=lambda n, f: heard.append((n, f))) == ["search"]
    assert solver.result("search").output("Value").all_items() == [4.0]  # the best: start + steps
    assert [m.text for m in solver.result("search").messages] == ["found 4"]
    assert solver.result("search").state == OK
    assert solver.result("plus").output("Result").all_items() == [14.0]
    assert heard[-1] == ("search", 1.0) and len(heard) >= 3


def test_a_stopped_search_keeps_the_best_it_found():
    solver = Solver(_graph(), anytime=True)
    solver.solve()
    token = CancelToken()
    token.cancel()
    assert run_improvements(solver, token=token) == []  # stopped before it began: the quick answer
    assert solver.result("plus").output("Result").all_items() == [11.0]
    assert run_improvements(solver, seconds=0.0) == []


def test_an_improvement_of_a_result_solved_again_since_is_refused_as_stale():
    graph = _graph()
    solver = Solver(graph, anytime=True)
    solver.solve()
    old = solver.improvers()["search"]
    graph.set_setting("search", "start", 5.0)  # an edit: the node is solved again
    solver.solve()
    published = []
    old(lambda: False, lambda values, remarks: published.append(values), lambda f: None)
    assert solver.adopt("search", published[-1]) is True  # the new result's improver is there…
    assert solver.result("search").improver is not old  # … but the old search is not it
    assert solver.result("search").improver is not None


def test_the_next_solve_reports_the_improved_node_as_solved():
    solver = Solver(_graph(), anytime=True)
    solver.solve()
    assert solver.adopt("search", 9.0, ["better"])
    report = solver.solve()
    assert report.solved[:2] == ["search", "plus"]
    assert solver.result("plus").output("Result").all_items() == [19.0]
