"""RulingDevelopable's Kind, Valid, Torsal and Folds, checked against geometry recomputed
here: closed forms and an independent warp (tests/support/warp_check.py), never the
node's own numbers.

The main case: two curves on opposite nappes of one cone (apex at the origin, axis z).
Every line joining them with det[B − A, A', B'] = 0 is a generator through the apex, and
there the sheet's normals R × A' and R × B' point to opposite sides (the apex lies
between the curves): no ruling between them is torsal, so the Torsal share is 0.
"""

from __future__ import annotations

import numpy as np
import pytest

from tests.support.node_helpers import out, run, texts, tree
from tests.support.warp_check import shared_both_sides, warp
from torsal.nodes.developable.ruling_developable import RulingDevelopable
from torsal.nodes.geometry.curves import Line, ParametricCurve
from torsal.nodes.geometry.strip_crossings import crossings

TOLERANCE = 0.01
SPAN = 2.5  # rad of the cone's generators the curves cover


def on_cone(w_of, dw_of) -> ParametricCurve:
    """x ↦ w(u)·(cos u, sin u, 1), u = SPAN·x: a curve on the cone x² + y² = z²."""

    def point(x):
        u = SPAN * np.asarray(x, dtype=float)
        w = w_of(u)
        return np.column_stack([w * np.cos(u), w * np.sin(u), w])

    def tangent(x):
        u = SPAN * np.asarray(x, dtype=float)
        w, dw = w_of(u), dw_of(u)
        return SPAN * np.column_stack([dw * np.cos(u) - w * np.sin(u), dw * np.sin(u) + w * np.cos(u), dw])

    return ParametricCurve(point, (0.0, 1.0), derivatives=(tangent,))


def nappes():
    """A on the upper nappe (w > 0), B on the lower one (w < 0)."""
    a = on_cone(lambda u: 1 + 0.2 * np.sin(3 * u), lambda u: 0.6 * np.cos(3 * u))
    b = on_cone(lambda u: -(1 + 0.3 * np.cos(2 * u)), lambda u: 0.6 * np.sin(2 * u))
    return a, b


def solve(a, b, segments=60, **inputs):
    return run(RulingDevelopable(), CurveA=tree({(0,): [a]}), CurveB=tree({(0,): [b]}), Segments=segments,
               **inputs)


def ends_of(node):
    rulings = out(node, "Rulings")[(0,)]
    return np.array([r.start for r in rulings]), np.array([r.end for r in rulings])


def least_warp_over_b(a, b, s, samples=20001):
    """For each A(s), the least angle between R × A' and R × B' over dense samples of B."""
    t = np.linspace(0.0, 1.0, samples)
    pb, tb = b.derivatives(t, 1)
    pa, ta = a.derivatives(s, 1)
    least = np.empty(len(s))
    for k in range(len(s)):
        r = pb - pa[k]
        n1, n2 = np.cross(r, ta[k]), np.cross(r, tb)
        least[k] = np.arctan2(np.linalg.norm(np.cross(n1, n2), axis=1), np.einsum("ij,ij->i", n1, n2)).min()
    return least


@pytest.fixture(scope="module")
def cone_across_nappes():
    a, b = nappes()
    return a, b, solve(a, b)


def test_no_ruling_between_opposite_nappes_is_torsal_so_the_torsal_share_is_0(cone_across_nappes):
    a, b, node = cone_across_nappes
    # independently: no ruling from any of 61 points of A to B has its normals within 0.4 rad
    # (measured: 0.42 at A's start, over 20,001 samples of B), far above the tolerance
    assert least_warp_over_b(a, b, np.linspace(0, 1, 61)).min() > 0.4
    kinds = np.array(out(node, "Kind")[(0,)])
    assert "torsal" not in kinds
    assert out(node, "Torsal")[(0,)] == [0.0]


def test_across_nappes_only_rulings_inside_a_fan_are_valid_and_the_rest_are_creases(cone_across_nappes):
    _, _, node = cone_across_nappes
    starts, ends = ends_of(node)
    kinds = np.array(out(node, "Kind")[(0,)])
    valid = np.array(out(node, "Valid")[(0,)])
    in_fan = shared_both_sides(starts) | shared_both_sides(ends)
    np.testing.assert_array_equal(kinds, np.where(in_fan, "fan", "crease"))
    assert not valid[~in_fan].any()
    assert (kinds == "crease").sum() > 100  # 113 of 118 measured


