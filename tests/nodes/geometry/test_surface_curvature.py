"""Curvature of surfaces against closed forms (issue 3 bars: 1e-6 relative).

The expression-defined surfaces here come *without* derivatives, as they do from the
ParametricSurface node, so these tests exercise the finite-difference scheme too.
Where the exact value is zero (parabolic circles, H of a minimal surface) the
tolerance is 1e-6 of the surface's curvature scale instead.
"""

from __future__ import annotations

import numpy as np
import pytest

from torsal.nodes.geometry.curvature import normal_curvature, principal_curvatures
from torsal.nodes.geometry.parametric_surface import ParametricSurface, cone, cylinder, sphere, torus

RTOL = 1e-6

# Interior and boundary samples of the unit square, corners included.
EDGE = np.array([0.0, 1.0])
INNER = np.array([0.013, 0.25, 0.5, 0.77, 0.987])
S_INT, T_INT = (a.ravel() for a in np.meshgrid(INNER, INNER, indexing="ij"))
S_BND = np.concatenate([EDGE.repeat(5), np.tile(INNER, 2), [0, 0, 1, 1]])
T_BND = np.concatenate([np.tile(INNER, 2), EDGE.repeat(5), [0, 1, 0, 1]])
SAMPLES = {"interior": (S_INT, T_INT), "boundary": (S_BND, T_BND)}


def assert_rel(actual, expected, scale, rtol=RTOL):
    """|actual − expected| <= rtol · max(|expected|, scale), elementwise."""
    actual, expected = np.asarray(actual), np.asarray(expected)
    bound = rtol * np.maximum(np.abs(expected), scale)
    err = np.abs(actual - expected)
    assert np.all(err <= bound), (
        f"worst relative error {np.max(err / np.maximum(np.abs(expected), scale)):.3g}"
    )


def user_params(surface, s, t):
    (u0, u1), (v0, v1) = surface.u_domain, surface.v_domain
    return u0 + s * (u1 - u0), v0 + t * (v1 - v0)


def torus_function(big, small):
    def f(u, v):
        ring = big + small * np.cos(v)
        return ring * np.cos(u), ring * np.sin(u), small * np.sin(v)

    return f


def torus_exact(v, big, small):
    """k1 >= k2 for the outward normal (the parameterisation's Su × Sv)."""
    parallel = -np.cos(v) / (big + small * np.cos(v))
    meridian = np.full_like(v, -1.0 / small)
    return np.maximum(parallel, meridian), np.minimum(parallel, meridian)


def check_principal(curv, k1, k2, scale):
    assert_rel(curv.k1, k1, scale)
    assert_rel(curv.k2, k2, scale)
    assert_rel(curv.gaussian, k1 * k2, scale**2)
    assert_rel(curv.mean, 0.5 * (k1 + k2), scale)


# ---------------------------------------------------------------- expression surfaces


@pytest.mark.parametrize("where", SAMPLES)
@pytest.mark.parametrize(
    "u_domain, v_domain",
    [((0.0, 2 * np.pi), (0.0, 2 * np.pi)), ((-3.7, 12.1), (-2.0, 9.0))],
    ids=["natural", "reparameterised"],
)
def test_torus_curvatures_match_closed_form(where, u_domain, v_domain):
    big, small = 2.0, 0.7
    surface = ParametricSurface(torus_function(big, small), u_domain, v_domain)
    s, t = SAMPLES[where]
    _, v = user_params(surface, s, t)
    k1, k2 = torus_exact(v, big, small)
    check_principal(surface.curvature(s, t), k1, k2, 1.0 / small)


def test_torus_gaussian_curvature_is_positive_outside_zero_on_top_negative_inside():
    big, small = 2.0, 0.7
    surface = ParametricSurface(torus_function(big, small), (0, 2 * np.pi), (0, 2 * np.pi))
    # v = 0 outer equator (elliptic), v = π/2 top circle (parabolic), v = π inner (hyperbolic)
    s = np.array([0.3, 0.3, 0.3, 0.0, 1.0])
    t = np.array([0.0, 0.25, 0.5, 0.75, 1.0])
    gauss = surface.gaussian_curvature(s, t)
    exact = np.cos(2 * np.pi * t) / (small * (big + small * np.cos(2 * np.pi * t)))
    assert gauss[0] > 0 and gauss[2] < 0 and gauss[4] > 0
    assert_rel(gauss, exact, 1.0 / small**2)
    assert np.all(np.abs(gauss[[1, 3]]) < 1e-8 / small**2)  # parabolic circles


