"""Interpolating splines pass through their points, with chord-length parameters."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from torsal.nodes.geometry.curves import InterpolatedCurve, NurbsCurve, chord_length_parameters


def random_points(seed: int, count: int) -> np.ndarray:
    return np.random.default_rng(seed).uniform(-10, 10, (count, 3))


@settings(max_examples=50, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(2, 40), st.booleans())
def test_interpolating_spline_passes_through_its_points_within_1e_12(seed, count, closed):
    if closed:
        count = max(count, 3)
    points = random_points(seed, count)
    curve = InterpolatedCurve(points, closed=closed)
    assert np.abs(curve.point_at(curve.parameters)[:count] - points).max() < 1e-12
    assert curve.closed == closed


def test_parameters_are_normalised_cumulative_chord_lengths():
    points = np.array([[0.0, 0, 0], [3, 0, 0], [3, 4, 0], [3, 4, 12]])
    curve = InterpolatedCurve(points)
    assert np.allclose(curve.parameters, [0, 3 / 19, 7 / 19, 1], atol=1e-15)
    assert np.allclose(chord_length_parameters(points), curve.parameters)


def test_closed_spline_is_c2_across_its_seam():
    curve = InterpolatedCurve(random_points(7, 9), closed=True)
    # a non-periodic copy evaluates t = 1 from the left instead of wrapping it to t = 0
    copy = NurbsCurve.from_arrays(curve.control_points, curve.knots, curve.degree)
    start, end = copy.derivatives(0.0, 2), copy.derivatives(1.0, 2)
    for a, b in zip(start, end, strict=True):
        assert np.allclose(a, b, rtol=1e-9, atol=1e-9 * np.abs(a).max())
    assert curve.periodic


def test_closed_spline_drops_a_repeated_last_point():
    points = random_points(2, 5)
    with_repeat = InterpolatedCurve(np.vstack([points, points[:1]]), closed=True)
    without = InterpolatedCurve(points, closed=True)
    assert np.array_equal(with_repeat.point_at(np.linspace(0, 1, 9)), without.point_at(np.linspace(0, 1, 9)))


def test_end_tangents_set_the_end_directions_with_chord_length_speed():
    points = random_points(3, 6)
    curve = InterpolatedCurve(points, start_tangent=[0, 0, 2], end_tangent=[1, 1, 0])
    chord = np.sum(np.linalg.norm(np.diff(points, axis=0), axis=1))
    assert np.allclose(curve.derivatives(0.0)[1], [0, 0, chord], atol=1e-10 * chord)
    assert np.allclose(curve.derivatives(1.0)[1], chord * np.array([1, 1, 0]) / np.sqrt(2))
    assert np.abs(curve.point_at(curve.parameters) - points).max() < 1e-12


def test_one_end_tangent_leaves_the_other_end_natural():
    curve = InterpolatedCurve(random_points(4, 5), end_tangent=[1, 0, 0])
    assert np.allclose(curve.derivatives(0.0, 2)[2], 0, atol=1e-9)


def test_points_on_a_line_give_that_line():
    points = np.array([[0.0, 0, 0], [1, 1, 1], [3, 3, 3], [3.5, 3.5, 3.5], [7, 7, 7]])
    curve = InterpolatedCurve(points)
    p = curve.point_at(np.linspace(0, 1, 50))
    assert np.allclose(p, p[:, :1] * np.ones(3), atol=1e-13)
    assert np.allclose(curve.curvature_at(np.linspace(0, 1, 50)), 0, atol=1e-12)


def test_two_points_give_a_straight_line_and_three_a_parabola():
    line = InterpolatedCurve([[0, 0], [2, 2]])
    assert line.degree == 1
    assert np.allclose(line.point_at(0.5), [1, 1, 0])
    parabola = InterpolatedCurve([[0, 0], [1, 1], [2, 0]])
    assert parabola.degree == 2
    assert np.allclose(parabola.point_at(parabola.parameters)[:, :2], [[0, 0], [1, 1], [2, 0]])


def test_degree_one_interpolation_is_the_polyline_through_the_points():
    points = random_points(5, 6)
    curve = InterpolatedCurve(points, degree=1)
    mid = 0.5 * (curve.parameters[:-1] + curve.parameters[1:])
    assert np.allclose(curve.point_at(mid), 0.5 * (points[:-1] + points[1:]), atol=1e-13)


def test_consecutive_duplicate_points_are_a_plain_error():
    with pytest.raises(ValueError, match="consecutive points coincide"):
        InterpolatedCurve([[0, 0], [1, 1], [1, 1], [2, 0]])


def test_closed_curve_takes_no_end_tangents():
    with pytest.raises(ValueError, match="no ends"):
        InterpolatedCurve(random_points(1, 5), closed=True, start_tangent=[1, 0, 0])


def test_too_few_points_are_a_plain_error():
    with pytest.raises(ValueError, match="at least 2 points"):
        InterpolatedCurve([[0, 0, 0]])
    with pytest.raises(ValueError, match="needs 3 points"):
        InterpolatedCurve([[0, 0, 0], [1, 0, 0]], closed=True)


def test_bezier_spans_made_together_are_the_curves_made_alone():
    rng = np.random.default_rng(11)
    for count in (2, 3, 4):
        points = rng.normal(size=(5, count, 3)) * 10.0 ** rng.integers(-3, 7, size=(5, 1, 1))
        for together, row in zip(InterpolatedCurve.beziers(points), points, strict=True):
            alone = InterpolatedCurve(row, degree=count - 1)
            for name in ("control_points", "knots", "parameters", "points"):
                np.testing.assert_array_equal(getattr(together, name), getattr(alone, name))
            assert together.degree == alone.degree and together.closed == alone.closed
            # through its points at their chord-length parameters (to rounding)
            np.testing.assert_allclose(together.point_at(together.parameters), row, rtol=0,
                                       atol=1e-12 * np.abs(row).max())
