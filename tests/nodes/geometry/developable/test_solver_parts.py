"""The parts of the RulingDevelopable solver: stations, bracketed roots, monotone choice."""

from __future__ import annotations

from itertools import pairwise

import numpy as np
import pytest
from scipy.integrate import quad

from tests.support.rational_rails import Rational, rails
from torsal.nodes.geometry.curves import Arc, InterpolatedCurve, ParametricCurve, Polyline
from torsal.nodes.geometry.developable import LengthMap, station_parameters
from torsal.nodes.geometry.developable.brackets import refine_roots
from torsal.nodes.geometry.developable.isolation import Pieces, certified_empty, certified_single, isolate
from torsal.nodes.geometry.developable.selection import monotone_path

CURVE = InterpolatedCurve([[0, 0, 0], [1, 2, 0.5], [3, 1, -0.5], [4, 3, 0.2], [6, 2, 0]])


# -- stations ------------------------------------------------------------------------------------


def test_length_map_total_matches_the_curves_own_length():
    assert LengthMap(CURVE).total == pytest.approx(CURVE.length, rel=1e-12)
    arc = Arc(radius=2.0, start_angle=0.0, end_angle=3.0)
    assert LengthMap(arc).total == pytest.approx(6.0, rel=1e-13)


def test_length_map_inverts_itself():
    lengths = LengthMap(CURVE)
    t = np.linspace(0, 1, 57)
    np.testing.assert_allclose(lengths.parameter_at(lengths.length_at(t)), t, atol=1e-10)


def _squared_rail(seed: int) -> tuple[Rational, ParametricCurve]:
    """A seeded rational rail (evaluated by scipy, :mod:`tests.support.rational_rails`) and
    the same rail run as t²: a curve that no longer reports where its knots are."""
    rail = rails(seed, near_planar=seed % 2 == 1)[0]

    def parts(x):
        x = np.asarray(x, dtype=float)
        _, d1, d2 = rail.derivatives(x * x, 2)
        return rail.derivatives(x * x, 0)[0], d1 * (2 * x)[:, None], d2 * (4 * x * x)[:, None] + 2 * d1

    curve = ParametricCurve(lambda x: parts(x)[0], (0.0, 1.0),
                            derivatives=(lambda x: parts(x)[1], lambda x: parts(x)[2]))
    return rail, curve


@pytest.mark.parametrize("seed", [0, 1, 3])
def test_length_map_of_a_rail_run_as_t_squared_matches_quadrature_over_its_knot_spans(seed):
    rail, curve = _squared_rail(seed)
    lengths = LengthMap(curve)
    x = np.linspace(0.0, 1.0, 23)
    knots = np.unique(rail.knots)

    def speed(u):
        return float(np.linalg.norm(rail.derivatives([u], 1)[1][0]))

    def length_to(u):  # scipy's adaptive quadrature, span by span of the rail's own knots
        return sum(quad(speed, lo, min(hi, u), epsabs=1e-14, epsrel=1e-13, limit=200)[0]
                   for lo, hi in pairwise(knots) if lo < u)

    expected = np.array([length_to(u) for u in x * x])
    # (measured 2e-11 of the length at most; Gauss pieces across the hidden knots alone: 5e-8)
    np.testing.assert_allclose(lengths.length_at(x), expected, rtol=0, atol=1e-10 * expected[-1])
    # t → ℓ → t and ℓ → t → ℓ come back to rounding (measured 7e-16 of the length)
    along = np.linspace(0.0, lengths.total, 101)
    np.testing.assert_allclose(lengths.length_at(lengths.parameter_at(along)), along, rtol=0,
                               atol=4e-15 * lengths.total)


def test_stations_are_evenly_spaced_in_arc_length_and_include_both_ends():
    t = station_parameters(CURVE, 31)
    assert t[0] == 0.0 and t[-1] == 1.0
    np.testing.assert_allclose(np.diff(CURVE.length_at(t)), CURVE.length / 30, atol=1e-6 * CURVE.length)


def test_stations_on_a_polyline_fall_on_equal_lengths():
    polyline = Polyline([[0, 0, 0], [1, 0, 0], [1, 3, 0]])
    np.testing.assert_allclose(station_parameters(polyline, 5), [0, 0.25, 0.5, 0.75, 1.0], atol=1e-15)


