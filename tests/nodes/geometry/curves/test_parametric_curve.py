"""Parametric curves: reparameterisation, analytic and finite-difference derivatives.

The helix ``(r cos u, r sin u, c u)`` has curvature ``r / (r² + c²)``, torsion
``c / (r² + c²)`` and speed ``√(r² + c²)`` in u.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsal.nodes.geometry.curves import InterpolatedCurve, ParametricCurve

R, C = 2.0, 0.5
TURNS = 3
DOMAIN = (-1.0, -1.0 + 2 * math.pi * TURNS)
T = np.linspace(0.0, 1.0, 401)


def helix(u):
    return np.column_stack([R * np.cos(u), R * np.sin(u), C * u])


def helix_d1(u):
    return np.column_stack([-R * np.sin(u), R * np.cos(u), np.full_like(u, C)])


def helix_d2(u):
    return np.column_stack([-R * np.cos(u), -R * np.sin(u), np.zeros_like(u)])


def helix_d3(u):
    return np.column_stack([R * np.sin(u), -R * np.cos(u), np.zeros_like(u)])


ANALYTIC = ParametricCurve(helix, DOMAIN, derivatives=(helix_d1, helix_d2, helix_d3))
NUMERIC = ParametricCurve(helix, DOMAIN)
KAPPA = R / (R * R + C * C)
TAU = C / (R * R + C * C)
LENGTH = (DOMAIN[1] - DOMAIN[0]) * math.hypot(R, C)


def test_point_at_t_is_the_function_at_the_mapped_parameter():
    u = DOMAIN[0] + T * (DOMAIN[1] - DOMAIN[0])
    assert np.array_equal(ANALYTIC.point_at(T), helix(u))
    assert ANALYTIC.domain == DOMAIN


def test_derivatives_scale_by_the_domain_length_per_order():
    u = DOMAIN[0] + T * (DOMAIN[1] - DOMAIN[0])
    width = DOMAIN[1] - DOMAIN[0]
    _, d1, d2 = ANALYTIC.derivatives(T, 2)
    assert np.allclose(d1, helix_d1(u) * width, atol=1e-13)
    assert np.allclose(d2, helix_d2(u) * width**2, atol=1e-11)


def test_helix_curvature_and_torsion_match_closed_form_within_1e_12():
    assert np.abs(ANALYTIC.curvature_at(T) / KAPPA - 1).max() < 1e-12
    assert np.abs(ANALYTIC.torsion_at(T) / TAU - 1).max() < 1e-12


def test_finite_difference_derivatives_meet_their_documented_accuracy():
    exact = ANALYTIC.derivatives(T, 3)
    numeric = NUMERIC.derivatives(T, 3)
    inside = (T > 0.05) & (T < 0.95)
    for k, at_ends, within in ((1, 1e-11, 1e-12), (2, 1e-9, 1e-11), (3, 1e-8, 1e-9)):
        error = np.abs(numeric[k] - exact[k]).max(axis=1) / np.abs(exact[k]).max()
        assert error.max() < at_ends, (k, error.max())
        assert error[inside].max() < within, (k, error[inside].max())


def test_helix_curvature_and_torsion_by_finite_differences_within_1e_9_and_1e_7():
    assert np.abs(NUMERIC.curvature_at(T) / KAPPA - 1).max() < 1e-9
    assert np.abs(NUMERIC.torsion_at(T) / TAU - 1).max() < 1e-7


def test_helix_arc_length_within_1e_9_relative():
    assert abs(ANALYTIC.length / LENGTH - 1) < 1e-9
    assert abs(NUMERIC.length / LENGTH - 1) < 1e-9


def test_helix_arc_length_of_a_fine_nurbs_interpolation_within_1e_7_relative():
    u = np.linspace(*DOMAIN, 401)
    assert abs(InterpolatedCurve(helix(u)).length / LENGTH - 1) < 1e-7


def test_helix_arc_length_grows_linearly_with_t():
    assert np.allclose(ANALYTIC.length_at(T), T * LENGTH, rtol=1e-12, atol=1e-12)


def test_function_may_return_coordinate_tuples_with_scalars():
    circle = ParametricCurve(lambda u: (np.cos(u), np.sin(u), 0.0), (0.0, 2 * math.pi))
    assert circle.closed
    assert np.allclose(circle.point_at(0.25), [0, 1, 0], atol=1e-15)
    assert abs(circle.length / (2 * math.pi) - 1) < 1e-12


def test_two_dimensional_function_gets_z_zero():
    parabola = ParametricCurve(lambda u: np.column_stack([u, u * u]), (-1.0, 1.0))
    assert parabola.point_at(1.0).tolist() == [1.0, 1.0, 0.0]
    assert not parabola.closed
    # curvature of y = x² at the vertex is 2
    assert parabola.curvature_at(0.5) == pytest.approx(2.0, rel=1e-9)


def test_empty_domain_is_rejected():
    with pytest.raises(ValueError, match="a < b"):
        ParametricCurve(helix, (1.0, 1.0))


def test_non_finite_points_are_rejected():
    with pytest.raises(ValueError, match="non-finite"):
        ParametricCurve(lambda u: (1.0 / np.where(u > 0, u, np.nan), u, u), (0.0, 1.0))


def test_wrong_shape_is_rejected_plainly():
    with pytest.raises(ValueError, match="Expected 9 points"):
        ParametricCurve(lambda u: np.ones((4, 3)), (0.0, 1.0))


def test_function_is_never_called_outside_its_domain():
    def guarded(u):
        assert np.all((u >= 0) & (u <= 1)), "called outside [0, 1]"
        return np.column_stack([u, np.sqrt(u), u**3])

    curve = ParametricCurve(guarded)
    curve.derivatives(np.array([0.0, 1e-9, 0.5, 1.0]), 3)
