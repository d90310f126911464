"""Seeded random numbers: the same seed gives the same numbers on every run and machine."""

from __future__ import annotations

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import DOMAIN, INTEGER, NUMBER
from torsal.engine.values import Domain
from torsal.nodes.common.checks import finite, whole
from torsal.nodes.limits import MAX_NUMBERS


class Random(Node):
    """Random numbers spread evenly over a domain, repeatable through their seed.

    The same Seed always gives the same numbers, so a graph solves identically each
    time it is opened; change the Seed for another set. Number = 3 over 0 to 10 gives
    three numbers between 0 and 10.
    """

    type_id = "maths.Random"
    nickname, aliases = "Rnd", ("random numbers",)
    inputs = (
        In("Range", DOMAIN, "R", "The interval the numbers fall in.", default=Domain(0.0, 1.0)),
        In("Number", INTEGER, "N", "How many numbers to make (0 or more).", default=10,
           min=0, max=MAX_NUMBERS),
        In("Seed", INTEGER, "S", "Any whole number 0 or more; each seed gives its own numbers.",
           default=0, min=0),
    )
    outputs = (Out("Random", NUMBER, "R", "The random numbers, in the Range.", access=LIST),)

    def solve(self, domain: Domain, number: int, seed: int) -> np.ndarray:
        if domain is None:
            raise NodeWarning("Range is empty (null)")
        low, high = finite("Range start", domain.min), finite("Range end", domain.max)
        n, s = whole("Number", number), whole("Seed", seed)  # bounded on the ports
        rng = np.random.default_rng(s)
        return low + (high - low) * rng.random(n)  # kept as an array branch
