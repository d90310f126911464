"""The Grasshopper staples a developable workflow needs: planes, deconstructing points,
vectors and domains, remapping, curve frames, bounding boxes and volumes — each against
a closed form."""

from __future__ import annotations

import math

import numpy as np
import pytest
import trimesh

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.values import Domain, Plane, Point, Vector
from torsal.nodes.curves.division import DivideLength
from torsal.nodes.curves.frames import CurveClosestPoint, CurveFrame, PerpFrames
from torsal.nodes.curves.intersect import CurvePlane
from torsal.nodes.curves.outlines import Polygon, Rectangle
from torsal.nodes.geometry.curves import Circle, Line
from torsal.nodes.geometry.vectors import Plane as KernelPlane
from torsal.nodes.lists.dispatching import Dispatch
from torsal.nodes.maths.remap import Bounds, DeconstructDomain, Remap
from torsal.nodes.params.deconstruct import DeconstructPoint, DeconstructVector
from torsal.nodes.params.planes import (
    ConstructPlane,
    DeconstructPlane,
    PlaneNormal,
    PlaneThreePoints,
    XYPlane,
    XZPlane,
    YZPlane,
)
from torsal.nodes.params.two_points import Distance, VectorTwoPoints
from torsal.nodes.surfaces.bounds import BoundingBox, Volume
from torsal.nodes.surfaces.closest import SurfaceClosestPoint


def one(result, port=None):
    (items,) = out(result, port).values()
    (item,) = items
    return item


def axes(plane: Plane) -> np.ndarray:
    x, y = np.asarray(plane.x), np.asarray(plane.y)
    return np.stack([x, y, np.cross(x, y)])


def test_world_planes_have_grasshoppers_axes_and_move_to_origin():
    xy = one(run(XYPlane(), Origin=Point(1, 2, 3)))
    assert xy == Plane(Point(1, 2, 3), Vector(1, 0, 0), Vector(0, 1, 0))
    xz = one(run(XZPlane()))
    np.testing.assert_array_equal(axes(xz), [[1, 0, 0], [0, 0, 1], [0, -1, 0]])
    yz = one(run(YZPlane()))
    np.testing.assert_array_equal(axes(yz), [[0, 1, 0], [0, 0, 1], [1, 0, 0]])


def test_construct_plane_keeps_x_and_makes_y_square_to_it():
    plane = one(run(ConstructPlane(), Origin=Point(0, 0, 1), XAxis=Vector(2, 0, 0), YAxis=Vector(1, 1, 0)))
    np.testing.assert_allclose(axes(plane), np.eye(3), atol=1e-15)
    assert plane.origin == Point(0, 0, 1)


def test_construct_plane_refuses_parallel_axes():
    result = run(ConstructPlane(), XAxis=Vector(1, 0, 0), YAxis=Vector(-3, 0, 0))
    assert result.state == "warning" and "parallel" in texts(result)[0]


def test_deconstruct_plane_gives_unit_axes_and_the_normal():
    result = run(DeconstructPlane(), Plane=Plane(Point(1, 1, 1), Vector(0, 3, 0), Vector(0, 0, 2)))
    assert one(result, "Origin") == Point(1, 1, 1)
    assert one(result, "XAxis") == Vector(0, 1, 0)
    assert one(result, "YAxis") == Vector(0, 0, 1)
    assert one(result, "ZAxis") == Vector(1, 0, 0)


def test_plane_normal_of_z_is_world_xy_and_of_a_slope_is_square_to_it():
    assert one(run(PlaneNormal())) == Plane(Point(0, 0, 0), Vector(1, 0, 0), Vector(0, 1, 0))
    slope = one(run(PlaneNormal(), Normal=Vector(0, 1, 1)))
    frame = axes(slope)
    np.testing.assert_allclose(frame[2], [0, 1 / math.sqrt(2), 1 / math.sqrt(2)], atol=1e-15)
    np.testing.assert_allclose(frame @ frame.T, np.eye(3), atol=1e-15)


def test_plane_through_three_points():
    plane = one(run(PlaneThreePoints(), A=Point(1, 0, 0), B=Point(1, 5, 0), C=Point(1, 0, 2)))
    np.testing.assert_allclose(axes(plane), [[0, 1, 0], [0, 0, 1], [1, 0, 0]], atol=1e-15)
    collinear = run(PlaneThreePoints(), A=Point(0, 0, 0), B=Point(1, 1, 1), C=Point(3, 3, 3))
    assert collinear.state == "warning" and "one line" in texts(collinear)[0]


def test_deconstruct_point_and_vector():
    result = run(DeconstructPoint(), Point=Point(1.5, -2, 7))
    assert [one(result, p) for p in "XYZ"] == [1.5, -2.0, 7.0]
    result = run(DeconstructVector(), Vector=Vector(3, 4, 12))
    assert [one(result, p) for p in ("X", "Y", "Z", "Length")] == [3.0, 4.0, 12.0, 13.0]


def test_deconstruct_domain():
    result = run(DeconstructDomain(), Domain=Domain(2.5, -1))
    assert (one(result, "Start"), one(result, "End")) == (2.5, -1.0)


