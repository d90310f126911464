"""Rationalise looks at the cancel token inside its kernel: before each trial strip and
each Newton step of the closest-point search (counted, not timed: the 50 ms figure is in
tests/benchmarks/bench_cancel.py)."""

from __future__ import annotations

import numpy as np
import pytest

from tests.support.cancelling import cancel_at_look
from torsal.engine.node import Cancelled
from torsal.nodes.developable.rationalise import Rationalise
from torsal.nodes.geometry.parametric_surface import ParametricSurface
from torsal.nodes.geometry.watch import watched


class Stop(Exception):
    """What the watching check raises (a node's Cancelled in the app)."""


def saddle() -> ParametricSurface:
    """z = (x² − y²) / 20 on [-5, 5]²."""
    square = (-5.0, 5.0)
    return ParametricSurface(lambda x, y: np.column_stack([x, y, (x**2 - y**2) / 20]), square, square)


def test_the_closest_point_search_looks_at_the_watching_check():
    calls = []
    with watched(lambda: calls.append(1)):
        saddle().closest_point(np.array([[1.0, 2.0, 3.0], [-2.0, 0.5, -1.0]]))
    assert len(calls) >= 1


def test_a_check_that_raises_stops_the_closest_point_search():
    def stop() -> None:
        raise Stop

    with watched(stop), pytest.raises(Stop):
        saddle().closest_point(np.array([[1.0, 2.0, 3.0]]))


def test_a_cancel_during_one_design_stops_the_node_before_its_strips_are_done():
    node = Rationalise()
    looks = cancel_at_look(node, 3)  # the token is cancelled inside the kernel
    with pytest.raises(Cancelled):
        node.solve(saddle(), 0.02, 40, None, [], 8, 1e-7)
    assert len(looks) == 3
