"""Planar pieces with corners: a straight A and a polyline B in one plane bound a polygon,
not a quad, and the strip is that polygon cut into fans (every ruling inside it)."""

from __future__ import annotations

import numpy as np
import pytest

from tests.support.strip_triangles import strip_triangles
from torsal.nodes.geometry.curves import Line, Polyline
from torsal.nodes.geometry.developable import ruling_developable

A = Line([0, 0, 0], [4, 0, 0])


def polygon_area(points: np.ndarray) -> float:
    x, y = points[:, 0], points[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def signed_areas(starts: np.ndarray, ends: np.ndarray) -> np.ndarray:
    """Signed areas (about +z) of the two triangles of every quad between consecutive rulings."""
    triangles = strip_triangles(starts, ends, ku=1, kv=1)
    return 0.5 * np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])[:, 2]


@pytest.mark.parametrize(
    "corners",
    [
        [[0, 2, 0], [2, 3, 0], [4, 2, 0]],  # a roof: a convex pentagon
        [[0, 3, 0], [2, 1, 0], [4, 3, 0]],  # a V towards A: the diagonals A(0)–B(0) … cut it off
        [[1, 2, 0], [2, 1, 0], [3, 2, 0]],  # a short V
        [[0, 2, 0], [1, 3, 0], [3, 1, 0], [4, 2, 0]],  # a zigzag with two corners
    ],
)
def test_a_polyline_coplanar_with_a_straight_edge_is_fanned_inside_their_polygon(corners):
    b = Polyline(corners)
    result = ruling_developable(A, b, 8)
    assert result.message is None and result.valid.all()
    assert result.max_warp == 0.0
    # the fans tile the polygon A(0) A(1) B(1) … B(0): no triangle turns over, none is missing
    areas = signed_areas(result.starts, result.ends)
    assert areas.min() >= -1e-12
    polygon = np.concatenate([[A.start, A.end], b.points[::-1]])
    assert areas.sum() == pytest.approx(polygon_area(polygon), rel=1e-12)
    # every corner of B is reached, and the rulings never cross
    for vertex in b.vertex_parameters:
        assert np.any(np.abs(result.t - vertex) < 1e-12)
    assert np.all(np.diff(result.s) >= 0) and np.all(np.diff(result.t) >= 0)


def test_a_v_towards_a_gets_fans_at_both_ends_of_a_and_one_through_its_corner():
    b = Polyline([[0, 3, 0], [2, 1, 0], [4, 3, 0]])
    result = ruling_developable(A, b, 8)
    corner = np.abs(result.t - 0.5) < 1e-12
    at_a0 = result.s == 0.0
    at_a1 = result.s == 1.0
    assert np.all(corner | at_a0 | at_a1)
    assert np.all(corner[result.stations])  # every station leans on the corner
    # the end triangles: A(0) fans over B's first leg, A(1) over its second
    assert (result.t[at_a0].min(), result.t[at_a0].max()) == (0.0, 0.5)
    assert (result.t[at_a1].min(), result.t[at_a1].max()) == (0.5, 1.0)
