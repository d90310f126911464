"""SurfacePatching looks at the cancel token inside its kernel: between blocks of pattern
copies clipped to the development, of segments tested for crossings and of points carried
onto the strip (counted, not timed: the 50 ms figure is in tests/benchmarks/bench_cancel.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support.cancelling import cancel_at_look
from torsal.engine.node import Cancelled
from torsal.nodes.geometry.curves.line import Polyline
from torsal.nodes.geometry.development_map import CROSSING_BLOCK, MAP_BLOCK
from torsal.nodes.geometry.parametric_surface import cylinder
from torsal.nodes.geometry.unroll import unroll_surface
from torsal.nodes.geometry.watch import watched
from torsal.nodes.patching.surface_patching import SurfacePatching

RADIUS, HEIGHT = 1.0, 2.0


@pytest.fixture(scope="module")
def development():
    """A cylinder of radius 1 and height 2, unrolled: a 2π × 2 rectangle."""
    return unroll_surface(cylinder(radius=RADIUS, height=HEIGHT), 48)


def test_points_carried_onto_the_strip_look_at_the_check_once_a_block(development):
    calls = []
    xmin, ymin, xmax, ymax = development.bounds
    rng = np.random.default_rng(0)
    k = 3 * MAP_BLOCK + 5
    points = np.column_stack([rng.uniform(xmin, xmax, k), rng.uniform(ymin, ymax, k)])
    with watched(lambda: calls.append(1)):
        mapped = development.map.to_3d(points)
    assert len(calls) == 4
    # on the cylinder (to its chords' sagitta, 1 − cos(π/48) ≈ 2.1e-3, between rulings)
    assert np.allclose(np.hypot(mapped[:, 0], mapped[:, 1]), RADIUS, atol=2.2e-3)


def test_segments_tested_for_crossings_look_at_the_check_once_a_block(development):
    calls = []
    xmin, ymin, xmax, ymax = development.bounds
    x = np.linspace(xmin, xmax, 2 * CROSSING_BLOCK + 2)
    lines = [np.array([[a, ymin + 0.1 * (ymax - ymin)], [a, ymax - 0.1 * (ymax - ymin)]]) for a in x[:-1]]
    with watched(lambda: calls.append(1)):
        development.map.subdivide_many(lines)
    assert len(calls) == math.ceil(len(lines) / CROSSING_BLOCK) + 2  # and twice in the sort


def square(x0: float, y0: float, size: float) -> Polyline:
    return Polyline(np.array([[x0, y0, 0.0], [x0 + size, y0, 0.0], [x0 + size, y0 + size, 0.0],
                              [x0, y0 + size, 0.0]]), closed=True)


def test_a_cancel_during_the_tiling_stops_the_node_before_its_panels_are_made(development):
    node = SurfacePatching()
    looks = cancel_at_look(node, 3)  # the token is cancelled inside the kernel
    with pytest.raises(Cancelled):
        node.solve(None, development, [square(0.0, 0.0, 0.1)], square(0.0, 0.0, 0.1), 1.0, 0.0, 1)
    assert len(looks) == 3
