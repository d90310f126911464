"""transform.Array and PolarArray: counts and spacing."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.values import Plane, Point, Vector
from torsal.nodes.geometry import curves as kernel
from torsal.nodes.transform.arrays import Array, PolarArray


def copies(result, path=(0,)):
    assert result.state == "ok", result.messages
    return out(result)[path]


def test_linear_array_counts_the_original_and_steps_by_direction():
    result = run(Array(), Geometry=tree({(0,): [Point(1, 1, 0)]}), Direction=Vector(2, 0, 0), Count=4)
    assert copies(result) == [Point(1, 1, 0), Point(3, 1, 0), Point(5, 1, 0), Point(7, 1, 0)]


def test_linear_array_of_a_curve_spaces_copies_evenly():
    circle = kernel.Circle(radius=1.0)
    result = run(Array(), Geometry=tree({(0,): [circle]}), Direction=Vector(0, 0, 1.5), Count=5)
    starts = np.array([c.start for c in copies(result)])
    assert len(starts) == 5
    assert np.allclose(np.diff(starts, axis=0), [0, 0, 1.5], atol=1e-14)


def test_linear_array_of_several_items_gives_each_its_own_branch():
    result = run(Array(), Geometry=tree({(0,): [Point(0, 0, 0), Point(0, 5, 0)]}), Count=2)
    assert out(result) == {
        (0, 0): [Point(0, 0, 0), Point(10, 0, 0)],
        (0, 1): [Point(0, 5, 0), Point(10, 5, 0)],
    }


@pytest.mark.parametrize("count", [0, -1])
def test_array_count_below_one_warns(count):
    result = run(Array(), Geometry=tree({(0,): [Point(0, 0, 0)]}), Count=count)
    assert result.state == "warning"
    assert texts(result) == [f"Count must be at least 1, not {count}"]


def test_array_with_zero_direction_warns():
    result = run(Array(), Geometry=tree({(0,): [Point(0, 0, 0)]}), Direction=Vector(0, 0, 0))
    assert texts(result) == ["Direction has zero length, so it has no direction"]


def test_polar_array_spaces_copies_evenly_round_a_full_turn():
    result = run(PolarArray(), Geometry=tree({(0,): [Point(2, 0, 1)]}), Count=6)
    points = np.asarray(copies(result))
    angles = np.arctan2(points[:, 1], points[:, 0]) % (2 * math.pi)
    assert np.allclose(angles, np.arange(6) * math.pi / 3, atol=1e-14)
    assert np.allclose(np.hypot(points[:, 0], points[:, 1]), 2.0) and np.allclose(points[:, 2], 1.0)


def test_polar_array_over_a_half_turn_steps_by_angle_over_count():
    result = run(PolarArray(), Geometry=tree({(0,): [Point(1, 0, 0)]}), Count=4, Angle=math.pi)
    points = np.asarray(copies(result))
    assert np.allclose(np.arctan2(points[:, 1], points[:, 0]), np.arange(4) * math.pi / 4, atol=1e-15)


def test_polar_array_about_a_plane_away_from_the_origin_keeps_distance_to_its_axis():
    plane = Plane(Point(5, 0, 0), Vector(1, 0, 0), Vector(0, 1, 0))
    line = kernel.Line([6, 0, 0], [7, 0, 0])
    result = run(PolarArray(), Geometry=tree({(0,): [line]}), Plane=plane, Count=3)
    for copy in copies(result):
        assert np.linalg.norm(copy.start - [5, 0, 0]) == pytest.approx(1.0)
        assert copy.length == pytest.approx(1.0)


def test_polar_array_with_zero_angle_warns():
    result = run(PolarArray(), Geometry=tree({(0,): [Point(1, 0, 0)]}), Angle=0.0)
    assert texts(result) == ["Angle is 0, so every copy would sit on the original"]
