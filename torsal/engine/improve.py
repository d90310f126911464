"""Node results that improve after the solve ("anytime" nodes), like an iterative nesting
plug-in in Grasshopper: the node answers at once with a good-enough result, and a search
goes on in the background, each better result replacing the last as it arrives.

The mechanism, in three small pieces:

- **A node** whose :attr:`~torsal.engine.node.Node.anytime` is true (the host supports it)
  returns its quick result from ``solve`` and calls
  :meth:`~torsal.engine.node.Node.improve_later` with an *improver*: a callable
  ``improver(stop, publish, progress)`` that searches, calls ``publish(values, remarks)``
  with each better result (``values`` as ``solve`` returns them, ``remarks`` the node's new
  remarks: a usage figure, say) and ``progress(fraction)`` as it goes, and returns when done
  or as soon as ``stop()`` says so (keeping its best). It runs on a thread of its own and
  must not touch the graph; the same inputs and seed should give the same final result.
- **The solver** (``Solver(..., anytime=True)``) keeps the improver with the node's result
  (:meth:`~torsal.engine.solver.Solver.improvers`) and takes each improvement with
  :meth:`~torsal.engine.solver.Solver.adopt`, which replaces the node's outputs and expires
  what is downstream, so the next solve re-solves only that and reports the node as solved
  (the viewport redraws it). A node solved again (an input changed) gets a fresh result and
  improver; an improvement of the old one is then refused as stale.
- **The host** runs improvers off the solve. The app runs each on a thread and adopts
  improvements on its GUI thread between solves (``torsal/app/gui/improvements.py``); Esc
  stops them, keeping the best. Headless, :func:`run_improvements` runs them one after the
  other for at most a given time (``torsal run --nesting-time S``), adopting each
  improvement, then solves what is downstream.

Without an anytime host (``torsal run`` without ``--nesting-time``, scripts, tests), nodes
compute their full result inside ``solve`` as before.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any, Protocol

from torsal.engine.node import CancelToken
from torsal.engine.solver import Solver

Publish = Callable[[Any, list[str]], None]


class Improver(Protocol):
    """Searches for a better result of one node's solve (see the module)."""

    def __call__(self, stop: Callable[[], bool], publish: Publish,
                 progress: Callable[[float], None]) -> None:
        ...


def run_improvements(solver: Solver, seconds: float | None = None, token: CancelToken | None = None,
                     node_progress: Callable[[str, float], None] | None = None) -> list[str]:
    """Run every pending improver of ``solver``'s results, one after the other, each until
    it ends, ``seconds`` (for all together) have passed, or ``token`` is cancelled; adopt
    each improvement and solve what is downstream. Returns the nodes improved."""
    deadline = None if seconds is None else time.monotonic() + max(0.0, float(seconds))
    token = token or CancelToken()
    improved: list[str] = []

    def stop() -> bool:
        return token.cancelled or (deadline is not None and time.monotonic() >= deadline)

    for node_id, improver in solver.improvers().items():
        best: list[tuple[Any, list[str]]] = []

        def publish(values: Any, remarks: list[str], best: list = best) -> None:
            best[:] = [(values, remarks)]

        def progress(fraction: float, node_id: str = node_id) -> None:
            if node_progress is not None:
                node_progress(node_id, fraction)

        if not stop():
            improver(stop, publish, progress)
        if best and solver.adopt(node_id, *best[0], improver=improver):
            improved.append(node_id)
        if node_progress is not None:
            node_progress(node_id, 1.0)
    if improved:
        solver.solve(token)
    return improved
