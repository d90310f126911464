"""Lines and polylines: exact evaluation, arc-length parameterisation, closest points."""

from __future__ import annotations

import numpy as np
import pytest

from torsal.nodes.geometry.curves import Line, NurbsCurve, Polyline
from torsal.nodes.geometry.transforms import apply_transform, rotation

RNG = np.random.default_rng(8)


def test_line_point_at_interpolates_its_ends():
    line = Line([1, 2, 3], [3, 2, 1])
    assert np.allclose(line.point_at([0, 0.5, 1]), [[1, 2, 3], [2, 2, 2], [3, 2, 1]])
    assert line.length == pytest.approx(np.sqrt(8))


def test_line_derivative_is_its_direction_and_the_rest_vanish():
    _, d1, d2 = Line([0, 0, 0], [1, 2, 3]).derivatives(np.array([0.1, 0.9]), 2)
    assert d1.tolist() == [[1, 2, 3]] * 2
    assert not d2.any()


def test_line_closest_point_is_the_clamped_projection():
    line = Line([0, 0, 0], [2, 0, 0])
    result = line.closest_point([[1, 5, 0], [-3, 1, 0], [9, 0, 4]])
    assert result.parameters.tolist() == [0.5, 0.0, 1.0]
    assert np.allclose(result.distances, [5, np.hypot(3, 1), np.hypot(7, 4)])


def test_zero_length_line_is_allowed_with_zero_tangent():
    line = Line([1, 1, 1], [1, 1, 1])
    assert line.length == 0
    assert not line.tangent_at(0.5).any()
    assert line.closest_point([[0, 0, 0]]).parameters.tolist() == [0.0]


def test_line_reversed_transformed_and_as_nurbs_are_exact():
    line = Line([0, 1, 2], [4, 3, 2])
    t = np.linspace(0, 1, 7)
    assert np.allclose(line.reversed().point_at(t), line.point_at(1 - t), atol=1e-15)
    m = rotation([0, 0, 1], 0.7)
    assert np.allclose(line.transformed(m).point_at(t), apply_transform(m, line.point_at(t)))
    assert np.allclose(line.to_nurbs().point_at(t), line.point_at(t), atol=1e-15)


def test_polyline_parameter_is_the_fraction_of_its_length():
    poly = Polyline([[0, 0], [1, 0], [1, 3]])
    assert poly.length == 4
    assert np.allclose(poly.point_at([0.125, 0.25, 0.5, 1.0]), [[0.5, 0, 0], [1, 0, 0], [1, 1, 0], [1, 3, 0]])
    assert np.allclose(poly.derivatives(np.array([0.1, 0.6]))[1], [[4, 0, 0], [0, 4, 0]])


def test_polyline_length_table_agrees_with_its_exact_length():
    poly = Polyline(RNG.normal(size=(30, 3)))
    assert poly._length_table.total == pytest.approx(poly.length, rel=1e-13)
    t = np.linspace(0, 1, 101)
    assert np.allclose(poly.length_at(t), t * poly.length, rtol=1e-12, atol=1e-12)


def test_closed_polyline_gains_a_closing_segment():
    poly = Polyline([[0, 0], [1, 0], [1, 1], [0, 1]], closed=True)
    assert poly.closed
    assert poly.length == 4
    assert len(poly.points) == 5
    assert poly.divide_by_count(4).tolist() == [0, 0.25, 0.5, 0.75]


def test_polyline_with_repeated_points_skips_zero_length_segments():
    poly = Polyline([[0, 0], [1, 0], [1, 0], [1, 1]])
    assert np.allclose(poly.point_at([0.5, 0.75, 1.0]), [[1, 0, 0], [1, 0.5, 0], [1, 1, 0]])
    assert np.allclose(poly.to_nurbs().point_at(np.linspace(0, 1, 9)), poly.point_at(np.linspace(0, 1, 9)))


def test_polyline_closest_points_match_brute_force():
    poly = Polyline(RNG.normal(size=(12, 3)))
    queries = RNG.normal(size=(200, 3)) * 2
    result = poly.closest_point(queries)
    dense = poly.point_at(np.linspace(0, 1, 200_001))
    brute = np.min(np.linalg.norm(queries[:, None, :] - dense[None, ::10], axis=2), axis=1)
    assert np.all(result.distances <= brute + 1e-12)
    assert np.allclose(poly.point_at(result.parameters), result.points, atol=1e-12)


def test_polyline_needs_two_distinct_points():
    with pytest.raises(ValueError, match="at least 2 points"):
        Polyline([[0, 0, 0]])
    with pytest.raises(ValueError, match="two distinct points"):
        Polyline([[1, 1], [1, 1]])


def test_polyline_as_nurbs_has_the_same_parameterisation():
    poly = Polyline(RNG.normal(size=(8, 3)))
    nurbs = poly.to_nurbs()
    assert isinstance(nurbs, NurbsCurve)
    t = np.linspace(0, 1, 77)
    assert np.allclose(nurbs.point_at(t), poly.point_at(t), atol=1e-14)
