"""A march's last strip narrower than MinWidth, merged into the one before it or widened.

Marching strips as wide as the tolerance allows from one edge of the design to the other
leaves what is left for the last strip, which can be any width (0.12 m on a wave at 5 cm,
where MinWidth is 0.2 m). :func:`last_two` remakes the last two strips: as one strip where
that is within the tolerance; else with the boundary between them moved back so that the
last is MinWidth wide (the one before is then only narrower: still within the tolerance,
and kept only while it is at least MinWidth too); else as they were.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Protocol, TypeVar

#: The last strip is aimed this much wider than MinWidth.
AIM = 1.01


class _Strip(Protocol):
    lo: float
    hi: float
    deviation: float

    @property
    def width(self) -> float: ...


S = TypeVar("S", bound=_Strip)


def last_two(make: Callable[[float, float], S | None], before: S, last: S, end: float,
             tolerance: float, min_width: float) -> list[S]:
    """The strips in place of ``before`` and ``last`` (levels ``before.lo`` … ``end``), made
    by ``make(lo, hi)`` (None where no strip can be made)."""
    merged = make(before.lo, end)
    if merged is not None and merged.deviation <= tolerance:
        return [merged]
    # the level of the boundary that makes the last strip MinWidth wide (a little more: the
    # boundaries do not move quite evenly), from its width per level so far
    middle, second, wide = last.lo, last, 0.0
    for _ in range(3):
        middle = end - (end - second.lo) * AIM * min_width / max(second.width, 1e-300)
        if not before.lo < middle < before.hi:
            return [before, last]
        made = make(middle, end)
        if made is None:
            return [before, last]
        second = made
        if second.width >= min_width:
            wide = second.width
            break
    first = make(before.lo, middle)
    if first is None or not wide:
        return [before, last]
    if first.deviation <= tolerance and first.width >= min_width and second.deviation <= tolerance:
        return [first, second]
    return [before, last]
