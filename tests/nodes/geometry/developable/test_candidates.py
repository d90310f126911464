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
