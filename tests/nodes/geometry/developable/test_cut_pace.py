"""A cut strip's pace: jumps of the pairing found where they are, and edges run by length.

Expected values are closed forms: a pairing with a step at a chosen x, two edges of
known length (a segment and a circular arc that turns a quarter in 2e-5 of its parameter),
segments run at known uneven speeds (their length a power of their parameter) and an arc
turned by the square of its parameter.
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
    # the ramp's ends are where the pace says its speed jumps (a fitted rail's triple knots)
    np.testing.assert_array_equal(a.jumps, a.knots[[i, j]])
    np.testing.assert_array_equal(b.jumps, a.jumps)
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


class _Uneven(Curve):
    """The segment from ``origin`` along ``direction`` (a unit vector) run at an uneven
    pace: at parameter c it has gone ``reach`` · c**``power``."""

    def __init__(self, origin: ArrayLike, direction: ArrayLike, reach: float, power: float) -> None:
        self.origin, self.direction = np.asarray(origin, float), np.asarray(direction, float)
        self.reach, self.power = reach, power

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[np.ndarray]:
        t = np.atleast_1d(np.asarray(t, dtype=float))
        n, L = self.power, self.reach
        along = [L * t**n, L * n * t ** (n - 1), L * n * (n - 1) * t ** max(n - 2, 0)]
        out = [self.origin + along[0][:, None] * self.direction]
        out += [a[:, None] * self.direction for a in along[1: order + 1]]
        return out[: order + 1]


class _Turning(Curve):
    """A circle of radius ``R`` in z = 1 turned by ``TURN`` · c² rad at parameter c: its
    length from 0 is R · TURN · c²."""

    R, TURN = 2.0, 0.5

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[np.ndarray]:
        t = np.atleast_1d(np.asarray(t, dtype=float))
        theta, rate = self.TURN * t**2, 2.0 * self.TURN * t
        ring = np.column_stack([np.cos(theta), np.sin(theta), np.zeros_like(t)])
        along = np.column_stack([-np.sin(theta), np.cos(theta), np.zeros_like(t)])
        out = [self.R * ring + np.array([0.0, 0.0, 1.0])]
        if order >= 1:
            out.append(self.R * rate[:, None] * along)
        if order >= 2:
            out.append(self.R * (2.0 * self.TURN * along - rate[:, None] ** 2 * ring))
        return out[: order + 1]


#: Lines of the sheet the pace is made through (uneven: the stretches differ in length).
LINES = np.array([0.0, 0.07, 0.2, 0.26, 0.5, 0.61, 0.9, 1.0])
NO_RAMPS = np.empty((0, 2))


def _segments() -> tuple[_Uneven, _Uneven]:
    """Two parallel segments, one at an even speed (length 4), one at a cubic one (length 9)."""
    return (_Uneven([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], 4.0, 1.0),
            _Uneven([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], 9.0, 3.0))


def test_each_stretch_takes_its_share_of_the_parameter_by_the_edges_summed_length():
    lower, upper = _segments()
    _, _, lines = by_length(lower, upper, LINES, LINES, NO_RAMPS, 0.0, 1.0)
    # closed form: along a segment the chords are its length, 4·c on one edge and 9·c³ on
    # the other, so the line at c is at (4·c + 9·c³) / 13
    np.testing.assert_allclose(lines, (4.0 * LINES + 9.0 * LINES**3) / 13.0, rtol=0, atol=1e-15)
    assert lines[0] == 0.0 and lines[-1] == 1.0
    # the same for an arc turned by the square of its parameter, whose chords fall a share
    # φ²/24 short of its arcs of φ (each chord of 1/8 of a stretch turns φ ≤ 0.3 · 2 · 0.5 / 8)
    arc = _Turning()
    _, _, lines = by_length(lower, arc, LINES, LINES, NO_RAMPS, 0.0, 1.0)
    expected = (4.0 * LINES + arc.R * arc.TURN * LINES**2) / (4.0 + arc.R * arc.TURN)
    np.testing.assert_allclose(lines, expected, rtol=0, atol=(0.3 * 2 * arc.TURN / 8) ** 2 / 24)


def test_both_edges_run_on_one_parameter_through_the_sheets_lines():
    lower, upper = _segments()
    a, b, lines = by_length(lower, upper, LINES, LINES, NO_RAMPS, 0.0, 1.0)
    # the lines of the sheet are the strip's lines, at their new parameters
    np.testing.assert_allclose(a.point_at(lines), lower.point_at(LINES), rtol=0, atol=1e-14)
    np.testing.assert_allclose(b.point_at(lines), upper.point_at(LINES), rtol=0, atol=1e-14)
    # between them too both edges are at one parameter of their curves (lower's c is x / 4,
    # upper's the cube root of x / 9), and neither runs back
    t = np.linspace(0.0, 1.0, 2001)
    c_lower, c_upper = a.point_at(t)[:, 0] / 4.0, np.cbrt(b.point_at(t)[:, 0] / 9.0)
    np.testing.assert_allclose(c_upper, c_lower, rtol=0, atol=1e-13)
    assert (np.diff(c_lower) >= 0.0).all()


def test_within_a_stretch_the_pace_is_even_in_the_sheets_u():
    # the segment at an even speed runs at one speed over each stretch: its length 4·Δc
    # over the stretch's share of the parameter (linear within it, so a fitted rail sees
    # the smoothness its edge has in the sheet, and a step of speed only at a stretch's end)
    lower, upper = _segments()
    a, _, lines = by_length(lower, upper, LINES, LINES, NO_RAMPS, 0.0, 1.0)
    share = np.linspace(0.05, 0.95, 7)
    t = (lines[:-1, None] + np.diff(lines)[:, None] * share).ravel()
    speed = np.linalg.norm(a.derivatives(t, 1)[1], axis=1).reshape(len(lines) - 1, -1)
    expected = 4.0 * np.diff(LINES) / np.diff(lines)
    np.testing.assert_allclose(speed, np.repeat(expected[:, None], len(share), axis=1), rtol=1e-12)


def test_lines_a_rounding_apart_are_one_end_not_a_stretch_where_both_edges_stand_still():
    lower, upper = _segments()
    # a chain's join at the line at 0.5, a rounding after it
    breaks = np.sort(np.concatenate([LINES, [np.nextafter(0.5, 1.0)]]))
    a, b, lines = by_length(lower, upper, LINES, breaks, NO_RAMPS, 0.0, 1.0)
    assert len(a.knots) == len(LINES)
    # either side of the line each edge runs at its speed there (4, and upper's 27·c²) over
    # the pace's rate on that side, the stretch's share of c over its share of t
    at_line = lines[LINES == 0.5]
    rates = np.diff(LINES)[3:5] / np.diff(lines)[3:5]
    for edge, speed in ((a, 4.0), (b, 27.0 * 0.25)):
        for side, rate in zip((-1e-12, 1e-12), rates, strict=True):
            got = np.linalg.norm(edge.derivatives(at_line + side, 1)[1], axis=1)
            np.testing.assert_allclose(got, speed * rate, rtol=1e-6)
