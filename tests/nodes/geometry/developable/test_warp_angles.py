"""Warp angles: between the end normal vectors (0…π), signed about the ruling, NaN where undefined."""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsal.nodes.geometry.curves import InterpolatedCurve
from torsal.nodes.geometry.developable import cylinder_rulings, in_plane_tangent, warp_angles, warp_of_rulings
from torsal.nodes.geometry.developable.warp import consistently_oriented


def test_warp_is_the_angle_between_the_end_normals():
    # ruling along y; tangents x and (x + z): normals z and (z − x)/√2 → 45°
    w = warp_angles([[0, 0, 0]], [[0, 1, 0]], [[1, 0, 0]], [[1, 0, 1]])
    assert w[0] == pytest.approx(math.pi / 4)


def test_warp_is_zero_when_the_ruling_and_both_tangents_are_coplanar():
    rng = np.random.default_rng(3)
    r = rng.normal(size=(100, 3))
    t1 = rng.normal(size=(100, 3))
    t2 = 0.7 * t1 + 1.3 * r  # in the plane of r and t1
    assert warp_angles(np.zeros((100, 3)), r, t1, t2).max() < 1e-14


def test_warp_is_between_vectors_so_opposite_tangents_give_a_half_turn():
    w = warp_angles([[0, 0, 0]], [[0, 1, 0]], [[1, 0, 0]], [[-1, 0, 0]])
    assert w[0] == pytest.approx(math.pi, abs=1e-15)


@pytest.mark.parametrize("half", [0.5, 1.0, 2.0, 5.0])
def test_warp_along_the_hyperbolic_paraboloid_is_twice_atan_of_its_half_length(half):
    """z = xy along x = 0 from y = −L to L: edge tangents (1, 0, ∓L) at y = ∓L, so the
    normals (−L, 0, −1)·2L and (L, 0, −1)·2L make the angle 2·atan(L), past π/2 for L > 1."""
    w = warp_angles([[0, -half, 0]], [[0, half, 0]], [[1, 0, -half]], [[1, 0, half]])
    assert w[0] == pytest.approx(2 * math.atan(half), abs=1e-15)


def test_signed_warp_tells_a_flipped_sheet_from_a_good_one():
    signed = warp_angles(
        [[0, 0, 0]] * 2, [[0, 1, 0]] * 2, [[1, 0, 0]] * 2, [[1, 0, 0], [-1, 0, 0]], signed=True
    )
    assert signed[0] == 0.0
    assert abs(signed[1]) == pytest.approx(math.pi)


def test_signed_warp_turns_about_the_ruling():
    # N1 = y × x = −z and N2 = y × (x + z) ∝ (1, 0, −1): turning −z towards +x about +y
    # is a negative (clockwise) turn
    s = warp_angles([[0, 0, 0]], [[0, 1, 0]], [[1, 0, 0]], [[1, 0, 1]], signed=True)
    assert s[0] == pytest.approx(-math.pi / 4)
    s = warp_angles([[0, 0, 0]], [[0, 1, 0]], [[1, 0, 0]], [[1, 0, -1]], signed=True)
    assert s[0] == pytest.approx(math.pi / 4)


def test_tiny_warps_keep_their_relative_accuracy():
    angle = 1e-12
    w = warp_angles([[0, 0, 0]], [[0, 1, 0]], [[1, 0, 0]], [[math.cos(angle), 0, math.sin(angle)]])
    assert w[0] == pytest.approx(angle, rel=1e-6)


def test_a_zero_length_ruling_has_no_warp_but_nan():
    assert np.isnan(warp_angles([[0, 0, 0]], [[0, 0, 0]], [[1, 0, 0]], [[0, 1, 1]])[0])
    assert np.isnan(warp_angles([[0, 0, 0]], [[0, 0, 0]], [[1, 0, 0]], [[0, 1, 1]], signed=True)[0])


def test_a_ruling_along_an_edge_tangent_has_no_warp_but_nan():
    assert np.isnan(warp_angles([[0, 0, 0]], [[0, 1, 0]], [[0, 2, 0]], [[1, 0, 1]])[0])
    assert np.isnan(warp_angles([[0, 0, 0]], [[0, 1, 0]], [[1, 0, 1]], [[0, -3, 0]])[0])


