"""What a ruled face of an exported strip holds exactly (:mod:`.threedm_strips`).

A face over several of a strip's rulings is fitted by least squares between them, but at
each ruling inside it (a double knot of its rails) the two control points there are fixed
so that the face's line at that u is the ruling itself and the rails' tangents there are
the strip's own (:func:`pinned`, from :func:`slopes_at`): the normals at the two ends of
the node's torsal rulings then agree on the face as they do on the strip (a least-squares
fit missed them by up to 5.5e-7 rad on the rationalise-canopy example). At a face's end
the end control point and the next one hold the ruling and the tangents the same way;
where a rail stands still there (next to a fan) its tangent is zero and the face's normal
at that corner comes from the rail's second derivative, held too (:func:`end_bends`).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy.interpolate import BSpline

from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.io.formats.threedm_rails import Rails
from torsal.nodes.io.formats.threedm_unstall import STALLED
from torsal.nodes.io.formats.threedm_untwist import derivative_basis


def slopes_at(strip: RuledSurface | Rails, span: np.ndarray,
              partner: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
    """Both rails' slopes at the rulings of ``span`` (rows: A's then B's), B at ``partner``
    of A's parameter: at the face's ends from inside (at a corner of a rail, as on a strip
    cut to a trim, or where its speed jumps, as where the pieces of a joined rail meet, the
    face's own side of it), at a ruling inside it the mean of its two sides. A's own; B's
    own for the strip's own pairing, else its pace from a difference of the partner points
    (where B's pace stands still at a ruling the partner parameter moves like a square root
    while the point moves smoothly) in the direction of B's own tangent where it has one
    (a difference of a partner moving like a square root turns by ~√step)."""
    lo, hi = float(span[0]), float(span[-1])
    step, tiny = 1e-7 * (hi - lo), 1e-12 * (hi - lo)
    probe = np.array([lo + step, hi - step])
    own_pairing = np.array_equal(partner(probe), probe)  # (a difference over a short face's
    b_points = strip.curve_b.point_at(span)  # step would carry the points' rounding)
    total, sides = np.zeros((len(span), 6)), np.zeros(len(span))
    for side in (-1.0, 1.0):
        has = span > lo if side < 0 else span < hi
        inside = span[has] + side * tiny
        own = strip.curve_b.derivatives(inside, 1)[1]
        slope_b = own
        if not own_pairing:
            near = strip.curve_b.point_at(partner(span[has] + side * step))
            slope_b = side * (near - b_points[has]) / step
            length = np.linalg.norm(own, axis=1, keepdims=True)
            along = np.einsum("ij,ij->i", slope_b, own)[:, None]
            slope_b = np.where((length > 0) & (along > 0), own / np.maximum(length, 1e-300)
                               * np.linalg.norm(slope_b, axis=1, keepdims=True), slope_b)
        total[has] += np.hstack([strip.curve_a.derivatives(inside, 1)[1], slope_b])
        sides[has] += 1.0
    return total / sides[:, None]


def pinned(knots: np.ndarray, at: np.ndarray, points: np.ndarray,
           slopes: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """The control points of a cubic spline on ``knots`` (double at each of ``at``) that make
    its points and slopes there ``points`` and ``slopes``: (their indices, their values);
    at a double knot just two control points are not zero there, so they are fixed by the
    two. None when a knot at ``at`` is not double (its control points would be shared)."""
    if not len(at):
        return np.empty(0, dtype=int), np.empty((0, 6))
    value = BSpline.design_matrix(at, knots, 3).toarray()
    slope = derivative_basis(at, knots).toarray()
    columns = np.argsort(value == 0.0, axis=1, kind="stable")[:, :2]
    count = (value != 0.0).sum(axis=1)
    if (count != 2).any() or len(np.unique(columns)) != 2 * len(at) or columns.min() < 2 or \
            columns.max() > len(knots) - 7:
        return None
    rows = np.arange(len(at))[:, None]
    system = np.stack([value[rows, columns], slope[rows, columns]], axis=1)  # (k, 2, 2)
    values = np.linalg.solve(system, np.stack([points, slopes], axis=1))  # (k, 2, 6)
    return columns.ravel(), values.reshape(-1, 6)


def end_bends(strip: RuledSurface | Rails, span: np.ndarray, partner: Callable[[np.ndarray], np.ndarray],
              slopes: np.ndarray) -> np.ndarray:
    """Per end of ``span`` and rail (end, rail, xyz), where the rail stands still there (its
    slope in ``slopes`` below :data:`~.threedm_unstall.STALLED` of its mean speed over the
    span): its second derivative there (A's; B's for the strip's own pairing); NaN elsewhere."""
    lo, hi = float(span[0]), float(span[-1])
    inside = np.array([lo + 1e-12 * (hi - lo), hi - 1e-12 * (hi - lo)])
    out = np.full((2, 2, 3), np.nan)
    probe = np.array([lo + 1e-7 * (hi - lo), hi - 1e-7 * (hi - lo)])
    own_pairing = np.array_equal(partner(probe), probe)
    for side, rail in enumerate((strip.curve_a, strip.curve_b)):
        if side == 1 and not own_pairing:
            continue
        points = rail.point_at(span[[0, -1]])
        mean = float(np.linalg.norm(points[1] - points[0])) / max(hi - lo, 1e-300)
        speed = np.linalg.norm(slopes[[0, -1], 3 * side:3 * side + 3], axis=1)
        still = (speed <= STALLED * mean) & (mean > 0)
        if still.any():
            try:
                out[still, side] = rail.derivatives(inside[still], 2)[2]
            except ValueError:  # a rail with no second derivative there
                continue
    return out
