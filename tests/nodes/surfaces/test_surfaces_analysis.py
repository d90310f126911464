"""surfaces.EvaluateSurface, SurfaceCurvature, Isocurve, SurfaceEdges, Area and MeshSurface."""

from __future__ import annotations

import math

import numpy as np
import pytest
import trimesh

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.values import Plane, Point, Vector
from torsal.nodes.geometry import curves as kernel
from torsal.nodes.geometry import parametric_surface
from torsal.nodes.geometry.mesh_surface import MeshSurface as KernelMeshSurface
from torsal.nodes.geometry.nurbs_surface import NurbsSurface as KernelNurbsSurface
from torsal.nodes.geometry.vectors import Plane as KernelPlane
from torsal.nodes.surfaces.analysis import Area, EvaluateSurface, Isocurve, SurfaceCurvature, SurfaceEdges
from torsal.nodes.surfaces.freeform import NurbsSurface
from torsal.nodes.surfaces.mesh import MeshSurface

UNIT_SQUARE = [Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(1, 1, 0)]
SPHERE = parametric_surface.sphere(2.0, (1.0, -1.0, 0.5))


def one(value):
    return tree({(0,): [value]})


def only(result, port=None):
    (value,) = out(result, port)[(0,)]
    return value


def unit_square():
    return only(run(NurbsSurface(), Points=UNIT_SQUARE, UCount=2, DegreeU=1, DegreeV=1))


# --------------------------------------------------------------------------- EvaluateSurface

def test_evaluate_unit_square_gives_the_point_normal_and_frame():
    result = run(EvaluateSurface(), Surface=one(unit_square()), UV=Point(0.25, 0.75, 0))
    assert only(result, "Point") == Point(0.25, 0.75, 0)
    assert only(result, "Normal") == Vector(0, 0, 1)
    assert only(result, "Frame") == Plane(Point(0.25, 0.75, 0), Vector(1, 0, 0), Vector(0, 1, 0))


def test_evaluate_sphere_normal_is_radial():
    uvs = [Point(u, v, 0) for u, v in [(0, 0.5), (0.3, 0.2), (1, 0.5), (0.7, 0.9)]]
    result = run(EvaluateSurface(), Surface=one(SPHERE), UV=tree({(0,): uvs}))
    points = np.asarray(out(result, "Point")[(0,)])
    normals = np.asarray(out(result, "Normal")[(0,)])
    assert np.abs(normals - (points - [1.0, -1.0, 0.5]) / 2.0).max() < 1e-14


def test_evaluate_sphere_normal_at_a_pole_is_the_limit_from_inside():
    """The kernel takes it 1e-6 (in u, v) inside the square: radial to ~π·1e-6."""
    poles = tree({(0,): [Point(0.3, 0, 0), Point(0.8, 1, 0)]})
    result = run(EvaluateSurface(), Surface=one(SPHERE), UV=poles)
    assert np.abs(np.asarray(out(result, "Normal")[(0,)]) - [[0, 0, -1], [0, 0, 1]]).max() < 1e-5


def test_evaluate_defaults_to_the_middle():
    assert only(run(EvaluateSurface(), Surface=one(unit_square())), "Point") == Point(0.5, 0.5, 0)


@pytest.mark.parametrize("uv", [Point(1.5, 0.5, 0), Point(0.5, -0.1, 0)])
def test_evaluate_outside_the_unit_square_warns(uv):
    result = run(EvaluateSurface(), Surface=one(unit_square()), UV=uv)
    assert result.state == "warning"
    u, v = uv.x, uv.y
    assert texts(result) == [
        f"UV must have x (u) and y (v) from 0 to 1, not ({u:g}, {v:g}): every surface is "
        "parameterised on [0, 1]²"
    ]