@pytest.mark.parametrize("where", SAMPLES)
@pytest.mark.parametrize(
    "u_domain, v_domain",
    [((-1.0, 1.0), (-1.0, 1.0)), ((-3.7, 12.1), (-2.0, 5.0))],
    ids=["natural", "reparameterised"],
)
def test_hyperbolic_paraboloid_gaussian_is_minus_one_over_w4(where, u_domain, v_domain):
    surface = ParametricSurface(lambda x, y: (x, y, x * y), u_domain, v_domain)
    s, t = SAMPLES[where]
    x, y = user_params(surface, s, t)
    w2 = 1.0 + x * x + y * y
    gauss = -1.0 / w2**2
    mean = -x * y / w2**1.5  # normal (−y, −x, 1)/W
    root = np.sqrt(mean**2 - gauss)
    curv = surface.curvature(s, t)
    assert_rel(curv.gaussian, gauss, 0.0)
    assert_rel(curv.mean, mean, np.abs(gauss) ** 0.5)
    assert_rel(curv.k1, mean + root, 0.0)
    assert_rel(curv.k2, mean - root, 0.0)


@pytest.mark.parametrize("where", SAMPLES)
@pytest.mark.parametrize(
    "u_domain, v_domain",
    [((0.0, 4 * np.pi), (-1.5, 1.5)), ((-3.7, 12.1), (0.2, 2.5))],
    ids=["natural", "reparameterised"],
)
def test_helicoid_is_minimal_with_gaussian_minus_c2_over_c2_plus_v2_squared(where, u_domain, v_domain):
    pitch = 0.5
    surface = ParametricSurface(lambda u, v: (v * np.cos(u), v * np.sin(u), pitch * u), u_domain, v_domain)
    s, t = SAMPLES[where]
    _, v = user_params(surface, s, t)
    k = pitch / (pitch**2 + v**2)
    curv = surface.curvature(s, t)
    assert_rel(curv.gaussian, -(k**2), 0.0)
    assert_rel(curv.k1, k, 0.0)
    assert_rel(curv.k2, -k, 0.0)
    assert np.all(np.abs(curv.mean) <= RTOL * k)


@pytest.mark.parametrize("where", SAMPLES)
@pytest.mark.parametrize(
    "u_domain, v_domain",
    [((0.0, 2 * np.pi), (0.2, np.pi - 0.2)), ((-3.7, 12.1), (0.4, 2.9))],
    ids=["natural", "reparameterised"],
)
def test_sphere_is_umbilic_with_curvature_one_over_radius(where, u_domain, v_domain):
    radius = 2.5

    def f(u, v):
        return radius * np.column_stack([np.cos(u) * np.sin(v), np.sin(u) * np.sin(v), np.cos(v)])

    surface = ParametricSurface(f, u_domain, v_domain)
    s, t = SAMPLES[where]
    curv = surface.curvature(s, t)
    points = surface.point_at(s, t)
    # Bending towards n is positive: k = −(n · radial)/R.
    expected = -np.einsum("ij,ij->i", curv.normal, points / radius) / radius
    check_principal(curv, expected, expected, 1.0 / radius)


def test_one_sided_stencils_keep_boundary_accuracy_when_extrapolation_is_off():
    big, small = 3.0, 1.1
    surface = ParametricSurface(torus_function(big, small), (-3.7, 12.1), (-2.0, 9.0), extrapolate=False)
    s, t = SAMPLES["boundary"]
    _, v = user_params(surface, s, t)
    k1, k2 = torus_exact(v, big, small)
    check_principal(surface.curvature(s, t), k1, k2, 1.0 / small)


def test_function_undefined_outside_its_domain_falls_back_to_one_sided_stencils():
    big, small = 2.0, 0.7
    inner = torus_function(big, small)

    def guarded(u, v):  # NaN outside [0, π] × [0, π], like sqrt of a negative number
        x, y, z = inner(u, v)
        outside = (u < 0) | (u > np.pi) | (v < 0) | (v > np.pi)
        return np.where(outside, np.nan, x), y, z

    surface = ParametricSurface(guarded, (0.0, np.pi), (0.0, np.pi))
    s, t = SAMPLES["boundary"]
    _, v = user_params(surface, s, t)
    k1, k2 = torus_exact(v, big, small)
    check_principal(surface.curvature(s, t), k1, k2, 1.0 / small)


