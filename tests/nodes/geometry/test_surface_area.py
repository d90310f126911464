"""Areas and centroids by adaptive cubature, against closed forms (bar: 1e-6 relative)."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from torsal.nodes.geometry.area import integrate_unit_square
from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.nurbs_surface import NurbsSurface
from torsal.nodes.geometry.parametric_surface import ParametricSurface, cone, sphere, torus


def test_sphere_area_is_four_pi_r_squared():
    radius = 1.7

    def f(u, v):
        return radius * np.column_stack([np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v)])

    expression = ParametricSurface(f, (0.0, 2 * np.pi), (0.0, np.pi))
    exact = 4 * np.pi * radius**2
    assert expression.area() == pytest.approx(exact, rel=1e-10)
    assert sphere(radius).area() == pytest.approx(exact, rel=1e-12)


@pytest.mark.parametrize("analytic", [True, False], ids=["analytic", "expression"])
def test_torus_area_is_four_pi_squared_big_r_small_r(analytic):
    big, small = 3.0, 0.4
    if analytic:
        surface = torus(big, small)
    else:
        surface = ParametricSurface(
            lambda u, v: (
                (big + small * np.cos(v)) * np.cos(u),
                (big + small * np.cos(v)) * np.sin(u),
                small * np.sin(v),
            ),
            (0.0, 2 * np.pi),
            (0.0, 2 * np.pi),
        )
    assert surface.area() == pytest.approx(4 * np.pi**2 * big * small, rel=1e-10)


@pytest.mark.parametrize("u_domain, v_domain", [((0.0, 4 * np.pi), (0.0, 1.5)), ((-3.7, 12.1), (-0.5, 2.0))])
def test_helicoid_area_matches_integral_of_sqrt_v2_plus_c2(u_domain, v_domain):
    pitch = 0.5
    surface = ParametricSurface(lambda u, v: (v * np.cos(u), v * np.sin(u), pitch * u), u_domain, v_domain)

    def antiderivative(v):  # ∫ sqrt(v² + c²) dv
        return 0.5 * v * np.sqrt(v * v + pitch**2) + 0.5 * pitch**2 * np.arcsinh(v / pitch)

    exact = (u_domain[1] - u_domain[0]) * (antiderivative(v_domain[1]) - antiderivative(v_domain[0]))
    assert surface.area() == pytest.approx(exact, rel=1e-10)


def test_cone_area_is_pi_r_times_slant_height():
    surface = cone(radius=1.2, height=2.5)
    assert surface.area() == pytest.approx(np.pi * 1.2 * np.hypot(1.2, 2.5), rel=1e-12)


def test_hemisphere_centroid_is_half_the_radius_above_the_base():
    radius = 2.0
    surface = ParametricSurface(
        lambda u, v: radius * np.column_stack([np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v)]),
        (0.0, 2 * np.pi),
        (0.0, np.pi / 2),
    )
    area, centroid = surface.area_and_centroid()
    assert area == pytest.approx(2 * np.pi * radius**2, rel=1e-10)
    np.testing.assert_allclose(centroid, [0.0, 0.0, radius / 2], atol=1e-10)


def test_bilinear_patch_area_equals_its_flat_rectangle():
    grid = np.array([[[0, 0, 0], [0, 2, 0]], [[3, 0, 0], [3, 2, 0]]], dtype=float)
    assert NurbsSurface(grid, 1, 1).area() == pytest.approx(6.0, rel=1e-14)


def test_cubature_is_exact_for_polynomials_and_adapts_to_peaks():
    value = integrate_unit_square(lambda u, v: u**7 * v**5 + 1.0)[0]
    assert value == pytest.approx(1 / 48 + 1.0, rel=1e-14)
    sharp = integrate_unit_square(lambda u, v: 1.0 / ((u - 0.3) ** 2 + (v - 0.6) ** 2 + 1e-3))[0]
    # Reference: the same integrand on a 4000 × 4000 midpoint grid is far too coarse;
    # compare with scipy's dblquad instead.
    from scipy import integrate

    ref = integrate.dblquad(
        lambda v, u: 1.0 / ((u - 0.3) ** 2 + (v - 0.6) ** 2 + 1e-3), 0, 1, 0, 1, epsabs=1e-13, epsrel=1e-13
    )[0]
    assert sharp == pytest.approx(ref, rel=1e-9)


def test_vector_valued_integrand_integrates_componentwise():
    result = integrate_unit_square(lambda u, v: np.column_stack([u, v * v, u * v]))
    np.testing.assert_allclose(result, [0.5, 1 / 3, 0.25], rtol=1e-14)


def test_mesh_surface_area_is_the_sum_of_triangle_areas():
    box = trimesh.creation.box(extents=(1.0, 2.0, 3.0))
    surface = MeshSurface(box)
    assert surface.area() == pytest.approx(2 * (2 + 3 + 6), rel=1e-14)
    area, centroid = surface.area_and_centroid()
    assert area == pytest.approx(22.0, rel=1e-14)
    np.testing.assert_allclose(centroid, 0.0, atol=1e-15)


def test_a_moved_and_scaled_surface_keeps_its_own_integrator_and_scales_its_area_by_k_squared(monkeypatch):
    from torsal.nodes.geometry.ruled import RuledSurface
    from torsal.nodes.geometry.surface_base import Surface
    from torsal.nodes.geometry.transforms import rotation, scaling, translation

    # a cone frustum between two circles as a ruled surface: lateral area π(r1 + r2)·slant
    angle = np.linspace(0.0, 2 * np.pi, 65)
    ring = np.column_stack([np.cos(angle), np.sin(angle), 0 * angle])
    ring[-1] = ring[0]
    frustum = RuledSurface.from_rulings(ring, 0.5 * ring + [0.0, 0.0, 1.0])
    area, centroid = frustum.area_and_centroid()
    matrix = translation([4.0, -1.0, 2.0]) @ rotation([1.0, 2.0, 0.5], 0.7) @ scaling(2.5)
    moved = frustum.transformed(matrix)

    def no_cubature(*_args, **_kwargs):
        raise AssertionError("used the generic cubature")

    monkeypatch.setattr(Surface, "area_and_centroid", no_cubature)
    moved_area, moved_centroid = moved.area_and_centroid()
    assert moved_area == pytest.approx(2.5**2 * area, rel=1e-13)
    np.testing.assert_allclose(moved_centroid, (matrix @ np.append(centroid, 1.0))[:3], atol=1e-12)
    monkeypatch.undo()

    # a non-uniform scale is not a similarity: the generic cubature integrates it
    flat = RuledSurface.from_rulings([[0, 0, 0], [1, 0, 0]], [[0, 1, 0], [1, 1, 0]])
    assert flat.transformed(np.diag([2.0, 3.0, 1.0, 1.0])).area() == pytest.approx(6.0, rel=1e-12)
