"""RuledSurface: from two curves and from rulings (the loft every developable node outputs)."""

from __future__ import annotations

import numpy as np
import pytest

from torsal.nodes.geometry.curves import Line
from torsal.nodes.geometry.nurbs_surface import NurbsSurface
from torsal.nodes.geometry.parametric_surface import ParametricSurface, cylinder, sphere
from torsal.nodes.geometry.ruled import RuledSurface, SplineRail


def random_rulings(count, seed=0):
    rng = np.random.default_rng(seed)
    u = np.linspace(0, 3, count)
    starts = np.column_stack([u, np.sin(u), 0 * u]) + rng.normal(scale=0.05, size=(count, 3))
    ends = starts + np.column_stack([0.2 * np.cos(u), 0.1 + 0 * u, 1 + 0 * u]) * rng.uniform(1, 3, (count, 1))
    return np.stack([starts, ends], axis=1)


@pytest.mark.parametrize("count", [2, 3, 4, 9, 41])
def test_isocurve_at_each_ruling_parameter_is_that_ruling(count):
    rulings = random_rulings(count) * 1000.0 + 5e4  # large, far-off coordinates
    surface = RuledSurface.from_rulings(rulings)
    np.testing.assert_array_equal(surface.ruling_parameters, np.linspace(0, 1, count))
    np.testing.assert_array_equal(surface.ruling_lines, rulings)
    t = np.linspace(0, 1, 13)[:, None]
    scale = np.abs(rulings).max()
    for i, u in enumerate(surface.ruling_parameters):
        iso = surface.isocurve("v", u).point_at(t.ravel())
        line = (1 - t) * rulings[i, 0] + t * rulings[i, 1]
        assert np.abs(iso - line).max() <= 1e-12 * scale


def test_from_rulings_accepts_separate_start_and_end_arrays():
    rulings = random_rulings(6)
    a = RuledSurface.from_rulings(rulings[:, 0], rulings[:, 1])
    b = RuledSurface.from_rulings(rulings)
    u = np.linspace(0, 1, 17)
    np.testing.assert_array_equal(a.point_at(u, 0.3), b.point_at(u, 0.3))


def test_closed_ring_of_rulings_gives_a_periodic_smooth_seam():
    angles = np.linspace(0, 2 * np.pi, 25)
    circle = np.column_stack([np.cos(angles), np.sin(angles), 0 * angles])
    circle[-1] = circle[0]
    surface = RuledSurface.from_rulings(circle, circle + np.array([0, 0, 2]))
    assert surface.closed_u
    d0 = surface.derivatives(0.0, 0.5, 2)
    d1 = surface.derivatives(1.0, 0.5, 2)
    for a, b in zip(d0, d1, strict=True):
        np.testing.assert_allclose(a, b, atol=1e-12)
    # Cylinder of radius 1 sampled with 24 segments: cubic spline error ~ h⁴.
    radius = np.hypot(*surface.point_at(np.linspace(0, 1, 1001), 0.5)[:, :2].T)
    assert np.abs(radius - 1).max() < 5e-5


def test_ruled_surface_is_linear_in_v_with_zero_svv():
    surface = RuledSurface.from_rulings(random_rulings(7))
    *_, sv, _suu, _suv, svv = surface.derivatives(np.linspace(0, 1, 9), 0.37, 2)
    np.testing.assert_array_equal(svv, 0.0)
    ends = surface.point_at(np.linspace(0, 1, 9), 1.0) - surface.point_at(np.linspace(0, 1, 9), 0.0)
    np.testing.assert_allclose(sv, ends, atol=1e-12)


def test_rail_derivatives_agree_with_finite_differences():
    surface = RuledSurface.from_rulings(random_rulings(8))
    u = np.linspace(0.05, 0.95, 11)
    v = np.linspace(0.1, 0.9, 11)
    h = 1e-5
    s, su, _sv, suu, _suv, _svv = surface.derivatives(u, v, 2)
    fd_su = (surface.point_at(u + h, v) - surface.point_at(u - h, v)) / (2 * h)
    fd_suu = (surface.point_at(u + h, v) - 2 * s + surface.point_at(u - h, v)) / h**2
    np.testing.assert_allclose(su, fd_su, atol=1e-8 * np.abs(su).max())
    np.testing.assert_allclose(suu, fd_suu, atol=1e-4 * np.abs(suu).max())


