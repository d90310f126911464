"""``torsal check``'s count of the calls a solve would make, found without the long work.

The graph is solved *dry* (:mod:`torsal.engine.call_budget`): every node is planned and
its calls counted against its own budget and the solve's. The nodes that declared a
budget of their own (strip solvers, analyses) and those of the palettes whose nodes do
the long work or touch files (:data:`SKIPPED_PALETTES`: developable, analysis,
patching, io, display) stop there instead of running, so a graph that asks
RulingDevelopable for a million strips is refused in well under a second. The nodes that
make the lists (params, maths, lists, curves, surfaces, transform) run for real, since
their outputs are what multiplies the calls downstream; a node fed by a skipped one gets
nothing, so its calls are counted by ``run`` only. A dry solve that takes longer than
:data:`CHECK_SECONDS` stops and says how far it got. Nothing is written.
"""

from __future__ import annotations

import threading
from collections.abc import Iterator
from dataclasses import dataclass

from torsal.engine.call_budget import MAX_SOLVE_CALLS
from torsal.engine.cluster import ClusterNode
from torsal.engine.graph import Graph
from torsal.engine.node import MAX_CALLS, CancelToken, Node
from torsal.engine.solver import Solver
from torsal.engine.writes import WriteAccess

CHECK_SECONDS = 5.0
#: Palettes whose nodes a dry solve plans but does not run: the long work and the files.
SKIPPED_PALETTES = ("developable", "analysis", "patching", "io", "display")


def is_heavy(node: Node) -> bool:
    """Whether ``node`` declared a budget of its own (its calls are costly)."""
    return node.max_calls < MAX_CALLS or node.max_work is not None


def skipped(node: Node) -> bool:
    """Whether a dry solve plans ``node`` without running it."""
    return is_heavy(node) or node.type_id.split(".", 1)[0] in SKIPPED_PALETTES


@dataclass
class BudgetReport:
    """What a dry solve found: the refusals (``node path: message``), the calls counted
    and whether it stopped at :data:`CHECK_SECONDS`."""

    refusals: list[str]
    calls: int
    stopped: bool

    def summary(self) -> str:
        counted = f"{self.calls:,} calls of the solve's {MAX_SOLVE_CALLS:,}"
        return counted + (f" (counted for the nodes solved in {CHECK_SECONDS:g} s)" if self.stopped else "")


def check_budget(graph: Graph) -> BudgetReport:
    """Solve ``graph`` dry and report the calls it would make and the nodes refused."""
    solver = Solver(graph, WriteAccess(), dry=skipped)
    token = CancelToken()
    timer = threading.Timer(CHECK_SECONDS, token.cancel)
    timer.daemon = True
    timer.start()
    try:
        report = solver.solve(token)
    finally:
        timer.cancel()
    return BudgetReport(list(_refusals(solver, "")), solver.budget.used, report.cancelled)


def _refusals(solver: Solver, prefix: str) -> Iterator[str]:
    for node_id, text in solver.refused:
        yield f"{prefix}{node_id}: {text}"
    for node_id, record in solver.graph.nodes.items():
        if isinstance(record.node, ClusterNode):
            inner = solver.cluster_solver(node_id)
            if inner is not None:
                yield from _refusals(inner, f"{prefix}{node_id}/")
