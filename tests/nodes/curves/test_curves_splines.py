"""curves.Interpolate, NurbsCurve and ParametricCurve."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support.node_helpers import out, run, texts
from torsal.engine.values import Domain, Point, Vector
from torsal.nodes.curves.splines import Interpolate, NurbsCurve, ParametricCurve

ZIGZAG = [Point(0, 0, 0), Point(1, 2, 0), Point(3, 1, 1), Point(4, 3, 0), Point(6, 0, 2)]


def only(result):
    (value,) = out(result)[(0,)]
    return value


def closest_distances(curve, points):
    return curve.closest_point(np.asarray(points, dtype=float)).distances


def test_interpolate_passes_through_every_vertex():
    curve = only(run(Interpolate(), Vertices=ZIGZAG))
    assert curve.degree == 3
    assert np.abs(curve.point_at(curve.parameters) - np.asarray(ZIGZAG)).max() < 1e-12
    assert closest_distances(curve, ZIGZAG).max() < 1e-12


def test_interpolate_starts_and_ends_at_the_first_and_last_vertex():
    curve = only(run(Interpolate(), Vertices=ZIGZAG))
    assert np.allclose(curve.start, ZIGZAG[0], atol=1e-14)
    assert np.allclose(curve.end, ZIGZAG[-1], atol=1e-14)


def test_closed_interpolation_passes_through_its_vertices_and_closes_smoothly():
    curve = only(run(Interpolate(), Vertices=ZIGZAG, Closed=True))
    assert curve.closed
    assert closest_distances(curve, ZIGZAG).max() < 1e-12
    assert np.allclose(curve.tangent_at(0.0), curve.tangent_at(1.0), atol=1e-12)


def test_interpolate_follows_the_end_tangents():
    result = run(Interpolate(), Vertices=ZIGZAG[:3], StartTangent=Vector(0, 0, 5),
                 EndTangent=Vector(1, 0, 0))
    curve = only(result)
    assert result.state == "ok"
    assert np.allclose(curve.tangent_at(0.0), [0, 0, 1], atol=1e-12)
    assert np.allclose(curve.tangent_at(1.0), [1, 0, 0], atol=1e-12)


def test_interpolate_degree_one_joins_the_vertices_straight():
    curve = only(run(Interpolate(), Vertices=ZIGZAG, Degree=1))
    lengths = np.linalg.norm(np.diff(np.asarray(ZIGZAG), axis=0), axis=1)
    assert curve.length == pytest.approx(lengths.sum(), rel=1e-12)


def test_interpolate_with_a_repeated_vertex_says_which():
    points = [Point(0, 0, 0), Point(1, 1, 0), Point(1, 1, 0), Point(2, 0, 0)]
    result = run(Interpolate(), Vertices=points)
    assert result.state == "warning"
    assert texts(result) == [
        "Vertices 1 and 2 are the same point: the curve cannot pass through one point twice "
        "in a row (remove the duplicate)"
    ]
    assert out(result) == {(0,): [None]}


def test_interpolate_with_degree_above_the_vertices_lowers_it_with_a_warning():
    result = run(Interpolate(), Vertices=ZIGZAG[:3], Degree=3)
    assert texts(result) == ["Degree 3 needs at least 4 vertices; with 3 the curve has degree 2"]
    curve = only(result)
    assert curve.degree == 2
    assert closest_distances(curve, ZIGZAG[:3]).max() < 1e-12


def test_interpolate_with_one_vertex_warns():
    result = run(Interpolate(), Vertices=[Point(0, 0, 0)])
    assert texts(result) == ["A curve needs at least 2 vertices; got 1"]


def test_interpolate_closed_with_tangents_is_refused():
    result = run(Interpolate(), Vertices=ZIGZAG, Closed=True, StartTangent=Vector(1, 0, 0))
    assert texts(result) == ["A closed curve has no ends: leave StartTangent and EndTangent at zero"]


@pytest.mark.parametrize("degree", [0, -2, 12])
def test_interpolate_degree_out_of_range_warns(degree):
    assert texts(run(Interpolate(), Vertices=ZIGZAG, Degree=degree)) == [
        f"Degree must be from 1 to 11, not {degree}"
    ]


def test_nurbs_curve_starts_and_ends_on_its_end_vertices_and_is_pulled_by_weights():
    plain = only(run(NurbsCurve(), Vertices=ZIGZAG))
    assert np.allclose(plain.start, ZIGZAG[0]) and np.allclose(plain.end, ZIGZAG[-1])
    heavy = only(run(NurbsCurve(), Vertices=ZIGZAG, Weights=[1, 1, 10, 1, 1]))
    assert heavy.is_rational
    target = np.asarray(ZIGZAG[2])
    assert closest_distances(heavy, [target])[0] < closest_distances(plain, [target])[0]


def test_nurbs_quadratic_on_three_vertices_is_the_bezier_parabola():
    p0, p1, p2 = Point(0, 0, 0), Point(1, 2, 0), Point(2, 0, 0)
    curve = only(run(NurbsCurve(), Vertices=[p0, p1, p2], Degree=2))
    # B(1/2) = (P0 + 2 P1 + P2) / 4
    assert np.allclose(curve.point_at(0.5), [1.0, 1.0, 0.0], atol=1e-15)


def test_nurbs_degree_too_high_for_the_vertices_warns():
    result = run(NurbsCurve(), Vertices=ZIGZAG[:3], Degree=3)
    assert result.state == "warning"
    assert texts(result) == [
        "A degree-3 curve needs at least 4 vertices; got 3 (lower Degree to 2 or add vertices)"
    ]


def test_nurbs_weights_must_match_the_vertices():
    result = run(NurbsCurve(), Vertices=ZIGZAG, Weights=[1, 2])
    assert texts(result) == ["Give one weight per vertex: there are 5 vertices and 2 weights"]


def test_nurbs_weights_must_be_positive():
    result = run(NurbsCurve(), Vertices=ZIGZAG, Weights=[1, 1, 0, 1, 1])
    assert texts(result) == ["Weights must be positive; weight 2 is 0"]


def test_periodic_nurbs_curve_is_closed():
    curve = only(run(NurbsCurve(), Vertices=ZIGZAG, Periodic=True))
    assert curve.closed
    assert np.allclose(curve.start, curve.end, atol=1e-12)


def test_parametric_helix_length_matches_the_closed_form_per_turn():
    r, c, turns = 2.0, 0.5, 3
    result = run(ParametricCurve(), X="2 * cos(t)", Y="2 * sin(t)", Z="0.5 * t",
                 Domain=Domain(0.0, turns * 2 * math.pi))
    helix = only(result)
    exact = turns * 2 * math.pi * math.sqrt(r * r + c * c)
    assert abs(helix.length / exact - 1) < 1e-9


def test_parametric_curve_points_follow_the_formulas_over_the_domain():
    curve = only(run(ParametricCurve(), X="t", Y="t**2", Z="1", Domain=Domain(-1.0, 3.0)))
    assert np.allclose(curve.point_at(0.5), [1.0, 1.0, 1.0])
    assert np.allclose(curve.start, [-1.0, 1.0, 1.0])
    assert np.allclose(curve.end, [3.0, 9.0, 1.0])


def test_parametric_default_is_the_unit_circle_with_curvature_one():
    curve = only(run(ParametricCurve()))
    assert curve.closed
    assert np.allclose(curve.curvature_at(np.linspace(0, 1, 7)), 1.0, atol=1e-8)


def test_parametric_curve_over_a_reversed_domain_runs_backwards():
    curve = only(run(ParametricCurve(), X="t", Y="0", Z="0", Domain=Domain(2.0, 0.0)))
    assert np.allclose(curve.start, [2, 0, 0]) and np.allclose(curve.end, [0, 0, 0])


def test_parametric_curve_with_an_unreadable_formula_warns_naming_it():
    result = run(ParametricCurve(), X="cos(t", Y="0", Z="0")
    assert result.state == "warning"
    assert texts(result)[0].startswith("X: Could not read the expression")


def test_parametric_curve_formula_in_an_unknown_variable_warns_naming_it():
    result = run(ParametricCurve(), X="u", Y="0", Z="0")
    assert result.state == "warning"
    assert texts(result)[0].startswith("X: ")
    assert "'u'" in texts(result)[0]


def test_parametric_curve_over_an_empty_domain_warns():
    result = run(ParametricCurve(), Domain=Domain(1.0, 1.0))
    assert texts(result) == ["The Domain is empty (1 to 1): t must run over an interval"]


def test_parametric_curve_with_a_non_finite_point_warns_where():
    result = run(ParametricCurve(), X="1 / t", Y="0", Z="0", Domain=Domain(-1.0, 1.0))
    assert result.state == "warning"
    assert texts(result) == [
        "The formulas give no finite point at t = 0 (division by zero, or a square root of a "
        "negative number?)"
    ]
