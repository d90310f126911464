"""A cut strip's pace: jumps of the pairing found where they are, and edges run by length.

Expected values are closed forms: a pairing with a step at a chosen x, and two edges of
known length (a segment and a circular arc that turns a quarter in 2e-5 of its parameter).
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.typing import ArrayLike

from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curves.line import Line
from torsal.nodes.geometry.developable.cut_pace import BISECTIONS, RAMP, by_length, jumps

STEP_AT, STEP = 0.4123456789, 0.3


def _stepped(x: ArrayLike) -> np.ndarray:
    x = np.asarray(x, dtype=float)
    return 0.5 * x + STEP * (x >= STEP_AT)


def test_a_step_of_the_pairing_is_crossed_on_a_ramp_around_it_wherever_the_samples_lie():
    rulings = np.array([0.0, 1.0])
    for count in (13, 29):
        x = np.linspace(0.0, 1.0, count)
        ramps = jumps(_stepped, x, _stepped(x), rulings, np.zeros(1, dtype=bool))
        assert ramps.shape == (1, 2)
        a, b = ramps[0]
        # the jump's bracket: the samples' gap halved BISECTIONS times
        assert a < STEP_AT < b and b - a <= 2 * RAMP + 2.0**-BISECTIONS / (count - 1) + 1e-15


def test_a_steep_smooth_pairing_has_no_jump_and_a_fan_is_skipped():
    x = np.linspace(0.0, 1.0, 13)
    steep = x**6  # slope up to 6: steep, but continuous
    one = np.array([0.0, 1.0])
    assert jumps(lambda t: np.asarray(t) ** 6, x, steep, one, np.zeros(1, bool)).shape == (0, 2)
    assert jumps(_stepped, x, _stepped(x), np.array([0.0, 1.0]), np.ones(1, bool)).shape == (0, 2)


def test_a_jump_at_a_ruling_starts_its_ramp_there():
    rulings = np.array([0.0, 0.5, 1.0])
    x = np.linspace(0.0, 1.0, 25)

    def partners(t: ArrayLike) -> np.ndarray:  # right of the ruling the partner is 0.2 further on
        t = np.asarray(t, dtype=float)
        return np.where(t > 0.5, np.minimum(t + 0.2, 1.0), t)

    tau = partners(x)
    ramps = jumps(partners, x, tau, rulings, np.zeros(2, dtype=bool))
    assert ramps.shape == (1, 2)
    assert ramps[0, 0] == 0.5 and 0.5 < ramps[0, 1] <= 0.5 + RAMP * 0.5 + 2.0**-BISECTIONS / 24 + 1e-15


class _Arc(Curve):
    """A circle of radius ``R`` turned 0.2 rad evenly over the parameter, and a quarter
    more between A and B (linearly: the arc a cone sweeps across a jump of the pace)."""

    R, A, B = 3.0, 0.5 - 1e-5, 0.5 + 1e-5

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[np.ndarray]:
        t = np.atleast_1d(np.asarray(t, dtype=float))
        inside = (t > self.A) & (t < self.B)
        theta = 0.2 * t + 0.5 * np.pi * np.clip((t - self.A) / (self.B - self.A), 0.0, 1.0)
        rate = 0.2 + np.where(inside, 0.5 * np.pi / (self.B - self.A), 0.0)
        ring = np.column_stack([np.cos(theta), np.sin(theta), np.zeros_like(t)])
        out = [self.R * ring]
        if order >= 1:
            along = np.column_stack([-np.sin(theta), np.cos(theta), np.zeros_like(t)])
            out.append(self.R * rate[:, None] * along)
        if order >= 2:
            out.append(-self.R * rate[:, None] ** 2 * ring)
        return out[: order + 1]


def test_edges_run_by_length_give_a_sweep_its_share_of_the_parameter():
    lower, upper = Line([0.0, 0.0, -1.0], [4.0, 0.0, -1.0]), _Arc()
    s = np.linspace(0.0, 1.0, 11)
    ramps = np.array([[_Arc.A, _Arc.B]])
    a, b, s_new = by_length(lower, upper, s, s, ramps, 0.0, 1.0)
    # the lines stay the lines: the same points at their new parameters
    np.testing.assert_allclose(a.point_at(s_new), lower.point_at(s), atol=1e-12)
    np.testing.assert_allclose(b.point_at(s_new), upper.point_at(s), atol=1e-12)
    # the sweep's share of the parameter is its share of the two edges' length (closed form)
    lengths = 4.0 + _Arc.R * (0.2 + 0.5 * np.pi)
    sweep = 4.0 * (_Arc.B - _Arc.A) + _Arc.R * (0.5 * np.pi + 0.2 * (_Arc.B - _Arc.A))
    i, j = np.searchsorted(a.at, [_Arc.A, _Arc.B])
    assert a.knots[j] - a.knots[i] == pytest.approx(sweep / lengths, rel=2e-3)
    # an even grid of the new parameter sees the arc in even steps (an even grid of the old
    # one stepped over the quarter turn in one step)
    t = np.linspace(0.0, 1.0, 401)
    steps = np.linalg.norm(np.diff(b.point_at(t), axis=0), axis=1)
    assert steps.max() <= 3.0 * lengths / 400
    old = np.linalg.norm(np.diff(upper.point_at(t), axis=0), axis=1)
    assert old.max() > 20 * steps.max()
    # derivatives: the chain rule through the new pace, against central differences
    u, h = np.array([0.1, 0.45, 0.7, 0.93]), 1e-7
    for edge in (a, b):
        numeric = (edge.point_at(u + h) - edge.point_at(u - h)) / (2 * h)
        np.testing.assert_allclose(edge.derivatives(u, 1)[1], numeric, rtol=1e-6, atol=1e-6)
