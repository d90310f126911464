"""Node.solve_many: all of a solve's item calls in one, across branches, or row by row."""

from __future__ import annotations

from torsal.engine.datatree import DataTree
from torsal.engine.node import LIST, In, Node, NodeError, NodeWarning, Out
from torsal.engine.solve_context import SolveContext, solving
from torsal.engine.solver import run_node
from torsal.engine.types import NUMBER


class Halve(Node):
    """x / 2 per item; ``solve_many`` does every row at once unless told to decline."""

    type_id = "test.Halve"
    inputs = (In("X", NUMBER, "X"), In("Y", NUMBER, "Y", default=0.0))
    outputs = (Out("Half", NUMBER, "H"), Out("Sum", NUMBER, "S"))

    def __init__(self, decline: bool = False) -> None:
        super().__init__()
        self.decline = decline
        self.batches: list[tuple[tuple[float, ...], ...]] = []
        self.calls = 0

    def solve(self, x: float, y: float) -> tuple[float, float]:
        self.calls += 1
        if x < 0:
            raise NodeWarning(f"X is negative: {x:g}")
        return x / 2, x + y

    def solve_many(self, xs, ys):
        self.batches.append((tuple(xs), tuple(ys)))
        if self.decline or any(x < 0 for x in xs):
            return None
        return [(x / 2, x + y) for x, y in zip(xs, ys, strict=True)]


class PlainHalve(Halve):
    """The same node without ``solve_many``: calls ``solve`` row by row."""

    solve_many = Node.solve_many


def _trees(x: dict, y: dict) -> list[DataTree]:
    return [DataTree(x), DataTree(y)]


def test_one_call_across_branches_gives_the_outputs_of_the_calls_row_by_row():
    x = {(0,): [1.0, 2.0, 3.0], (1,): [4.0], (2,): [5.0, 6.0]}
    y = {(0,): [10.0]}
    node, plain = Halve(), PlainHalve()
    outputs = run_node(node, _trees(x, y), [True, True])
    expected = run_node(plain, _trees(x, y), [True, True])
    assert {p: t.to_dict() for p, t in outputs.items()} == {p: t.to_dict() for p, t in expected.items()}
    assert node.batches == [((1.0, 2.0, 3.0, 4.0, 5.0, 6.0), (10.0,) * 6)]
    assert node.calls == 0 and plain.calls == 6


def test_branches_of_one_call_each_keep_their_paths():
    x = {(0, i): [float(i)] for i in range(4)}
    node = Halve()
    outputs = run_node(node, _trees(x, {(0,): [1.0]}), [True, True])
    assert outputs["Half"].to_dict() == {"{0;0}": [0.0], "{0;1}": [0.5], "{0;2}": [1.0], "{0;3}": [1.5]}
    assert len(node.batches) == 1


def test_a_declined_batch_is_solved_row_by_row_with_the_messages_of_solve():
    x = {(0,): [1.0, -2.0, 3.0]}
    node = Halve()
    outputs = run_node(node, _trees(x, {(0,): [0.0]}), [True, True])
    assert outputs["Half"].to_dict() == {"{0}": [0.5, None, 1.5]}
    assert node.calls == 3
    assert [m.text for m in node.messages] == ["X is negative: -2"]


def test_a_single_call_is_not_batched():
    node = Halve()
    outputs = run_node(node, _trees({(0,): [4.0]}, {(0,): [1.0]}), [True, True])
    assert outputs["Sum"].to_dict() == {"{0}": [5.0]}
    assert node.batches == [] and node.calls == 1


class Total(Node):
    """A list-access node: its calls are per branch, never batched."""

    type_id = "test.Total"
    inputs = (In("X", NUMBER, "X", access=LIST),)
    outputs = (Out("Sum", NUMBER, "S"),)

    def solve(self, xs):
        return float(sum(xs))

    def solve_many(self, xs):
        raise AssertionError("list access is not batched")


def test_list_access_calls_are_not_batched():
    outputs = run_node(Total(), [DataTree({(0,): [1.0, 2.0], (1,): [3.0]})], [True])
    assert outputs["Sum"].to_dict() == {"{0}": [3.0], "{1}": [3.0]}


class TalkingHalve(Halve):
    """Halve whose rows say things: a remark per odd x, a warning (and None) per negative x,
    an error at x = 99; ``solve_many`` says them itself, in row order."""

    def solve(self, x: float, y: float) -> tuple[float, float]:
        if x == 99:
            raise NodeError("X is 99")
        if x % 2 == 1:
            self.remark(f"X is odd: {x:g}")
        return super().solve(x, y)

    def solve_many(self, xs, ys):
        self.batches.append((tuple(xs), tuple(ys)))
        if self.decline:
            self.remark("said before declining")
            return None
        results = []
        for x, y in zip(xs, ys, strict=True):
            if x == 99:
                raise NodeError("X is 99")
            if x % 2 == 1:
                self.remark(f"X is odd: {x:g}")
            if x < 0:
                self.refuse_row(NodeWarning(f"X is negative: {x:g}"))
                results.append(None)
            else:
                results.append((x / 2, x + y))
        return results


class PlainTalkingHalve(TalkingHalve):
    solve_many = Node.solve_many


def _solved(node: Node, x: dict) -> tuple[dict, list[tuple[str, str]]]:
    """The outputs and messages of one solve of ``node`` (an error as its last message)."""
    context = SolveContext(node)
    with solving(context):
        try:
            outputs = run_node(node, _trees(x, {(0,): [0.0]}), [True, True])
            found = {p: t.to_dict() for p, t in outputs.items()}
        except NodeError as exc:
            node.warn(f"error: {exc}")
            found = {}
    return found, [(m.level.name, m.text) for m in context.messages]


def test_the_rows_messages_said_by_a_batch_are_kept_in_the_order_of_the_rows():
    x = {(0,): [1.0, -3.0, 2.0], (1,): [3.0, 1.0]}
    batched, plain = TalkingHalve(), PlainTalkingHalve()
    assert _solved(batched, x) == _solved(plain, x)
    assert batched.calls == 0 and len(batched.batches) == 1
    assert [text for _, text in _solved(TalkingHalve(), x)[1]] == [
        "X is odd: 1", "X is odd: -3", "X is negative: -3", "X is odd: 3",
    ]


def test_an_error_in_a_batch_comes_after_the_messages_of_the_rows_before_it():
    x = {(0,): [1.0, 99.0, 3.0]}
    batched, plain = TalkingHalve(), PlainTalkingHalve()
    assert _solved(batched, x) == _solved(plain, x)
    assert _solved(TalkingHalve(), x)[1] == [("REMARK", "X is odd: 1"), ("WARNING", "error: X is 99")]


def test_what_a_declining_batch_said_is_forgotten():
    x = {(0,): [1.0, 2.0]}
    declining = TalkingHalve(decline=True)
    assert _solved(declining, x) == _solved(PlainTalkingHalve(), x)
    assert declining.calls == 2