def test_station_spacing_must_be_length_or_parameter():
    with pytest.raises(ValueError, match="spacing"):
        station_parameters(CURVE, 5, "chord")  # type: ignore[arg-type]


# -- bracketed roots -----------------------------------------------------------------------------


def test_bracketed_roots_converge_to_machine_precision_for_either_slope():
    dottie = 0.7390851332151607  # the root of cos x = x
    increasing = refine_roots(
        lambda x, i: (x - np.cos(x), 1 + np.sin(x), np.ones_like(x)), np.zeros(1), np.ones(1), -np.ones(1)
    )
    decreasing = refine_roots(
        lambda x, i: (np.cos(x) - x, -1 - np.sin(x), np.ones_like(x)), np.zeros(1), np.ones(1), np.ones(1)
    )
    assert increasing[0] == pytest.approx(dottie, abs=2e-16)
    assert decreasing[0] == pytest.approx(dottie, abs=2e-16)


def test_bracketed_roots_of_a_jump_converge_onto_the_jump():
    def step(x, index):
        return np.where(x < 0.3, -1.0, 1.0), np.zeros_like(x), np.ones_like(x)

    roots = refine_roots(step, np.zeros(1), np.ones(1), -np.ones(1))
    assert roots[0] == pytest.approx(0.3, abs=1e-14)


def test_many_brackets_are_refined_together():
    targets = np.linspace(0.1, 0.9, 50)
    roots = refine_roots(
        lambda x, i: (x**3 - targets[i] ** 3, 3 * x**2, np.ones_like(x)),
        np.zeros(50),
        np.ones(50),
        -(targets**3),
    )
    np.testing.assert_allclose(roots, targets, atol=1e-15)


# -- certified isolation -------------------------------------------------------------------------


def parabola_b(c: float):
    """B(t) = (0, t − ½, (t − ½)² + c) against A = 0 with tangent x: there
    f(t) = det[B − A, x, B'] = c − (t − ½)², roots ½ ± √c; B and two derivatives (B''' = 0)."""

    def evaluate(x):
        x = np.asarray(x, float)
        zero, one = np.zeros_like(x), np.ones_like(x)
        return [
            np.column_stack([zero, x - 0.5, (x - 0.5) ** 2 + c]),
            np.column_stack([zero, one, 2 * (x - 0.5)]),
            np.column_stack([zero, zero, 2 * one]),
        ]

    return evaluate


def one_piece(evaluate, x0: float, x1: float) -> Pieces:
    """The interval [x0, x1] for the station A = 0, Â' = x, with its B-data."""
    ends = evaluate(np.array([x0, x1]))
    plane = np.cross(ends[0], [1.0, 0.0, 0.0])  # det[R, Â', X] = X · (R × Â')
    f = np.einsum("ij,ij->i", plane, ends[1])
    d = np.einsum("ij,ij->i", plane, ends[2])
    speed, second = np.linalg.norm(ends[1], axis=1), np.linalg.norm(ends[2], axis=1)
    return Pieces(
        np.array([0]), np.array([x0]), np.array([x1]), f[:1], f[1:], d[:1], d[1:],
        speed[:1], speed[1:], second[:1], second[1:], np.zeros(1),  # B''' = 0: β3 = 0
        *np.linalg.norm(ends[0], axis=1)[:, None],  # |B − A| at both ends
    )


def test_two_roots_hidden_between_two_samples_are_isolated_in_separate_brackets():
    c = 1e-6  # roots 0.499 and 0.501, f < 0 at both ends of [0.25, 0.75]
    evaluate = parabola_b(c)
    a0, a1 = np.zeros((1, 3)), np.array([[1.0, 0.0, 0.0]])
    found = isolate(one_piece(evaluate, 0.25, 0.75), np.array([4.0 * 0.25]), evaluate, a0, a1)
    order = np.argsort(found.low)
    low, high = found.low[order], found.high[order]
    assert len(low) == 2
    roots = [0.5 - np.sqrt(c), 0.5 + np.sqrt(c)]
    assert low[0] <= roots[0] <= high[0] < low[1] <= roots[1] <= high[1]


