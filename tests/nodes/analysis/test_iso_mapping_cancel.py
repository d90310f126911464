"""IsoMapping looks at the cancel token inside its unrolling: before each refined sampling
of the rails and between the stages of laying the strip down (counted, not timed: the
50 ms figure is in tests/benchmarks/bench_cancel.py)."""

from __future__ import annotations

import numpy as np
import pytest

from tests.support.cancelling import cancel_at_look
from torsal.engine.node import Cancelled
from torsal.nodes.analysis.iso_mapping import IsoMapping
from torsal.nodes.geometry.parametric_surface import cone
from torsal.nodes.geometry.unroll import unroll_rulings
from torsal.nodes.geometry.watch import watched


class Stop(Exception):
    """What the watching check raises (a node's Cancelled in the app)."""


def half_cylinder() -> tuple[np.ndarray, np.ndarray]:
    """Rulings of half a cylinder of radius 1 and height 2."""
    phi = np.linspace(0.0, np.pi, 9)
    base = np.column_stack([np.cos(phi), np.sin(phi), 0.0 * phi])
    return base, base + np.array([0.0, 0.0, 2.0])


def test_laying_a_strip_down_looks_at_the_watching_check_between_its_stages():
    calls = []
    with watched(lambda: calls.append(1)):
        development = unroll_rulings(*half_cylinder())
    assert len(calls) == 3  # after the frames, after the triangle map, after the edge check
    assert development.ends2d[-1] == pytest.approx([16 * np.sin(np.pi / 16), 2.0])  # 8 chords


def test_a_check_that_raises_stops_laying_the_strip_down():
    def stop() -> None:
        raise Stop

    with watched(stop), pytest.raises(Stop):
        unroll_rulings(*half_cylinder())


def test_a_cancel_during_one_unrolling_stops_the_node_before_it_is_done():
    node = IsoMapping()
    looks = cancel_at_look(node, 3)  # the token is cancelled inside the kernel
    with pytest.raises(Cancelled):
        node.solve(cone(radius=1.0, height=2.0), 100, 1)
    assert len(looks) == 3
