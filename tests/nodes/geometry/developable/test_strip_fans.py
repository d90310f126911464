"""RulingDevelopable where the curves admit no torsal ruling over a stretch: no holes.

The pair: the low cut of a cylinder with a straight chord in its middle, blended in over
two short stretches of A, against the high cut. Over the blends no ruling from A is
torsal (measured independently: the least warp over 20 001 samples of B is above 0.1
rad); the strip is closed there by flat triangles, marked as fan rulings, and stays one
continuous developable strip from end to end that unrolls to a simple polygon.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from tests.support import curve_pairs
from tests.support.node_helpers import out, run, texts, tree
from tests.support.warp_check import shared_both_sides
from torsal.nodes.developable.ruling_developable import RulingDevelopable
from torsal.nodes.geometry.developable import ruling_developable
from torsal.nodes.geometry.developable.closings import zigzag, zigzag_all
from torsal.nodes.geometry.developable.fans import fan_share, fan_shares, fan_shares_all, patch_areas
from torsal.nodes.geometry.unroll import unroll_rulings

TOLERANCE = 0.01


@pytest.fixture(scope="module")
def chorded():
    a, b = curve_pairs.chorded_pair()
    return a, b, ruling_developable(a, b, 60, TOLERANCE)


def least_warp_over_b(a, b, s: np.ndarray, samples: int = 20001) -> np.ndarray:
    """For each station A(s), the least angle (0 to π) between the end normals R × A' and
    R × B' over a dense sampling of B: no torsal ruling exists where it is large."""
    t = np.linspace(0.0, 1.0, samples)
    points_b, tangents_b = b.derivatives(t, 1)
    points_a, tangents_a = a.derivatives(s, 1)
    least = np.empty(len(s))
    for k, (p, d) in enumerate(zip(points_a, tangents_a, strict=True)):
        r = points_b - p
        n1, n2 = np.cross(r, d), np.cross(r, tangents_b)
        angle = np.arctan2(np.linalg.norm(np.cross(n1, n2), axis=1), np.einsum("ij,ij->i", n1, n2))
        least[k] = angle.min()
    return least


def test_the_strip_spans_both_curves_end_to_end_without_crossing(chorded):
    _, _, result = chorded
    assert (result.s[0], result.t[0], result.s[-1], result.t[-1]) == (0.0, 0.0, 1.0, 1.0)
    assert np.all(np.diff(result.s) >= 0) and np.all(np.diff(result.t) >= 0)
    assert result.stations.sum() == 61


def test_kind_marks_exactly_the_stations_that_have_no_torsal_ruling(chorded):
    a, b, result = chorded
    stations = result.stations
    least = least_warp_over_b(a, b, result.s[stations])
    np.testing.assert_array_equal(result.fan[stations], least > TOLERANCE)
    assert 0 < result.fan[stations].sum() < 61


def test_torsal_rulings_away_from_the_chord_are_the_true_generators(chorded):
    _, _, result = chorded
    pair = curve_pairs.cylinder_sections_pair()
    s0, s1 = curve_pairs.CHORD
    away = result.stations & ((result.s < s0 - curve_pairs.BLEND) | (result.s > s1 + curve_pairs.BLEND))
    assert not result.fan[away].any()
    np.testing.assert_allclose(result.t[away], pair.partner(result.s[away]), atol=1e-8)


def test_every_piece_next_to_a_fan_ruling_is_a_flat_triangle(chorded):
    _, _, result = chorded
    p0, p1, q0, q1 = result.starts[:-1], result.starts[1:], result.ends[:-1], result.ends[1:]
    in_fan = result.fan[:-1] | result.fan[1:]
    assert in_fan.any()
    size = np.linalg.norm(np.ptp(np.concatenate([result.starts, result.ends]), axis=0))
    volume = np.abs(np.einsum("ij,ij->i", p1 - p0, np.cross(q0 - p0, q1 - p0)))
    assert (volume[in_fan] / size**3).max() < 1e-12
    shares_end = np.all(p0 == p1, axis=1) | np.all(q0 == q1, axis=1)
    assert shares_end[in_fan].all()


def test_the_unrolled_strip_is_a_simple_polygon(chorded):
    _, _, result = chorded
    development = unroll_rulings(result.starts, result.ends)
    assert shapely.Polygon(development.outline).is_valid
    assert abs(development.max_edge_length_error) < 1e-9


def test_the_fan_share_is_the_area_of_the_pieces_next_to_fan_rulings(chorded):
    _, _, result = chorded
    # independent area: each piece as two triangles split along one diagonal
    p0, p1, q0, q1 = result.starts[:-1], result.starts[1:], result.ends[:-1], result.ends[1:]
    first = np.linalg.norm(np.cross(p1 - p0, q1 - p0), axis=1)
    second = np.linalg.norm(np.cross(q1 - p0, q0 - p0), axis=1)
    area = 0.5 * (first + second)
    in_fan = result.fan[:-1] | result.fan[1:]
    assert result.fan_share == pytest.approx(area[in_fan].sum() / area.sum(), rel=1e-3)


