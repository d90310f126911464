"""BendingCheck looks at the cancel token within a strip, between blocks of grid points
(counted, not timed: the 50 ms figure is in tests/benchmarks/bench_cancel.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support.cancelling import cancel_at_look
from torsal.engine.node import Cancelled
from torsal.nodes.analysis.bending import CHECK_BLOCK, BendingCheck, bending_radii
from torsal.nodes.geometry.parametric_surface import cylinder
from torsal.nodes.geometry.surface_base import uv_grid
from torsal.nodes.geometry.watch import watched


def test_bending_radii_checks_once_a_block_of_grid_points():
    calls = []
    u, v = uv_grid(100, 100)
    with watched(lambda: calls.append(1)):
        radii = bending_radii(cylinder(radius=0.35, height=2.0), u, v)
    assert len(calls) == math.ceil(100 * 100 / CHECK_BLOCK)
    assert np.allclose(radii, 0.35, rtol=1e-12)  # blocks change nothing: r everywhere


def test_a_cancel_during_one_dense_strip_stops_the_node_before_the_strip_is_done():
    node = BendingCheck()
    looks = cancel_at_look(node, 3)  # the token is cancelled inside the kernel
    with pytest.raises(Cancelled):
        node.solve([cylinder(radius=0.5, height=1.0)], "Steel 1.5 mm", "m", 1.0, 100)
    assert len(looks) == 3
