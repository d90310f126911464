"""Random rational NURBS rails (seeded) and an independent look at their torsal rulings.

The rails are evaluated here with scipy's BSpline on homogeneous control points and the
quotient rule, none of Torsal's curve code. For a point A(s) the torsal partners on B are
the roots of f(t) = det[B(t) − A(s), A'(s), B'(t)], found by dense sampling and brentq;
a root is *oriented* when the normals R × A' and R × B' point to the same side (its
warp is ~0, not ~π): a ruling of a strip whose curves run the same way.
"""

from __future__ import annotations

from bisect import bisect_right

import numpy as np
from scipy.interpolate import BSpline
from scipy.optimize import brentq

from torsal.nodes.geometry.curves import NurbsCurve


class Rational:
    """A clamped rational B-spline on [0, 1], evaluated by scipy alone."""

    def __init__(self, points: np.ndarray, weights: np.ndarray, degree: int = 3) -> None:
        self.points, self.weights, self.degree = np.asarray(points, float), np.asarray(weights, float), degree
        inner = np.linspace(0.0, 1.0, len(self.points) - degree + 1)
        self.knots = np.concatenate([[0.0] * degree, inner, [1.0] * degree])
        homogeneous = np.column_stack([self.points * self.weights[:, None], self.weights])
        self.spline = BSpline(self.knots, homogeneous, degree)

    def derivatives(self, t, order: int = 1) -> list[np.ndarray]:
        """Point and derivatives up to ``order`` (at most 2) by the quotient rule."""
        t = np.atleast_1d(np.asarray(t, float))
        h = [self.spline(t, nu=k) for k in range(order + 1)]
        x, w = [v[:, :3] for v in h], [v[:, 3:] for v in h]
        out = [x[0] / w[0]]
        if order >= 1:
            out.append((x[1] - w[1] * out[0]) / w[0])
        if order >= 2:
            out.append((x[2] - 2 * w[1] * out[1] - w[2] * out[0]) / w[0])
        return out

    def as_torsal(self) -> NurbsCurve:
        """The same curve as Torsal's NurbsCurve, for the node under test."""
        return NurbsCurve.from_arrays(self.points, self.knots, self.degree, self.weights)


def rails(seed: int, near_planar: bool = False, count: int = 7) -> tuple[Rational, Rational]:
    """Two cubic rational rails about 4 long and 1.5 apart, weights 0.5 to 2. Near-planar:
    each rail within 1 % of its own plane, the two planes parallel and 1 apart, wider
    wiggles (the curves' tangents then turn parallel at several places)."""
    rng = np.random.default_rng(seed)
    x = np.linspace(0.0, 4.0, count)
    a = np.column_stack([x, rng.normal(0, 0.3, count), rng.normal(0, 0.5, count)])
    b = np.column_stack([x + rng.normal(0, 0.3, count), 1.5 + rng.normal(0, 0.3, count),
                         rng.normal(0, 0.5, count)])
    if near_planar:
        a[:, 2] *= 0.01
        b[:, 2] = 1.0 + 0.01 * b[:, 2]
        a[:, 1] *= 3.0
        b[:, 1] = 1.5 + 3.0 * (b[:, 1] - 1.5)
    return Rational(a, rng.uniform(0.5, 2.0, count)), Rational(b, rng.uniform(0.5, 2.0, count))


def coplanarity(a, s: float, b, t) -> np.ndarray:
    """f(t) = det[B(t) − A(s), A'(s), B'(t)]."""
    a0, a1 = a.derivatives([s], 1)
    b0, b1 = b.derivatives(t, 1)
    return np.einsum("ij,ij->i", b0 - a0, np.cross(a1, b1))


def warp(a, s, b, t) -> np.ndarray:
    """Angle (0 to π) between R × A' and R × B' of the rulings A(s) → B(t)."""
    a0, a1 = a.derivatives(np.atleast_1d(s), 1)
    b0, b1 = b.derivatives(np.atleast_1d(t), 1)
    r = b0 - a0
    n1, n2 = np.cross(r, a1), np.cross(r, b1)
    return np.arctan2(np.linalg.norm(np.cross(n1, n2), axis=1), np.einsum("ij,ij->i", n1, n2))


def oriented_roots(a, b, s: float, samples: int = 4001) -> np.ndarray:
    """The oriented torsal partners t of A(s) on B, increasing."""
    t = np.linspace(0.0, 1.0, samples)
    f = coplanarity(a, s, b, t)
    found = [brentq(lambda x: coplanarity(a, s, b, [x])[0], t[j], t[j + 1], xtol=1e-15)
             for j in np.flatnonzero(np.sign(f[:-1]) * np.sign(f[1:]) < 0)]
    found += list(t[f == 0.0])
    roots = np.array(sorted(found))
    if len(roots):
        roots = roots[warp(a, np.full(len(roots), s), b, roots) < 1e-6]
    return roots


def longest_chain(roots: list[np.ndarray]) -> int:
    """How many stations the longest chain of roots covers, one root per station, t never
    decreasing (patience sorting; a station's roots taken largest first so that no chain
    takes two of them)."""
    tails: list[float] = []
    for here in roots:
        for x in sorted(here, reverse=True):
            j = bisect_right(tails, x + 1e-12)
            if j == len(tails):
                tails.append(x)
            else:
                tails[j] = min(tails[j], x)
    return len(tails)
