"""A node's run state for one solve: cancel token, file access, progress, messages, scratch.

The solver makes one :class:`SolveContext` per node it solves and makes it *active*
(:func:`solving`) while that node's ``solve`` calls run; :class:`~torsal.engine.node.Node`'s
``warn``, ``remark``, ``token``, ``files``, ``progress`` and ``run_state`` read the
active context. Nothing of a solve is written on the node object, so one node object
can be solved by two solvers in two threads (the app's worker and a sweep) without
their messages or tokens mixing. The active context is a context variable: each
thread sees its own.

A node used on its own (a test calling ``solve``, a script) has no active context and
gets one of its own the first time it asks (:meth:`Node.own_context`).
"""

from __future__ import annotations

import contextvars
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from torsal.engine.messages import CancelToken, Message

if TYPE_CHECKING:
    from torsal.engine.call_budget import SolveBudget
    from torsal.engine.writes import NodeFiles


@dataclass(eq=False, slots=True)
class SolveContext:
    """What one solve of one node knows and collects.

    ``state`` is the node's scratch for the solve (counts that ``after_solve``
    summarises in one message); it starts empty each solve. ``with context:`` makes it
    the active one for the block (what :func:`solving` does).
    """

    #: The node being solved, told apart from others by identity alone (so this module
    #: needs nothing of the node class).
    node: object
    token: CancelToken | None = None
    files: NodeFiles | None = None
    on_progress: Callable[[float], None] | None = None
    messages: list[Message] = field(default_factory=list)
    state: dict[str, Any] = field(default_factory=dict)
    #: the solve's count of calls (:mod:`torsal.engine.call_budget`); None: not counted
    budget: SolveBudget | None = None
    #: a dry solve (``torsal check``): the nodes this says are planned and checked, not run
    dry: Callable[[Any], bool] | None = None  # given the node
    #: the host improves results after the solve (the app): see torsal/engine/improve.py
    anytime: bool = False
    improver: Any = None  #: what the node asked to run after its solve (an Improver)
    #: the distinct messages of ``messages``, so that :meth:`say` finds a repeat in one
    #: lookup (a solve of 280 strips says hundreds of messages, most of them repeats)
    _said: set[Message] = field(default_factory=set, repr=False)
    _reset: contextvars.Token[SolveContext | None] | None = field(default=None, repr=False)

    def say(self, message: Message) -> None:
        """Add ``message`` to :attr:`messages` unless this solve has said it already.
        ``say`` and :meth:`forget_since` are the only ways messages change, so the set of
        those said is always the list's."""
        if message not in self._said:
            self._said.add(message)
            self.messages.append(message)

    def forget_since(self, count: int) -> None:
        """Drop every message said after the first ``count``."""
        del self.messages[count:]
        self._said = set(self.messages)

    def __enter__(self) -> SolveContext:
        self._reset = _ACTIVE.set(self)
        return self

    def __exit__(self, *exc_info: object) -> None:
        if self._reset is not None:
            _ACTIVE.reset(self._reset)
            self._reset = None


_ACTIVE: contextvars.ContextVar[SolveContext | None] = contextvars.ContextVar(
    "torsal_solve_context", default=None
)


def active() -> SolveContext | None:
    """The context of the node being solved in this thread, if any."""
    return _ACTIVE.get()


def solving(context: SolveContext) -> SolveContext:
    """``with solving(context):`` makes ``context`` the active one for the block (the
    solver wraps each node's solve in it)."""
    return context