def test_evaluate_a_collapsed_surface_says_it_has_no_normal():
    flat = KernelNurbsSurface(np.array([[[0, 0, 0], [1, 0, 0]], [[2, 0, 0], [3, 0, 0]]], float), 1, 1)
    result = run(EvaluateSurface(), Surface=one(flat))
    assert texts(result) == [
        "The surface has no normal at (0.5, 0.5): its u and v directions are parallel or zero all "
        "around there"
    ]


def test_evaluate_needs_a_surface():
    assert texts(run(EvaluateSurface(), UV=Point(0.5, 0.5, 0))) == ["Input Surface collected no data"]


# --------------------------------------------------------------------------- SurfaceCurvature

def test_curvature_of_a_cylinder_is_zero_along_its_rulings():
    cylinder = parametric_surface.cylinder(1.5, 3.0)
    result = run(SurfaceCurvature(), Surface=one(cylinder), UV=Point(0.2, 0.0, 0))
    assert only(result, "K1") == pytest.approx(0.0, abs=1e-15)
    assert only(result, "K2") == pytest.approx(-1 / 1.5, rel=1e-14)
    assert only(result, "Gaussian") == pytest.approx(0.0, abs=1e-15)
    assert np.allclose(only(result, "Direction1"), [0, 0, 1], atol=1e-14)
    assert abs(np.dot(only(result, "Direction2"), only(result, "Normal"))) < 1e-14


def test_curvature_at_a_sphere_pole_is_that_of_the_sphere():
    result = run(SurfaceCurvature(), Surface=one(SPHERE), UV=Point(0.4, 1.0, 0))
    assert np.allclose(only(result, "Point"), [1.0, -1.0, 2.5], atol=1e-15)
    assert only(result, "Gaussian") == pytest.approx(0.25, rel=1e-9)
    assert only(result, "Mean") == pytest.approx(-0.5, rel=1e-9)


# --------------------------------------------------------------------------- Isocurve

def test_isocurves_of_the_unit_square_are_its_parameter_lines():
    result = run(Isocurve(), Surface=one(unit_square()), UV=Point(0.25, 0.75, 0))
    u_curve, v_curve = only(result, "U"), only(result, "V")
    assert np.allclose(u_curve.point_at(np.array([0.0, 1.0])), [[0, 0.75, 0], [1, 0.75, 0]])
    assert np.allclose(v_curve.point_at(np.array([0.0, 1.0])), [[0.25, 0, 0], [0.25, 1, 0]])


def test_sphere_isocurves_are_a_parallel_and_a_meridian():
    result = run(Isocurve(), Surface=one(SPHERE), UV=Point(0.0, 0.5, 0))
    assert only(result, "U").length == pytest.approx(2 * math.pi * 2.0, rel=1e-12)
    assert only(result, "V").length == pytest.approx(math.pi * 2.0, rel=1e-12)


# --------------------------------------------------------------------------- SurfaceEdges

def test_edges_of_the_unit_square_are_numbered_counter_clockwise_from_v_0():
    edges = out(run(SurfaceEdges(), Surface=one(unit_square())))[(0,)]
    ends = [(e.point_at(0.0).tolist(), e.point_at(1.0).tolist()) for e in edges]
    assert ends == [
        ([0, 0, 0], [1, 0, 0]),  # 0: v = 0, u from 0 to 1
        ([1, 0, 0], [1, 1, 0]),  # 1: u = 1, v from 0 to 1
        ([1, 1, 0], [0, 1, 0]),  # 2: v = 1, u from 1 to 0
        ([0, 1, 0], [0, 0, 0]),  # 3: u = 0, v from 1 to 0
    ]
    assert [e.length for e in edges] == pytest.approx([1, 1, 1, 1], rel=1e-14)


def test_sphere_edges_remark_on_the_poles():
    result = run(SurfaceEdges(), Surface=one(SPHERE))
    assert result.state == "ok"
    assert texts(result) == ["Edges 0 and 2 are collapsed to points (zero length)"]
    edges = out(result)[(0,)]
    assert edges[1].length == pytest.approx(2 * math.pi, rel=1e-12)


# --------------------------------------------------------------------------- Area