def test_finite_difference_derivatives_match_analytic_ones():
    analytic = torus(2.0, 0.7)
    numeric = ParametricSurface(torus_function(2.0, 0.7), (0, 2 * np.pi), (0, 2 * np.pi))
    s = np.concatenate([S_INT, S_BND])
    t = np.concatenate([T_INT, T_BND])
    exact = analytic.derivatives(s, t, 2)
    approx = numeric.derivatives(s, t, 2)
    scale = [1.0, 2 * np.pi * 2.7, 2 * np.pi * 2.7, 40 * 2.7, 40 * 2.7, 40 * 2.7]
    for name, e, a, sc, tol in zip(
        ["S", "Su", "Sv", "Suu", "Suv", "Svv"],
        exact,
        approx,
        scale,
        [1e-15, 1e-10, 1e-10, 1e-8, 1e-8, 1e-8],
        strict=True,
    ):
        assert np.abs(e - a).max() <= tol * sc, name


# ---------------------------------------------------------------- primitives (analytic)


def test_analytic_torus_curvatures_match_closed_form():
    big, small = 2.0, 0.7
    surface = torus(big, small, center=(1.0, -2.0, 3.0))
    s = np.concatenate([S_INT, S_BND])
    t = np.concatenate([T_INT, T_BND])
    k1, k2 = torus_exact(2 * np.pi * t, big, small)
    check_principal(surface.curvature(s, t), k1, k2, 1.0 / small)


def test_analytic_sphere_has_outward_normal_and_curvature_minus_one_over_radius():
    surface = sphere(3.0, center=(1.0, 2.0, 3.0))
    curv = surface.curvature(S_INT, T_INT)
    radial = (surface.point_at(S_INT, T_INT) - [1.0, 2.0, 3.0]) / 3.0
    np.testing.assert_allclose(curv.normal, radial, atol=1e-14)
    np.testing.assert_allclose(curv.k1, -1 / 3.0, rtol=1e-13)
    np.testing.assert_allclose(curv.k2, -1 / 3.0, rtol=1e-13)
    np.testing.assert_allclose(curv.gaussian, 1 / 9.0, rtol=1e-13)


def test_sphere_pole_normal_and_curvature_come_from_a_point_just_inside():
    surface = sphere(2.0)
    curv = surface.curvature([0.3, 0.3], [0.0, 1.0])  # south and north pole
    np.testing.assert_allclose(curv.normal, [[0, 0, -1], [0, 0, 1]], atol=1e-5)
    np.testing.assert_allclose(curv.gaussian, 0.25, rtol=1e-9)
    np.testing.assert_allclose(surface.normal_at([0.3, 0.3], [0.0, 1.0]), curv.normal)


def test_cylinder_has_one_zero_principal_curvature_along_the_axis():
    surface = cylinder(radius=1.5, height=4.0)
    curv = surface.curvature(S_INT, T_INT)
    np.testing.assert_allclose(curv.k1, 0.0, atol=1e-15)
    np.testing.assert_allclose(curv.k2, -1 / 1.5, rtol=1e-14)
    np.testing.assert_allclose(np.abs(curv.direction1[:, 2]), 1.0, rtol=1e-14)  # along z
    np.testing.assert_allclose(curv.gaussian, 0.0, atol=1e-15)


def test_cone_curvature_falls_off_as_one_over_distance_to_apex():
    radius, height = 1.0, 2.0
    surface = cone(radius, height)
    curv = surface.curvature(S_INT, T_INT)
    slant = np.hypot(radius, height)
    dist_to_apex = (1.0 - T_INT) * slant
    # Circle curvature 1/ρ projected on the normal: ρ = r(1−v), cos = h/slant.
    expected = -(height / slant) / (radius * (1.0 - T_INT))
    np.testing.assert_allclose(curv.k2, expected, rtol=1e-13)
    np.testing.assert_allclose(curv.k2 * dist_to_apex, -height / radius, rtol=1e-13)
    np.testing.assert_allclose(curv.gaussian, 0.0, atol=1e-13)


