"""spline_values gives what scipy's BSpline call gives, bit for bit."""

import numpy as np
import pytest
from scipy.interpolate import BSpline

from torsal.nodes.geometry.spline_eval import spline_values


@pytest.mark.parametrize("degree", [1, 2, 3, 5])
def test_spline_values_equal_scipys_call_for_every_derivative_order(degree):
    rng = np.random.default_rng(degree)
    knots = np.r_[[0.0] * degree, np.sort(rng.random(6)), [1.0] * degree]
    spline = BSpline.construct_fast(knots, rng.random((len(knots) - degree - 1, 4)), degree, extrapolate=True)
    u = np.r_[rng.random(40), -0.1, 1.2, 0.0, 1.0]
    for nu in range(degree + 2):
        np.testing.assert_array_equal(spline_values(spline, u, nu), spline(u, nu=nu))


def test_spline_values_of_a_periodic_spline_wrap_as_scipys_call_does():
    knots = np.arange(-3.0, 9.0)
    spline = BSpline.construct_fast(knots, np.ones((8, 3)), 3, extrapolate="periodic")
    u = np.array([-0.5, 2.5, 7.5])
    np.testing.assert_array_equal(spline_values(spline, u, 1), spline(u, nu=1))
