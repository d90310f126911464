"""Polyline approximation of curves by adaptive subdivision on chord deviation."""

from __future__ import annotations

import numpy as np

from .array_types import FloatArray
from .curve_protocol import ParametricCurve


def _distance_to_chords(points: FloatArray, a: FloatArray, b: FloatArray) -> FloatArray:
    """Distance of each point to the segment from ``a`` to ``b`` (row by row)."""
    d = b - a
    dd = np.einsum("ij,ij->i", d, d)
    s = np.einsum("ij,ij->i", points - a, d) / np.where(dd > 0, dd, 1.0)
    foot = a + np.clip(s, 0.0, 1.0)[:, None] * d
    return np.linalg.norm(points - foot, axis=1)


def tessellation_parameters(
    curve: ParametricCurve,
    tolerance: float,
    per_span: int = 4,
    max_points: int = 1_000_000,
    initial: FloatArray | None = None,
) -> FloatArray:
    """Increasing parameters whose polyline stays within ``tolerance`` of the curve.

    Starts from ``per_span`` pieces per smooth span (or from the increasing parameters
    ``initial``, 0 and 1 included); each round measures the curve at
    the quarter, half and three-quarter points of every piece against its chord and
    halves the pieces that deviate by more than ``tolerance``. Features narrower than a
    quarter of a starting piece can be missed.
    """
    if not tolerance > 0:
        raise ValueError(f"The tolerance must be a positive length; got {tolerance}.")
    if initial is None:
        breaks = curve._breakpoints()
        fractions = np.linspace(0.0, 1.0, per_span + 1)[:-1]
        t = np.concatenate(
            [(breaks[:-1, None] + fractions[None, :] * np.diff(breaks)[:, None]).reshape(-1), [1.0]]
        )
    else:
        t = np.asarray(initial, dtype=float)
    quarters = np.array([0.25, 0.5, 0.75])
    while len(t) < max_points:
        a, b = t[:-1], t[1:]
        probe = a[:, None] + quarters[None, :] * (b - a)[:, None]
        ends = curve.point_at(t)
        inner = curve.point_at(probe.reshape(-1)).reshape(len(a), 3, 3)
        deviation = np.max([_distance_to_chords(inner[:, q], ends[:-1], ends[1:]) for q in range(3)], axis=0)
        split = (deviation > tolerance) & (b - a > 1e-12)
        if not split.any():
            break
        t = np.sort(np.concatenate([t, 0.5 * (a[split] + b[split])]))
    return t
