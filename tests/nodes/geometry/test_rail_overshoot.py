"""Loft rails through unevenly spaced ruling ends do not overshoot (nodes/geometry/rail_tangents.py).

The S-shaped wiggles at the corners of the Kaohsiung cut sheets came from the loft's
C² spline rails, which swung back past a ruling end wherever the ends on one rail were
spaced very unevenly; a fan of rulings through one point made the rail wander around it.
"""

from __future__ import annotations

import numpy as np
from scipy.interpolate import make_interp_spline

from torsal.nodes.geometry.rail_tangents import bezier_spline
from torsal.nodes.geometry.ruled import RuledSurface

U = np.linspace(0.0, 1.0, 4001)


def loft(a: np.ndarray, b: np.ndarray) -> RuledSurface:
    return RuledSurface.from_rulings(a, b)


def test_rail_through_unevenly_spaced_points_on_a_line_stays_on_it_and_never_doubles_back():
    x = np.array([0.0, 0.1, 0.2, 5.0, 10.0, 10.5, 17.0])
    a = np.column_stack([x, 0 * x, 0 * x])
    rail = loft(a, a + np.array([0.0, 1.0, 0.0])).curve_a.point_at(U)
    assert np.abs(rail[:, 1:]).max() < 1e-15 * 17
    assert np.diff(rail[:, 0]).min() >= 0.0
    assert rail[:, 0].min() == 0.0 and rail[:, 0].max() == 17.0


def test_a_plain_cubic_spline_through_those_points_does_double_back():
    """The cause: the C² interpolant itself (scipy's, not-a-knot) runs backwards."""
    x = np.array([0.0, 0.1, 0.2, 5.0, 10.0, 10.5, 17.0])
    spline = make_interp_spline(np.linspace(0, 1, len(x)), x, k=3)
    assert np.diff(spline(U)).min() < 0.0


def test_rail_of_a_fan_stays_on_its_apex():
    phi = np.linspace(0.0, 1.5, 9)
    a = np.column_stack([np.cos(phi), np.sin(phi), 0 * phi]) * 10.0
    apex = np.array([2.0, 3.0, 4.0])
    b = np.array([[0.0, -1.0, 4.0], [0.5, 0.5, 4.0], apex, apex, apex, apex, apex, [1.0, 6.0, 4.0],
                  [0.0, 7.0, 4.0]])
    surface = loft(a, b)
    u = U[(U >= 2 / 8) & (U <= 6 / 8)]
    assert np.abs(surface.curve_b.point_at(u) - apex).max() < 1e-15 * 10
    # so the loft over the fan is the cone through the apex: every ruling there ends at it
    ends = surface.point_at(u, np.ones_like(u))
    assert np.abs(ends - apex).max() < 1e-14 * 10


def test_closed_rail_of_a_fan_stays_on_its_apex_and_is_smooth_across_its_seam():
    phi = np.linspace(0.0, 2 * np.pi, 13)
    a = np.column_stack([np.cos(phi), np.sin(phi), 0 * phi])
    b = 0.5 * a + [0.0, 0.0, 1.0]
    apex = b[3].copy()
    b[3:7] = apex
    surface = loft(a, b)
    u = U[(U >= 3 / 12) & (U <= 6 / 12)]
    assert np.abs(surface.curve_b.point_at(u) - apex).max() < 1e-15
    d0, d1 = surface.curve_b.derivatives(np.array([0.0, 1.0]), 1)[1]
    assert np.abs(d0 - d1).max() < 1e-12


def test_evenly_spaced_rails_are_the_not_a_knot_cubic_spline():
    t = np.linspace(0.0, 3.0, 25)
    a = np.column_stack([np.cos(t), np.sin(t), 0.3 * t])
    b = a * [2.0, 2.0, 1.0] + [0.0, 0.0, 1.0]
    surface = loft(a, b)
    params = np.linspace(0.0, 1.0, len(t))
    for rail, points in ((surface.curve_a, a), (surface.curve_b, b)):
        expected = make_interp_spline(params, points, k=3)(U)
        assert np.abs(rail.point_at(U) - expected).max() < 1e-14


def test_rail_on_an_unevenly_divided_circle_turns_one_way_only():
    """Ends 0.02 rad apart, then 0.5 rad apart (a ruling end that barely moves, then jumps)."""
    phi = np.cumsum([0.0, 0.02, 0.02, 0.5, 0.5, 0.5, 0.02, 0.5])
    b = np.column_stack([np.cos(phi), np.sin(phi), 0 * phi]) * 5.0
    a = b * 2.0 + [0.0, 0.0, 3.0]
    rail = loft(a, b).curve_b.point_at(U)
    angle = np.unwrap(np.arctan2(rail[:, 1], rail[:, 0]))
    assert np.diff(angle).min() >= 0.0


def test_bezier_spline_interpolates_values_and_each_spans_end_tangents():
    params = np.array([0.0, 0.25, 0.7, 1.0])
    points = np.array([[0.0, 0.0], [1.0, 2.0], [3.0, 2.5], [4.0, 0.0]])
    start = np.array([[1.0, 0.0], [2.0, 1.0], [0.0, -3.0]])
    end = np.array([[0.5, 0.5], [0.0, -1.0], [1.0, 1.0]])
    spline = bezier_spline(params, points, start, end)
    assert np.abs(spline(params) - points).max() < 1e-15
    eps = 1e-12  # one-sided derivatives at the spans' ends
    assert np.abs(spline(params[:-1] + eps, nu=1) - start).max() < 1e-8
    assert np.abs(spline(params[1:] - eps, nu=1) - end).max() < 1e-8


def test_rail_through_a_fan_on_a_circle_keeps_the_circles_tangent_at_the_apex():
    """B divides a circle evenly but stays on one point for three rulings (a fan): the rail
    reaches and leaves that point along the circle's tangent there, not with a kink."""
    phi = np.r_[np.arange(6) * 0.3, [1.5, 1.5, 1.5], 1.5 + np.arange(1, 6) * 0.3]
    b = np.column_stack([5 * np.cos(phi), 5 * np.sin(phi), 0 * phi])
    a = np.column_stack([np.linspace(0, 6, len(phi)), np.full(len(phi), -3.0), np.full(len(phi), 2.0)])
    rail = loft(a, b).curve_b
    h = 1.0 / (len(phi) - 1)
    arrive = rail.derivatives(np.array([5 * h - 1e-9]), 1)[1][0]
    leave = rail.derivatives(np.array([8 * h + 1e-9]), 1)[1][0]
    tangent = np.array([-np.sin(1.5), np.cos(1.5), 0.0])
    # each run's own spline ends 0.27° off the circle's tangent (0.3 rad between points);
    # one spline through all of them, apex three times, is 5.2° off
    for direction in (arrive, leave):
        assert np.degrees(np.arccos(direction @ tangent / np.linalg.norm(direction))) < 0.3