def test_remap_keeps_proportions_and_clips_to_the_target():
    result = run(Remap(), Values=[0.0, 5.0, 10.0, 12.0], Source=Domain(0, 10), Target=Domain(100, 200))
    assert out(result, "Mapped") == {(0,): [100.0, 150.0, 200.0, 220.0]}
    assert out(result, "Clipped") == {(0,): [100.0, 150.0, 200.0, 200.0]}


def test_remap_without_source_uses_the_values_own_bounds():
    result = run(Remap(), Values=[2.0, 4.0, 6.0])
    assert out(result, "Mapped") == {(0,): [0.0, 0.5, 1.0]}


def test_bounds_spans_the_smallest_to_the_largest():
    assert one(run(Bounds(), Numbers=[3.0, -1.0, 7.5, 2.0])) == Domain(-1.0, 7.5)
    empty = run(Bounds(), Numbers=tree({(0,): []}))
    assert empty.state == "warning"


def test_curve_frame_on_a_circle_points_at_the_centre():
    circle = Circle(KernelPlane.from_normal([1, 2, 0], [0, 0, 1]), 3.0)
    for t in (0.0, 0.3, 0.8):
        frame = one(run(CurveFrame(), Curve=tree({(0,): [circle]}), Parameter=t))
        radius = np.asarray(frame.origin) - [1, 2, 0]
        assert np.linalg.norm(radius) == pytest.approx(3.0, abs=1e-12)
        np.testing.assert_allclose(frame.y, -radius / 3, atol=1e-12)  # towards the centre
        np.testing.assert_allclose(frame.x, [radius[1] / -3, radius[0] / 3, 0], atol=1e-12)  # anticlockwise
        np.testing.assert_allclose(axes(frame)[2], [0, 0, 1], atol=1e-12)


def test_perp_frames_along_a_line_are_square_to_it_and_evenly_spaced():
    line = Line([0, 0, 0], [0, 0, 8])
    result = run(PerpFrames(), Curve=tree({(0,): [line]}), Count=4)
    (frames,) = out(result, "Frames").values()
    assert [f.origin[2] for f in frames] == pytest.approx([0, 2, 4, 6, 8], abs=1e-12)
    for frame in frames:
        np.testing.assert_allclose(axes(frame)[2], [0, 0, 1], atol=1e-12)


def test_bounding_box_of_a_circle_and_a_point():
    circle = Circle(KernelPlane.from_normal([0, 0, 0], [0, 0, 1]), 2.0)
    result = run(BoundingBox(), Geometry=tree({(0,): [circle, Point(5, 1, 3)]}))
    assert one(result, "Min") == pytest.approx(Point(-2, -2, 0), abs=1e-9)
    assert one(result, "Max") == pytest.approx(Point(5, 2, 3), abs=1e-9)
    box = one(result, "Box")
    assert box.volume == pytest.approx(7 * 4 * 3, rel=1e-9)


def test_volume_and_centroid_of_a_box_and_an_open_mesh_refused():
    move = trimesh.transformations.translation_matrix([1, 1, 1])
    box = trimesh.creation.box(extents=[2, 3, 4], transform=move)
    result = run(Volume(), Mesh=tree({(0,): [box]}))
    assert one(result, "Volume") == pytest.approx(24.0, rel=1e-12)
    assert one(result, "Centroid") == pytest.approx(Point(1, 1, 1), abs=1e-12)
    open_box = box.copy()
    open_box.update_faces(np.arange(len(box.faces)) != 0)
    result = run(Volume(), Mesh=tree({(0,): [open_box]}))
    assert result.state == "warning" and "open" in texts(result)[0]


def test_vector_between_two_points_and_its_unit_direction():
    result = run(VectorTwoPoints(), A=Point(1, 1, 1), B=Point(4, 5, 1))
    assert one(result, "Vector") == Vector(3, 4, 0) and one(result, "Length") == 5.0
    unit = run(VectorTwoPoints(), A=Point(1, 1, 1), B=Point(4, 5, 1), Unit=True)
    assert one(unit, "Vector") == pytest.approx(Vector(0.6, 0.8, 0), abs=1e-15)
    same = run(VectorTwoPoints(), A=Point(1, 1, 1), B=Point(1, 1, 1), Unit=True)
    assert same.state == "warning" and "zero length" in texts(same)[0]


def test_distance_between_points():
    assert one(run(Distance(), A=Point(1, 2, 3), B=Point(3, 5, 9))) == 7.0


def test_curve_closest_point_on_a_circle_is_along_the_radius():
    circle = Circle(KernelPlane.from_normal([0, 0, 0], [0, 0, 1]), 2.0)
    result = run(CurveClosestPoint(), Point=Point(3, 4, 1), Curve=tree({(0,): [circle]}))
    assert one(result, "Point") == pytest.approx(Point(1.2, 1.6, 0), abs=1e-12)  # 2 · (3, 4)/5
    assert one(result, "Distance") == pytest.approx(math.sqrt(3**2 + 1), abs=1e-12)  # 5 − 2 in plan, 1 up
    assert 0 <= one(result, "Parameter") <= 1