def test_nan_input_gives_nan_warp():
    w = warp_angles([[0, 0, 0], [0, 0, 0]], [[0, 1, 0], [0, 1, 0]], [[1, 0, 0], [np.nan, 0, 0]],
                    [[1, 0, 0], [1, 0, 0]])
    assert w[0] == 0.0 and np.isnan(w[1])


def test_an_edge_standing_still_takes_the_other_ends_plane():
    """A zero tangent is a fan's apex: the triangles there contain the ruling and the other
    edge's tangent, so the warp is 0 — and NaN when the other end has no plane either."""
    w = warp_angles([[0, 0, 0]] * 3, [[0, 1, 0]] * 3, [[0, 0, 0]] * 3,
                    [[1, 0, 1], [0, 1, 0], [0, 0, 0]])
    assert w[0] == 0.0
    assert np.isnan(w[1]) and np.isnan(w[2])


def test_an_end_flagged_on_the_edge_of_regression_takes_the_other_ends_plane():
    # a tangent developable's ruling starts along the curve's tangent
    w = warp_angles([[0, 0, 0]], [[0, 1, 0]], [[0, 1, 0]], [[1, 1, 0]], apex_a=[True])
    assert w[0] == 0.0


def test_warp_of_rulings_of_a_cylinder_is_zero():
    curve = InterpolatedCurve([[0, 0, 0], [1, 1, 0.2], [2, 0, 0.5], [3, 1, 0.1]])
    r = cylinder_rulings(curve, [0.2, 0.1, 1.0], 2.0, 40)
    assert warp_of_rulings(r.starts, r.ends).max() < 1e-12


def test_warp_of_rulings_of_a_hyperbolic_paraboloid_matches_its_exact_warp():
    """z = xy between the lines x = 0 and x = 1: the ruling at y joins (0, y, 0) to (1, y, y);
    the edges are straight (tangents (0,1,0) and (0,1,1)), so edge differences are exact."""
    y = np.linspace(0, 1, 21)
    starts = np.column_stack([np.zeros_like(y), y, np.zeros_like(y)])
    ends = np.column_stack([np.ones_like(y), y, y])
    exact = warp_angles(starts, ends, np.tile([0, 1, 0], (21, 1)), np.tile([0, 1, 1], (21, 1)))
    np.testing.assert_allclose(warp_of_rulings(starts, ends), exact, atol=1e-14)
    assert exact.min() > 0.6


def test_in_plane_tangent_at_a_corner_lies_in_the_plane_of_ruling_and_other_tangent():
    ruling = np.array([[0.0, 1.0, 0.0]])
    other = np.array([[1.0, 0.0, 0.0]])
    left, right = np.array([[1.0, 0.0, 1.0]]), np.array([[1.0, 0.0, -1.0]])  # straddle the plane z = 0
    t = in_plane_tangent(ruling, other, left, right)
    np.testing.assert_allclose(t, [[1.0, 0.0, 0.0]], atol=1e-15)
    assert warp_angles(np.zeros((1, 3)), ruling, other, t)[0] < 1e-15


def test_warp_of_rulings_measures_a_fan_in_the_plane_of_its_triangles():
    """Rulings from one point to a space curve (a cone's rulings): the start polyline
    stands still, so every ruling takes the plane through it and the far edge's tangent."""
    u = np.linspace(0.0, 2.0, 15)
    ends = np.column_stack([np.cos(u), np.sin(u), 0.3 * u * u])
    starts = np.tile([0.2, -0.1, 2.0], (15, 1))
    w = warp_of_rulings(starts, ends)
    assert np.all(w == 0.0)


def test_warp_of_rulings_inside_a_fan_through_a_point_of_one_edge_is_zero():
    starts = np.array([[0, 0, 0], [1, 0, 0], [1, 0, 0], [1, 0, 0], [2, 0, 0.5]], dtype=float)
    ends = np.array([[0, 1, 0], [0.5, 1, 0.2], [1, 1, 0.3], [1.5, 1, 0.2], [2, 1, 0]], dtype=float)
    w = warp_of_rulings(starts, ends)
    assert w[2] == 0.0
    assert np.all(np.isfinite(w))


