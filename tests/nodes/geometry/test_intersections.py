"""Curve–plane intersections."""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsal.nodes.geometry.curves import Circle, Line, ParametricCurve
from torsal.nodes.geometry.intersections import curve_plane_intersections
from torsal.nodes.geometry.vectors import WORLD_XY, Plane

TILTED = Plane.from_axes([1.0, -2.0, 0.5], [1, 1, 0], [0, 1, 1])


def test_circle_crosses_a_plane_through_its_centre_twice_at_the_closed_form_points():
    circle = Circle(TILTED, 2.0)
    cut = Plane.from_normal(TILTED.origin, TILTED.x + 0.3 * TILTED.z)
    hits = curve_plane_intersections(circle, cut)
    assert len(hits.parameters) == 2
    # the chord through the centre: ±r along the line where the planes meet
    direction = np.cross(TILTED.z, cut.z)
    direction /= np.linalg.norm(direction)
    expected = TILTED.origin + 2.0 * np.array([direction, -direction])
    distances = np.linalg.norm(hits.points[:, None] - expected[None], axis=2).min(axis=1)
    assert distances.max() < 1e-12


def test_plane_tangent_to_a_circle_touches_it_once():
    circle = Circle(WORLD_XY, 2.0)
    hits = curve_plane_intersections(circle, Plane.from_normal([0, 2, 0], [0, 1, 0]))
    assert len(hits.parameters) == 1
    assert np.allclose(hits.points, [[0, 2, 0]], atol=1e-7)  # a double root: √ε accuracy


def test_helix_meets_each_horizontal_plane_once_at_its_height():
    r, c, turns = 1.0, 0.2, 5
    helix = ParametricCurve(
        lambda u: np.column_stack([r * np.cos(u), r * np.sin(u), c * u]), (0, 2 * math.pi * turns)
    )
    for height in (0.1, 1.0, 3.3, 6.2):
        hits = curve_plane_intersections(helix, Plane.from_normal([0, 0, height], [0, 0, 1]))
        u = height / c
        assert hits.parameters == pytest.approx([u / (2 * math.pi * turns)], abs=1e-13)


def test_sine_wave_crosses_the_axis_at_every_multiple_of_pi():
    wave = ParametricCurve(lambda u: np.column_stack([u, np.sin(u), 0 * u]), (0.5, 20.0))
    hits = curve_plane_intersections(wave, Plane.from_normal([0, 0, 0], [0, 1, 0]))
    assert np.allclose(hits.points[:, 0], np.pi * np.arange(1, 7), atol=1e-12)


def test_line_lying_in_the_plane_reports_points_along_it():
    hits = curve_plane_intersections(Line([0, 0, 0], [1, 0, 0]), WORLD_XY)
    assert hits.parameters[0] == 0 and hits.parameters[-1] == 1


def test_curve_missing_the_plane_has_no_intersections():
    hits = curve_plane_intersections(Circle(WORLD_XY, 1.0), Plane.from_normal([0, 0, 1], [0, 0, 1]))
    assert hits.parameters.shape == (0,) and hits.points.shape == (0, 3)


def test_crossing_at_the_seam_of_a_closed_curve_is_reported_once():
    hits = curve_plane_intersections(Circle(WORLD_XY, 2.0), Plane.from_normal([0, 0, 0], [0, 1, 0]))
    assert hits.parameters == pytest.approx([0.0, 0.5], abs=1e-14)
