"""The strip solver can be stopped between its steps (Esc in the app)."""

import pytest

from tests.support.curve_pairs import PAIRS
from torsal.nodes.geometry.developable import ruling_developable
from torsal.nodes.geometry.watch import watched


class Stop(Exception):
    """What the watching check raises (a node's Cancelled in the app)."""


def test_the_strip_solver_looks_at_the_watching_check_between_its_steps():
    pair = PAIRS["cone"]()
    calls = []
    with watched(lambda: calls.append(1)):
        ruling_developable(pair.a, pair.b, 200)
    assert len(calls) >= 5  # stations, partner search, fans, a check round, end cones


def test_a_check_that_raises_stops_the_strip_solver():
    pair = PAIRS["cone"]()

    def stop() -> None:
        raise Stop

    with watched(stop), pytest.raises(Stop):
        ruling_developable(pair.a, pair.b, 200)