def test_a_double_root_is_reported_as_a_touching_point():
    evaluate = parabola_b(0.0)  # f = −(t − ½)²: touches zero at ½
    a0, a1 = np.zeros((1, 3)), np.array([[1.0, 0.0, 0.0]])
    found = isolate(one_piece(evaluate, 0.2, 0.7), np.array([4.0 * 0.25]), evaluate, a0, a1)
    assert len(found.rows) == 0
    assert found.double_t == pytest.approx([0.5], abs=1e-12)


def test_an_interval_far_from_zero_is_certified_empty_and_a_dip_to_zero_is_not():
    # f = 1 + u − u² on [0, 1] with |f''| = 2: stays >= 1
    def empty(f0: float, f1: float, e0: float, e1: float, m: float) -> bool:
        return bool(certified_empty(*(np.array([x]) for x in (f0, f1, e0, e1, m)))[0])

    assert empty(1.0, 1.0, 1.0, -1.0, 2.0)
    # f = (u − ½)² − 0.01 has f(0) = f(1) = 0.24 > 0 but dips below zero
    assert not empty(0.24, 0.24, -1.0, 1.0, 2.0)


def test_an_interval_within_the_rounding_of_zero_is_not_certified_empty():
    # f = 1e-17 + 1e-18·u(1 − u) > 0 throughout, but within a rounding of 1e-15 of zero: a
    # touching point of f is not ruled out (a cylinder's generator at an inflection)
    f0 = f1 = np.array([1e-17])
    e0, e1, m = np.array([1e-18]), np.array([-1e-18]), np.array([2e-18])
    assert certified_empty(f0, f1, e0, e1, m).all()
    assert not certified_empty(f0, f1, e0, e1, m, np.array([1e-15])).any()
    assert certified_empty(f0 + 1e-14, f1 + 1e-14, e0, e1, m, np.array([1e-15])).all()


def test_a_sign_change_is_certified_single_only_when_the_slope_cannot_turn():
    f0, f1 = np.array([-1.0]), np.array([1.0])
    assert certified_single(f0, f1, np.array([2.0]), np.array([2.0]), np.array([1.0])).all()
    # slopes of opposite sign at the ends: three roots cannot be ruled out
    assert not certified_single(f0, f1, np.array([-0.5]), np.array([4.0]), np.array([1.0])).any()


# -- monotone choice -----------------------------------------------------------------------------


def test_monotone_choice_follows_one_branch_rather_than_jumping():
    s = np.linspace(0, 1, 6)
    branch = 0.2 + 0.5 * s  # slope 0.5
    other = 0.9 - 0.5 * s  # a decreasing branch crossing it
    t = np.column_stack([np.minimum(branch, other), np.maximum(branch, other)])
    slope = np.where(branch[:, None] == t, 0.5, -0.5)
    pick = monotone_path(t, slope, np.diff(s))
    np.testing.assert_allclose(t[np.arange(6), pick], branch)


def test_monotone_choice_prefers_the_branch_spanning_b_from_end_to_end():
    s = np.linspace(0, 1, 5)
    t = np.column_stack([0.5 * s, s])  # two smooth increasing branches
    slope = np.tile([0.5, 1.0], (5, 1))
    pick = monotone_path(t, slope, np.diff(s))
    np.testing.assert_array_equal(pick, 1)


def test_monotone_choice_never_steps_back_when_it_can_avoid_it():
    s = np.linspace(0, 1, 7)
    t = np.array(
        [[0.0, 0.9], [0.1, 0.95], [0.2, np.nan], [0.3, np.nan], [0.4, 0.35], [0.5, np.nan], [0.6, np.nan]]
    )
    slope = np.where(np.isnan(t), np.nan, 0.6)
    pick = monotone_path(t, slope, np.diff(s))
    chosen = t[np.arange(7), pick]
    assert np.all(np.diff(chosen) >= 0)
    np.testing.assert_allclose(chosen, [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6])


def test_monotone_choice_handles_a_single_station_and_single_candidates():
    assert monotone_path(np.array([[0.2, 0.7]]), np.zeros((1, 2)), np.empty(0)).tolist() == [1]
    t = np.linspace(0, 1, 9)[:, None]
    np.testing.assert_array_equal(monotone_path(t, np.ones_like(t), np.diff(t[:, 0])), 0)
