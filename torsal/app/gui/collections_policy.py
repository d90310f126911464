"""When Python's garbage collector may scan the whole heap.

A full (generation-2) collection scans every object the window holds: a tenth to a
third of a second with a large example open, during which no thread runs Python. While
a slider is dragged that is a frame or two lost, so :class:`FullCollectionsHeld` holds
them off for the drag (the young generations are still collected, which is where a
solve's short-lived garbage goes) and lets them run again when it ends.

Start-up is the other such time: importing Qt, pyvista (with VTK and matplotlib), scipy
and the node library allocates a million objects that live as long as the app, and the
collector, run every 700 allocations, scans them again and again on the way: about 0.3
CPU seconds of the ~2 before the first solved frame (four full collections ~0.2, the
young ones ~0.1; measured on the flagship, see ``tests/benchmarks/bench_startup.py``),
none of which frees anything worth having. :class:`StartUpCollectionsHeld` switches
automatic collection off from launch until the first solved frame has been drawn (or
the process has used :data:`START_UP_LIMIT_S` CPU seconds, whichever comes first), then
on again.
"""

from __future__ import annotations

import gc

#: Generation-1 collections before a full one while held (CPython's default is 10): a
#: drag of minutes makes far fewer.
HELD_THRESHOLD = 1_000_000
#: Automatic collection stays off at most until the process has used this many CPU seconds
#: (every thread), however long the first solve takes: what a long first solve leaves in
#: reference cycles meanwhile is bounded by what it can allocate in that much work. CPU
#: seconds, not wall: a loaded machine stretches the wall time of the same start-up.
START_UP_LIMIT_S = 10.0


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


class StartUpCollectionsHeld:
    """Automatic collection off from :meth:`hold` (at launch) to :meth:`release` (after
    the first solved frame, or at :data:`START_UP_LIMIT_S` CPU seconds; the caller
    arranges both).

    Nothing is collected by hand at the release: the first young collection after it
    (the app's next allocations) goes through what start-up left, as the collector would
    have at its own pace. If automatic collection was already off (a host that manages
    it), it is left as it was.
    """

    def __init__(self) -> None:
        self._held = False

    @property
    def held(self) -> bool:
        return self._held

    def hold(self) -> None:
        if not self._held and gc.isenabled():
            gc.disable()
            self._held = True

    def release(self) -> None:
        if self._held:
            self._held = False
            gc.enable()
