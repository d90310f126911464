"""A cone's rail run at an even pace along its length (threedm_rails.Lengthwise): a rail that
sweeps most of its length in a sliver of its interval (a cut strip's edge round a fan) comes
out at one speed. Expected values: closed-form curves."""

from __future__ import annotations

import numpy as np

from torsal.nodes.geometry.curves.parametric import ParametricCurve
from torsal.nodes.io.formats.threedm_rails import Lengthwise


def _sweeping() -> ParametricCurve:
    """A quarter circle of radius 2 at the angle (π/2)·(1 − (1 − t)^40000): 98 % of its
    length in the first 1e-4 of t, monotone and smooth."""
    def angle(t):
        return 0.5 * np.pi * (1.0 - (1.0 - t) ** 40000)

    def point(t):
        a = angle(np.asarray(t, dtype=float))
        return np.column_stack([2.0 * np.cos(a), 2.0 * np.sin(a), 0.0 * a])

    def first(t):
        t = np.asarray(t, dtype=float)
        a, da = angle(t), 0.5 * np.pi * 40000 * (1.0 - t) ** 39999
        return np.column_stack([-2.0 * np.sin(a) * da, 2.0 * np.cos(a) * da, 0.0 * a])

    return ParametricCurve(point, (0.0, 1.0), [first])


def test_a_sweeping_rail_runs_at_one_pace_along_its_length_through_the_same_points():
    rail = _sweeping()
    lengthwise = Lengthwise(rail, 0.0, 0.5)
    # the same ends, the same curve (every point on the circle)
    np.testing.assert_allclose(lengthwise.point_at([0.0, 0.5]), rail.point_at([0.0, 0.5]), atol=1e-12)
    u = np.linspace(0.0, 0.5, 101)
    points = lengthwise.point_at(u)
    np.testing.assert_allclose(np.linalg.norm(points[:, :2], axis=1), 2.0, atol=1e-12)
    # at an even pace along its length: the angle (arc length / 2) even in u
    ends = np.arctan2(*rail.point_at([0.0, 0.5])[:, [1, 0]].T)
    angles = np.arctan2(points[:, 1], points[:, 0])
    np.testing.assert_allclose(angles, np.linspace(ends[0], ends[1], 101), atol=1e-6)
    # its speed the length over the interval, everywhere but at t = 0.5, where the rail stands
    # still ((1 − t)^39999 underflows: the exporter unstalls a rail before it runs it lengthwise)
    speed = np.linalg.norm(lengthwise.derivatives(u[:-1], 1)[1], axis=1)
    np.testing.assert_allclose(speed, 2.0 * (ends[1] - ends[0]) / 0.5, rtol=1e-4)
