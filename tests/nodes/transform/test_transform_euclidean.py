"""transform.Move, Rotate, Scale, ScaleNonUniform, Mirror and Orient against closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest
import trimesh

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.values import WORLD_XY, Plane, Point, Vector
from torsal.nodes.geometry import curves as kernel
from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.parametric_surface import sphere
from torsal.nodes.transform.euclidean import Mirror, Move, Orient, Rotate, Scale, ScaleNonUniform

T = np.linspace(0.0, 1.0, 101)
LINE = kernel.Line([1, 0, 0], [3, 0, 0])
CIRCLE = kernel.Circle(radius=2.0)
SPLINE = kernel.InterpolatedCurve([[0, 0, 0], [1, 2, 0], [3, 1, 1], [4, 3, 0]])


def moved(node, geometry, **inputs):
    result = run(node, Geometry=tree({(0,): [geometry]}), **inputs)
    assert result.state == "ok", result.messages
    (value,) = out(result)[(0,)]
    return value


def test_move_a_point_by_the_motion():
    assert moved(Move(), Point(1, 2, 3), Motion=Vector(10, 0, -1)) == Point(11, 2, 2)


def test_move_a_curve_moves_every_point():
    curve = moved(Move(), SPLINE, Motion=Vector(1, 2, 3))
    assert np.allclose(curve.point_at(T), SPLINE.point_at(T) + np.array([1, 2, 3]), atol=1e-14)


def test_move_a_line_gives_a_line():
    line = moved(Move(), LINE, Motion=Vector(0, 5, 0))
    assert isinstance(line, kernel.Line)
    assert np.array_equal(line.start, [1, 5, 0]) and np.array_equal(line.end, [3, 5, 0])


def test_move_leaves_a_vector_unchanged():
    assert moved(Move(), Vector(1, 0, 0), Motion=Vector(5, 5, 5)) == Vector(1, 0, 0)


def test_move_a_plane_moves_its_origin_only():
    plane = moved(Move(), WORLD_XY, Motion=Vector(0, 0, 4))
    assert plane == Plane(Point(0, 0, 4), Vector(1, 0, 0), Vector(0, 1, 0))


def test_move_a_mesh_and_a_surface():
    box = trimesh.creation.box()
    mesh = moved(Move(), box, Motion=Vector(0, 0, 1))
    assert np.allclose(mesh.vertices, box.vertices + np.array([0, 0, 1]))
    assert np.allclose(box.bounds, [[-0.5] * 3, [0.5] * 3])  # the input is left as it was
    ball = moved(Move(), sphere(1.0), Motion=Vector(2, 0, 0))
    assert np.allclose(ball.point_at(0.3, 0.7), sphere(1.0).point_at(0.3, 0.7) + np.array([2, 0, 0]))


def test_rotate_a_point_a_quarter_turn_about_z():
    p = moved(Rotate(), Point(1, 0, 5), Angle=math.pi / 2)
    assert np.allclose(p, [0, 1, 5], atol=1e-15)


def test_rotate_about_a_plane_through_another_origin():
    plane = Plane(Point(1, 1, 0), Vector(1, 0, 0), Vector(0, 1, 0))
    p = moved(Rotate(), Point(2, 1, 0), Angle=math.pi, Plane=plane)
    assert np.allclose(p, [0, 1, 0], atol=1e-15)


def test_rotate_a_curve_rotates_every_point_and_keeps_its_length():
    angle = 0.7
    curve = moved(Rotate(), SPLINE, Angle=angle)
    c, s = math.cos(angle), math.sin(angle)
    expected = SPLINE.point_at(T) @ np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]).T
    assert np.allclose(curve.point_at(T), expected, atol=1e-14)
    assert curve.length == pytest.approx(SPLINE.length, rel=1e-12)


def test_rotate_a_line_about_the_x_axis():
    yz = Plane(Point(0, 0, 0), Vector(0, 1, 0), Vector(0, 0, 1))  # normal +x
    line = moved(Rotate(), kernel.Line([0, 1, 0], [0, 2, 0]), Angle=math.pi / 2, Plane=yz)
    assert np.allclose(line.start, [0, 0, 1], atol=1e-15) and np.allclose(line.end, [0, 0, 2], atol=1e-15)


def test_scale_about_a_centre_scales_distances_from_it():
    assert moved(Scale(), Point(3, 1, 1), Centre=Point(1, 1, 1), Factor=2.0) == Point(5, 1, 1)


def test_scale_a_circle_scales_its_radius_and_curvature():
    circle = moved(Scale(), CIRCLE, Centre=Point(0, 0, 0), Factor=1.5)
    assert np.allclose(np.linalg.norm(circle.point_at(T), axis=1), 3.0, atol=1e-14)
    assert circle.length == pytest.approx(6 * math.pi, rel=1e-12)
    assert np.allclose(circle.curvature_at(T), 1 / 3.0, rtol=1e-12)


def test_scale_by_zero_warns():
    result = run(Scale(), Geometry=tree({(0,): [Point(1, 1, 1)]}), Factor=0.0)
    assert result.state == "warning"
    assert texts(result) == ["Factor is 0, which would flatten the geometry to nothing"]


def test_scale_non_uniform_turns_a_circle_into_an_ellipse():
    ellipse = moved(ScaleNonUniform(), CIRCLE, X=2.0, Y=0.5, Z=1.0)
    p = ellipse.point_at(T)
    assert np.allclose((p[:, 0] / 4.0) ** 2 + (p[:, 1] / 1.0) ** 2, 1.0, atol=1e-14)


def test_scale_non_uniform_along_a_tilted_plane():
    tilted = Plane(Point(1, 0, 0), Vector(0, 1, 0), Vector(-1, 0, 0))  # x along world y
    p = moved(ScaleNonUniform(), Point(1, 2, 3), Plane=tilted, X=3.0, Y=1.0, Z=1.0)
    assert np.allclose(p, [1, 6, 3], atol=1e-14)


def test_mirror_in_the_default_yz_plane_negates_x():
    assert moved(Mirror(), Point(2, 3, 4)) == Point(-2, 3, 4)


def test_mirror_a_curve_in_a_tilted_plane():
    plane = Plane(Point(0, 0, 1), Vector(1, 0, 0), Vector(0, 1, 0))  # z = 1
    curve = moved(Mirror(), SPLINE, Plane=plane)
    expected = SPLINE.point_at(T) * [1, 1, -1] + [0, 0, 2]
    assert np.allclose(curve.point_at(T), expected, atol=1e-14)


def test_mirror_a_line_and_a_mesh_keeps_the_mesh_outward_facing():
    line = moved(Mirror(), LINE)
    assert np.array_equal(line.start, [-1, 0, 0]) and np.array_equal(line.end, [-3, 0, 0])
    mesh = moved(Mirror(), trimesh.creation.box().apply_translation([2, 0, 0]))
    assert mesh.volume == pytest.approx(1.0)
    assert mesh.bounds[0][0] == pytest.approx(-2.5)


def test_orient_carries_the_source_plane_onto_the_target():
    target = Plane(Point(5, 5, 5), Vector(0, 1, 0), Vector(0, 0, 1))  # x → y, y → z
    assert np.allclose(moved(Orient(), Point(1, 2, 3), Target=target), [5 + 3, 5 + 1, 5 + 2], atol=1e-14)


def test_orient_a_circle_onto_a_vertical_plane():
    target = Plane(Point(0, 0, 10), Vector(1, 0, 0), Vector(0, 0, 1))
    circle = moved(Orient(), CIRCLE, Target=target)
    p = circle.point_at(T)
    assert np.allclose(p[:, 1], 0.0, atol=1e-14)
    assert np.allclose(np.linalg.norm(p - [0, 0, 10], axis=1), 2.0, atol=1e-14)


def test_orient_a_line_between_two_planes():
    source = Plane(Point(1, 0, 0), Vector(1, 0, 0), Vector(0, 1, 0))
    target = Plane(Point(0, 0, 0), Vector(0, 1, 0), Vector(-1, 0, 0))
    line = moved(Orient(), LINE, Source=source, Target=target)
    assert np.allclose(line.start, [0, 0, 0], atol=1e-15) and np.allclose(line.end, [0, 2, 0], atol=1e-15)


def test_orient_needs_a_target():
    result = run(Orient(), Geometry=tree({(0,): [Point(0, 0, 0)]}))
    assert texts(result) == ["Input Target collected no data"]


def test_non_geometry_is_refused_with_a_plain_message():
    result = run(Move(), Geometry=tree({(0,): ["hello", Point(0, 0, 0)]}))
    assert result.state == "warning"
    assert texts(result) == [
        "Geometry Text 'hello' is not geometry; transforms work on points, vectors, planes, curves, "
        "surfaces and meshes"
    ]
    assert out(result) == {(0,): [None, Point(0, 0, 10)]}


def test_rotate_about_a_degenerate_plane_warns():
    bad = Plane(Point(0, 0, 0), Vector(0, 0, 0), Vector(0, 1, 0))
    result = run(Rotate(), Geometry=tree({(0,): [Point(1, 0, 0)]}), Plane=bad)
    assert texts(result) == ["Plane's X axis has zero length, so the plane has no orientation"]


def test_rotate_a_vector_and_a_plane():
    assert np.allclose(moved(Rotate(), Vector(1, 0, 0), Angle=math.pi / 2), [0, 1, 0], atol=1e-15)
    plane = moved(Rotate(), Plane(Point(1, 0, 0), Vector(1, 0, 0), Vector(0, 0, 1)), Angle=math.pi / 2)
    assert np.allclose(plane.origin, [0, 1, 0], atol=1e-15)
    assert np.allclose(plane.x, [0, 1, 0], atol=1e-15) and np.allclose(plane.y, [0, 0, 1], atol=1e-15)


def test_scale_a_mesh_surface_scales_its_area_by_the_factor_squared():
    surface = MeshSurface(trimesh.creation.icosphere(subdivisions=2))
    scaled = moved(Scale(), surface, Factor=3.0)
    assert isinstance(scaled, MeshSurface)
    assert scaled.area() == pytest.approx(9 * surface.area(), rel=1e-12)
