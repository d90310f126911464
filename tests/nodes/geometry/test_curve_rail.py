"""Ruled surfaces whose edges run on the given curves (torsal.nodes.geometry.curve_rail)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsal.nodes.geometry.curve_rail import CurveRail, ruled_between, ruled_between_all, unwrap_cyclic
from torsal.nodes.geometry.curves.conics import Arc, Circle
from torsal.nodes.geometry.curves.line import Line
from torsal.nodes.geometry.vectors import Plane


def frustum_arcs(sweep: float = math.pi) -> tuple[Arc, Arc]:
    """Arcs of radius 1 at z = 0 and 0.5 at z = 1 over the same angles: a cone's frustum."""
    bottom = Arc(Plane.from_normal([0, 0, 0], [0, 0, 1]), 1.0, 0.0, sweep)
    top = Arc(Plane.from_normal([0, 0, 1], [0, 0, 1]), 0.5, 0.0, sweep)
    return bottom, top


def test_each_ruling_is_exactly_the_isocurve_at_its_parameter():
    a, b = frustum_arcs()
    s = np.array([0.0, 0.1, 0.35, 0.5, 0.9, 1.0])
    t = np.array([0.0, 0.2, 0.3, 0.6, 0.8, 1.0])
    strip = ruled_between(a, s, b, t)
    u = np.linspace(0.0, 1.0, len(s))
    assert np.abs(strip.point_at(u, np.zeros_like(u)) - a.point_at(s)).max() <= 1e-15
    assert np.abs(strip.point_at(u, np.ones_like(u)) - b.point_at(t)).max() <= 1e-15


def test_the_edges_lie_on_the_curves_between_the_rulings():
    a, b = frustum_arcs()
    strip = ruled_between(a, [0.0, 0.3, 0.7, 1.0], b, [0.0, 0.5, 0.6, 1.0])
    u = np.linspace(0.0, 1.0, 401)
    edge_a = strip.point_at(u, np.zeros_like(u))
    edge_b = strip.point_at(u, np.ones_like(u))
    # on the circles r = 1, z = 0 and r = 0.5, z = 1
    assert np.abs(np.hypot(edge_a[:, 0], edge_a[:, 1]) - 1.0).max() <= 1e-14
    assert np.abs(np.hypot(edge_b[:, 0], edge_b[:, 1]) - 0.5).max() <= 1e-14
    assert np.abs(edge_b[:, 2] - 1.0).max() <= 1e-15


def test_the_rail_tangent_at_a_ruling_is_parallel_to_the_curves_tangent():
    a, _ = frustum_arcs()
    s = np.array([0.0, 0.25, 0.3, 0.8, 1.0])
    rail = CurveRail(a, np.linspace(0, 1, 5), s)
    _, d = rail.derivatives(np.linspace(0, 1, 5), 1)
    tangent = a.derivatives(s, 1)[1]
    cosine = np.einsum("ij,ij->i", d, tangent) / np.linalg.norm(d, axis=1) / np.linalg.norm(tangent, axis=1)
    assert np.abs(cosine - 1.0).max() <= 1e-14


def test_rail_derivatives_match_finite_differences():
    a, _ = frustum_arcs()
    rail = CurveRail(a, np.linspace(0, 1, 6), [0.0, 0.1, 0.15, 0.5, 0.8, 1.0])
    u = np.array([0.13, 0.41, 0.77])
    h = 1e-5
    values = rail.derivatives(u, 3)
    for k in (1, 2, 3):
        lower = rail.derivatives(u - h, k - 1)[k - 1]
        upper = rail.derivatives(u + h, k - 1)[k - 1]
        assert np.abs((upper - lower) / (2 * h) - values[k]).max() <= 1e-5 * (1 + np.abs(values[k]).max())


def test_a_frustums_area_is_the_cones_closed_form():
    a, b = frustum_arcs()
    strip = ruled_between(a, np.linspace(0, 1, 9), b, np.linspace(0, 1, 9))
    slant = math.sqrt(0.5**2 + 1.0)
    assert strip.area() == pytest.approx(math.pi / 2 * (1.0 + 0.5) * slant, rel=1e-11)


def test_a_fan_keeps_its_apex_still():
    a, b = frustum_arcs()
    s = np.array([0.0, 0.4, 0.4, 0.4, 1.0])
    strip = ruled_between(a, s, b, [0.0, 0.2, 0.4, 0.6, 1.0])
    u = np.linspace(0.25, 0.75, 21)
    apex = a.point_at(0.4)
    assert np.abs(strip.point_at(u, np.zeros_like(u)) - apex).max() <= 1e-15


def test_parameters_running_through_a_closed_curves_seam_are_unwrapped():
    assert unwrap_cyclic(np.array([0.7, 0.9, 0.05, 0.3])).tolist() == pytest.approx([0.7, 0.9, 1.05, 1.3])
    circle = Circle(Plane.from_normal([0, 0, 0], [0, 0, 1]), 2.0)
    rail = CurveRail(circle, np.linspace(0, 1, 4), [0.8, 0.95, 0.1, 0.2])
    points = rail.point_at(np.linspace(0, 1, 50))
    assert np.abs(np.linalg.norm(points, axis=1) - 2.0).max() <= 1e-14
    angles = np.unwrap(np.arctan2(points[:, 1], points[:, 0]))
    assert np.all(np.diff(angles) > 0), "the rail runs once forward through the seam"
    assert np.abs(rail.point_at(1.0) - circle.point_at(0.2)).max() <= 1e-15


def test_strips_made_together_are_each_the_strip_made_alone_bit_for_bit():
    a, b = frustum_arcs()
    circle = Circle(Plane.from_normal([0, 0, 2], [0, 0, 1]), 2.0)
    line_a, line_b = Line([0, 0, 0], [2, 0, 0]), Line([0, 1, 0], [3, 2, 1])
    s5 = np.array([0.0, 0.0, 0.3, 0.7, 1.0])  # (a fan through A(0): a flat run of the pace)
    t5 = np.array([0.0, 0.2, 0.5, 0.5, 1.0])
    jobs = [
        (a, [0.0, 1.0], b, [0.0, 1.0], None),  # two rulings: both slopes the chord's
        (a, [0.0, 0.4, 1.0], b, [0.0, 0.9, 1.0], None),  # three: an overshooting end slope is cut
        (line_a, s5, line_b, t5, (line_a.point_at(s5), line_b.point_at(t5))),  # the ends given
        (a, [0.0, 0.5, 0.4, 1.0], b, [0.0, 0.2, 0.6, 1.0], None),  # running back: refused
        (a, [0.0, 0.3, 0.6, 1.0], circle, [0.8, 0.95, 0.1, 0.2], None),  # through B's seam
        (a, [0.0, 0.1, 0.35, 0.5, 0.9, 1.0], b, [0.0, 0.2, 0.3, 0.6, 0.8, 1.0], None),
    ]
    together = ruled_between_all(jobs)
    u = np.linspace(-0.1, 1.1, 23)
    for job, made in zip(jobs, together, strict=True):
        try:
            alone = ruled_between(*job)
        except ValueError as exc:
            assert isinstance(made, ValueError) and str(made) == str(exc)
            continue
        assert made.ruling_lines.tobytes() == alone.ruling_lines.tobytes()
        assert made.closed_u == alone.closed_u
        for v in (0.0, 0.3, 1.0):  # the rails' paces and their derivatives
            mine, its = (surface.derivatives(u, np.full_like(u, v), 2) for surface in (made, alone))
            assert [x.tobytes() for x in mine] == [x.tobytes() for x in its]
    assert isinstance(together[3], ValueError)
