"""An item-access node whose calls each take a while is checked for a cancel between them.

The solver used to look at the token every 4,096 calls only, so 236 strips of a few
milliseconds each ran to the end after Esc. It now checks once 20 ms have passed, reading
the clock after every call of 1 ms or more.
"""

from __future__ import annotations

import time

from tests.benchmarks.check_gaps import check_gaps
from torsal.engine.graph import Graph
from torsal.engine.node import In, Node, Out
from torsal.engine.types import NUMBER


class Slow(Node):
    """Sleeps 2 ms per item (at least: a sleep never ends early)."""

    type_id = "test.SlowItems"
    inputs = (In("X", NUMBER, "X", "Numbers."),)
    outputs = (Out("Y", NUMBER, "Y", "The same numbers."),)

    def solve(self, x: float) -> float:
        time.sleep(0.002)
        return x


def test_a_hundred_slow_calls_are_checked_for_a_cancel_between_them():
    graph = Graph()
    graph.add_node(Slow(), "slow")
    graph.set_input_value("slow", "X", [float(i) for i in range(100)])
    gaps = check_gaps(graph)["slow"]
    # 100 calls of >= 2 ms take >= 200 ms: a check each 20 ms is at least 9; the old
    # count (every 4,096 calls) made none
    assert gaps.checks >= 5
