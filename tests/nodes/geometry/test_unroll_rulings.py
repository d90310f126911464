"""IsoMapping's kernel: unrolling ruled strips, closed-form checks.

Discrete strips unroll exactly (each quad is laid down as two congruent triangles),
so a chord-sampled cylinder unrolls to a rectangle whose width is the sum of its
chords, and a cone to a fan of isosceles triangles. The smooth limits (2πr, 2πr/L,
(R² + h²)/R) are reached through :func:`unroll_surface`, which samples more rulings
than it reports.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate

from torsal.nodes.geometry.curves import NurbsCurve
from torsal.nodes.geometry.parametric_surface import ParametricSurface, cone, cylinder, sphere
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.geometry.unroll import bilinear_quad_areas, unroll_rulings, unroll_surface

R_CYL, H_CYL = 1.5, 2.0
R_CONE, H_CONE = 1.0, math.sqrt(3.0)  # slant L = 2, so the sector angle 2πr/L is π
L_CONE = math.hypot(R_CONE, H_CONE)
R_HELIX, H_HELIX, RULING = 2.0, 0.5, 3.0  # helix (R cos t, R sin t, h t), rulings 3 long
RHO = (R_HELIX**2 + H_HELIX**2) / R_HELIX  # radius of the developed helix


def circle(n: int, radius: float, z: float = 0.0) -> np.ndarray:
    phi = np.linspace(0.0, 2.0 * np.pi, n + 1)
    return np.column_stack([radius * np.cos(phi), radius * np.sin(phi), np.full_like(phi, z)])


def helix_tangent_rulings(n: int, turns: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    t = np.linspace(0.0, 2.0 * np.pi * turns, n + 1)
    c = np.column_stack([R_HELIX * np.cos(t), R_HELIX * np.sin(t), H_HELIX * t])
    d = np.column_stack([-R_HELIX * np.sin(t), R_HELIX * np.cos(t), np.full_like(t, H_HELIX)])
    return c, c + RULING * d / np.linalg.norm(d, axis=1, keepdims=True)


def helix_tangent_surface(turns: float = 1.0) -> ParametricSurface:
    speed = math.hypot(R_HELIX, H_HELIX)

    def f(u, v):
        c = np.column_stack([R_HELIX * np.cos(u), R_HELIX * np.sin(u), H_HELIX * u])
        d = np.column_stack([-R_HELIX * np.sin(u), R_HELIX * np.cos(u), np.full_like(u, H_HELIX)])
        return c + v[:, None] * d / speed

    return ParametricSurface(f, (0.0, 2.0 * np.pi * turns), (0.0, RULING))


def helix_tangent_area(turns: float = 1.0) -> float:
    # |S_s × S_v| = v·κ over arc length s, so the area is length · κ · L²/2
    length = 2.0 * np.pi * turns * math.hypot(R_HELIX, H_HELIX)
    return length * (R_HELIX / (R_HELIX**2 + H_HELIX**2)) * RULING**2 / 2.0


def fit_circle(points: np.ndarray) -> tuple[np.ndarray, float]:
    m = np.column_stack([2.0 * points, np.ones(len(points))])
    sol = np.linalg.lstsq(m, (points**2).sum(axis=1), rcond=None)[0]
    return sol[:2], float(np.sqrt(sol[2] + sol[:2] @ sol[:2]))


def swept_angle(apex: np.ndarray, ends: np.ndarray) -> float:
    d = ends - apex
    z = d[:, 0] + 1j * d[:, 1]
    return float(np.abs(np.sum(np.angle(z[1:] / z[:-1]))))


# ----------------------------------------------------------------------------- cylinder


def test_cylinder_unrolls_to_a_rectangle_whose_width_is_the_sum_of_its_chords():
    n = 100
    base = circle(n, R_CYL)
    dev = unroll_rulings(base, base + np.array([0.0, 0.0, H_CYL]))
    chord = 2.0 * R_CYL * math.sin(math.pi / n)
    x = np.arange(n + 1) * chord
    assert np.abs(dev.starts2d - np.column_stack([x, 0 * x])).max() < 1e-12
    assert np.abs(dev.ends2d - np.column_stack([x, np.full_like(x, H_CYL)])).max() < 1e-12


def test_cylinder_surface_unrolls_to_a_2pi_r_by_h_rectangle():
    dev = unroll_surface(cylinder(R_CYL, H_CYL), 100)
    starts, ends = dev.rulings2d
    assert len(starts) == 101
    assert abs(starts[-1, 0] / (2.0 * math.pi * R_CYL) - 1.0) < 3e-6
    assert np.abs(starts[:, 1]).max() < 1e-12 and np.abs(ends[:, 1] - H_CYL).max() < 1e-12
    assert abs(dev.area_3d / (2.0 * math.pi * R_CYL * H_CYL) - 1.0) < 1e-11
    assert abs(dev.area_error) <= 1e-4


def test_area_error_of_a_full_cylinder_at_100_chords_is_the_chord_deficit():
    n = 100
    base = circle(n, R_CYL)
    dev = unroll_rulings(base, base + np.array([0.0, 0.0, H_CYL]), area_3d=2 * math.pi * R_CYL * H_CYL)
    deficit = n * math.sin(math.pi / n) / math.pi - 1.0  # chord sum over circumference
    assert dev.area_error == pytest.approx(deficit, rel=1e-9)


# ----------------------------------------------------------------------------- cone


def test_cone_unrolls_to_a_fan_of_isosceles_triangles_with_apex_angle_from_the_chord():
    n = 100
    apex = np.array([0.0, 0.0, H_CONE])
    base = circle(n, R_CONE)
    dev = unroll_rulings(np.broadcast_to(apex, base.shape), base)
    assert np.abs(dev.starts2d).max() < 1e-13  # every ruling starts at the developed apex
    assert np.abs(np.linalg.norm(dev.ends2d, axis=1) - L_CONE).max() < 1e-14
    expected = 2.0 * n * math.asin(R_CONE / L_CONE * math.sin(math.pi / n))
    assert swept_angle(np.zeros(2), dev.ends2d) == pytest.approx(expected, rel=1e-12)


def test_cone_unrolls_to_a_sector_of_angle_2pi_r_over_L():
    dev = unroll_surface(cone(R_CONE, H_CONE), 100)
    apex2d = dev.ends2d[0]  # the factory's rulings run from the base (v = 0) to the apex
    assert np.abs(dev.ends2d - apex2d).max() < 1e-12
    angle = swept_angle(apex2d, dev.starts2d)
    assert angle == pytest.approx(2.0 * math.pi * R_CONE / L_CONE, rel=5e-6)
    assert abs(dev.area_3d / (math.pi * R_CONE * L_CONE) - 1.0) < 1e-10
    assert abs(dev.area_error) <= 1e-4


def test_edge_lengths_are_preserved_to_1e_12_relative():
    apex = np.array([0.2, -0.1, H_CONE])
    base = circle(100, R_CONE)
    for starts, ends in [
        (base, base + np.array([0.0, 0.0, H_CYL])),
        (np.broadcast_to(apex, base.shape), base),
        helix_tangent_rulings(100, turns=2.5),
    ]:
        dev = unroll_rulings(starts, ends)
        assert dev.max_edge_length_error < 1e-12
        lengths3d = np.linalg.norm(ends - starts, axis=1)
        lengths2d = np.linalg.norm(dev.ends2d - dev.starts2d, axis=1)
        assert np.abs(lengths2d / lengths3d - 1.0).max() < 1e-13


# ----------------------------------------------------------------------------- helix


def test_helix_regression_edge_develops_onto_a_circle_of_radius_R2_plus_h2_over_R():
    starts, ends = helix_tangent_rulings(100)
    dev = unroll_rulings(starts, ends)
    centre, radius = fit_circle(dev.starts2d)
    # congruent quads (screw symmetry): the developed edge lies on a circle exactly …
    assert np.abs(np.linalg.norm(dev.starts2d - centre, axis=1) - radius).max() < 1e-12 * radius
    # … whose radius tends to 1/κ as O(1/n²)
    assert abs(radius / RHO - 1.0) < 2e-5
    # the outer rail lies on a concentric circle (a band), of radius √(ρ² + L²) for
    # rulings tangent to the inner one
    outer = np.linalg.norm(dev.ends2d - centre, axis=1)
    assert np.ptp(outer) < 1e-12 * radius
    assert abs(outer.mean() / math.hypot(RHO, RULING) - 1.0) < 1e-5


def test_tangent_developable_of_a_helix_unrolls_with_area_error_below_1e_4_at_100_segments():
    dev = unroll_surface(helix_tangent_surface(), 100)
    assert abs(dev.area_3d / helix_tangent_area() - 1.0) < 1e-9
    assert abs(dev.area_error) <= 1e-4
    assert dev.max_edge_length_error < 1e-12
    _, radius = fit_circle(dev.starts2d)
    assert abs(radius / RHO - 1.0) < 1e-6


def test_a_tangent_developable_of_more_than_a_turn_of_development_overlaps_itself():
    # the developed edge turns by κ·length = 2πR/√(R² + h²) per helix turn
    per_turn = 2.0 * math.pi * R_HELIX / math.hypot(R_HELIX, H_HELIX)
    assert not unroll_rulings(*helix_tangent_rulings(100, turns=0.95 * 2 * math.pi / per_turn)).overlaps
    assert unroll_rulings(*helix_tangent_rulings(100, turns=1.1 * 2 * math.pi / per_turn)).overlaps


def test_chord_unrolling_converges_to_the_smooth_area_at_second_order():
    exact = helix_tangent_area()
    errors = [abs(unroll_rulings(*helix_tangent_rulings(n)).area_2d / exact - 1.0) for n in (100, 200, 400)]
    assert errors[0] / errors[1] == pytest.approx(4.0, rel=0.01)
    assert errors[1] / errors[2] == pytest.approx(4.0, rel=0.01)


# ----------------------------------------------------------------------------- non-developable


def hypar_rulings(n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    u = np.linspace(0.0, 1.0, n)
    return u, np.column_stack([u, 0 * u, 0 * u]), np.column_stack([u, 1 + 0 * u, u])


def test_hyperbolic_paraboloid_unrolls_with_ruling_lengths_kept_and_area_changed():
    n = 11
    u, starts, ends = hypar_rulings(n)  # z = xy on the unit square
    dev = unroll_rulings(starts, ends)
    assert np.abs(np.linalg.norm(dev.ends2d - dev.starts2d, axis=1) - np.sqrt(1 + u**2)).max() < 1e-14
    exact, _ = integrate.dblquad(lambda y, x: math.sqrt(1 + x * x + y * y), 0, 1, 0, 1, epsabs=1e-13)
    assert dev.area_3d == pytest.approx(exact, rel=1e-11)  # the bilinear loft is the hypar itself
    # triangles (A_i, A_{i+1}, B_i), (A_{i+1}, B_{i+1}, B_i): ½Δu·(√(1 + u_i²) + √(2 + u_{i+1}²))
    flat = 0.5 / (n - 1) * np.sum(np.sqrt(1 + u[:-1] ** 2) + np.sqrt(2 + u[1:] ** 2))
    assert dev.area_2d == pytest.approx(flat, rel=1e-13)
    assert dev.area_error == pytest.approx(flat / exact - 1.0, rel=1e-9)
    assert dev.area_error > 0.04
    assert dev.hinge_angles.min() > 0.05  # every quad is warped


def test_non_ruled_surface_is_refused_with_a_message():
    with pytest.raises(ValueError, match="surface has no straight rulings"):
        unroll_surface(sphere(1.0), 10)


def test_zero_length_ruling_is_refused():
    starts = np.array([[0.0, 0, 0], [1, 0, 0], [2, 0, 0]])
    ends = starts + np.array([[0, 1, 0], [0, 0, 0], [0, 1, 0]])
    with pytest.raises(ValueError, match="ruling 1 has zero length"):
        unroll_rulings(starts, ends)


def test_bilinear_area_of_a_planar_trapezoid_is_exact():
    starts = np.array([[0.0, 0, 0], [3, 0, 0]])
    ends = np.array([[1.0, 2, 0], [2, 2, 0]])
    assert bilinear_quad_areas(starts, ends)[0] == pytest.approx(4.0, rel=1e-15)


# ---------------------------------------------------------------------- large strips


def test_ten_thousand_rulings_unroll_keeping_every_edge_length():
    """How fast, against plain numpy on the same strip in the same run: bench_unroll.py."""
    starts, ends = helix_tangent_rulings(9999, turns=10)
    dev = unroll_rulings(starts, ends)
    assert len(dev.starts2d) == 10_000
    assert dev.max_edge_length_error < 1e-12


def test_a_strip_far_from_the_origin_unrolls_to_the_shape_it_has_at_the_origin():
    """Rails on control points exact at 1e9 m (multiples of 2⁻²⁰ m), so the moved strip is
    the strip, moved, to the bit. Sampled at world coordinates its ruling ends rounded to
    1.2e-7 m and the 2,245 quads, laid one after another, turned by that: the flat shape
    moved by 1e-9 of its size. Sampled about the strip's anchor it is the origin's."""
    rng = np.random.default_rng(3)
    a = np.cumsum(rng.uniform(5.0, 15.0, (7, 3)) * [1.0, 0.3, 0.3], axis=0)
    b = a + np.array([0.0, 20.0, 5.0]) + rng.normal(0.0, 3.0, (7, 3))
    a, b = (np.round(p * 2**20) / 2**20 for p in (a, b))
    wa, wb = rng.uniform(0.5, 2.0, 7), rng.uniform(0.5, 2.0, 7)

    def unrolled(offset):
        return unroll_surface(RuledSurface(NurbsCurve(a + offset, 3, weights=wa),
                                           NurbsCurve(b + offset, 3, weights=wb)), 12, 8, 1e-7)

    origin, far = unrolled(np.zeros(3)), unrolled(np.full(3, 1e9))
    assert len(far.starts2d) == len(origin.starts2d) > 2000
    size = float(np.linalg.norm(np.ptp(np.vstack([origin.starts2d, origin.ends2d]), axis=0)))
    for flat_far, flat in ((far.starts2d, origin.starts2d), (far.ends2d, origin.ends2d)):
        assert np.abs(flat_far - flat).max() <= 1e-13 * size
    ulp = float(np.spacing(1e9))  # the 3D side is in world coordinates, rounded there
    np.testing.assert_allclose(far.starts3d - 1e9, origin.starts3d, rtol=0, atol=ulp)
    np.testing.assert_allclose(far.map.vertices3d - 1e9, origin.map.vertices3d, rtol=0, atol=ulp)
