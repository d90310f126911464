"""curves.DivideCurve, EvaluateCurve, CurveLength, Flip and EndPoints against closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.graph import Graph
from torsal.engine.solver import Solver
from torsal.engine.values import Domain, Point, Vector
from torsal.nodes.curves.analysis import CurveLength, DivideCurve, EndPoints, EvaluateCurve, Flip
from torsal.nodes.curves.primitives import Arc, Circle, Line
from torsal.nodes.geometry import curves as kernel

CIRCLE = kernel.Circle(radius=2.0)
LINE = kernel.Line([0, 0, 0], [3, 4, 0])


def curve(value):
    return tree({(0,): [value]})


def test_divided_circle_points_lie_on_it_equally_spaced():
    result = run(DivideCurve(), Curve=curve(CIRCLE), Count=7)
    points = np.asarray(out(result, "Points")[(0,)])
    assert len(points) == 7  # closed: the end would repeat the start
    assert np.abs(np.linalg.norm(points, axis=1) - 2.0).max() < 1e-12
    chords = np.linalg.norm(np.roll(points, -1, axis=0) - points, axis=1)
    assert np.abs(chords - 2 * 2.0 * math.sin(math.pi / 7)).max() < 1e-12


def test_divided_circle_tangents_are_unit_and_perpendicular_to_the_radius():
    result = run(DivideCurve(), Curve=curve(CIRCLE), Count=5)
    points = np.asarray(out(result, "Points")[(0,)])
    tangents = np.asarray(out(result, "Tangents")[(0,)])
    assert np.allclose(np.linalg.norm(tangents, axis=1), 1.0, atol=1e-14)
    assert np.abs(np.einsum("ij,ij->i", points, tangents)).max() < 1e-12
    assert all(type(t) is Vector for t in out(result, "Tangents")[(0,)])


def test_divided_open_curve_gives_count_plus_one_points_from_start_to_end():
    result = run(DivideCurve(), Curve=curve(LINE), Count=4)
    assert out(result, "Parameters") == {(0,): [0.0, 0.25, 0.5, 0.75, 1.0]}
    assert out(result, "Points")[(0,)][2] == Point(1.5, 2.0, 0.0)


def test_divide_count_zero_warns():
    result = run(DivideCurve(), Curve=curve(LINE), Count=0)
    assert result.state == "warning"
    assert texts(result) == ["Count must be at least 1, not 0"]


def test_divide_negative_count_warns_and_makes_no_points():
    result = run(DivideCurve(), Curve=curve(LINE), Count=-3)
    assert texts(result) == ["Count must be at least 1, not -3"]
    assert out(result, "Points") == {}


def test_dividing_several_curves_puts_each_in_its_own_branch():
    result = run(DivideCurve(), Curve=tree({(0,): [LINE, CIRCLE]}), Count=2)
    points = out(result, "Points")
    assert list(points) == [(0, 0), (0, 1)]
    assert len(points[(0, 0)]) == 3 and len(points[(0, 1)]) == 2


def test_circle_wired_into_divide_curve_in_one_graph():
    graph = Graph()
    graph.add_node(Circle(), "circle")
    graph.add_node(DivideCurve(), "divide")
    graph.set_input_value("circle", "Radius", 3.0)
    graph.set_input_value("divide", "Count", 6)
    graph.connect("circle", "Circle", "divide", "Curve")
    solver = Solver(graph)
    solver.solve()
    points = np.asarray(list(solver.result("divide").output("Points").branches[0]))
    assert np.allclose(points[1], [1.5, 1.5 * math.sqrt(3), 0.0], atol=1e-12)


def test_evaluate_curvature_of_a_circle_is_one_over_its_radius():
    for t in (0.0, 0.1, 0.37, 0.5, 1.0):
        result = run(EvaluateCurve(), Curve=curve(CIRCLE), Parameter=t)
        (kappa,) = out(result, "Curvature")[(0,)]
        assert kappa == pytest.approx(0.5, rel=1e-12)
        (point,) = out(result, "Point")[(0,)]
        (vector,) = out(result, "CurvatureVector")[(0,)]
        # the curvature vector points to the centre, 1/r long
        assert np.allclose(vector, -np.asarray(point) / 4.0, atol=1e-12)


def test_evaluate_a_line_has_zero_curvature_and_its_direction_as_tangent():
    result = run(EvaluateCurve(), Curve=curve(LINE), Parameter=0.5)
    assert out(result, "Point") == {(0,): [Point(1.5, 2.0, 0.0)]}
    assert out(result, "Tangent") == {(0,): [Vector(0.6, 0.8, 0.0)]}
    assert out(result, "Curvature") == {(0,): [0.0]}
    assert out(result, "CurvatureVector") == {(0,): [Vector(0, 0, 0)]}


def test_evaluate_outside_zero_to_one_warns():
    result = run(EvaluateCurve(), Curve=curve(LINE), Parameter=1.5)
    assert texts(result) == ["Parameter must be from 0 to 1 (the curve's domain), not 1.5"]


def test_length_of_an_arc_is_radius_times_angle():
    (arc,) = out(run(Arc(), Radius=2.5, Angle=Domain(0.3, 2.9)))[(0,)]
    assert out(run(CurveLength(), Curve=curve(arc)))[(0,)][0] == pytest.approx(2.5 * 2.6, rel=1e-14)


def test_length_of_a_line_made_by_the_line_node():
    (line,) = out(run(Line(), Start=Point(1, 1, 1), End=Point(2, 3, 3)))[(0,)]
    assert out(run(CurveLength(), Curve=curve(line))) == {(0,): [3.0]}


def test_length_of_a_general_nurbs_arc_by_quadrature_is_r_theta():
    arc = kernel.Arc(radius=1.5, start_angle=0.0, end_angle=2.0).reversed()  # not an Arc any more
    (length,) = out(run(CurveLength(), Curve=curve(arc)))[(0,)]
    assert length == pytest.approx(3.0, rel=1e-12)


def test_flip_swaps_start_and_end_and_reverses_tangents():
    (flipped,) = out(run(Flip(), Curve=curve(LINE)))[(0,)]
    assert np.array_equal(flipped.start, [3, 4, 0]) and np.array_equal(flipped.end, [0, 0, 0])
    ends = run(EndPoints(), Curve=curve(flipped))
    assert out(ends, "Start") == {(0,): [Point(3, 4, 0)]}
    assert out(ends, "End") == {(0,): [Point(0, 0, 0)]}


def test_flipped_circle_runs_clockwise():
    (flipped,) = out(run(Flip(), Curve=curve(CIRCLE)))[(0,)]
    assert np.allclose(flipped.tangent_at(0.0), [0, -1, 0], atol=1e-12)


def test_end_points_of_a_closed_curve_coincide():
    result = run(EndPoints(), Curve=curve(CIRCLE))
    assert np.allclose(out(result, "Start")[(0,)][0], out(result, "End")[(0,)][0], atol=1e-15)


def test_a_curve_input_given_a_number_says_it_cannot_be_used():
    result = run(CurveLength(), Curve=tree({(0,): [2.0]}))
    assert result.state == "error"
    assert texts(result) == ["input Curve: Number 2.0 cannot be used as Curve"]
