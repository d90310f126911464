"""RulingDevelopable's Kind, Valid, Torsal and Folds, checked against geometry recomputed
here: closed forms and an independent warp (tests/support/warp_check.py), never the
node's own numbers.

The main case: two curves on opposite nappes of one cone (apex at the origin, axis z),
A(x) on the upper nappe and B(x) on the lower one at the same angle SPAN·x. Every line
joining them with det[B − A, A', B'] = 0 is a generator through the apex: B(x)'s partner
on A is A(x). Traced by angle the same way, the two run against each other in space
(B(x) lies across the axis from A(x)), and their ends say so as a loft reads them: A's
ends lie nearer B's crossed than in order. So the node solves the strip with B reversed,
B_r(t) = B(1 − t), whichever way B was drawn. Along B_r the generators' normals R × A'
and R × B_r' agree, but their partners run backwards (t = 1 − s): a strip whose t never
decreases takes at most one of them, where its path crosses t = 1 − s, and closes the
rest with flat triangles. B as drawn, the kernel's strip (no alignment) joins A(x) to
B(x) through the apex: every generator there has opposite normals (the apex lies between
the curves), so none is torsal, and the strip folds through the apex and crosses itself.
"""

from __future__ import annotations

import numpy as np
import pytest

from tests.support.node_helpers import out, run, texts, tree
from tests.support.strip_triangles import crossing_pairs
from tests.support.warp_check import shared_both_sides, warp
from torsal.nodes.common.strip_folds import fold_report
from torsal.nodes.developable.ruling_developable import RulingDevelopable
from torsal.nodes.geometry.curves import Line, ParametricCurve
from torsal.nodes.geometry.developable.kinds import ruling_kinds
from torsal.nodes.geometry.developable.ruling import ruling_developable
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


def parameters(starts, ends):
    """Each ruling's s on A and t on B_r, read from its end points: A(s) lies at the angle
    SPAN·s, B(x) (w < 0) across the axis from the angle SPAN·x, and B_r(t) = B(1 − t)."""
    s = np.mod(np.arctan2(starts[:, 1], starts[:, 0]), 2 * np.pi) / SPAN
    t = 1.0 - np.mod(np.arctan2(-ends[:, 1], -ends[:, 0]), 2 * np.pi) / SPAN
    return s, t


def independent_kinds(a, b_r, starts, ends):
    """Kind from the geometry alone: inside a fan (an end shared with both neighbours),
    else torsal where the warp with the curves' exact tangents is within the tolerance,
    else a crease; and that warp."""
    s, t = parameters(starts, ends)
    bent = warp(starts, ends, a.derivatives(s, 1)[1], b_r.derivatives(t, 1)[1])
    in_fan = shared_both_sides(starts) | shared_both_sides(ends)
    return np.where(in_fan, "fan", np.where(bent <= TOLERANCE, "torsal", "crease")), bent, in_fan


@pytest.fixture(scope="module")
def cone_across_nappes():
    a, b = nappes()
    return a, b, solve(a, b), solve(a, b.reversed())


def test_across_nappes_b_drawn_either_way_gives_one_strip_with_b_as_a_loft_aligns_it(cone_across_nappes):
    a, b, drawn, reversed_ = cone_across_nappes
    (a0, a1), (b0, b1) = a.point_at(np.array([0.0, 1.0])), b.point_at(np.array([0.0, 1.0]))
    # the ends as a loft reads them: crossed (4.8) nearer than in order (6.5)
    crossed = np.linalg.norm(a0 - b1) + np.linalg.norm(a1 - b0)
    assert crossed < np.linalg.norm(a0 - b0) + np.linalg.norm(a1 - b1)
    assert any(t.startswith("CurveB runs against CurveA by their ends") for t in texts(drawn))
    assert not any(t.startswith("CurveB runs against CurveA") for t in texts(reversed_))
    for name in ("Kind", "Valid", "Torsal", "Folds"):
        assert out(drawn, name) == out(reversed_, name), name
    (s1, e1), (s2, e2) = ends_of(drawn), ends_of(reversed_)
    np.testing.assert_array_equal(s1, s2)
    np.testing.assert_array_equal(e1, e2)


def test_across_nappes_with_b_reversed_the_only_torsal_partners_are_the_generators_run_backwards():
    """Independently of the node: along B_r, the torsal partner of A(s) (normals within
    the tolerance, over 20,001 samples of B_r) is the generator's, t = 1 − s, and only
    partners within ~0.03 of it come within 0.05 rad."""
    a, b = nappes()
    b_r = b.reversed()
    t = np.linspace(0.0, 1.0, 20001)
    pb, tb = b_r.derivatives(t, 1)
    for s in np.linspace(0.0, 1.0, 11):
        pa, ta = a.derivatives(np.array([s]), 1)
        r = pb - pa[0]
        n1, n2 = np.cross(r, ta[0]), np.cross(r, tb)
        angle = np.arctan2(np.linalg.norm(np.cross(n1, n2), axis=1), np.einsum("ij,ij->i", n1, n2))
        assert angle.min() < 1e-12
        assert np.abs(t[angle <= 0.05] - (1.0 - s)).max() < 0.03  # (0.028 measured)


