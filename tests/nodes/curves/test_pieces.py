"""Join Curves, Explode and Shatter: lengths and corners from closed forms, joins against shapely."""

from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from shapely.ops import linemerge

from tests.support.node_helpers import out, run, texts, tree
from torsal.nodes.curves.pieces import Explode, JoinCurves, Shatter
from torsal.nodes.geometry.curves import Arc, Circle, Line, NurbsCurve, Polyline
from torsal.nodes.geometry.curves.pieces import PolyCurve, SubCurve
from torsal.nodes.geometry.vectors import Plane


def _items(result, port=None):
    return [item for branch in out(result, port).values() for item in branch]


def test_join_chains_shuffled_and_reversed_lines_into_the_polyline_shapely_merges():
    pieces = [((1, 0), (1, 1)), ((0, 0), (1, 0)), ((0, 1), (1, 1)), ((0, 1), (0, 3))]
    curves = [Line([*a, 0.0], [*b, 0.0]) for a, b in pieces]
    (joined,) = _items(run(JoinCurves(), Curves=tree({(0,): curves})))
    merged = linemerge(shapely.MultiLineString(pieces))  # an independent library's chain
    assert isinstance(joined, Polyline)
    ours = {tuple(p) for p in joined.points[:, :2].tolist()}
    assert ours == set(merged.coords)
    assert joined.length == pytest.approx(merged.length, rel=1e-15)
    assert len(joined.points) == 5


def test_join_leaves_curves_that_meet_nothing_as_they_were():
    apart = [Line([0, 0, 0], [1, 0, 0]), Line([5, 5, 0], [6, 5, 0])]
    joined = _items(run(JoinCurves(), Curves=tree({(0,): apart})))
    assert joined == apart


def test_two_half_circles_join_into_one_closed_curve_of_length_two_pi_r():
    r = 2.5
    top = Arc(Plane.from_normal([0, 0, 0], [0, 0, 1]), r, 0.0, math.pi)
    bottom = Arc(Plane.from_normal([0, 0, 0], [0, 0, 1]), r, math.pi, 2 * math.pi).reversed()
    (joined,) = _items(run(JoinCurves(), Curves=tree({(0,): [top, bottom]})))
    assert isinstance(joined, PolyCurve) and joined.closed
    assert joined.length == pytest.approx(2 * math.pi * r, rel=1e-12)
    t = np.linspace(0, 1, 101)
    assert np.abs(np.linalg.norm(joined.point_at(t), axis=1) - r).max() < 1e-12 * r
    # the reversed half is run forwards: the tangent turns one way all round (counter-clockwise)
    tangents, points = joined.tangent_at(t[1:-1]), joined.point_at(t[1:-1])
    assert np.all(np.cross(points, tangents)[:, 2] > 0)


def test_join_honours_a_tolerance_in_model_units():
    gapped = [Line([0, 0, 0], [1, 0, 0]), Line([1.01, 0, 0], [2, 0, 0])]
    assert len(_items(run(JoinCurves(), Curves=tree({(0,): gapped})))) == 2
    assert len(_items(run(JoinCurves(), Curves=tree({(0,): gapped}), Tolerance=0.02))) == 1


def test_explode_gives_a_polylines_segments_and_its_corners():
    square = Polyline([[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]], closed=True)
    result = run(Explode(), Curve=tree({(0,): [square]}))
    segments = _items(result, "Segments")
    assert [s.length for s in segments] == [2.0, 1.0, 2.0, 1.0]
    assert all(isinstance(s, Line) for s in segments)
    corners = np.array([list(p) for p in _items(result, "Vertices")])
    assert corners.tolist() == [[0, 0, 0], [2, 0, 0], [2, 1, 0], [0, 1, 0]]  # closed: start not repeated


def test_explode_cuts_a_nurbs_curve_at_its_kink_and_not_at_smooth_knots():
    # degree 2 with a double inner knot at a corner (control point (2, 0) reached exactly)
    kinked = NurbsCurve([[0, 0, 0], [1, 1, 0], [2, 0, 0], [3, 1, 0], [4, 0, 0]], degree=2,
                        knots=[0, 0, 0, 1, 1, 2, 2, 2])
    pieces = _items(run(Explode(), Curve=tree({(0,): [kinked]})), "Segments")
    assert len(pieces) == 2
    assert pieces[0].end_points[1] == pytest.approx([2, 0, 0], abs=1e-15)
    smooth = NurbsCurve([[0, 0, 0], [1, 1, 0], [2, 0, 0], [3, 1, 0], [4, 0, 0]], degree=3)
    assert _items(run(Explode(), Curve=tree({(0,): [smooth]})), "Segments") == [smooth]


def test_shatter_cuts_a_polyline_into_exact_polylines_at_lengths():
    bent = Polyline([[0, 0, 0], [3, 0, 0], [3, 1, 0]])  # 4 long: t is the share of the length
    pieces = _items(run(Shatter(), Curve=tree({(0,): [bent]}), Parameters=[0.5, 0.25, 0.25, 1.5]))
    assert [p.length for p in pieces] == pytest.approx([1.0, 1.0, 2.0], rel=1e-15)
    assert isinstance(pieces[2], Polyline) and pieces[2].points.tolist() == [[2, 0, 0], [3, 0, 0], [3, 1, 0]]


def test_shatter_a_circle_into_arcs_of_the_angles_between_the_cuts():
    r = 3.0
    circle = Circle(Plane.from_normal([0, 0, 0], [0, 0, 1]), r)
    result = run(Shatter(), Curve=tree({(0,): [circle]}), Parameters=[0.2, 0.7])
    pieces = _items(result)
    assert all(isinstance(p, SubCurve) for p in pieces)
    angles = [math.atan2(y, x) % (2 * math.pi) for x, y, _ in circle.point_at(np.array([0.2, 0.7]))]
    expected = [angles[0], angles[1] - angles[0], 2 * math.pi - angles[1]]
    assert [p.length for p in pieces] == pytest.approx([r * a for a in expected], rel=1e-11)
    assert pieces[1].point_at(0.0) == pytest.approx(circle.point_at(0.2), abs=1e-14)


def test_shatter_with_a_nan_parameter_warns_naming_parameters():
    result = run(Shatter(), Curve=tree({(0,): [Line([0, 0, 0], [1, 0, 0])]}), Parameters=[0.5, float("nan")])
    assert result.state == "warning"
    assert "Parameters" in texts(result)[0]
