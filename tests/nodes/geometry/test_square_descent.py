"""The shared steps of a Newton descent on the parameter square, against closed forms."""

from __future__ import annotations

import numpy as np
import pytest

from torsal.nodes.geometry.square_descent import backtrack, pinned_step, project, step_length


def _quadratic(center):
    """f = ½|x − c|² with x = (u, v): gradient x − c, Hessian the identity."""
    center = np.asarray(center, dtype=float)

    def gradient(u, v):
        return u - center[0], v - center[1]

    return gradient


def test_an_inner_newton_step_lands_on_a_quadratics_minimum():
    u, v = np.array([0.2, 0.7]), np.array([0.4, 0.1])
    g_u, g_v = _quadratic([0.5, 0.5])(u, v)
    one, zero = np.ones(2), np.zeros(2)
    du, dv = pinned_step(u, v, g_u, g_v, one, zero, one, False, False)
    np.testing.assert_allclose(u + du, 0.5, rtol=0, atol=1e-15)
    np.testing.assert_allclose(v + dv, 0.5, rtol=0, atol=1e-15)


def test_a_coupled_hessian_is_inverted():
    # f = ½ xᵀ H x with H = [[2, 1], [1, 3]]: from any x the Newton step is −x
    u, v = np.array([0.3]), np.array([0.6])
    g_u, g_v = 2 * u + v, u + 3 * v
    du, dv = pinned_step(u, v, g_u, g_v, np.array([2.0]), np.array([1.0]), np.array([3.0]), False, False)
    np.testing.assert_allclose([du[0], dv[0]], [-0.3, -0.6], rtol=1e-15)


def test_a_parameter_on_its_bound_stays_while_the_descent_leaves_the_square():
    # minimum at (−1, 0.5), start on the edge u = 0: u stays, v takes the 1-D step along it
    u, v = np.array([0.0]), np.array([0.2])
    g_u, g_v = _quadratic([-1.0, 0.5])(u, v)
    du, dv = pinned_step(u, v, g_u, g_v, np.ones(1), np.full(1, 0.5), np.ones(1), False, False)
    assert du[0] == 0.0
    assert dv[0] == pytest.approx(0.3, abs=1e-15)  # −g_v / h_vv, not the coupled step


def test_a_closed_direction_has_no_bound():
    u, v = np.array([0.0]), np.array([0.5])
    g_u, g_v = _quadratic([-0.25, 0.5])(u, v)
    du, _ = pinned_step(u, v, g_u, g_v, np.ones(1), np.zeros(1), np.ones(1), True, False)
    assert du[0] == pytest.approx(-0.25)
    assert project(u + du, v, True, False)[0][0] == pytest.approx(0.75)


def test_a_singular_hessian_gives_no_step_not_nan():
    du, dv = pinned_step(np.array([0.5]), np.array([0.5]), np.array([1.0]), np.array([1.0]),
                         np.zeros(1), np.zeros(1), np.zeros(1), False, False)
    assert (du[0], dv[0]) == (0.0, 0.0)


def test_project_clips_an_open_direction_and_wraps_a_closed_one():
    u, v = project(np.array([-0.2, 1.3]), np.array([-0.2, 1.3]), False, True)
    np.testing.assert_allclose(u, [0.0, 1.0])
    np.testing.assert_allclose(v, [0.8, 0.3])


def test_a_step_across_the_seam_is_short():
    u, v = np.array([0.98]), np.array([0.5])
    assert step_length(u, v, np.array([0.01]), v, True, False)[0] == pytest.approx(0.03)
    assert step_length(u, v, np.array([0.01]), v, False, False)[0] == pytest.approx(0.97)


def test_backtracking_halves_a_step_that_overshoots_until_the_value_falls():
    # f(u) = (u − 0.5)², start 0.25 (f = 1/16), step +0.75 overshoots to 1 (f = 1/4); half of
    # it lands on 0.625 (f = 1/64): one halving (every number here is exact in binary)
    def value(pending, u, v):
        return (u - 0.5) ** 2

    u, v = np.array([0.25]), np.array([0.5])
    new_u, _ = backtrack(value, value(None, u, v), u, v, np.array([0.75]), np.zeros(1), False, False,
                         halvings=10)
    assert new_u[0] == 0.625


def test_a_start_no_halving_helps_stays_where_it_was():
    def uphill(pending, u, v):
        return u

    u, v = np.array([0.3, 0.3]), np.array([0.5, 0.5])
    new_u, new_v = backtrack(uphill, u.copy(), u, v, np.array([0.2, -0.2]), np.zeros(2), False, False,
                             halvings=5)
    assert new_u[0] == 0.3  # after five halvings the step still climbs
    assert new_u[1] == pytest.approx(0.1, abs=1e-15)  # the downhill start moves
    np.testing.assert_array_equal(new_v, v)
