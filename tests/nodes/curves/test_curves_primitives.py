"""curves.Line, Polyline, Circle and Arc: closed-form lengths and plain messages."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.values import Domain, Plane, Point, Vector
from torsal.nodes.curves.primitives import Arc, Circle, Line, Polyline


def only(result, port=None):
    (value,) = out(result, port)[(0,)]
    return value


def test_line_from_3_4_0_is_5_long():
    line = only(run(Line(), Start=Point(0, 0, 0), End=Point(3, 4, 0)))
    assert line.length == 5.0
    assert np.array_equal(line.point_at(0.5), [1.5, 2.0, 0.0])


def test_line_with_equal_ends_warns_and_gives_a_zero_length_line():
    result = run(Line(), Start=Point(1, 2, 3), End=Point(1, 2, 3))
    assert result.state == "warning"
    assert texts(result) == ["Start and End are the same point, so the line has zero length"]
    (line,) = out(result)[(0,)]
    assert line.length == 0.0
    assert np.array_equal(line.point_at(0.5), [1.0, 2.0, 3.0])


def test_line_needs_both_ends():
    result = run(Line(), Start=Point(0, 0, 0))
    assert texts(result) == ["Input End collected no data"]


def test_lines_from_lists_pair_start_and_end_points():
    result = run(Line(), Start=[Point(0, 0, 0), Point(0, 1, 0)], End=Point(2, 0, 0))
    assert [line.length for line in out(result)[(0,)]] == [2.0, math.sqrt(5.0)]


def test_polyline_length_is_the_sum_of_its_segments():
    square = [Point(0, 0, 0), Point(2, 0, 0), Point(2, 2, 0), Point(0, 2, 0)]
    assert only(run(Polyline(), Vertices=square)).length == 6.0
    closed = only(run(Polyline(), Vertices=square, Closed=True))
    assert closed.length == 8.0
    assert closed.closed


def test_polyline_with_one_vertex_warns():
    result = run(Polyline(), Vertices=[Point(1, 1, 1)])
    assert texts(result) == ["A polyline needs at least 2 vertices; got 1"]


def test_polyline_with_an_empty_vertex_says_so():
    result = run(Polyline(), Vertices=tree({(0,): [Point(0, 0, 0), None, Point(1, 0, 0)]}))
    assert texts(result) == ["Vertices contains empty (null) items: remove them or fix what made them"]


def test_circle_points_are_at_the_radius_in_its_plane():
    plane = Plane(Point(1, 2, 3), Vector(0, 1, 0), Vector(0, 0, 1))  # the YZ plane through (1, 2, 3)
    circle = only(run(Circle(), Plane=plane, Radius=2.5))
    p = circle.point_at(np.linspace(0, 1, 10_001))
    assert np.abs(np.linalg.norm(p - [1, 2, 3], axis=1) - 2.5).max() < 1e-12
    assert np.abs(p[:, 0] - 1).max() < 1e-15
    assert circle.closed
    assert circle.length == pytest.approx(5 * math.pi, rel=1e-15)


def test_circle_starts_on_the_planes_x_axis():
    circle = only(run(Circle(), Radius=2.0))
    assert np.allclose(circle.start, [2, 0, 0], atol=1e-15)


@pytest.mark.parametrize("radius, message", [
    (0.0, "Radius must be a positive length, not 0"),
    (-1.0, "Radius must be a positive length, not -1"),
])
def test_circle_radius_must_be_positive(radius, message):
    result = run(Circle(), Radius=radius)
    assert result.state == "warning"
    assert texts(result) == [message]


def test_circle_plane_with_parallel_axes_is_refused():
    plane = Plane(Point(0, 0, 0), Vector(1, 0, 0), Vector(2, 0, 0))
    assert texts(run(Circle(), Plane=plane)) == ["Plane's X and Y axes are parallel, so they span no plane"]


def test_circle_on_a_point_uses_the_xy_plane_through_it():
    circle = only(run(Circle(), Plane=Point(0, 0, 5), Radius=1.0))
    assert np.allclose(circle.point_at(0.3)[2], 5.0)


def test_arc_length_is_radius_times_angle():
    arc = only(run(Arc(), Radius=3.0, Angle=Domain(0.25, 2.0)))
    assert arc.length == pytest.approx(3.0 * 1.75, rel=1e-14)
    assert np.allclose(arc.start, [3 * math.cos(0.25), 3 * math.sin(0.25), 0], atol=1e-14)
    assert np.allclose(arc.end, [3 * math.cos(2.0), 3 * math.sin(2.0), 0], atol=1e-14)


def test_arc_over_a_reversed_domain_runs_clockwise():
    arc = only(run(Arc(), Radius=1.0, Angle=Domain(math.pi / 2, 0.0)))
    assert np.allclose(arc.start, [0, 1, 0], atol=1e-15)
    assert np.allclose(arc.end, [1, 0, 0], atol=1e-15)
    assert arc.length == pytest.approx(math.pi / 2, rel=1e-12)


def test_arc_over_an_empty_domain_warns():
    result = run(Arc(), Angle=Domain(1.0, 1.0))
    assert texts(result) == ["The Angle domain is empty (1 to 1), so the arc would have no length"]


def test_arc_of_more_than_a_turn_warns():
    result = run(Arc(), Angle=Domain(0.0, 7.0))
    assert texts(result) == ["The Angle domain spans 7 radians, more than a full turn (2π ≈ 6.28319)"]
