"""analysis.SurfaceAnalysis: exact curvature, single-curved share of the area, valid rulings,
the coloured mesh, on surfaces with closed forms (cylinder, cone, torus, saddles)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support.analysis_shapes import (
    capsule,
    helicoid,
    helicoid_gaussian,
    hypar,
    hypar_gaussian,
    tilted_cylinder,
)
from tests.support.node_helpers import out, run, texts, tree
from torsal.nodes.analysis.colours import STOPS
from torsal.nodes.analysis.surface_analysis import SurfaceAnalysis
from torsal.nodes.geometry.curves import Circle
from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.parametric_surface import cone, cylinder, torus

R_CYL, H_CYL = 1.5, 2.0
R_TORUS, r_TORUS = 2.0, 0.5
LISTS = {"CurvatureLines", "ValidRulings", "Gaussian", "Mean", "K1", "K2", "Points"}


def analysed(surface, **inputs):
    result = run(SurfaceAnalysis(), Surface=tree({(0,): [surface]}), **inputs)
    if result.state == "warning" and not result.outputs["K1"].branches:
        return result, {}
    values = {port: out(result, port)[(0,)] if port in LISTS else out(result, port)[(0,)][0]
              for port in result.outputs}
    return result, values


def directions(lines) -> tuple[np.ndarray, np.ndarray]:
    starts = np.array([line.start for line in lines])
    ends = np.array([line.end for line in lines])
    return starts, ends


def sine_to(axis: np.ndarray, vectors: np.ndarray) -> np.ndarray:
    unit = vectors / np.linalg.norm(vectors, axis=1, keepdims=True)
    return np.linalg.norm(np.cross(unit, axis / np.linalg.norm(axis)), axis=1)


def torus_gaussian(points: np.ndarray) -> np.ndarray:
    cos_v = (np.hypot(points[:, 0], points[:, 1]) - R_TORUS) / r_TORUS
    return cos_v / (r_TORUS * (R_TORUS + r_TORUS * cos_v))


def test_cylinder_is_100_percent_single_curved():
    result, v = analysed(cylinder(R_CYL, H_CYL), UDensity=12, VDensity=5)
    assert v["DevelopableFraction"] == pytest.approx(1.0, abs=1e-12)
    assert np.abs(v["Gaussian"]).max() < 1e-12
    assert texts(result) == ["100 % of the area is single-curved within 0.01 /m; 12 valid rulings"]


def test_cylinder_valid_rulings_run_along_its_generators_parallel_to_the_axis_within_1e_9():
    _, v = analysed(cylinder(R_CYL, H_CYL), UDensity=12, VDensity=5)
    starts, ends = directions(v["ValidRulings"])
    assert len(starts) == 12  # one per generator through the grid: the others find it again
    assert sine_to(np.array([0.0, 0.0, 1.0]), ends - starts).max() < 1e-9
    assert np.abs(np.linalg.norm(ends - starts, axis=1) - H_CYL).max() < 1e-9  # edge to edge
    assert np.abs(np.hypot(starts[:, 0], starts[:, 1]) - R_CYL).max() < 1e-12
    angles = np.sort(np.mod(np.arctan2(starts[:, 1], starts[:, 0]), 2 * math.pi))
    assert np.allclose(angles, np.arange(12) * 2 * math.pi / 12, atol=1e-12)


def test_general_cylinder_rulings_are_parallel_to_its_extrusion_direction_within_1e_9():
    direction = np.array([1.0, 2.0, 3.0])
    _, v = analysed(tilted_cylinder(tuple(direction)), UDensity=9, VDensity=4)
    assert v["DevelopableFraction"] == pytest.approx(1.0, abs=1e-9)
    starts, ends = directions(v["ValidRulings"])
    assert len(starts) == 9
    assert sine_to(direction, ends - starts).max() < 1e-9
    assert np.abs(np.linalg.norm(ends - starts, axis=1) - 2.0).max() < 1e-9


def test_cone_rulings_run_from_the_base_to_the_apex_once_each():
    _, v = analysed(cone(1.0, 2.0), UDensity=8, VDensity=9)
    starts, ends = directions(v["ValidRulings"])
    assert len(starts) == 8  # the grid's apex row adds none
    tips = np.where((np.abs(ends - [0, 0, 2]).max(axis=1) < 1e-9)[:, None], ends, starts)
    assert np.abs(tips - [0.0, 0.0, 2.0]).max() < 1e-9
    assert np.abs(np.linalg.norm(ends - starts, axis=1) - math.sqrt(5.0)).max() < 1e-9


def test_hyperbolic_paraboloid_is_0_percent_with_no_valid_rulings():
    _, v = analysed(hypar(), UDensity=15, VDensity=15)
    assert v["DevelopableFraction"] == 0.0
    assert v["ValidRulings"] == []
    assert np.all(np.asarray(v["Gaussian"]) < 0)


def test_torus_shows_three_curvature_regions_positive_outside_zero_top_and_bottom_negative_inside():
    _, v = analysed(torus(R_TORUS, r_TORUS), UDensity=8, VDensity=8)
    gaussian, points = np.asarray(v["Gaussian"]), np.asarray(v["Points"])
    assert len(gaussian) == 64  # closed both ways: no seam point twice
    positive, zero, negative = gaussian > 1e-9, np.abs(gaussian) <= 1e-9, gaussian < -1e-9
    assert (positive.sum(), zero.sum(), negative.sum()) == (24, 16, 24)
    rho = np.hypot(points[:, 0], points[:, 1])
    assert np.all(rho[positive] > R_TORUS) and np.all(rho[negative] < R_TORUS)
    assert np.allclose(np.abs(points[zero, 2]), r_TORUS, atol=1e-12)


def test_torus_single_curved_share_is_its_top_and_bottom_bands():
    tol = 0.01
    _, v = analysed(torus(R_TORUS, r_TORUS), UDensity=8, VDensity=8, CurvatureTolerance=tol)
    # |cos v| / (R + r cos v) <= tol for cos v from −b to a: two bands, weighted by R + r cos v
    a, b = tol * R_TORUS / (1 - tol * r_TORUS), tol * R_TORUS / (1 + tol * r_TORUS)
    v1, v2 = math.acos(a), math.acos(-b)
    share = (R_TORUS * (v2 - v1) + r_TORUS * (math.sin(v2) - math.sin(v1))) / (math.pi * R_TORUS)
    assert v["DevelopableFraction"] == pytest.approx(share, rel=2e-3)  # measured 1.0e-3 (an 8 × 8 sampling)


def test_developable_fraction_weighs_area_not_parameters():
    # a short cylinder (half the parameters, a sixth of the area) capped by a hemisphere
    _, v = analysed(capsule(), UDensity=10, VDensity=10)
    assert v["DevelopableFraction"] == pytest.approx(1 / 6, abs=0.007)  # measured 0.005 under (10 × 10)


@pytest.mark.parametrize("name", ["hypar", "torus", "helicoid"])
def test_gaussian_curvature_matches_the_closed_form_to_rounding_at_interior_and_boundary_points(name):
    """From the exact derivatives: measured 1.5e-14 (torus), 1.0e-15 (hypar, helicoid)."""
    surface, closed_form = {"hypar": (hypar(), hypar_gaussian),
                            "torus": (torus(R_TORUS, r_TORUS), torus_gaussian),
                            "helicoid": (helicoid(), helicoid_gaussian)}[name]
    _, v = analysed(surface, UDensity=21, VDensity=21)
    points, gaussian = np.asarray(v["Points"]), np.asarray(v["Gaussian"])
    expected = closed_form(points)
    scale = np.maximum(np.abs(expected), 1e-3 * np.abs(expected).max())
    assert np.max(np.abs(gaussian - expected) / scale) < 1e-13
    k1, k2 = np.asarray(v["K1"]), np.asarray(v["K2"])
    assert np.allclose(k1 * k2, gaussian, rtol=1e-12, atol=1e-15)
    assert np.allclose(0.5 * (k1 + k2), v["Mean"], rtol=1e-12, atol=1e-15)


def test_curvature_lines_are_abs_k_times_scale_long_along_the_principal_directions():
    _, v = analysed(cylinder(R_CYL, H_CYL), UDensity=6, VDensity=3, Scale=3.0)
    lines, points = v["CurvatureLines"], np.asarray(v["Points"])
    assert len(lines) == 2 * len(points)
    # outward normal: the cylinder bends away from it, k2 = −1/r < k1 = 0
    straight, bent = directions(lines[0::2]), directions(lines[1::2])
    assert np.allclose(np.linalg.norm(bent[1] - bent[0], axis=1), 3.0 / R_CYL, atol=1e-12)
    assert np.allclose(0.5 * (bent[0] + bent[1]), points, atol=1e-12)  # centred on the point
    assert np.abs((bent[1] - bent[0])[:, 2]).max() < 1e-12  # around the cylinder
    assert np.abs(np.einsum("ij,ij->i", bent[1] - bent[0], points * [1, 1, 0])).max() < 1e-12
    assert np.abs(straight[1] - straight[0]).max() == 0.0  # k1 = 0 along the generators


def test_coloured_mesh_is_bright_pink_on_a_cylinder_with_its_colour_bar():
    _, v = analysed(cylinder(R_CYL, H_CYL), CurvatureTolerance=0.02)
    mesh = v["ColouredMesh"]
    assert np.all(mesh.visual.vertex_colors[:, :3] == STOPS[0][1])
    assert len(mesh.metadata["scalars"]) == len(mesh.vertices)
    assert mesh.metadata["clim"] == (0.0, 0.04) and len(mesh.metadata["cmap"]) == 256
    assert np.array_equal(mesh.vertex_attributes["min_abs_curvature"], mesh.metadata["scalars"])


def test_coloured_mesh_is_purple_on_a_saddle():
    _, v = analysed(hypar())
    rgb = v["ColouredMesh"].visual.vertex_colors[:, :3].astype(int)
    purple, dark = np.array(STOPS[2][1]), np.array(STOPS[3][1])
    assert np.all((rgb <= np.maximum(purple, dark)) & (rgb >= np.minimum(purple, dark)))


def test_warp_tolerance_stops_a_line_on_a_nearly_flat_saddle_at_warp_over_twist_rate():
    # z = ε·x·y is single-curved within 0.01 /m for ε = 0.004, but its normal turns by ε per
    # unit length along the diagonal: the line through the middle is valid for W / ε
    eps, warp = 0.004, 0.005
    saddle = hypar(rise=eps)
    _, v = analysed(saddle, UDensity=3, VDensity=3, WarpTolerance=warp)
    longest = max(line.length for line in v["ValidRulings"])
    assert longest == pytest.approx(warp / eps, rel=1e-3)
    _, loose = analysed(saddle, UDensity=3, VDensity=3, WarpTolerance=0.1)
    # corner to corner (the foot of the line reaches the corner ε² late)
    assert max(line.length for line in loose["ValidRulings"]) == pytest.approx(2 * math.sqrt(2), rel=1e-4)


def test_mesh_surface_uses_the_discrete_estimator():
    mesh = cylinder(1.0, 2.0).to_mesh(48, 12)
    mesh.merge_vertices()
    result, v = analysed(MeshSurface(mesh), UDensity=6, VDensity=6)
    assert result.state == "ok"
    assert v["DevelopableFraction"] == pytest.approx(1.0, abs=1e-12)
    assert np.abs(v["K1"]).max() < 1e-2 and np.allclose(v["K2"], -1.0, atol=0.05)
    starts, ends = directions(v["ValidRulings"])
    assert len(starts) > 0 and sine_to(np.array([0.0, 0.0, 1.0]), ends - starts).max() < 0.01
    assert np.abs(np.linalg.norm(ends - starts, axis=1) - 2.0).max() < 0.01


@pytest.mark.parametrize("inputs, message", [
    ({"UDensity": 1}, "UDensity must be at least 2, not 1"),
    ({"VDensity": 100_000}, "VDensity is 100,000; at most 500 can be made at once"),
    ({"Scale": -1.0}, "Scale must be 0 or more, not -1: it sets the lines' length per unit of curvature"),
    ({"CurvatureTolerance": 0.0}, "CurvatureTolerance must be positive, in 1/m (e.g. 0.01), not 0"),
    ({"WarpTolerance": -0.1}, "WarpTolerance must be a positive angle in radians, such as 0.01, not -0.1"),
])
def test_bad_inputs_warn_with_what_to_change(inputs, message):
    result, _ = analysed(cylinder(1.0, 1.0), **inputs)
    assert result.state == "warning"
    assert texts(result) == [message]


def test_a_curve_is_not_a_surface():
    result = run(SurfaceAnalysis(), Surface=tree({(0,): [Circle(radius=1.0)]}))
    assert result.state == "warning"
    assert texts(result)[0].startswith("Surface Curve")
    assert texts(result)[0].endswith("is not a surface: give a surface, a mesh or a mesh surface")
