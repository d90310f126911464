"""When Python's garbage collector may scan the whole heap.

A full (generation-2) collection scans every object the window holds: a tenth to a
third of a second with a large example open, during which no thread runs Python. While
a slider is dragged that is a frame or two lost, so :class:`FullCollectionsHeld` holds
them off for the drag (the young generations are still collected, which is where a
solve's short-lived garbage goes) and lets them run again when it ends.
"""

from __future__ import annotations

import gc

#: Generation-1 collections before a full one while held (CPython's default is 10): a
#: drag of minutes makes far fewer.
HELD_THRESHOLD = 1_000_000


class FullCollectionsHeld:
    """Holds full collections off between :meth:`hold` and :meth:`release` (nested holds
    count; the thresholds found at the first hold come back at the last release)."""

    def __init__(self) -> None:
        self._depth = 0
        self._saved: tuple[int, ...] | None = None

    @property
    def held(self) -> bool:
        return self._depth > 0

    def hold(self) -> None:
        if self._depth == 0:
            self._saved = gc.get_threshold()
            young, middle, _full = self._saved
            gc.set_threshold(young, middle, HELD_THRESHOLD)
        self._depth += 1

    def release(self) -> None:
        if self._depth == 0:
            return
        self._depth -= 1
        if self._depth == 0 and self._saved is not None:
            gc.set_threshold(*self._saved)
            self._saved = None