# -- the triangulation and the areas ---------------------------------------------------------


def test_zigzag_advances_one_chain_at_a_time_in_step_with_both_lengths():
    i, j = zigzag(np.array([0.0, 1.0, 2.0, 3.0]), np.array([0.0, 10.0, 30.0]))
    assert (i[0], j[0], i[-1], j[-1]) == (0, 0, 3, 2)
    assert np.all((np.diff(i) + np.diff(j)) == 1)
    # edges' middles as fractions of length: A's at 1/6, 1/2, 5/6 and B's at 1/6, 2/3, taken
    # in that order; at the tie (1/6, no points to compare diagonals) A steps first
    np.testing.assert_array_equal(i, [0, 1, 1, 2, 2, 3])
    np.testing.assert_array_equal(j, [0, 0, 1, 1, 2, 2])


def _rulings(i, j):
    return set(zip(i.tolist(), j.tolist(), strict=True))


@pytest.mark.parametrize("seed", range(6))
def test_zigzag_read_from_the_chains_other_ends_is_the_same_strip(seed):
    rng = np.random.default_rng(seed)
    length_a = np.cumsum(np.r_[0.0, rng.uniform(0.1, 1.0, rng.integers(1, 9))])
    length_b = np.cumsum(np.r_[0.0, rng.uniform(0.1, 1.0, rng.integers(1, 9))])
    i, j = zigzag(length_a, length_b)
    ri, rj = zigzag(length_a[-1] - length_a[::-1], length_b[-1] - length_b[::-1])
    na, nb = len(length_a) - 1, len(length_b) - 1
    assert _rulings(i, j) == _rulings(na - ri, nb - rj)


def test_pairs_of_chains_stepped_together_get_what_each_gets_alone():
    rng = np.random.default_rng(7)
    lengths, points = [], []
    for k in range(40):  # uneven chains, evenly spaced ones (ties), single points, no length
        na, nb = int(rng.integers(1, 7)), int(rng.integers(1, 7))
        if k % 4 == 0:
            lengths.append((np.cumsum(rng.random(na)), np.cumsum(rng.random(nb))))
        elif k % 4 == 1:
            lengths.append((np.arange(na) * 0.3, np.arange(nb) * 0.7))
        elif k % 4 == 2:
            lengths.append((np.arange(2) * 1.0, np.arange(3) * 1.0))
        else:
            lengths.append((np.zeros(na), np.arange(nb) * 1.0))
        points.append((rng.random((len(lengths[-1][0]), 3)), rng.random((len(lengths[-1][1]), 3))))
    asked = []

    def chains(pairs):
        asked.append(pairs)
        return [points[k] for k in pairs]

    together = zigzag_all(lengths, chains)
    assert len(asked) == 1  # the points of the pairs with a tie, asked for once
    for k, (length, (i, j)) in enumerate(zip(lengths, together, strict=True)):
        alone_i, alone_j = zigzag(*length, lambda k=k: points[k])
        assert i.tolist() == alone_i.tolist() and j.tolist() == alone_j.tolist()
    swapped = [k for k, (i, j) in enumerate(together)
               if not np.array_equal(np.stack([i, j]), np.stack(zigzag(*lengths[k])))]
    assert swapped and set(swapped) <= set(asked[0])  # some ties were cut the other way


def test_a_tie_is_cut_along_the_quads_shorter_diagonal_whichever_way_the_chains_run():
    # A and B evenly spaced, 3 vertices each: their edges' middles tie (1/4, 3/4); B is
    # shifted along x so that A_0 B_1 and A_1 B_2 (B stepping first) are the short diagonals
    length = np.array([0.0, 1.0, 2.0])
    points_a = np.column_stack([length, np.zeros(3), np.zeros(3)])
    points_b = points_a + np.array([-0.7, 1.0, 0.0])
    i, j = zigzag(length, length, lambda: (points_a, points_b))
    assert _rulings(i, j) == {(0, 0), (0, 1), (1, 1), (1, 2), (2, 2)}
    ri, rj = zigzag(length, length, lambda: (points_a[::-1], points_b[::-1]))
    assert _rulings(2 - ri, 2 - rj) == _rulings(i, j)


def test_patch_areas_are_exact_for_flat_quads_and_triangles():
    starts = np.array([[0.0, 0, 0], [2, 0, 0], [2, 0, 0]])
    ends = np.array([[0.0, 1, 0], [2, 1, 0], [3, 1, 0]])
    np.testing.assert_allclose(patch_areas(starts, ends), [2.0, 0.5])
    assert fan_share(starts, ends, np.array([False, False, True])) == pytest.approx(0.5 / 2.5)


