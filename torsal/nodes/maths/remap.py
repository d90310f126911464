"""Domains taken apart, numbers mapped from one domain to another, and the domain of a list."""

from __future__ import annotations

from typing import Any

import numpy as np

from torsal.engine.datatree import Branch
from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import DOMAIN, NUMBER
from torsal.engine.values import Domain
from torsal.nodes.common.checks import finite, given

UNIT = Domain(0.0, 1.0)


def _ends(name: str, value: Any) -> tuple[float, float]:
    domain = given(name, value)
    return finite(f"{name} start", domain.min), finite(f"{name} end", domain.max)


class DeconstructDomain(Node):
    """The start and end of a domain."""

    type_id = "maths.DeconstructDomain"
    nickname, aliases = "DeDom", ("Deconstruct Domain", "domain ends", "domain start")
    inputs = (In("Domain", DOMAIN, "I", "The domain to take apart.", default=UNIT),)
    outputs = (
        Out("Start", NUMBER, "S", "The number the domain starts at."),
        Out("End", NUMBER, "E", "The number the domain ends at."),
    )

    def solve(self, domain: Any) -> tuple[float, float]:
        return _ends("Domain", domain)


class Remap(Node):
    """Map numbers from a Source domain onto a Target domain, keeping their proportions.

    A value a quarter of the way through Source lands a quarter of the way through
    Target: ``T0 + (v − S0)·(T1 − T0)/(S1 − S0)``. A value outside Source lands outside
    Target (Clipped holds it at Target's ends). Leave Source unset to use the list's
    own smallest and largest value, as Grasshopper's Bounds → Remap does.
    """

    type_id = "maths.Remap"
    nickname, aliases = "ReMap", ("Remap Numbers", "normalise", "normalize", "rescale", "map range")
    inputs = (
        In("Values", NUMBER, "V", "The numbers to map.", access=LIST, arrays=True),
        In("Source", DOMAIN, "S", "The domain they come from (unset: from their smallest to largest).",
           optional=True),
        In("Target", DOMAIN, "T", "The domain to map them onto.", default=UNIT),
    )
    outputs = (
        Out("Mapped", NUMBER, "R", "Each value mapped onto Target.", access=LIST),
        Out("Clipped", NUMBER, "C", "Each mapped value held inside Target.", access=LIST),
    )

    def solve(self, values: Branch, source: Any, target: Any) -> tuple[list[float], list[float]]:
        if any(v is None for v in values):
            raise NodeWarning("Values contains empty (null) items: remove them or fix what made them")
        array = np.asarray(list(values), dtype=float)
        if array.size == 0:
            return [], []
        if not np.all(np.isfinite(array)):
            raise NodeWarning("Values contains a number that is not finite")
        if source is None:
            s0, s1 = float(array.min()), float(array.max())
        else:
            s0, s1 = _ends("Source", source)
        t0, t1 = _ends("Target", target)
        if s0 == s1:
            if source is not None:
                raise NodeWarning(f"Source is empty ({s0:g} to {s1:g}): it must run over an interval")
            self.remark("Every value is the same, so each maps to the middle of Target")
            mapped = np.full(array.shape, 0.5 * (t0 + t1))
        else:
            mapped = t0 + (array - s0) * ((t1 - t0) / (s1 - s0))
        clipped = np.clip(mapped, min(t0, t1), max(t0, t1))
        return mapped.tolist(), clipped.tolist()


class Bounds(Node):
    """The domain a list of numbers spans: from its smallest to its largest."""

    type_id = "maths.Bounds"
    nickname, aliases = "Bnd", ("Bounds", "min max", "range of numbers", "extent")
    inputs = (In("Numbers", NUMBER, "N", "The numbers to span.", access=LIST, arrays=True),)
    outputs = (Out("Domain", DOMAIN, "I", "From the smallest number to the largest."),)

    def solve(self, numbers: Branch) -> Domain:
        if any(v is None for v in numbers):
            raise NodeWarning("Numbers contains empty (null) items: remove them or fix what made them")
        array = np.asarray(list(numbers), dtype=float)
        if array.size == 0:
            raise NodeWarning("Numbers is empty, so it spans no domain")
        if not np.all(np.isfinite(array)):
            raise NodeWarning("Numbers contains a number that is not finite")
        return Domain(float(array.min()), float(array.max()))