def test_across_nappes_one_ruling_is_torsal_the_generator_where_the_strip_crosses_t_equal_1_minus_s(
    cone_across_nappes,
):
    a, b, node, _ = cone_across_nappes
    starts, ends = ends_of(node)
    size = float(np.linalg.norm(np.ptp(np.vstack([starts, ends]), axis=0)))
    s, t = parameters(starts, ends)
    assert (np.diff(s) >= -1e-12).all() and (np.diff(t) >= -1e-12).all()  # rulings never cross
    kinds = np.array(out(node, "Kind")[(0,)])
    torsal = np.flatnonzero(kinds == "torsal")
    assert len(torsal) == 1  # at most one generator fits a strip whose t never decreases
    k = int(torsal[0])
    # a generator through the apex (s + t = 1 on B_r), its end normals agreeing
    assert s[k] + t[k] == pytest.approx(1.0, abs=1e-12)
    line = ends[k] - starts[k]
    assert np.linalg.norm(np.cross(line, starts[k])) / np.linalg.norm(line) < 1e-12 * size
    _, bent, in_fan = independent_kinds(a, b.reversed(), starts, ends)
    assert bent[k] < 1e-12 and not in_fan[k]
    # between a fan through B (the ruling before shares its end on B) and one through A
    np.testing.assert_array_equal(ends[k - 1], ends[k])
    np.testing.assert_array_equal(starts[k + 1], starts[k])
    assert out(node, "Valid")[(0,)][k]
    assert out(node, "Torsal")[(0,)] == [pytest.approx(1 / len(kinds))]


def test_across_nappes_every_ruling_is_what_the_geometry_says(cone_across_nappes):
    a, b, node, _ = cone_across_nappes
    starts, ends = ends_of(node)
    expected = independent_kinds(a, b.reversed(), starts, ends)[0]
    kinds = np.array(out(node, "Kind")[(0,)])
    np.testing.assert_array_equal(kinds, expected)
    valid = np.array(out(node, "Valid")[(0,)])
    assert not valid[kinds == "crease"].any()
    assert (kinds == "crease").sum() > 50  # 62 of 118 measured


def test_across_nappes_the_node_warns_where_the_sheet_creases_and_it_crosses_nowhere(cone_across_nappes):
    a, b, node, _ = cone_across_nappes
    starts, ends = ends_of(node)
    assert node.state == "warning"
    folds = [t for t in texts(node) if t.startswith("the sheet folds")]
    assert len(folds) == 1
    # the sharp creases: outside fans, where the planes through the ruling and A', and
    # through it and B_r', differ by over 0.5 rad; their middles are Folds, in order
    _, bent, in_fan = independent_kinds(a, b.reversed(), starts, ends)
    sharp = np.flatnonzero(~in_fan & ~(bent <= 0.5))
    assert len(sharp) > 20  # 46 measured
    assert f"{len(sharp)} creases sharper than 0.5 rad" in folds[0]
    points = np.array(out(node, "Folds")[(0,)])
    np.testing.assert_allclose(points, 0.5 * (starts[sharp] + ends[sharp]), rtol=0, atol=1e-15)
    # no two of its triangles cross (counted independently): the strip keeps off the apex
    # but along its one generator
    assert crossing_pairs(starts, ends) == 0
    assert "cross each other" not in folds[0]


def test_with_b_as_drawn_the_kernels_strip_folds_through_the_apex_with_no_torsal_ruling():
    """The strip as drawn (the kernel does not align B; the node would reverse it): no
    ruling is torsal, only rulings inside a fan are valid, and the fold report names its
    creases and the pairs of its triangles that cross at the apex."""
    a, b = nappes()
    # independently: no ruling from any of 61 points of A to B has its normals within 0.4 rad
    # (measured: 0.42 at A's start, over 20,001 samples of B), far above the tolerance
    assert least_warp_over_b(a, b, np.linspace(0, 1, 61)).min() > 0.4
    result = ruling_developable(a, b, 60, TOLERANCE)
    starts, ends = result.starts, result.ends
    kinds = ruling_kinds(a, b, result.s, result.t, starts, ends, TOLERANCE)
    in_fan = shared_both_sides(starts) | shared_both_sides(ends)
    np.testing.assert_array_equal(kinds.kind, np.where(in_fan, "fan", "crease"))
    assert not kinds.valid[~in_fan].any()
    assert kinds.torsal_share == 0.0
    crossed = crossing_pairs(starts, ends)
    assert crossed > 1000  # 1917 counted here (1943 by strip_crossings, which counts touching ones too)
    report = fold_report(starts, ends, kinds.crease_angle, 0.5)
    assert report.message is not None and report.message.startswith("the sheet folds: ")
    bent = warp(starts, ends, a.derivatives(result.s, 1)[1], b.derivatives(result.t, 1)[1])
    sharp = np.flatnonzero(~in_fan & ~(bent <= 0.5))
    assert f"{len(sharp)} creases sharper than 0.5 rad" in report.message
    assert f"{len(crossings(starts, ends))} pairs of its triangles cross each other" in report.message
    assert report.crossing_pairs >= crossed


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
