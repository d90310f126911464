"""How much of a surface is single-curved: the flatness measure and its area share.

A point is single-curved within a tolerance when min(|k1|, |k2|) <= tol. Measured at
mesh vertices only, a thin band of single curvature (a torus's top circle) would
count a whole row of vertex areas or nothing; so the share of area is integrated
over the triangles, each with the measure interpolated linearly between its
corners, exactly (:func:`share_within`).

The measure interpolated is the *signed* flatness ``sign(K)·min(|k1|, |k2|)``: it
is continuous where the flatter direction swaps from k1 to k2 (on a saddle, where
k1 = −k2, the unsigned smaller curvature keeps its size but would flip sign if taken
from k1 or k2 directly) and passes through zero where the surface turns from
dome-like to saddle-like, which is exactly where it is single-curved.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from torsal.nodes.geometry.array_types import FloatArray


def signed_flatness(k1: ArrayLike, k2: ArrayLike) -> FloatArray:
    """``sign(k1·k2)·min(|k1|, |k2|)``: 0 where single-curved, continuous across umbilics."""
    a, b = np.asarray(k1, dtype=float), np.asarray(k2, dtype=float)
    return np.sign(a * b) * np.minimum(np.abs(a), np.abs(b))


def _below(t: float, g0: FloatArray, g1: FloatArray, g2: FloatArray) -> FloatArray:
    """Share of each triangle's area where a linear function with sorted corner values
    g0 <= g1 <= g2 is at most ``t`` (piecewise quadratic in t)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        rising = (t - g0) ** 2 / ((g1 - g0) * (g2 - g0))
        falling = 1.0 - (g2 - t) ** 2 / ((g2 - g1) * (g2 - g0))
    return np.where(t >= g2, 1.0, np.where(t < g0, 0.0, np.where(t <= g1, rising, falling)))


def share_within(values: ArrayLike, faces: ArrayLike, tolerance: float) -> FloatArray:
    """Per triangle, the share of its area where |value| <= ``tolerance``, with the
    vertex ``values`` interpolated linearly over each triangle (exact for that
    interpolation). ``faces`` is ``(f, 3)`` vertex indices."""
    g = np.sort(np.asarray(values, dtype=float)[np.asarray(faces)], axis=1)
    g0, g1, g2 = g[:, 0], g[:, 1], g[:, 2]
    upper = _below(tolerance, g0, g1, g2)
    # below −tol: the complement of "−value <= tol", whose sorted corners are −g2, −g1, −g0
    lower = 1.0 - _below(tolerance, -g2, -g1, -g0)
    share = np.clip(upper - lower, 0.0, 1.0)
    return np.where(np.isfinite(share), share, 0.0)


def area_fraction(values: ArrayLike, faces: ArrayLike, areas: ArrayLike, tolerance: float) -> float:
    """The share of the total area (triangle ``areas``) where |value| <= ``tolerance``."""
    a = np.asarray(areas, dtype=float)
    total = float(a.sum())
    if not total > 0:
        return 0.0
    return min(1.0, float(np.dot(a, share_within(values, faces, tolerance)) / total))