def test_across_nappes_the_node_warns_that_the_sheet_folds_and_says_where(cone_across_nappes):
    _, _, node = cone_across_nappes
    starts, ends = ends_of(node)
    assert node.state == "warning"
    folds = [t for t in texts(node) if t.startswith("the sheet folds")]
    assert len(folds) == 1
    assert "creases sharper than 0.5 rad" in folds[0]
    assert "pairs of its triangles cross each other" in folds[0]
    # the sharp creases are the rulings outside fans where the planes through the ruling and
    # A', and through it and B', differ by over 0.5 rad (independent warp with the curves'
    # exact tangents; the parameters from the points: A is w·(cos u, sin u, 1) with w > 0, B
    # with w < 0); their middles come first in Folds
    a, b = nappes()
    s = np.mod(np.arctan2(starts[:, 1], starts[:, 0]), 2 * np.pi) / SPAN
    t = np.mod(np.arctan2(-ends[:, 1], -ends[:, 0]), 2 * np.pi) / SPAN
    bent = warp(starts, ends, a.derivatives(s, 1)[1], b.derivatives(t, 1)[1])
    in_fan = shared_both_sides(starts) | shared_both_sides(ends)
    sharp = np.flatnonzero(~in_fan & ~(bent <= 0.5))
    assert f"{len(sharp)} creases sharper than 0.5 rad" in folds[0]
    points = np.array(out(node, "Folds")[(0,)])
    np.testing.assert_allclose(points[: len(sharp)], 0.5 * (starts[sharp] + ends[sharp]), rtol=0, atol=1e-15)
    assert len(points) > len(sharp)  # and the crossings
    # every fold point lies on the strip: within the hull of the rulings' ends
    low, high = np.minimum(starts, ends).min(axis=0), np.maximum(starts, ends).max(axis=0)
    assert ((points >= low - 1e-12) & (points <= high + 1e-12)).all()


def test_two_curves_on_one_nappe_are_torsal_everywhere_with_no_fold():
    """The same cone, both curves on the upper nappe: every generator is a torsal ruling
    (independent warp ~0 with the curves' exact tangents)."""
    a = on_cone(lambda u: 1 + 0.2 * np.sin(3 * u), lambda u: 0.6 * np.cos(3 * u))
    b = on_cone(lambda u: 2 + 0.3 * np.cos(2 * u), lambda u: -0.6 * np.sin(2 * u))
    node = solve(a, b, 40)
    starts, ends = ends_of(node)
    s = np.arctan2(starts[:, 1], starts[:, 0]) / SPAN
    t = np.arctan2(ends[:, 1], ends[:, 0]) / SPAN
    independent = warp(starts, ends, a.derivatives(s, 1)[1], b.derivatives(t, 1)[1])
    assert independent.max() < 1e-9
    np.testing.assert_array_equal(out(node, "Kind")[(0,)], ["torsal"] * 41)
    assert out(node, "Torsal")[(0,)] == [1.0]
    assert out(node, "Folds")[(0,)] == []
    assert not any(t.startswith("the sheet folds") for t in texts(node))


def test_two_coplanar_segments_are_fans_except_where_the_two_fans_meet():
    """The docstring's planar quad: a fan through B(0) from three stations, then a fan
    through A(1). The ruling from A(1) to B(0) has a fan through B(0) on one side and
    one through A(1) on the other; it lies in the plane of both curves, so it is torsal
    (both tangents in its plane); every other ruling lies inside one fan."""
    a, b = Line([0, 0, 0], [2, 0, 0]), Line([0, 1, 0], [3, 2, 0])
    node = solve(a, b, 2)
    assert out(node, "Kind")[(0,)] == ["fan", "fan", "torsal", "fan", "fan", "fan"]
    assert out(node, "Valid")[(0,)] == [True] * 6
    assert out(node, "Torsal")[(0,)] == [pytest.approx(1 / 6)]


# -- crossings of a strip --------------------------------------------------------------------


def looped_band(u0: float, u1: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """A band over the prolate cycloid (u − 2 sin u, 0, 1 − 2 cos u), its rulings along y
    from −1 to 1: for |u| > u* (u* = 2 sin u*) the centre line loops and the band passes
    through itself along the line x = 0, z = 1 − 2 cos u*."""
    u = np.linspace(u0, u1, n)
    centre = np.column_stack([u - 2 * np.sin(u), np.zeros(n), 1 - 2 * np.cos(u)])
    side = np.array([0.0, 1.0, 0.0])
    return centre - side, centre + side


def test_a_band_over_a_looping_curve_crosses_itself_on_the_line_where_the_loop_crosses():
    u_star = 1.8954942670339809  # u = 2 sin u (solved with scipy.optimize.brentq once: 1.89549426703398)
    assert u_star == pytest.approx(2 * np.sin(u_star), abs=1e-14)
    starts, ends = looped_band(-2.5, 2.5, 201)
    found = crossings(starts, ends)
    assert len(found) > 0
    z_star = 1 - 2 * np.cos(u_star)
    h = 5.0 / 200  # the ruling spacing in u: chords of the loop are off by O(h²)
    np.testing.assert_allclose(found.points[:, 0], 0.0, atol=h**2)
    np.testing.assert_allclose(found.points[:, 2], z_star, atol=h**2)
    # the two triangles of each pair are far apart along the band: one on each branch of the loop
    u = np.linspace(-2.5, 2.5, 201)
    assert (np.sign(u[found.first] + 0.01) != np.sign(u[found.second] + 0.01)).all()


def test_a_band_over_the_same_curve_before_it_loops_does_not_cross_itself():
    starts, ends = looped_band(-1.8, 1.8, 201)
    assert len(crossings(starts, ends)) == 0


def test_a_fan_of_triangles_through_one_point_touches_there_without_crossing():
    angles = np.linspace(0, 1.5 * np.pi, 50)
    ends = np.column_stack([np.cos(angles), np.sin(angles), 0.3 * angles])
    starts = np.zeros_like(ends)
    assert len(crossings(starts, ends)) == 0