def test_area_of_the_unit_square_patch_is_one_with_its_centroid_in_the_middle():
    result = run(Area(), Geometry=one(unit_square()))
    assert only(result, "Area") == pytest.approx(1.0, rel=1e-14)
    assert np.allclose(only(result, "Centroid"), [0.5, 0.5, 0], atol=1e-14)


def test_area_of_a_tilted_circle_is_pi_r_squared_about_its_centre():
    plane = KernelPlane.from_normal([1, 2, 3], [1, -2, 0.5])
    result = run(Area(), Geometry=one(kernel.Circle(plane, 1.5)))
    assert only(result, "Area") == pytest.approx(math.pi * 1.5**2, rel=1e-12)
    assert np.allclose(only(result, "Centroid"), [1, 2, 3], atol=1e-12)


def test_area_of_a_closed_polyline_l_shape():
    corners = [[0, 0, 0], [2, 0, 0], [2, 1, 0], [1, 1, 0], [1, 2, 0], [0, 2, 0]]
    result = run(Area(), Geometry=one(kernel.Polyline(np.array(corners, float), closed=True)))
    assert only(result, "Area") == pytest.approx(3.0, rel=1e-13)
    # two unit squares and one more: centroid (5/6, 5/6)
    assert np.allclose(only(result, "Centroid"), [5 / 6, 5 / 6, 0], atol=1e-13)


def test_area_of_a_mesh_is_the_sum_of_its_triangles():
    box = trimesh.creation.box(extents=(1.0, 2.0, 3.0))
    result = run(Area(), Geometry=one(box))
    assert only(result, "Area") == pytest.approx(22.0, rel=1e-14)
    assert np.allclose(only(result, "Centroid"), [0, 0, 0], atol=1e-14)


def test_area_of_an_open_curve_warns():
    result = run(Area(), Geometry=one(kernel.Line([0, 0, 0], [1, 0, 0])))
    assert result.state == "warning"
    assert texts(result) == ["The curve is open: only a closed planar curve encloses an area"]


def test_area_of_a_closed_curve_that_is_not_planar_warns():
    saddle = kernel.Polyline(np.array([[0, 0, 0], [1, 0, 1], [1, 1, 0], [0, 1, 1]], float), closed=True)
    result = run(Area(), Geometry=one(saddle))
    assert texts(result) == [
        "The curve is not planar (its points lie up to 1 apart across its plane): only a closed planar "
        "curve encloses an area"
    ]


def test_area_of_text_warns():
    result = run(Area(), Geometry=one("hello"))
    assert texts(result) == [
        "Geometry Text 'hello' has no area: give a surface, a mesh or a closed planar curve"
    ]


# --------------------------------------------------------------------------- MeshSurface

def test_mesh_surface_keeps_the_mesh_area():
    ball = trimesh.creation.icosphere(subdivisions=3, radius=2.0)
    surface = only(run(MeshSurface(), Mesh=one(ball)))
    assert isinstance(surface, KernelMeshSurface)
    result = run(Area(), Geometry=one(surface))
    assert only(result, "Area") == pytest.approx(ball.area, rel=1e-14)


def test_mesh_surface_from_a_surface_meshes_it():
    surface = only(run(MeshSurface(), Mesh=one(unit_square())))
    assert surface.area() == pytest.approx(1.0, rel=1e-14)


def test_mesh_surface_of_a_mesh_without_faces_warns():
    empty = trimesh.Trimesh(vertices=np.zeros((3, 3)), faces=np.zeros((0, 3), int), process=False)
    result = run(MeshSurface(), Mesh=one(empty))
    assert texts(result) == ["Mesh has no faces, so it has no surface"]


def test_mesh_surface_cannot_be_evaluated_at_a_uv():
    ball = KernelMeshSurface(trimesh.creation.icosphere(subdivisions=1))
    result = run(EvaluateSurface(), Surface=one(ball))
    assert result.state == "error"
    assert texts(result)[0].startswith("input Surface: MeshSurface")
