"""surfaces.ParametricSurface → SurfaceCurvature and Area against closed forms.

Every surface here is built by the ParametricSurface node from expression text, and
read by the SurfaceCurvature, EvaluateSurface and Area nodes in one graph with the
real Solver. Curvatures must match the closed forms to 1e-6 relative, at interior
points and on all four edges and corners, also over arbitrary domains such as
u ∈ [−3.7, 12.1]. Where a closed form is 0 (a torus's parabolic circles, a
helicoid's mean curvature) "relative" is measured against the point's largest
principal curvature |k|, the natural scale of every curvature there.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support.node_helpers import Source
from torsal.engine.datatree import DataTree
from torsal.engine.graph import Graph
from torsal.engine.solver import Solver
from torsal.engine.types import encode_value
from torsal.engine.values import Domain, Point
from torsal.nodes.surfaces.analysis import Area, EvaluateSurface, SurfaceCurvature
from torsal.nodes.surfaces.freeform import ParametricSurface

REL = 1e-6

#: Corners, points on every edge, and interior points of the parameter square.
UVS = np.array([
    (0, 0), (1, 0), (0, 1), (1, 1),
    (0.5, 0), (1, 0.61), (0.23, 1), (0, 0.37),
    (0.31, 0.77), (0.5, 0.5), (0.9, 0.13), (0.07, 0.93),
])

ARBITRARY = Domain(-3.7, 12.1)


def solve_on(reader, formulas, u_domain, v_domain, uvs=UVS, port="Surface"):
    """ParametricSurface(formulas) wired into ``reader``'s ``port`` (and UV, unless None)."""
    graph = Graph()
    graph.add_node(ParametricSurface(), "surface")
    for name, text in zip("XYZ", formulas, strict=True):
        graph.set_input_value("surface", name, text)
    graph.set_input_value("surface", "UDomain", encode_value(u_domain))
    graph.set_input_value("surface", "VDomain", encode_value(v_domain))
    graph.add_node(reader, "reader")
    graph.connect("surface", "Surface", "reader", port)
    if uvs is not None:
        graph.add_node(Source(DataTree({(0,): [Point(u, v, 0) for u, v in uvs]})), "uv")
        graph.connect("uv", "Tree", "reader", "UV")
    solver = Solver(graph)
    solver.solve()
    assert solver.result("surface").state == "ok", solver.result("surface").messages
    result = solver.result("reader")
    assert result.state == "ok", result.messages
    return {name: np.asarray(tree.branches[0], dtype=float) for name, tree in result.outputs.items()}


def curvature(formulas, u_domain, v_domain, uvs=UVS):
    return solve_on(SurfaceCurvature(), formulas, u_domain, v_domain, uvs)


def parameters(u_domain, v_domain, uvs=UVS):
    """The original (u, v) of normalised ``uvs``."""
    u = u_domain[0] + uvs[:, 0] * (u_domain[1] - u_domain[0])
    v = v_domain[0] + uvs[:, 1] * (v_domain[1] - v_domain[0])
    return u, v


def assert_close(actual, expected, scale):
    """|actual − expected| <= REL · max(|expected|, scale), elementwise."""
    actual, expected = np.asarray(actual), np.asarray(expected)
    bound = REL * np.maximum(np.abs(expected), scale)
    worst = np.max(np.abs(actual - expected) / bound)
    assert worst <= 1.0, f"error {worst:.3g} × the allowed {REL:g} relative"


def assert_curvatures(c, k1, k2):
    """K1, K2, Gaussian and Mean against closed-form principal curvatures."""
    scale = np.maximum(np.abs(k1), np.abs(k2))
    assert_close(c["K1"], k1, scale)
    assert_close(c["K2"], k2, scale)
    assert_close(c["Gaussian"], k1 * k2, scale**2)
    assert_close(c["Mean"], (k1 + k2) / 2, scale)


# --------------------------------------------------------------------------- sphere

SPHERE = ("2.5 * cos(u) * cos(v)", "2.5 * sin(u) * cos(v)", "2.5 * sin(v)")