# -- the node ----------------------------------------------------------------------------------


def test_the_node_says_per_ruling_whether_it_is_torsal_and_reports_the_share(chorded):
    a, b, result = chorded
    node = run(RulingDevelopable(), CurveA=tree({(0,): [a]}), CurveB=tree({(0,): [b]}), Segments=60)
    kinds = np.array(out(node, "Kind")[(0,)])
    # the stations with no torsal partner (least warp over B above the tolerance, measured
    # independently) are never torsal; the rest of the stations are, unless they lie inside
    # a fan (sharing an end with both neighbours, as the kernel's fans of step 6 do)
    stations = result.stations
    least = least_warp_over_b(a, b, result.s[stations])
    in_fan = (shared_both_sides(result.starts) | shared_both_sides(result.ends))[stations]
    assert not (kinds[stations][least > TOLERANCE] == "torsal").any()
    has = least <= TOLERANCE
    assert (kinds[stations][has] == np.where(in_fan[has], "fan", "torsal")).all()
    assert (kinds[stations][has] == "torsal").sum() > 30
    assert out(node, "Torsal")[(0,)][0] == pytest.approx(np.mean(kinds == "torsal"))
    share = f"{100 * result.fan_share:.3g} %"
    assert node.state == "warning"  # above the default FanLimit of 10 %
    count = result.fan[result.stations].sum()
    assert texts(node)[0].startswith(
        f"no torsal ruling within 0.01 rad keeps the rulings' order at {count} of 61 stations"
    )
    assert f"closed by flat triangles ({share} of the strip's area), above FanLimit 10 %" in texts(node)[0]


def test_the_node_reverses_b_itself_when_its_torsal_rulings_run_backwards_along_it():
    """(It named reversing B in a warning; now it solves the strip so, as a loft aligns its
    curves, and says what it did.)"""
    pair = curve_pairs.PAIRS["cone"]()
    curves = {"CurveA": tree({(0,): [pair.a]}), "CurveB": tree({(0,): [pair.b.reversed()]})}
    node = run(RulingDevelopable(), **curves, Segments=40)
    assert node.state == "ok"
    assert texts(node)[0].startswith("CurveB runs against CurveA")
    assert out(node, "Torsal")[(0,)] == [1.0]  # every ruling torsal, as with B drawn the same way


# -- a stretch of B that t jumps over ------------------------------------------------------------


def test_a_fold_of_b_that_no_torsal_ruling_reaches_is_closed_by_flat_triangles():
    a, b = curve_pairs.folded_cone_pair()
    result = ruling_developable(a, b, 60)
    assert result.fan[result.stations].sum() == 0  # every station has its torsal ruling
    assert result.fan.any() and np.all(np.diff(result.t) >= 0)
    # the triangles cover the stretch of B between the last torsal partner before the fold
    # and the first after it, and only that
    torsal_t = result.t[~result.fan]
    gap = int(np.argmax(np.diff(torsal_t)))
    assert np.all((result.t[result.fan] > torsal_t[gap]) & (result.t[result.fan] < torsal_t[gap + 1]))
    p0, p1, q0, q1 = result.starts[:-1], result.starts[1:], result.ends[:-1], result.ends[1:]
    in_fan = result.fan[:-1] | result.fan[1:]
    assert (np.all(p0 == p1, axis=1) | np.all(q0 == q1, axis=1))[in_fan].all()
    assert result.message.startswith("no torsal ruling in the strip's order reaches part of curve B")


def test_fan_shares_of_several_strips_at_once_are_each_strips_own():
    # a unit square, then a fan through B's point (1, 1): a triangle of area 1/2
    square_fan = (np.array([[0.0, 0, 0], [1, 0, 0], [2, 0, 0]]),
                  np.array([[0.0, 1, 0], [1, 1, 0], [1, 1, 0]]), np.array([False, False, True]))
    # three triangles whose apex changes curve at every ruling: one creased run
    zigzag = (np.array([[0.0, 0, 0], [1, 0, 0], [1, 0, 0], [2, 0, 0]]),
              np.array([[0.0, 1, 0], [0, 1, 0], [1, 1, 0], [1, 1, 0]]), np.ones(4, dtype=bool))
    rng = np.random.default_rng(5)
    wild = (rng.normal(size=(9, 3)), rng.normal(size=(9, 3)), rng.random(9) < 0.5)
    strips = [square_fan, zigzag, wild]
    together = fan_shares_all(strips)
    assert together[0] == pytest.approx((1 / 3, 0.0), abs=1e-15)
    assert together[1] == (1.0, 1.0)
    assert together == [fan_shares(*strip) for strip in strips]
