"""How many calls of ``solve`` one solve may make, per node and in all, counted before work.

A list input multiplies a node's calls (a Series of 1,000,000 into RulingDevelopable's
WarpTolerance asks for a million strip solves). The solver plans every call of a node
before the first (:func:`torsal.engine.solver.run_node`) and refuses, naming the node and
the input that multiplied it, when the plan passes

- the node's own budget (:attr:`Node.max_calls`; :attr:`Node.max_work` for nodes whose one
  call can take seconds), or
- the solve's budget, :data:`MAX_SOLVE_CALLS` calls of every node together (cluster
  instances' inner nodes included), kept in a :class:`SolveBudget`.

Such a refusal is a :class:`BudgetExceeded` (a node error). ``torsal check`` finds them
without the long work: it solves *dry* (``Solver(graph, dry=skip)``), where the nodes
``skip`` names — those that declared a budget of their own, and what the front-end knows
to be slow — are planned and checked but not run.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from dataclasses import dataclass, field

from torsal.engine.errors import NodeError

#: Calls of ``solve`` in one solve, every node together (the flagship makes ~10,000).
MAX_SOLVE_CALLS = 5_000_000


class BudgetExceeded(NodeError):
    """A node refused before its first call: too many calls or too much work."""


@dataclass
class SolveBudget:
    """The calls made so far in one solve (shared with the solves of cluster instances)."""

    limit: int = MAX_SOLVE_CALLS
    used: int = 0
    _lock: threading.Lock = field(default_factory=threading.Lock, repr=False)

    def spend(self, calls: int, why: Callable[[], str]) -> None:
        """Count ``calls`` more, or :class:`BudgetExceeded` (``why()`` names the node and
        its input) when they would pass the limit."""
        with self._lock:
            if self.used + calls > self.limit:
                raise BudgetExceeded(f"{why()}; with the {self.used:,} calls other nodes made, the solve "
                                     f"would pass its budget of {self.limit:,} calls in all")
            self.used += calls

    def reset(self) -> None:
        with self._lock:
            self.used = 0