def test_warp_of_rulings_where_an_edge_doubles_back_is_nan():
    starts = np.array([[0, 0, 0], [1, 0, 0], [0, 0, 0]], dtype=float)
    ends = np.array([[0, 1, 0], [1, 1, 0.2], [2, 1, 0]], dtype=float)
    w = warp_of_rulings(starts, ends)
    assert np.isnan(w[1]) and np.isfinite(w[[0, 2]]).all()


def test_curve_warp_at_a_corner_uses_the_side_whose_tangent_does_not_run_along_the_ruling():
    """A ruling from the corner of A = (0,0,0)–(1,0,0)–(1,1,0) along A's first side to the
    line B at x = 2 (tangent y): the side along x gives no normal, the side along y gives
    the plane z = 0, which holds B's tangent too, so the warp is 0."""
    from torsal.nodes.geometry.curves import Line, Polyline
    from torsal.nodes.geometry.developable.warp import curve_warp

    a = Polyline([[0, 0, 0], [1, 0, 0], [1, 1, 0]])
    b = Line([2, 0, 0], [2, 2, 0])
    w = curve_warp(a, b, [0.5], [0.0], [[1.0, 0, 0]], [[2.0, 0, 0]])
    assert w[0] == pytest.approx(0.0, abs=1e-15)


def test_curve_warp_is_that_of_the_curves_tangents_away_from_corners():
    from torsal.nodes.geometry.curves import Line
    from torsal.nodes.geometry.developable.warp import curve_warp

    half = 2.0  # the hyperbolic paraboloid's ruling along x = 0, from y = −L to L
    a, b = Line([-1, -half, half], [1, -half, -half]), Line([-1, half, -half], [1, half, half])
    w = curve_warp(a, b, [0.5], [0.5], [[0, -half, 0]], [[0, half, 0]])
    assert w[0] == pytest.approx(2 * math.atan(half), abs=1e-15)


@pytest.mark.parametrize("seam", [0.0, 1.0])
def test_curve_warp_sees_the_corner_at_the_seam_of_a_closed_polyline(seam):
    """The unit square's corner (0, 0, 0) is its seam: tangents (0, −1, 0) before it and
    (1, 0, 0) after. The plane of the ruling to (−1, −1, 1) and B's tangent (1, −1, 0) has
    normal (1, 1, 2), which separates them: a cone through the corner, warp 0."""
    from torsal.nodes.geometry.curves import Line, Polyline
    from torsal.nodes.geometry.developable.warp import curve_warp

    square = Polyline([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], closed=True)
    b = Line([-1.5, -0.5, 1], [-0.5, -1.5, 1])
    w = curve_warp(square, b, [seam], [0.5], [[0.0, 0, 0]], [[-1.0, -1, 1]])
    assert w[0] == pytest.approx(0.0, abs=1e-15)


def test_consistent_orientation_holds_exactly_for_normals_less_than_a_right_angle_apart():
    # R = (0, 1, 0), T1 = (1, 0, 0), T2 = (cos θ, 0, sin θ): the normals are θ apart
    theta = np.array([0.0, 0.3, 1.5, 1.6, 3.0, np.pi])
    n = len(theta)
    starts, ends = np.zeros((n, 3)), np.tile([0.0, 1.0, 0.0], (n, 1))
    ta = np.tile([1.0, 0.0, 0.0], (n, 1))
    tb = np.column_stack([np.cos(theta), np.zeros(n), np.sin(theta)])
    assert consistently_oriented(starts, ends, ta, tb).tolist() == [True, True, True, False, False, False]


def test_consistent_orientation_needs_defined_normals_and_lets_a_standing_end_take_the_other():
    starts = np.zeros((4, 3))
    ends = np.array([[0.0, 1, 0], [0, 1, 0], [0, 0, 0], [0, 1, 0]])
    ta = np.array([[1.0, 0, 0], [0, 0, 0], [1, 0, 0], [0, 0, 0]])
    tb = np.array([[0.0, 2, 0], [1, 0, 0], [1, 0, 0], [0, 0, 0]])
    # along the ruling (no normal), a fan's apex (takes B's), zero length, both standing
    assert consistently_oriented(starts, ends, ta, tb).tolist() == [False, True, False, False]
