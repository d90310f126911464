"""An independent warp check for the toolbox tests: the warp of output rulings recomputed
here from the geometry, with none of the kernel's warp code.

The warp of a ruling R with edge tangents T1, T2 at its ends is the angle between the
normal vectors N1 = R × T1 and N2 = R × T2. Here it comes from the triple product
(N1 × N2 = R·det[R, T1, T2], so |N1 × N2| = |R|·|det|) and Lagrange's identity
(N1·N2 = |R|²(T1·T2) − (R·T1)(R·T2)), not from the normals themselves. Undefined (NaN):
a ruling of zero length, or one along an edge tangent (|R × T| ≤ 1e-9·|R||T|). Inside a
fan (an end shared with every neighbouring ruling: both inside, the one neighbour of the
first and last rulings) the end takes the other end's plane.
"""

from __future__ import annotations

import numpy as np

#: |R × T| / (|R||T|) below this: the ruling runs along the tangent, no plane.
ALONG = 1e-9
#: A one-sided tangent jump above this (rad) is a corner.
CORNER = 1e-6


def _rows(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    return np.einsum("ij,ij->i", x, y)


def warp(a: np.ndarray, b: np.ndarray, ta: np.ndarray, tb: np.ndarray,
         apex_a: np.ndarray | None = None, apex_b: np.ndarray | None = None) -> np.ndarray:
    """Warp angles in [0, π] of rulings a → b with edge tangents ta, tb (NaN where undefined)."""
    r = b - a
    n = len(r)
    apex_a = np.zeros(n, bool) if apex_a is None else np.asarray(apex_a, bool)
    apex_b = np.zeros(n, bool) if apex_b is None else np.asarray(apex_b, bool)
    ta = np.where(apex_a[:, None], tb, ta)  # the other end's plane: same tangent, same normal
    tb = np.where(apex_b[:, None], ta, tb)
    rr = _rows(r, r)
    length = np.sqrt(rr)
    det = _rows(r, np.cross(ta, tb))
    dot = rr * _rows(ta, tb) - _rows(r, ta) * _rows(r, tb)
    angle = np.arctan2(length * np.abs(det), dot)
    size = np.linalg.norm(np.ptp(np.vstack([a, b]), axis=0))
    for t in (ta, tb):
        along = np.linalg.norm(np.cross(r, t), axis=1) <= ALONG * length * np.linalg.norm(t, axis=1)
        angle[along] = np.nan
    angle[(length <= 1e-12 * size) | (apex_a & apex_b)] = np.nan
    return angle


def shared_both_sides(points: np.ndarray) -> np.ndarray:
    """Rows whose point equals every neighbour's (in a fan through it)."""
    size = float(np.linalg.norm(np.ptp(points, axis=0))) or 1.0
    same = np.linalg.norm(np.diff(points, axis=0), axis=1) <= 1e-12 * size
    inside = np.zeros(len(points), bool)
    inside[1:-1] = same[:-1] & same[1:]
    if len(same):
        inside[0] |= same[0]
        inside[-1] |= same[-1]
    return inside


def curve_tangents(curve, points: np.ndarray, rulings: np.ndarray, other: np.ndarray) -> np.ndarray:
    """Tangents of ``curve`` at the ``points`` on it; at a corner, a tangent of the corner's
    cone in the plane of the ruling and ``other`` where one exists (else the better side)."""
    t = curve.closest_point(points).parameters
    tangent = curve.derivatives(t, 1)[1]
    step = 1e-9
    left = curve.derivatives(np.clip(t - step, 0, 1), 1)[1]
    right = curve.derivatives(np.clip(t + step, 0, 1), 1)[1]
    lu = left / np.linalg.norm(left, axis=1)[:, None]
    ru = right / np.linalg.norm(right, axis=1)[:, None]
    corner = np.arccos(np.clip(_rows(lu, ru), -1, 1)) > CORNER
    for i in np.flatnonzero(corner):
        f_left = float(np.dot(rulings[i], np.cross(other[i], lu[i])))
        f_right = float(np.dot(rulings[i], np.cross(other[i], ru[i])))
        if f_left * f_right <= 0:  # the plane through ruling and other tangent splits the corner
            if f_left == f_right == 0:
                tangent[i] = other[i]
            else:
                tangent[i] = (f_right * lu[i] - f_left * ru[i]) / (f_right - f_left)
        else:
            pick = [lu[i], ru[i]]
            w = [warp(points[i:i + 1] * 0, rulings[i:i + 1], p[None], other[i:i + 1])[0] for p in pick]
            tangent[i] = pick[int(np.nanargmin(w))]
    return tangent


def strip_between_curves(curve_a, curve_b, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Warp of rulings a → b between two curves, with the curves' own tangents."""
    r = b - a
    ta0 = curve_a.derivatives(curve_a.closest_point(a).parameters, 1)[1]
    tb0 = curve_b.derivatives(curve_b.closest_point(b).parameters, 1)[1]
    ta = curve_tangents(curve_a, a, r, tb0)
    tb = curve_tangents(curve_b, b, r, ta0)
    return warp(a, b, ta, tb, shared_both_sides(a), shared_both_sides(b))


def central(points: np.ndarray) -> np.ndarray:
    """Polyline tangents: (P[i+1] − P[i−1]) / 2 inside, one-sided differences at the ends."""
    t = np.empty_like(points)
    t[1:-1] = 0.5 * (points[2:] - points[:-2])
    t[0], t[-1] = points[1] - points[0], points[-1] - points[-2]
    return t
