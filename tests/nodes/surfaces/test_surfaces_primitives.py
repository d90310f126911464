"""surfaces.Sphere, Torus, Cylinder and Cone: placed on their plane, closed-form areas and curvature."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.graph import Graph
from torsal.engine.solver import Solver
from torsal.engine.types import encode_value
from torsal.engine.values import Plane, Point, Vector
from torsal.nodes.surfaces.analysis import Area, SurfaceCurvature
from torsal.nodes.surfaces.primitives import Cone, Cylinder, Sphere, Torus

#: A tilted plane: origin (1, 2, 3), normal (0, −0.6, 0.8).
TILTED = Plane(Point(1, 2, 3), Vector(1, 0, 0), Vector(0, 0.8, 0.6))
NORMAL = np.array([0.0, -0.6, 0.8])
GRID = np.linspace(0, 1, 21)
U, V = (a.ravel() for a in np.meshgrid(GRID, GRID))


def only(result, port=None):
    (value,) = out(result, port)[(0,)]
    return value


def area_of(node, **inputs):
    """``node`` wired into Area in one graph: the area and centroid it measures."""
    graph = Graph()
    graph.add_node(node, "primitive")
    for name, value in inputs.items():
        graph.set_input_value("primitive", name, encode_value(value))
    graph.add_node(Area(), "area")
    (port,) = [p.name for p in node.outputs]
    graph.connect("primitive", port, "area", "Geometry")
    solver = Solver(graph)
    solver.solve()
    result = solver.result("area")
    assert result.state == "ok", result.messages
    return only(result, "Area"), np.asarray(only(result, "Centroid"))


def test_sphere_area_is_4_pi_r_squared():
    area, centroid = area_of(Sphere(), Plane=TILTED, Radius=1.7)
    assert area == pytest.approx(4 * math.pi * 1.7**2, rel=1e-10)
    assert np.allclose(centroid, [1, 2, 3], atol=1e-10)


def test_sphere_on_a_tilted_plane_is_centred_on_its_origin_with_poles_on_its_normal():
    sphere = only(run(Sphere(), Plane=TILTED, Radius=1.7))
    assert np.abs(np.linalg.norm(sphere.point_at(U, V) - [1, 2, 3], axis=1) - 1.7).max() < 1e-14
    assert np.allclose(sphere.point_at(0.3, 1.0), np.array([1, 2, 3]) + 1.7 * NORMAL, atol=1e-14)
    assert np.allclose(sphere.point_at(0.0, 0.5), [2.7, 2, 3], atol=1e-14)  # u = 0 on the plane's X axis


def test_sphere_on_a_point_is_centred_there():
    sphere = only(run(Sphere(), Plane=Point(0, 0, 5), Radius=2.0))
    assert np.allclose(sphere.point_at(0.5, 1.0), [0, 0, 7], atol=1e-14)


def test_sphere_curvature_is_minus_one_over_r_everywhere_poles_included():
    sphere = only(run(Sphere(), Plane=TILTED, Radius=1.7))
    c = sphere.curvature(U, V)
    assert np.abs(c.k1 * 1.7 + 1).max() < 1e-9 and np.abs(c.k2 * 1.7 + 1).max() < 1e-9


@pytest.mark.parametrize("radius, message", [
    (0.0, "Radius must be a positive length, not 0"),
    (-2.0, "Radius must be a positive length, not -2"),
])
def test_sphere_radius_must_be_positive(radius, message):
    result = run(Sphere(), Radius=radius)
    assert result.state == "warning"
    assert texts(result) == [message]


def test_torus_area_is_4_pi_squared_big_r_small_r():
    area, centroid = area_of(Torus(), Plane=TILTED, MajorRadius=3.0, MinorRadius=0.8)
    assert area == pytest.approx(4 * math.pi**2 * 3.0 * 0.8, rel=1e-10)
    assert np.allclose(centroid, [1, 2, 3], atol=1e-10)


def test_torus_gaussian_curvature_through_the_node_matches_the_closed_form():
    torus = only(run(Torus(), Plane=TILTED, MajorRadius=3.0, MinorRadius=0.8))
    uvs = [Point(u, v, 0) for u, v in [(0, 0), (0.3, 0.25), (0.6, 0.5), (1, 0.75), (0.1, 1)]]
    result = run(SurfaceCurvature(), Surface=tree({(0,): [torus]}), UV=tree({(0,): uvs}))
    v = 2 * math.pi * np.array([p.y for p in uvs])
    exact = np.cos(v) / (0.8 * (3.0 + 0.8 * np.cos(v)))
    assert np.abs(np.asarray(out(result, "Gaussian")[(0,)]) - exact).max() < 1e-12


def test_torus_whose_tube_fills_the_hole_is_refused():
    result = run(Torus(), MajorRadius=1.0, MinorRadius=1.0)
    assert texts(result) == [
        "MinorRadius (1) must be less than MajorRadius (1), or the tube closes the hole and passes "
        "through itself"
    ]


def test_cylinder_area_is_2_pi_r_h_and_it_stands_on_its_plane():
    area, centroid = area_of(Cylinder(), Plane=TILTED, Radius=1.2, Height=2.5)
    assert area == pytest.approx(2 * math.pi * 1.2 * 2.5, rel=1e-10)
    assert np.allclose(centroid, np.array([1, 2, 3]) + 1.25 * NORMAL, atol=1e-10)


def test_cylinder_with_a_negative_height_goes_below_its_plane_facing_out():
    cylinder = only(run(Cylinder(), Plane=TILTED, Radius=1.2, Height=-2.5))
    assert np.allclose(cylinder.point_at(0.0, 1.0) - cylinder.point_at(0.0, 0.0), -2.5 * NORMAL, atol=1e-14)
    points, normals = cylinder.point_at(U, V), cylinder.normal_at(U, V)
    axis = np.array([1, 2, 3]) + np.outer((points - [1, 2, 3]) @ NORMAL, NORMAL)
    assert np.allclose(normals, (points - axis) / 1.2, atol=1e-12)


def test_cylinder_of_height_zero_warns():
    result = run(Cylinder(), Height=0.0)
    assert texts(result) == ["Height is 0, so the cylinder would be flat: give it a length"]


def test_cone_area_is_pi_r_times_the_slant_height():
    area, _ = area_of(Cone(), Plane=TILTED, Radius=1.5, Height=2.0)
    assert area == pytest.approx(math.pi * 1.5 * math.hypot(1.5, 2.0), rel=1e-10)


def test_cone_apex_is_height_along_the_normal():
    cone = only(run(Cone(), Plane=TILTED, Radius=1.5, Height=2.0))
    assert np.allclose(cone.point_at(0.4, 1.0), np.array([1, 2, 3]) + 2.0 * NORMAL, atol=1e-14)
    assert np.allclose(cone.point_at(0.0, 0.0), [2.5, 2, 3], atol=1e-14)
    assert np.abs(cone.gaussian_curvature(U, V * 0.99)).max() < 1e-12


def test_cone_of_zero_radius_warns():
    assert texts(run(Cone(), Radius=0.0)) == ["Radius must be a positive length, not 0"]
