"""What an exported strip's face holds exactly: its rulings and the rails' tangents at them
(two control points per double knot), and a stalled rail's second derivative at an end.
Expected values: scipy's own B-spline evaluation and closed-form curves."""

from __future__ import annotations

import numpy as np
from scipy.interpolate import BSpline

from torsal.nodes.geometry.curves.parametric import ParametricCurve
from torsal.nodes.io.formats.threedm_held import end_bends, pinned, slopes_at
from torsal.nodes.io.formats.threedm_rails import Rails


def test_the_two_control_points_at_each_double_knot_make_its_point_and_slope():
    rng = np.random.default_rng(3)
    at = np.array([0.3, 0.55])
    knots = np.concatenate([[0.0] * 4, [0.1, 0.3, 0.3, 0.42, 0.55, 0.55, 0.8], [1.0] * 4])
    points, slopes = rng.normal(size=(2, 6)), rng.normal(size=(2, 6))
    columns, values = pinned(knots, at, points, slopes)
    controls = rng.normal(size=(len(knots) - 4, 6))  # the others whatever they are
    controls[columns] = values
    spline = BSpline(knots, controls, 3)
    np.testing.assert_allclose(spline(at), points, atol=1e-12)
    np.testing.assert_allclose(spline.derivative()(at), slopes, atol=1e-11)
    # from either side: the spline is C1 at a double knot
    np.testing.assert_allclose(spline.derivative()(at - 1e-13), slopes, atol=1e-9)


def test_a_single_knot_is_not_held_and_a_lone_double_knot_leaves_the_end_tangents_alone():
    knots = np.concatenate([[0.0] * 4, [0.3, 0.6], [1.0] * 4])
    assert pinned(knots, np.array([0.3]), np.zeros((1, 6)), np.zeros((1, 6))) is None
    lone = np.concatenate([[0.0] * 4, [0.3, 0.3], [1.0] * 4])  # six control points: 1 and 4 the ends'
    assert pinned(lone, np.array([0.3]), np.zeros((1, 6)), np.zeros((1, 6)))[0].tolist() == [2, 3]


def _curve(point, first):
    return ParametricCurve(point, (0.0, 1.0), [first])


def test_a_rail_that_stands_still_at_an_end_has_its_second_derivative_held_there():
    d = np.array([1.0, 2.0, 0.5])
    # A(u) = (0, 0, 0) + u² d stands still at u = 0; B(u) = (0, 0, 1) + u (1, 0, 0) moves
    a = _curve(lambda u: u[:, None] ** 2 * d, lambda u: 2.0 * u[:, None] * d)
    b = _curve(lambda u: np.column_stack([u, 0.0 * u, 1.0 + 0.0 * u]),
               lambda u: np.column_stack([1.0 + 0.0 * u, 0.0 * u, 0.0 * u]))
    span = np.array([0.0, 0.5, 1.0])
    rails = Rails(a, b)
    slopes = slopes_at(rails, span, lambda u: u)
    np.testing.assert_allclose(slopes[:, :3], 2.0 * span[:, None] * d, atol=1e-10)
    np.testing.assert_allclose(slopes[:, 3:], [[1.0, 0.0, 0.0]] * 3, atol=1e-12)
    bends = end_bends(rails, span, lambda u: u, slopes)
    np.testing.assert_allclose(bends[0, 0], 2.0 * d, atol=1e-9)  # A at its stalled start
    assert np.isnan(bends[1]).all() and np.isnan(bends[0, 1]).all()  # B moves; A moves at the end