def test_divide_length_marks_every_length_along_a_line_and_refuses_a_count_past_the_cap():
    line = Line([0, 0, 0], [10, 0, 0])
    result = run(DivideLength(), Curve=tree({(0,): [line]}), Length=3.0)
    (found,) = out(result, "Points").values()
    assert [p[0] for p in found] == pytest.approx([0, 3, 6, 9], abs=1e-12)  # 10 is not a whole 3s
    whole = run(DivideLength(), Curve=tree({(0,): [line]}), Length=2.5)
    assert [p[0] for p in out(whole, "Points")[(0,)]] == pytest.approx([0, 2.5, 5, 7.5, 10], abs=1e-12)
    tiny = run(DivideLength(), Curve=tree({(0,): [line]}), Length=1e-9)
    assert tiny.state == "warning" and "at most" in texts(tiny)[0]


def test_surface_closest_point_on_a_sphere_lies_along_the_radius():
    from torsal.nodes.surfaces.primitives import Sphere

    sphere = one(run(Sphere(), Radius=2.0))
    result = run(SurfaceClosestPoint(), Point=Point(0, 3, 4), Surface=tree({(0,): [sphere]}))
    assert one(result, "Point") == pytest.approx(Point(0, 1.2, 1.6), abs=1e-9)  # 2 · (0, 3, 4)/5
    assert one(result, "Distance") == pytest.approx(3.0, abs=1e-9)  # 5 − 2


def test_rectangle_is_centred_on_the_plane_with_its_perimeter():
    plane = Plane(Point(1, 1, 5), Vector(0, 1, 0), Vector(0, 0, 1))  # a wall: X along y, Y up
    result = run(Rectangle(), Plane=plane, Width=4.0, Height=2.0)
    outline = one(result, "Rectangle")
    np.testing.assert_allclose(outline.point_at(0.0), [1, -1, 4], atol=1e-12)  # (−W/2, −H/2) in the plane
    np.testing.assert_allclose(outline.point_at(0.5), [1, 3, 6], atol=1e-12)  # half the perimeter on
    assert outline.closed and one(result, "Length") == 12.0
    assert outline.length == pytest.approx(12.0, abs=1e-12)


def test_polygon_corners_lie_on_the_circle_and_its_perimeter_is_2nr_sin_pi_over_n():
    result = run(Polygon(), Radius=2.0, Segments=6)
    outline = one(result, "Polygon")
    assert one(result, "Length") == pytest.approx(12.0, abs=1e-12)  # a hexagon's side is its radius
    assert outline.length == pytest.approx(12.0, abs=1e-12)
    np.testing.assert_allclose(outline.point_at(0.0), [2, 0, 0], atol=1e-12)


def test_dispatch_sends_items_by_the_pattern():
    result = run(Dispatch(), List=[10.0, 11.0, 12.0, 13.0, 14.0], Pattern=[True, False])
    assert out(result, "A") == {(0,): [10.0, 12.0, 14.0]}
    assert out(result, "B") == {(0,): [11.0, 13.0]}
    empty = run(Dispatch(), List=[1.0], Pattern=tree({(0,): []}))
    assert empty.state == "warning"


def test_curve_plane_finds_both_crossings_of_a_circle():
    circle = Circle(KernelPlane.from_normal([0, 0, 0], [0, 0, 1]), 2.0)
    xz = Plane(Point(0, 0, 0), Vector(1, 0, 0), Vector(0, 0, 1))
    result = run(CurvePlane(), Curve=tree({(0,): [circle]}), Plane=xz)
    (found,) = out(result, "Points").values()
    assert sorted(p[0] for p in found) == pytest.approx([-2.0, 2.0], abs=1e-12)
    assert all(abs(p[1]) < 1e-12 for p in found)
    above = Plane(Point(0, 0, 1), Vector(1, 0, 0), Vector(0, 1, 0))  # parallel, 1 above: no crossing
    assert out(run(CurvePlane(), Curve=tree({(0,): [circle]}), Plane=above), "Points") == {(0,): []}


def test_volume_at_site_coordinates_is_the_volume_at_the_origin():
    sphere = trimesh.creation.icosphere(4, 3.0)
    at_origin = run(Volume(), Mesh=tree({(0,): [sphere]}))
    far = sphere.copy()
    far.apply_translation([1e6, -2e6, 30.0])
    result = run(Volume(), Mesh=tree({(0,): [far]}))
    # the vertices themselves hold 1e6 + 3 to ~1e-10: 2.6e-12 relative measured
    assert one(result, "Volume") == pytest.approx(one(at_origin, "Volume"), rel=1e-11)
    # about the world origin the centroid came out 1e-5 off (trimesh's mass properties)
    centre = np.asarray(one(result, "Centroid")) - [1e6, -2e6, 30.0]
    assert np.abs(centre - np.asarray(one(at_origin, "Centroid"))).max() < 1e-9
