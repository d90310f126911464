"""The curve rails' pace σ is the PCHIP interpolant: checked against scipy's PchipInterpolator."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.interpolate import PchipInterpolator

from torsal.nodes.geometry.curve_rail import Pace


def _cases() -> list[tuple[np.ndarray, np.ndarray]]:
    rng = np.random.default_rng(7)
    cases = [(np.array([0.0, 1.0]), np.array([0.2, 0.7]))]  # two points: a straight line
    for n in (3, 5, 13, 40):
        u = np.sort(rng.random(n))
        cases.append((u, np.cumsum(rng.random(n))))  # increasing
        cases.append((u, np.cumsum(rng.random(n) * (rng.random(n) > 0.4))))  # with flat runs (fans)
        cases.append((u, rng.random(n)))  # not monotone: the slope rules at sign changes
    return cases


@pytest.mark.parametrize("u, p", _cases())
def test_pace_and_its_three_derivatives_equal_scipys_pchip_inside_and_beyond_the_ends(u, p):
    x = np.concatenate([np.linspace(u[0] - 0.3, u[-1] + 0.3, 301), u])
    reference = PchipInterpolator(u, p, extrapolate=True)
    mine = Pace(u, p).derivatives(x, 3)
    for k in range(4):
        expected = reference(x, nu=k)
        # rounding of the cubic's coefficients, amplified by 1/h^k on the shortest piece
        scale = np.abs(expected).max() + np.abs(p).max() / np.diff(u).min() ** k
        assert np.abs(mine[k] - expected).max() <= 1e-13 * scale


def test_a_flat_run_of_the_pace_stays_flat_between_its_points():
    u = np.linspace(0.0, 1.0, 6)
    p = np.array([0.0, 0.3, 0.3, 0.3, 0.8, 1.0])
    x = np.linspace(0.2, 0.6, 41)
    assert np.all(Pace(u, p)(x) == 0.3)
