"""developable.strip: the strips of a solve set up together (stations on A, A there, the
samples of B), each the strip it is alone; stations evenly spaced along several
curves at once; lengths along several curves and the stretches of B that gaps span, found
for many strips at once, each what it is alone."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad

from torsal.nodes.geometry.curves import Arc, InterpolatedCurve, Line, NurbsCurve, Polyline
from torsal.nodes.geometry.developable.stations import LengthMap, lengths_at, parameters_at, spaced_parameters
from torsal.nodes.geometry.developable.strip import Steady, gap_lengths_all, set_up, with_maps_b


def _wavy(z: float, phase: float, points: int = 9) -> NurbsCurve:
    u = np.linspace(0.0, 1.0, points)
    return NurbsCurve(np.column_stack([4 * u, np.sin(3 * u + phase), z + 0.2 * np.cos(5 * u)]), degree=3)


def _jobs() -> list[tuple]:
    still_end = NurbsCurve([[0, 1, 1], [1, 1.2, 1], [2, 1, 1.4], [2, 1, 1.4]], degree=2)  # B' = 0 at its end
    return [
        (_wavy(0.0, 0.0), _wavy(1.0, 0.2, 14), 9, 0.01),
        (Line([0, 0, 0], [0, 0, 0]), Line([0, 1, 0], [3, 2, 0]), 3, 0.01),  # A of zero length
        (Polyline([[0, 0, 0], [1, 0, 0], [2, 0.5, 0]]), still_end, 5, 0.02),
        (Line([0, 0, 0], [2, 0, 0]), Line([1, 1, 1], [1, 1, 1]), 2, 0.01),  # B of zero length
        (InterpolatedCurve([[0, 0, 0], [1, 2, 0.5], [3, 1, -0.5], [4, 3, 0.2]]), _wavy(2.0, 1.0), 12, 0.01),
    ]


@pytest.mark.parametrize("spacing", ["length", "parameter"])
def test_strips_set_up_together_are_the_ones_set_up_alone(spacing):
    jobs = _jobs()
    together = set_up(jobs, spacing, 24)
    for job, strip in zip(jobs, together, strict=True):
        (alone,) = set_up([job], spacing, 24)
        if isinstance(alone, ValueError):
            assert isinstance(strip, ValueError) and str(strip) == str(alone)
            continue
        for name in ("s", "a0", "a1", "a2", "kinks_a", "kinks_b", "chords_b"):
            np.testing.assert_array_equal(getattr(strip, name), getattr(alone, name))
        for name in ("t", "at", "points", "tangents", "second", "third"):
            np.testing.assert_array_equal(getattr(strip.grid, name), getattr(alone.grid, name))
        assert strip.map_a.total == alone.map_a.total
        assert type(strip.curve_b) is type(alone.curve_b)
    assert "Curve A has zero length" in str(together[1]) and "Curve B has zero length" in str(together[3])
    assert isinstance(together[2].curve_b, Steady)  # (its tangent at the still end is B'')


def test_stations_along_several_curves_at_once_fall_on_equal_lengths():
    # an arc of radius 2 over 3 rad (length 6) and a polyline of legs 1 and 3 (length 4)
    arc = Arc(radius=2.0, start_angle=0.0, end_angle=3.0)
    polyline = Polyline([[0, 0, 0], [1, 0, 0], [1, 3, 0]])
    on_arc, on_polyline = spaced_parameters(LengthMap.many([arc, polyline]), [7, 5])
    angle = np.linspace(0.0, 3.0, 7)  # (equal lengths along the arc: equal angles)
    expected = np.column_stack([2 * np.cos(angle), 2 * np.sin(angle), np.zeros(7)])
    np.testing.assert_allclose(arc.point_at(on_arc), expected, atol=1e-12)
    np.testing.assert_allclose(on_polyline, [0, 0.25, 0.5, 0.75, 1.0], atol=1e-15)


def test_lengths_along_several_curves_at_once_are_each_curves_own():
    arc = Arc(radius=2.0, start_angle=0.0, end_angle=3.0)  # (length 2·angle)
    curves = [arc, _wavy(0.0, 0.3), Polyline([[0, 0, 0], [1, 0, 0], [1, 3, 0]])]
    ts = [np.array([0.0, 0.25, 0.5, 1.0, -0.2, 1.3]), np.linspace(0.0, 1.0, 17),
          np.array([0.25, 0.5, np.nan])]
    maps = LengthMap.many(curves)
    together = lengths_at(maps, ts)
    for length_map, t, found in zip(maps, ts, together, strict=True):
        np.testing.assert_array_equal(found, length_map.length_at(t))
    np.testing.assert_allclose(together[0], [0.0, 1.5, 3.0, 6.0, 0.0, 6.0], rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(together[2][:2], [1.0, 2.0], rtol=1e-13)


def test_stretches_of_b_of_many_strips_found_at_once_are_the_ones_found_alone():
    jobs = [job for job in _jobs() if job[1].length > 0 and job[0].length > 0]
    jobs.append((Line([0, 0, 0], [3, 0, 0]), Polyline([[0, 1, 0], [1, 1.5, 0], [3, 1, 0.5]]), 8, 0.01))
    # a fan's two ends alone, many rulings between, a stretch run backwards, one over B's corner
    stretches = [(0.1, 0.15), (0.0, 0.9), (0.6, 0.4), (0.3, 1.0)]
    together = [strip for strip in set_up(jobs, "length", 24) if not isinstance(strip, ValueError)]
    gap_lengths_all([(strip, low, high) for strip in together for low, high in stretches])
    for job, strip in zip(jobs, together, strict=True):
        (alone,) = set_up([job], "length", 24)
        for low, high in stretches:
            tb, lb = strip.gap_lengths(low, high)
            tb_alone, lb_alone = alone.gap_lengths(low, high)
            np.testing.assert_array_equal(tb, tb_alone)
            np.testing.assert_array_equal(lb, lb_alone)
            np.testing.assert_array_equal(lb, alone.map_b.length_at(tb))
            assert tb[0] == low and tb[-1] == max(low, high)  # (a stretch run backwards: its start)


def test_an_edge_between_two_strips_is_measured_once_as_its_own_map_would_measure_it():
    low = NurbsCurve(np.array([[0.0, 0, 0], [1, 0.4, 0], [2, 0, 0.3], [3, 0.2, 0]]), degree=3)
    middle = NurbsCurve(np.array([[0.0, 1, 0], [1, 1.5, 0.2], [2, 1, 0], [3, 1.3, 0.1]]), degree=3)
    high = Line([0, 2, 0], [3, 2.5, 0.5])
    strips = set_up([(low, middle, 8, 0.01), (middle, high, 8, 0.01)], "length", 24)
    with_maps_b(strips)
    assert strips[0].map_b is strips[1].map_a  # the middle edge: the second strip's A
    alone = LengthMap(middle)
    for name in ("nodes", "lengths", "start_speeds", "end_speeds", "_rise", "_inverse", "_poly"):
        assert getattr(strips[0].map_b, name).tobytes() == getattr(alone, name).tobytes()
    assert strips[1].map_b.curve is high


def test_length_maps_of_curves_on_one_layout_made_together_are_each_curves_own():
    # Béziers share one layout of pieces (their tables made as rows of one stack); the sharp
    # rational one among them has pieces split where its speed changes fast
    rng = np.random.default_rng(5)
    curves = [NurbsCurve(rng.normal(size=(3, 3)), degree=2) for _ in range(4)]
    sharp = NurbsCurve(np.array([[0.0, 0, 0], [1, 0, 0], [1, 1e-3, 0]]), degree=2, weights=[1, 400, 1])
    curves.insert(2, sharp)
    maps = LengthMap.many(curves)
    assert len(maps[2].nodes) > len(maps[0].nodes) == len(maps[1].nodes)  # (split, and not)
    for curve, together in zip(curves, maps, strict=True):
        alone = LengthMap(curve)
        for name in ("nodes", "lengths", "start_speeds", "end_speeds", "_rise", "_inverse", "_poly"):
            assert getattr(together, name).tobytes() == getattr(alone, name).tobytes()
    # the length of a Bézier by scipy's adaptive quadrature of its speed
    def speed(t: float) -> float:
        return float(np.linalg.norm(curves[0].derivatives(np.array([t]), 1)[1]))

    assert maps[0].total == pytest.approx(quad(speed, 0.0, 1.0, epsabs=0, epsrel=1e-13)[0], rel=1e-12)


def test_no_curves_have_no_length_maps():
    assert LengthMap.many([]) == []


def test_strips_whose_every_b_is_another_strips_a_measure_no_curve_again():
    # the edges of a closed ring of two strips: each B is the other's A (a fuzzed file
    # found that nothing was left to measure, and measuring nothing failed)
    first, second = Line([0, 0, 0], [3, 0, 0]), Polyline([[0, 1, 0], [1, 1.5, 0], [3, 1, 0.5]])
    strips = set_up([(first, second, 8, 0.01), (second, first, 8, 0.01)], "length", 24)
    with_maps_b(strips)
    assert strips[0].map_b is strips[1].map_a
    assert strips[1].map_b is strips[0].map_a


def test_evenly_spaced_samples_in_the_stretches_of_several_strips_are_each_strips_own():
    from types import SimpleNamespace

    from torsal.nodes.geometry.developable.strip import _even_lengths

    # B 10 long with 11 samples (every 1.0), B 3 long with 7 (every 0.5), B 1 long with 2
    strips = [SimpleNamespace(grid=SimpleNamespace(t=np.zeros(n)), map_b=SimpleNamespace(total=total))
              for n, total in ((11, 10.0), (7, 3.0), (2, 1.0))]
    lows = [np.array([0.5, 2.0, 9.5]), np.array([1.2]), np.array([0.3, 0.0])]
    highs = [np.array([3.0, 2.5, 12.0]), np.array([0.9]), np.array([0.4, 0.0])]
    found = _even_lengths(strips, lows, highs)
    # the multiples of each strip's spacing inside any of its stretches (on B), once each
    assert [lengths.tolist() for lengths in found] == [[1.0, 2.0, 3.0, 10.0], [], [0.0]]


def test_maps_searched_from_the_tables_they_were_made_in_or_joined_are_each_maps_own():
    curves = [Arc(radius=2.0, start_angle=0.0, end_angle=3.0), _wavy(0.0, 0.3), _wavy(0.1, 0.2),
              Polyline([[0, 0, 0], [1, 0, 0], [1, 3, 0]])]
    made, other = LengthMap.many(curves[:3]), LengthMap.many(curves[3:])
    alone = [LengthMap(curve) for curve in curves]
    # a subset out of order; one map; maps of two makings; a map made alone among others
    for picked in ([2, 0], [1], [0, 3, 2], [3, 1]):
        maps = [other[0] if k == 3 else made[k] for k in picked]
        ts = [np.linspace(-0.1, 1.1, 9 + k) for k in range(len(maps))]
        lengths = [alone[k].total * np.linspace(0.0, 1.0, 5 + k) for k in picked]
        for k, t, found in zip(picked, ts, lengths_at(maps, ts), strict=True):
            assert found.tobytes() == alone[k].length_at(t).tobytes()
        for k, length, found in zip(picked, lengths, parameters_at(maps, lengths), strict=True):
            assert found.tobytes() == alone[k].parameter_at(length).tobytes()
