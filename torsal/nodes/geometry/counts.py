"""The kernel's one check of a count it is handed: Segments (rulings minus one) and the
like (an unrolled strip's subdivisions).

Nodes check what a designer typed with its own words and bounds (``nodes/common/checks.py``,
the port's declared bounds); a kernel function called directly (a script, a test) checks
its count here, once, the same way everywhere.
"""

from __future__ import annotations

from typing import Any


def segment_count(segments: Any, name: str = "Segments") -> int:
    """``segments`` as an int: a whole number of at least 1, else a ValueError that says so
    (naming the count ``name``).

    >>> segment_count(4.0)
    4
    """
    if int(segments) != segments or segments < 1:
        raise ValueError(f"{name} must be a whole number >= 1; got {segments}.")
    return int(segments)
