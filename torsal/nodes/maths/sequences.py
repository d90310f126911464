"""Number sequences: evenly stepped series and evenly divided ranges."""

from __future__ import annotations

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import DOMAIN, INTEGER, NUMBER
from torsal.engine.values import Domain
from torsal.nodes.common.checks import finite, whole
from torsal.nodes.limits import MAX_NUMBERS


class Series(Node):
    """Count numbers up from Start in equal steps: Start, Start + Step, Start + 2·Step, …

    Start = 1, Step = 0.5, Count = 4 gives [1.0, 1.5, 2.0, 2.5]. Each Count you give
    makes its own list.
    """

    type_id = "maths.Series"
    nickname, aliases = "Series", ("arithmetic sequence", "count up")
    inputs = (
        In("Start", NUMBER, "S", "The first number of the series.", default=0.0),
        In("Step", NUMBER, "N", "The difference between neighbouring numbers.", default=1.0),
        In("Count", INTEGER, "C", "How many numbers to make (0 or more).", default=10,
           min=0, max=MAX_NUMBERS),
    )
    outputs = (Out("Series", NUMBER, "S", "The numbers, Start first.", access=LIST),)

    def solve(self, start: float, step: float, number: int) -> np.ndarray:
        start, step = finite("Start", start), finite("Step", step)
        n = whole("Count", number)  # 0 to MAX_NUMBERS: the port's bounds
        return start + step * np.arange(n, dtype=np.float64)  # kept as an array branch


class Range(Node):
    """Divide a domain into equal steps: Steps + 1 numbers from its start to its end.

    Domain 0 to 10 with Steps = 4 gives [0.0, 2.5, 5.0, 7.5, 10.0]. A reversed domain
    (10 to 0) counts down.
    """

    type_id = "maths.Range"
    nickname, aliases = "Range", ("divide domain",)
    inputs = (
        In("Domain", DOMAIN, "D", "The interval to divide, from its start to its end.",
           default=Domain(0.0, 1.0)),
        In("Steps", INTEGER, "N", "How many equal steps to divide it into (1 or more).", default=10,
           min=1, max=MAX_NUMBERS),
    )
    outputs = (Out("Range", NUMBER, "R", "The Steps + 1 numbers, both ends included.", access=LIST),)

    def solve(self, domain: Domain, steps: int) -> np.ndarray:
        if domain is None:
            raise NodeWarning("Domain is empty (null)")
        low, high = finite("Domain start", domain.min), finite("Domain end", domain.max)
        n = whole("Steps", steps)  # 1 to MAX_NUMBERS: the port's bounds
        values = np.linspace(low, high, n + 1)
        values[-1] = high  # exactly the end, whatever the rounding
        return values  # kept as an array branch