# ---------------------------------------------------------------- directions and forms


def test_torus_principal_directions_are_parallels_and_meridians():
    surface = torus(2.0, 0.7)
    s, t = S_INT, T_INT
    _, su, sv = surface.derivatives(s, t, 1)
    curv = surface.curvature(s, t)
    along_u = su / np.linalg.norm(su, axis=1, keepdims=True)
    along_v = sv / np.linalg.norm(sv, axis=1, keepdims=True)
    np.testing.assert_allclose(np.abs(np.einsum("ij,ij->i", curv.direction1, along_u)), 1, atol=1e-12)
    np.testing.assert_allclose(np.abs(np.einsum("ij,ij->i", curv.direction2, along_v)), 1, atol=1e-12)


def test_principal_directions_form_a_right_handed_frame_with_the_normal():
    surface = ParametricSurface(lambda x, y: (x, y, x * y + 0.3 * x**3), (-1, 2), (-1, 1))
    curv = surface.curvature(S_INT, T_INT)
    frame = np.stack([curv.direction1, curv.direction2, curv.normal], axis=1)
    np.testing.assert_allclose(
        frame @ frame.transpose(0, 2, 1), np.broadcast_to(np.eye(3), frame.shape), atol=1e-12
    )
    np.testing.assert_allclose(np.linalg.det(frame), 1.0, atol=1e-12)


def test_normal_curvature_along_principal_directions_equals_k1_and_k2():
    surface = ParametricSurface(lambda x, y: (x, y, np.sin(x) * np.cosh(y)), (-1, 2), (-1, 1))
    s, t = S_INT, T_INT
    _, su, sv = surface.derivatives(s, t, 1)
    forms = surface.fundamental_forms(s, t)
    curv = surface.curvature(s, t)
    for direction, k in ((curv.direction1, curv.k1), (curv.direction2, curv.k2)):
        # Parameter-space components (du, dv) of the tangent direction: I·(du, dv) = (Su·d, Sv·d).
        rhs = np.stack([np.einsum("ij,ij->i", su, direction), np.einsum("ij,ij->i", sv, direction)], 1)
        metric = np.stack([np.stack([forms.E, forms.F], 1), np.stack([forms.F, forms.G], 1)], 1)
        duv = np.linalg.solve(metric, rhs[..., None])[..., 0]
        np.testing.assert_allclose(normal_curvature(forms, duv[:, 0], duv[:, 1]), k, rtol=1e-8, atol=1e-10)


def test_umbilic_directions_stay_orthonormal_and_tangent():
    # A sphere's shape operator is a multiple of the identity everywhere.
    su = np.array([[1.0, 0.0, 0.0]])
    sv = np.array([[0.3, 2.0, 0.0]])
    n = np.array([[0.0, 0.0, 1.0]])
    e, f, g = 1.0, 0.3, 0.09 + 4.0
    k = 0.5  # II = k·I
    curv = principal_curvatures(su, sv, k * e * n, k * f * n, k * g * n)
    np.testing.assert_allclose([curv.k1[0], curv.k2[0]], [k, k], rtol=1e-15)
    np.testing.assert_allclose(np.linalg.norm(curv.direction1), 1.0)
    np.testing.assert_allclose(curv.direction1 @ curv.direction2.T, 0.0, atol=1e-15)
    np.testing.assert_allclose(curv.direction1 @ n.T, 0.0, atol=1e-15)


def test_fundamental_forms_of_plane_graph_match_textbook_values():
    surface = ParametricSurface(lambda x, y: (x, y, x * y), (-1.0, 1.0), (-1.0, 1.0))
    forms = surface.fundamental_forms(0.75, 0.25)  # x = 0.5, y = -0.5 (chain rule: ×2)
    x, y = 0.5, -0.5
    w = np.sqrt(1 + x * x + y * y)
    np.testing.assert_allclose(
        [forms.E[0], forms.F[0], forms.G[0]], [4 * (1 + y * y), 4 * x * y, 4 * (1 + x * x)], rtol=1e-10
    )
    np.testing.assert_allclose([forms.L[0], forms.M[0], forms.N[0]], [0.0, 4 / w, 0.0], atol=1e-9)
