"""A strip's width is measured across it, between its edges, not along its rulings.

Closed forms: two parallel lines 0.3 apart joined by rulings slanted 2 m along them (each
ruling ~2.02 m long, the strip 0.3 wide); two concentric arcs of radii 4 and 4.25 in one
plane (0.25 wide) joined by rulings that run 0.6 rad along them.
"""

from __future__ import annotations

import numpy as np

from torsal.nodes.geometry.curve_rail import ruled_between
from torsal.nodes.geometry.curves import Arc, Line
from torsal.nodes.geometry.developable.strip_width import to_polyline, width_across
from torsal.nodes.geometry.vectors import Plane


def test_rulings_running_along_parallel_edges_leave_the_strip_as_wide_as_the_edges_are_apart():
    low = Line(np.array([0.0, 0.0, 0.0]), np.array([10.0, 0.0, 0.0]))
    high = Line(np.array([0.0, 0.3, 0.0]), np.array([10.0, 0.3, 0.0]))
    s = np.linspace(0.0, 0.8, 9)
    strip = ruled_between(low, s, high, s + 0.2)  # each ruling 2 m along, 0.3 across
    lengths = np.linalg.norm(strip.ruling_lines[:, 1] - strip.ruling_lines[:, 0], axis=1)
    assert np.median(lengths) > 2.0
    assert abs(width_across(strip.curve_a, strip.curve_b) - 0.3) <= 1e-12


def test_concentric_arcs_are_their_radii_apart_whatever_way_the_rulings_run():
    plane = Plane.from_axes(np.zeros(3), np.array([1.0, 0, 0]), np.array([0, 1.0, 0]))
    inner, outer = Arc(plane, 4.0, 0.0, 3.0), Arc(plane, 4.25, 0.0, 3.0)
    s = np.linspace(0.0, 0.8, 11)
    strip = ruled_between(inner, s, outer, s + 0.2)  # each ruling 0.6 rad along (~2.5 m long)
    lengths = np.linalg.norm(strip.ruling_lines[:, 1] - strip.ruling_lines[:, 0], axis=1)
    assert lengths.min() > 2.0
    # the polyline of 129 points on 2.4 rad of an arc of 4.25 m radius sags by r (1 − cos(δ/2))
    sag = 4.25 * (1.0 - np.cos(2.4 / 128 / 2))
    assert abs(width_across(strip.curve_a, strip.curve_b) - 0.25) <= sag + 1e-12


def test_distance_to_a_polyline_is_to_its_nearest_segment_or_vertex():
    polyline = np.array([[0.0, 0, 0], [1.0, 0, 0], [1.0, 1.0, 0]])
    points = np.array([[0.5, -0.2, 0], [2.0, 0.5, 0], [1.5, -0.5, 0.0], [-1.0, 0, 2.0]])
    expected = [0.2, 1.0, np.hypot(0.5, 0.5), np.hypot(1.0, 2.0)]
    np.testing.assert_allclose(to_polyline(points, polyline), expected, rtol=0, atol=1e-15)