def test_bilinear_hyperbolic_paraboloid_from_two_lines_has_closed_form_curvature():
    # Rulings from (x, −1, −x) to (x, 1, x): the saddle z = x·y over [−1, 1]².
    x = np.linspace(-1, 1, 2)
    surface = RuledSurface.from_rulings(
        np.column_stack([x, -1 + 0 * x, -x]), np.column_stack([x, 1 + 0 * x, x])
    )
    s = np.linspace(0, 1, 7)
    u, v = np.meshgrid(s, s, indexing="ij")
    xx, yy = 2 * u.ravel() - 1, 2 * v.ravel() - 1
    curv = surface.curvature(u.ravel(), v.ravel())
    np.testing.assert_allclose(curv.gaussian, -1.0 / (1 + xx**2 + yy**2) ** 2, rtol=1e-12)
    np.testing.assert_allclose(surface.point_at(u.ravel(), v.ravel())[:, 2], xx * yy, atol=1e-15)


def test_ruled_surface_between_two_curves_follows_their_parameters():
    lower = cylinder(1.0, 1.0).isocurve("u", 0.0)  # unit circle at z = 0
    upper = cylinder(2.0, 1.0).isocurve("u", 1.0)  # radius-2 circle at z = 1
    surface = RuledSurface(lower, upper)
    assert surface.closed_u and not surface.closed_v
    u = np.linspace(0, 1, 11)
    np.testing.assert_allclose(surface.point_at(u, 0.0), lower.point_at(u), atol=1e-15)
    np.testing.assert_allclose(surface.point_at(u, 1.0), upper.point_at(u), atol=1e-15)
    # A frustum: K = 0, area = π (r1 + r2) · slant.
    assert surface.area() == pytest.approx(np.pi * 3 * np.hypot(1, 1), rel=1e-11)
    np.testing.assert_allclose(surface.gaussian_curvature(u, 0.5), 0.0, atol=1e-12)


def test_rulings_of_a_ruled_surface_are_returned_as_start_end_pairs():
    rulings = random_rulings(5)
    surface = RuledSurface.from_rulings(rulings)
    np.testing.assert_allclose(surface.rulings(5), rulings, atol=1e-14)
    assert surface.is_ruled and surface.ruling_direction == "v"


def test_ruling_detection_on_generic_surfaces():
    assert cylinder().ruling_direction == "v"
    assert not sphere().is_ruled
    bilinear = NurbsSurface(np.array([[[0, 0, 0], [0, 1, 1]], [[1, 0, 1], [1, 1, 0]]], float), 1, 1)
    assert bilinear.is_ruled
    flipped = ParametricSurface(lambda u, v: (u, np.cos(v), np.sin(v)), (0, 1), (0, 1))
    assert flipped.ruling_direction == "u"
    np.testing.assert_allclose(flipped.rulings(2)[:, :, 0], [[0, 1], [0, 1]])
    with pytest.raises(ValueError, match="no straight rulings"):
        sphere().rulings(3)


def test_from_rulings_rejects_bad_input():
    with pytest.raises(ValueError, match="at least two rulings"):
        RuledSurface.from_rulings(np.zeros((1, 2, 3)))
    with pytest.raises(ValueError):
        RuledSurface.from_rulings(np.zeros((4, 3)), np.zeros((5, 3)))
    with pytest.raises(ValueError, match="finite"):
        RuledSurface.from_rulings(np.full((3, 2, 3), np.nan))


def test_spline_rail_interpolates_its_points_at_its_parameters():
    params = np.array([0.0, 0.1, 0.45, 0.5, 1.0])
    points = np.random.default_rng(2).normal(size=(5, 3))
    rail = SplineRail(params, points)
    np.testing.assert_allclose(rail.point_at(params), points, atol=1e-14)


def test_rulings_can_be_given_and_returned_as_line_curves():
    rulings = random_rulings(5)
    lines = RuledSurface.from_rulings(rulings).ruling_curves()
    assert all(isinstance(line, Line) for line in lines)
    again = RuledSurface.from_rulings(lines)
    np.testing.assert_array_equal(again.ruling_lines, rulings)
    assert len(again.ruling_curves(3)) == 3
    lower = cylinder(1.0, 1.0).isocurve("u", 0.0)
    with pytest.raises(ValueError, match="give a count"):
        RuledSurface(lower, lower).ruling_curves()


def test_torsion_of_a_rail_uses_its_third_derivative():
    # A helix sampled densely: the cubic rail's torsion approaches c / (r² + c²).
    t = np.linspace(0, 1, 401)
    radius, pitch = 1.0, 0.3
    angle = 4 * np.pi * t
    points = np.column_stack([radius * np.cos(angle), radius * np.sin(angle), pitch * angle])
    rail = SplineRail(t, points)
    tau = rail.torsion_at(np.linspace(0.2, 0.8, 7))
    np.testing.assert_allclose(tau, pitch / (radius**2 + pitch**2), rtol=1e-3)
