"""Whether two curves are one: the check that refuses a strip between a curve and itself."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from torsal.nodes.geometry.curve_base import Curve

#: Two curves closer than this (relative to their size) everywhere count as one.
COINCIDENT = 1e-9


def coincident(curve_a: Curve, curve_b: Curve) -> bool:
    """Whether every sample of A lies on B and every sample of B on A (to rounding)."""
    if _ends_differ(curve_a, curve_b):
        return False
    t = np.linspace(0.0, 1.0, 17)
    a, b = curve_a.point_at(t), curve_b.point_at(t)
    size = float(np.linalg.norm(np.ptp(np.vstack([a, b]), axis=0)))
    if size == 0.0:
        return True
    # cheap rejection first: a sample of A far from B's dense polyline settles it
    if _polyline_gap(a, curve_b.point_at(np.linspace(0.0, 1.0, 257))) > 1e-3 * size:
        return False
    gap = max(curve_b.closest_point(a).distances.max(), curve_a.closest_point(b).distances.max())
    return bool(gap <= COINCIDENT * size)


def _ends_differ(curve_a: Curve, curve_b: Curve) -> bool:
    """The cheapest rejection: a curve given twice has the same ends (either way round),
    unless both are loops, whose seams may lie anywhere. Ends count as the same within
    1e-6 of their spread (or when all four coincide)."""
    return ends_differ_each([(curve_a, curve_b)])[0]


def ends_differ_each(pairs: Sequence[tuple[Curve, Curve]]) -> list[bool]:
    """:func:`_ends_differ` of every pair of curves of ``pairs``, all at once: those pairs
    are not :func:`coincident`."""
    if not pairs:
        return []
    ends = np.array([np.concatenate([a.end_points, b.end_points]) for a, b in pairs])  # a0, a1, b0, b1
    size = (ends.max(axis=1) - ends.min(axis=1)).max(axis=1)  # (vec_ops.extent of each pair's)
    # the largest coordinate gap of each pair of ends, all six at once
    a0b0, a1b1, a0b1, a1b0, a0a1, b0b1 = (
        np.abs(ends[:, _FIRST] - ends[:, _SECOND]).max(axis=2) <= 1e-6 * size[:, None]
    ).T
    same = (a0b0 & a1b1) | (a0b1 & a1b0)
    return (~(same | (a0a1 & b0b1))).tolist()


#: The pairs of end points :func:`_ends_differ` compares (rows of a0, a1, b0, b1):
#: a0–b0, a1–b1, a0–b1, a1–b0, a0–a1, b0–b1.
_FIRST, _SECOND = np.array([0, 1, 0, 1, 0, 2]), np.array([2, 3, 3, 2, 1, 3])


def _polyline_gap(points: np.ndarray, polyline: np.ndarray) -> float:
    """The largest distance from ``points`` to the polyline through ``polyline`` (vectorised)."""
    start, step = polyline[:-1], np.diff(polyline, axis=0)
    length2 = np.maximum(np.einsum("ij,ij->i", step, step), 1e-300)
    offset = points[:, None, :] - start[None, :, :]
    along = np.clip(np.einsum("pkj,kj->pk", offset, step) / length2, 0.0, 1.0)
    nearest = np.linalg.norm(offset - along[..., None] * step[None], axis=2).min(axis=1)
    return float(nearest.max())
