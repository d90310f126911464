"""Domains: numeric intervals, made from their two ends."""

from __future__ import annotations

from torsal.engine.node import In, Node, Out
from torsal.engine.types import DOMAIN, NUMBER
from torsal.engine.values import Domain as DomainValue
from torsal.nodes.common.checks import finite


class Domain(Node):
    """An interval of numbers from Start to End, such as the 0 to 1 of a curve's parameter.

    Start may be larger than End: the domain is then reversed, and a Range over it
    counts down.
    """

    type_id = "maths.Domain"
    nickname, aliases = "Dom", ("Construct Domain", "interval")
    inputs = (
        In("Start", NUMBER, "A", "The number the interval starts at.", default=0.0),
        In("End", NUMBER, "B", "The number the interval ends at.", default=1.0),
    )
    outputs = (Out("Domain", DOMAIN, "D", "The interval from Start to End."),)

    def solve(self, start: float, end: float) -> DomainValue:
        return DomainValue(finite("Start", start), finite("End", end))