@pytest.mark.parametrize("u_domain, v_domain", [
    (Domain(0, 2 * math.pi), Domain(-1.5, 1.5)),
    (ARBITRARY, Domain(-1.2, 1.4)),
])
def test_sphere_curvatures_are_minus_one_over_r_with_the_outward_normal(u_domain, v_domain):
    c = curvature(SPHERE, u_domain, v_domain)
    n = len(UVS)
    assert_curvatures(c, np.full(n, -1 / 2.5), np.full(n, -1 / 2.5))


def test_sphere_over_a_reversed_domain_turns_its_normal_and_mean_curvature_over():
    c = curvature(SPHERE, Domain(12.1, -3.7), Domain(-1.2, 1.4))
    n = len(UVS)
    assert_curvatures(c, np.full(n, 1 / 2.5), np.full(n, 1 / 2.5))
    assert np.allclose(np.einsum("ij,ij->i", c["Normal"], c["Point"]) / 2.5, -1.0, atol=1e-9)


def test_sphere_normal_from_evaluate_surface_is_radial():
    out = solve_on(EvaluateSurface(), SPHERE, ARBITRARY, Domain(-1.2, 1.4))
    radial = out["Point"] / np.linalg.norm(out["Point"], axis=1, keepdims=True)
    assert np.abs(np.linalg.norm(out["Point"], axis=1) - 2.5).max() < 1e-12
    assert np.abs(out["Normal"] - radial).max() < 1e-9


# --------------------------------------------------------------------------- torus

BIG, SMALL = 3.0, 1.2
TORUS = ("(3 + 1.2 * cos(v)) * cos(u)", "(3 + 1.2 * cos(v)) * sin(u)", "1.2 * sin(v)")


def torus_principal(v):
    """k1 along the parallels, −cos v/(R + r cos v); k2 = −1/r round the tube."""
    return -np.cos(v) / (BIG + SMALL * np.cos(v)), np.full(len(v), -1 / SMALL)


@pytest.mark.parametrize("u_domain, v_domain", [
    (Domain(0, 2 * math.pi), Domain(0, 2 * math.pi)),
    (ARBITRARY, Domain(-2.0, 9.5)),
])
def test_torus_curvatures_match_the_closed_forms(u_domain, v_domain):
    c = curvature(TORUS, u_domain, v_domain)
    _, v = parameters(u_domain, v_domain)
    assert_curvatures(c, *torus_principal(v))


@pytest.mark.parametrize("region, v_domain, sign", [
    ("outer equator: elliptic", Domain(0.0, 1.0), 1),
    ("top circle: parabolic", Domain(math.pi / 2, 4.0), 0),
    ("bottom circle: parabolic", Domain(-math.pi / 2, 0.3), 0),
    ("inner equator: hyperbolic", Domain(math.pi, 4.0), -1),
])
def test_torus_regions_on_the_boundary_edge(region, v_domain, sign):
    """Edge v = 0 of each patch lies on the named circle of the torus."""
    uvs = np.array([(0.0, 0.0), (0.4, 0.0), (1.0, 0.0)])
    c = curvature(TORUS, ARBITRARY, v_domain, uvs)
    _, v = parameters(ARBITRARY, v_domain, uvs)
    k1, k2 = torus_principal(v)
    assert_curvatures(c, k1, k2)
    gaussian = np.cos(v[0]) / (SMALL * (BIG + SMALL * np.cos(v[0])))
    assert_close(c["Gaussian"], np.full(3, gaussian), 1 / SMALL**2)
    assert np.all(np.sign(np.round(c["Gaussian"], 9)) == sign), region


def test_torus_first_principal_direction_runs_round_the_axis():
    c = curvature(TORUS, ARBITRARY, Domain(-2.0, 9.5))
    u, _ = parameters(ARBITRARY, Domain(-2.0, 9.5))
    along_u = np.column_stack([-np.sin(u), np.cos(u), np.zeros_like(u)])
    assert np.abs(np.abs(np.einsum("ij,ij->i", c["Direction1"], along_u)) - 1).max() < REL
    assert np.abs(np.einsum("ij,ij->i", c["Direction2"], along_u)).max() < REL
    assert np.abs(np.einsum("ij,ij->i", c["Direction1"], c["Normal"])).max() < 1e-12


