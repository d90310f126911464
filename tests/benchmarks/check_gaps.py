"""How often a solve looks at its cancel token: the longest stretch without a check, per node.

Esc is seen at the next check of the token, so the longest time between two checks
within a node (from its start to its first check, between checks, from its last check to
its end) is the longest a cancel can wait in that node. :func:`check_gaps` solves a graph
with a token that writes down the time of every check, and the solver's progress
callback marks where each node starts.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from itertools import pairwise

from torsal.engine.graph import Graph
from torsal.engine.node import CancelToken
from torsal.engine.solver import Solver


class RecordingToken(CancelToken):
    """A cancel token that notes the time of every check (and cancels itself ``stop_after``
    seconds after the first check, when given, to keep a long solve short)."""

    def __init__(self, stop_after: float | None = None) -> None:
        super().__init__()
        self.times: list[float] = []
        self.stop_after = stop_after

    def check(self) -> None:
        now = time.perf_counter()
        self.times.append(now)
        if self.stop_after is not None and now - self.times[0] > self.stop_after:
            self.cancel()
        super().check()


@dataclass
class NodeGaps:
    """One node's solve as the token saw it."""

    seconds: float  #: the node's time, from its start to the next node's (or the solve's end)
    checks: int  #: checks of the token while it ran
    longest: float  #: the longest time without a check while it ran


def check_gaps(graph: Graph, stop_after: float | None = None) -> dict[str, NodeGaps]:
    """Solve ``graph`` (every node) with a :class:`RecordingToken`; each solved node's gaps."""
    token = RecordingToken(stop_after)
    starts: list[tuple[float, str]] = []
    solver = Solver(graph)

    def started(_index: int, _total: int, node_id: str) -> None:
        starts.append((time.perf_counter(), node_id))

    solver.solve(token, progress=started)
    end = time.perf_counter()
    gaps: dict[str, NodeGaps] = {}
    for i, (start, node_id) in enumerate(starts):
        stop = starts[i + 1][0] if i + 1 < len(starts) else end
        inside = [t for t in token.times if start < t < stop]
        marks = [start, *inside, stop]
        longest = max(b - a for a, b in pairwise(marks))
        gaps[node_id] = NodeGaps(stop - start, len(inside), longest)
    return gaps
