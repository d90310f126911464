"""The one root solver (roots.refine_roots, and safeguarded_newton over it) against Cardano's formula.

x³ + x − c = 0 has one real root for every c, x = ∛(c/2 + √(c²/4 + 1/27)) + ∛(c/2 − √(c²/4 + 1/27)).
"""

from __future__ import annotations

import numpy as np

from torsal.nodes.geometry.roots import refine_roots, safeguarded_newton


def cardano(c: np.ndarray) -> np.ndarray:
    root = np.sqrt(c * c / 4 + 1 / 27)
    return np.cbrt(c / 2 + root) + np.cbrt(c / 2 - root)


def cubic_problems(count: int = 20_000) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    rng = np.random.default_rng(5)
    c = rng.uniform(-10.0, 10.0, count)
    return c, np.full(count, -3.0), np.full(count, 3.0)


def test_safeguarded_newton_matches_cardano_on_twenty_thousand_cubics():
    c, low, high = cubic_problems()
    roots = safeguarded_newton(lambda x, i: (x**3 + x - c[i], 3 * x**2 + 1), low, high, 0.5 * (low + high))
    # measured 1e-14 (the closed form's own rounding is of that order)
    np.testing.assert_allclose(roots, cardano(c), rtol=0, atol=2e-14)


def test_every_cubic_converges_within_ten_newton_iterations():
    """From the bracket's middle Newton needs ~7 steps on the worst of these; a solver that
    bisects onto a root it has already hit (~40 more calls) would exceed 10."""
    c, low, high = cubic_problems()
    calls = []

    def f(x: np.ndarray, i: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        calls.append(len(i))
        return x**3 + x - c[i], 3 * x**2 + 1

    safeguarded_newton(f, low, high, 0.5 * (low + high))
    assert len(calls) <= 10


def test_refine_roots_finds_roots_of_decreasing_functions():
    c, low, high = cubic_problems(1000)
    roots = refine_roots(
        lambda x, i: (c[i] - x**3 - x, -3 * x**2 - 1, np.abs(c[i]) + np.abs(x**3) + np.abs(x)),
        low, high, c - low**3 - low,
    )
    np.testing.assert_allclose(roots, cardano(c), rtol=0, atol=2e-14)
