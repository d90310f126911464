"""Cancellation and progress for long kernels, without threading them through every call.

A node wraps a long kernel call in ``with watched(self.check_cancelled, self.progress):``;
kernels deep inside (the adaptive area cubature, a NURBS surface's span rules, the
development map's closest-point search) call :func:`watch_check` between blocks of work
(a few tens of milliseconds each), which raises the node's ``Cancelled`` when the user
pressed Esc, and report the fraction done to :func:`watch_progress`. Outside a
``watched`` block both are None and the kernels run as before. The state is a context
variable, so solves in other threads are not affected.
"""

from __future__ import annotations

import contextlib
import contextvars
from collections.abc import Callable, Iterator

Check = Callable[[], None]
Progress = Callable[[float], None]

_WATCH: contextvars.ContextVar[tuple[Check | None, Progress | None]] = contextvars.ContextVar(
    "kernel_watch", default=(None, None)
)


@contextlib.contextmanager
def watched(check: Check | None, progress: Progress | None = None) -> Iterator[None]:
    """Within this block the kernels call ``check`` between blocks of work (it stops
    them by raising) and report the fraction done to ``progress``."""
    token = _WATCH.set((check, progress))
    try:
        yield
    finally:
        _WATCH.reset(token)


def watch_check() -> Check | None:
    """The ``check`` of the enclosing :func:`watched` block, if any."""
    return _WATCH.get()[0]


def watch_progress() -> Progress | None:
    """The ``progress`` of the enclosing :func:`watched` block, if any."""
    return _WATCH.get()[1]
