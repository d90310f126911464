"""curves.Offset: exact for lines, polylines and circles; sampled and re-interpolated otherwise."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.values import Domain, Plane, Point, Vector
from torsal.nodes.curves.offset import Offset
from torsal.nodes.curves.splines import ParametricCurve
from torsal.nodes.geometry import curves as kernel

SAMPLES = np.linspace(0.0, 1.0, 10_001)


def curve(value):
    return tree({(0,): [value]})


def offset(value, **inputs):
    result = run(Offset(), Curve=curve(value), **inputs)
    (shape,) = out(result)[(0,)]
    return result, shape


def radius_error(shape, centre, radius):
    return np.abs(np.linalg.norm(shape.point_at(SAMPLES) - centre, axis=1) - radius).max()


def test_sampled_offset_of_a_circle_by_d_is_the_circle_of_radius_r_plus_d():
    (circle,) = out(run(ParametricCurve(), X="2 * cos(t)", Y="2 * sin(t)", Z="0"))[(0,)]
    result, shape = offset(circle, Distance=0.5)
    assert result.state == "ok"
    assert radius_error(shape, [0, 0, 0], 2.5) < 1e-6
    assert shape.closed


def test_sampled_inward_offset_of_a_circle_shrinks_it():
    (circle,) = out(run(ParametricCurve(), X="3 + 2 * cos(t)", Y="2 * sin(t)", Z="1"))[(0,)]
    _, shape = offset(circle, Distance=-0.75)
    assert radius_error(shape, [3, 0, 1], 1.25) < 1e-6


def test_exact_offset_of_a_circle_node_output_is_a_circle():
    _, shape = offset(kernel.Circle(radius=2.0), Distance=0.5)
    assert isinstance(shape, kernel.Circle)
    assert radius_error(shape, [0, 0, 0], 2.5) < 1e-12


def test_offset_of_a_circle_seen_from_below_goes_inwards():
    below = Plane(Point(0, 0, 0), Vector(0, 1, 0), Vector(1, 0, 0))  # normal −z
    _, shape = offset(kernel.Circle(radius=2.0), Distance=0.5, Plane=below)
    assert radius_error(shape, [0, 0, 0], 1.5) < 1e-12


def test_offset_of_an_arc_keeps_its_angles():
    arc = kernel.Arc(radius=1.0, start_angle=0.0, end_angle=math.pi / 2)
    _, shape = offset(arc, Distance=1.0)
    assert np.allclose(shape.start, [2, 0, 0], atol=1e-15) and np.allclose(shape.end, [0, 2, 0], atol=1e-15)


def test_inward_offset_past_the_centre_of_a_circle_warns():
    result = run(Offset(), Curve=curve(kernel.Circle(radius=1.0)), Distance=-1.0)
    assert result.state == "warning"
    assert texts(result) == [
        "Offsetting a circle of radius 1 inwards by 1 leaves nothing: the distance is at least the radius"
    ]


def test_offset_of_a_counter_clockwise_square_has_mitred_corners():
    square = kernel.Polyline([[0, 0], [2, 0], [2, 2], [0, 2]], closed=True)
    _, shape = offset(square, Distance=0.5)
    assert np.allclose(shape.points, [[-0.5, -0.5, 0], [2.5, -0.5, 0], [2.5, 2.5, 0], [-0.5, 2.5, 0],
                                      [-0.5, -0.5, 0]])
    assert shape.length == pytest.approx(12.0, rel=1e-15)


def test_offset_of_an_open_polyline_moves_its_ends_square_to_the_segments():
    bend = kernel.Polyline([[0, 0], [1, 0], [1, 1]])
    _, shape = offset(bend, Distance=-0.25)  # to the left: the inside of this left turn
    assert np.allclose(shape.points, [[0, 0.25, 0], [0.75, 0.25, 0], [0.75, 1, 0]])


def test_offset_of_a_line_is_parallel_at_the_distance():
    _, shape = offset(kernel.Line([0, 0, 0], [4, 0, 0]), Distance=1.0)
    assert isinstance(shape, kernel.Line)
    assert np.allclose(shape.start, [0, -1, 0]) and np.allclose(shape.end, [4, -1, 0])


def test_sampled_offset_of_a_spline_is_at_the_distance_everywhere():
    spline = kernel.InterpolatedCurve([[0, 0], [1, 1], [2, 0], [3, 1]])
    _, shape = offset(spline, Distance=0.2)
    distances = spline.closest_point(shape.point_at(SAMPLES)).distances
    assert np.abs(distances - 0.2).max() < 1e-6


def test_offset_of_a_non_planar_curve_warns_and_keeps_heights():
    (helix,) = out(run(ParametricCurve(), Z="0.1 * t", Domain=Domain(0.0, math.pi)))[(0,)]
    result, shape = offset(helix, Distance=0.5)
    assert result.state == "warning"
    assert texts(result)[0].startswith(
        "The curve is not flat in the Plane (its height above it varies by 0.314"
    )
    p = shape.point_at(SAMPLES)
    assert np.abs(np.hypot(p[:, 0], p[:, 1]) - 1.5).max() < 1e-6


def test_offset_further_than_a_bends_radius_warns_that_it_loops():
    (ellipse,) = out(run(ParametricCurve(), X="3 * cos(t)", Y="sin(t)", Z="0"))[(0,)]
    result = run(Offset(), Curve=curve(ellipse), Distance=-0.5)  # inside; the ends bend at radius 1/3
    assert result.state == "warning"
    assert "the offset loops over itself there" in texts(result)[0]


def test_offset_of_a_line_along_the_planes_normal_warns():
    result = run(Offset(), Curve=curve(kernel.Line([0, 0, 0], [0, 0, 1])), Distance=1.0)
    assert "Segment 0 runs along the Plane's normal" in texts(result)[-1]


def test_zero_distance_gives_the_curve_back():
    circle = kernel.Circle(radius=1.0)
    assert offset(circle, Distance=0.0)[1] is circle
