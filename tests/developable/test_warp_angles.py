"""Warp angles: between the lines of the end normals (0…π/2), and signed about the ruling."""

from __future__ import annotations

import math

import numpy as np
import pytest

from nodes.geometry.curves import InterpolatedCurve
from nodes.geometry.developable import cylinder_rulings, in_plane_tangent, warp_angles, warp_of_rulings


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


def test_warp_is_between_lines_so_opposite_tangents_give_no_warp():
    w = warp_angles([[0, 0, 0]], [[0, 1, 0]], [[1, 0, 0]], [[-1, 0, 0]])
    assert w[0] == 0.0


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


def test_zero_length_vectors_count_as_no_warp():
    assert warp_angles([[0, 0, 0]], [[0, 0, 0]], [[1, 0, 0]], [[0, 1, 1]])[0] == 0.0
    assert warp_angles([[0, 0, 0]], [[0, 1, 0]], [[0, 0, 0]], [[0, 1, 1]])[0] == 0.0


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
