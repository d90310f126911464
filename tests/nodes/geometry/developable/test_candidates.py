"""developable.candidates: the least-warped sample of B for stations without a partner,
every strip's stations and samples at once."""

from __future__ import annotations

import numpy as np

from torsal.nodes.geometry.developable.candidates import _least_warped


def _angle(a: np.ndarray, ta: np.ndarray, b: np.ndarray, tb: np.ndarray) -> float:
    """The angle between N1 = R × A' and N2 = R × B' (R = B − A), from the cross products."""
    r = b - a
    n1, n2 = np.cross(r, ta), np.cross(r, tb)
    return float(np.arctan2(np.linalg.norm(np.cross(n1, n2)), n1 @ n2))


def _strip(rng: np.random.Generator, stations: int, count: int) -> tuple:
    a0, a1 = rng.normal(size=(stations, 3)) * 5.0, rng.normal(size=(stations, 3))
    t = np.sort(rng.uniform(0.0, 1.0, count))
    points, tangents = rng.normal(size=(count, 3)) * 5.0, rng.normal(size=(count, 3))
    lo, hi = rng.uniform(0.0, 0.5, stations), rng.uniform(0.5, 1.0, stations)
    return a0, a1, (lo, hi), (t, points, tangents)


def test_each_station_gets_its_least_warped_sample_in_its_window_or_nan():
    rng = np.random.default_rng(3)
    strips = [_strip(rng, n, m) for n, m in ((4, 30), (1, 7), (6, 0), (3, 1), (5, 52))]
    wanted = [rng.uniform(size=len(a0)) < 0.7 for a0, *_ in strips]
    wanted[1][:] = True
    tolerances = [3.0, 0.5, 1.0, 3.2, 0.05]
    picked, rows = _least_warped(tolerances, [s[0] for s in strips], [s[1] for s in strips], wanted,
                                 [s[2] for s in strips], [s[3] for s in strips])
    every = np.concatenate(picked)
    assert np.isnan(every).any() and not np.isnan(every).all()  # (both outcomes are checked)
    for (a0, a1, (lo, hi), (t, points, tangents)), want, own, tolerance, found in zip(
        strips, wanted, rows, tolerances, picked, strict=True
    ):
        assert own.tolist() == np.flatnonzero(want).tolist()
        for row, value in zip(own, found, strict=True):
            angles = [_angle(a0[row], a1[row], p, d) if lo[row] <= tj <= hi[row] else np.inf
                      for tj, p, d in zip(t, points, tangents, strict=True)]
            least = min(angles, default=np.inf)
            if least <= tolerance:
                assert value == t[int(np.argmin(angles))]
            else:
                assert np.isnan(value)


def test_each_station_without_a_partner_gets_the_window_between_its_own_strips_neighbours():
    from types import SimpleNamespace

    from torsal.nodes.geometry.curves import Line
    from torsal.nodes.geometry.developable.candidates import _windows
    from torsal.nodes.geometry.developable.stations import LengthMap

    def strip(count: int, total: float, length_b: float) -> SimpleNamespace:
        along_b = LengthMap(Line([0, 0, 0], [length_b, 0, 0]))
        return SimpleNamespace(station_lengths=np.linspace(0.0, total, count),
                               map_a=SimpleNamespace(total=total), map_b=along_b)

    nan = np.nan
    strips = [strip(6, 5.0, 2.0), strip(2, 1.0, 4.0), strip(3, 2.0, 1.0)]
    ts = [np.array([nan, 0.2, nan, nan, 0.8, nan]), np.array([nan, nan]), np.array([0.1, nan, 0.5])]
    # (station, lo, hi, loft's share of the way from lo to hi) by hand: A's stations 1.0 apart
    # in the first strip (ends 0 and 5), 1.0 in the second, 1.0 in the third
    expected = [[(0, 0.0, 0.2, 0.0), (2, 0.2, 0.8, 1 / 3), (3, 0.2, 0.8, 2 / 3), (5, 0.8, 1.0, 1.0)],
                [(0, 0.0, 1.0, 0.0), (1, 0.0, 1.0, 1.0)], [(1, 0.1, 0.5, 0.5)]]
    for (missing, lo, hi, b_lo, b_hi, loft), own, along_b in zip(
        _windows(strips, ts), expected, (2.0, 4.0, 1.0), strict=True
    ):
        assert missing.tolist() == [row for row, *_ in own]
        np.testing.assert_allclose(lo, [w[1] for w in own], rtol=0, atol=1e-15)
        np.testing.assert_allclose(hi, [w[2] for w in own], rtol=0, atol=1e-15)
        np.testing.assert_allclose(b_lo, along_b * lo, rtol=1e-13, atol=1e-15)
        np.testing.assert_allclose(b_hi, along_b * hi, rtol=1e-13, atol=1e-15)
        share = np.array([w[3] for w in own])
        np.testing.assert_allclose(loft, along_b * (lo + share * (hi - lo)), rtol=1e-13, atol=1e-15)