# --------------------------------------------------------------------------- saddle and helicoid

@pytest.mark.parametrize("u_domain, v_domain", [
    (Domain(-1, 1), Domain(-1, 1)),
    (ARBITRARY, Domain(-2.5, 1.5)),
])
def test_hyperbolic_paraboloid_z_equals_xy(u_domain, v_domain):
    """K = −1/W⁴ and H = −uv/W³ with W² = 1 + u² + v² (normal (−v, −u, 1)/W)."""
    c = curvature(("u", "v", "u * v"), u_domain, v_domain)
    u, v = parameters(u_domain, v_domain)
    w2 = 1 + u * u + v * v
    gaussian, mean = -1 / w2**2, -u * v / w2**1.5
    root = np.sqrt(mean * mean - gaussian)
    assert_curvatures(c, mean + root, mean - root)


@pytest.mark.parametrize("u_domain, v_domain", [
    (Domain(0.5, 3), Domain(0, 4 * math.pi)),
    (ARBITRARY, Domain(-3.7, 12.1)),
])
def test_helicoid_is_minimal_with_k_equal_to_c_over_c2_plus_u2(u_domain, v_domain):
    """(u cos v, u sin v, c v): k1,2 = ±c/(c² + u²), so H = 0 and K = −c²/(c² + u²)²."""
    c = curvature(("u * cos(v)", "u * sin(v)", "0.8 * v"), u_domain, v_domain)
    u, _ = parameters(u_domain, v_domain)
    k = 0.8 / (0.64 + u * u)
    assert_curvatures(c, k, -k)


# --------------------------------------------------------------------------- areas

def area(formulas, u_domain, v_domain):
    out = solve_on(Area(), formulas, u_domain, v_domain, uvs=None, port="Geometry")
    return float(out["Area"][0]), out["Centroid"][0]


def test_sphere_area_is_4_pi_r_squared_and_its_centroid_the_centre():
    value, centroid = area(SPHERE, Domain(0, 2 * math.pi), Domain(-math.pi / 2, math.pi / 2))
    assert abs(value / (4 * math.pi * 2.5**2) - 1) < REL
    assert np.abs(centroid).max() < 1e-9


def test_sphere_zone_area_over_an_arbitrary_domain():
    """A zone between latitudes a and b, swept through Δu radians: r²·Δu·(sin b − sin a)."""
    value, _ = area(SPHERE, ARBITRARY, Domain(-1.2, 1.4))
    exact = 2.5**2 * 15.8 * (math.sin(1.4) - math.sin(-1.2))
    assert abs(value / exact - 1) < REL


def test_torus_area_is_4_pi_squared_big_r_small_r():
    value, centroid = area(TORUS, Domain(0, 2 * math.pi), Domain(0, 2 * math.pi))
    assert abs(value / (4 * math.pi**2 * BIG * SMALL) - 1) < REL
    assert np.abs(centroid).max() < 1e-9


@pytest.mark.parametrize("u_domain, v_domain", [
    (Domain(0, 3), Domain(0, 2 * math.pi)),
    (ARBITRARY, Domain(-1.0, 5.5)),
])
def test_helicoid_area_matches_the_closed_form(u_domain, v_domain):
    """Δv/2·[F(b) − F(a)], F(u) = u√(u² + c²) + c² asinh(u/c), for u from a to b."""
    value, _ = area(("u * cos(v)", "u * sin(v)", "0.8 * v"), u_domain, v_domain)

    def f(u):
        return u * math.sqrt(u * u + 0.64) + 0.64 * math.asinh(u / 0.8)

    exact = (v_domain.max - v_domain.min) / 2 * (f(u_domain.max) - f(u_domain.min))
    assert abs(value / exact - 1) < REL
