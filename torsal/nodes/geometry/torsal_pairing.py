"""The developable pairing of two rails between a strip's rulings.

A strip between curves A and B is solved at stations: rulings A(u_i) → B(u_i) that are
torsal (the tangent plane is the same all along them). Between stations the strip's rails
pair A(u) with B(u) at an interpolated pace, which is not torsal in general, so the
surface twists a little there. :func:`torsal_partners` pairs each A(u) between stations
with the point of B that makes the ruling developable:

- a point B(w), w between the two stations, where det(A'(u), B'(w), B(w) − A(u)) = 0
  (found by scipy's bracketing root finder, Chandrupatla's method, vectorised);
- where there is none, the end of the interval at which rail B stands still (its speed
  is least): rulings through one point of B make a cone, which is developable whatever A
  does — the continuation of a fan.

:func:`switches` finds where the pairing changes from one kind to the other (the
pairing has a kink there), so a fit can put a knot on it.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize.elementwise import find_root

from .curve_base import Curve, FloatArray

#: How the partner of a parameter was found.
SAME, ROOT, CONE = 0, 1, 2


def torsal_partners(rail_a: Curve, rail_b: Curve, stations: FloatArray, at: FloatArray,
                    steps: FloatArray | None = None) -> tuple[FloatArray, np.ndarray]:
    """For each rail-A parameter ``at`` (within ``stations``, increasing), the rail-B
    parameter of its developable partner and how it was found (:data:`SAME` at a station,
    :data:`ROOT` or :data:`CONE`). Where rail B stands still its direction is its chord over
    ± the step (``steps``, one per parameter; by default 1e-5 of the stations' range), so
    many spans' parameters are found in one call as each span's would be alone."""
    at = np.asarray(at, dtype=float)
    i = np.clip(np.searchsorted(stations, at, side="right") - 1, 0, len(stations) - 2)
    lo, hi = stations[i], stations[i + 1]
    point_a, tangent_a = rail_a.derivatives(at, 1)
    tangent_a = _unit(tangent_a)
    if steps is None:
        steps = np.full(len(at), 1e-5 * float(stations[-1] - stations[0]))

    def tangent_b(w: FloatArray, step: FloatArray) -> tuple[FloatArray, FloatArray]:
        point, tangent = rail_b.derivatives(w, 1)
        speed = np.linalg.norm(tangent, axis=1)
        slow = speed < 1e-6 * max(float(speed.max()), 1e-300)
        if slow.any():  # where the rail stands still its direction is its chord's
            tangent[slow] = rail_b.point_at(w[slow] + step[slow]) - rail_b.point_at(w[slow] - step[slow])
        return point, _unit(tangent)

    def warp(w: FloatArray, *columns: FloatArray) -> FloatArray:
        shape = np.shape(w)
        point, tangent = tangent_b(np.ravel(w), np.ravel(columns[6]))
        a = np.column_stack([np.ravel(c) for c in columns[:3]])
        t = np.column_stack([np.ravel(c) for c in columns[3:6]])
        ruling = _unit(point - a)
        return np.einsum("ij,ij->i", np.cross(t, tangent), ruling).reshape(shape)

    columns = (*point_a.T, *tangent_a.T, np.asarray(steps, dtype=float))
    partner, kind = at.copy(), np.full(len(at), SAME)
    inner = (at > lo) & (at < hi)
    bracket = inner & (np.sign(warp(lo, *columns)) * np.sign(warp(hi, *columns)) < 0)
    if bracket.any():
        found = find_root(warp, (lo[bracket], hi[bracket]), args=tuple(c[bracket] for c in columns),
                          tolerances={"xatol": 1e-15, "xrtol": 1e-15})
        partner[bracket] = np.where(found.success, found.x, at[bracket])
        kind[bracket] = np.where(found.success, ROOT, SAME)
    cone = inner & ~bracket
    if cone.any():
        slow_lo = np.linalg.norm(rail_b.derivatives(lo[cone], 1)[1], axis=1)
        slow_hi = np.linalg.norm(rail_b.derivatives(hi[cone], 1)[1], axis=1)
        partner[cone] = np.where(slow_lo <= slow_hi, lo[cone], hi[cone])
        kind[cone] = CONE
    return partner, kind


def switches(rail_a: Curve, rail_b: Curve, stations: FloatArray, per: int = 48,
             halvings: int = 40) -> FloatArray:
    """The parameters where the pairing changes kind between stations (to ``halvings``
    bisections of the ``per`` samples per interval that first see it)."""
    lower = np.linspace(0.0, 1.0, per + 1)[:-1]
    at = (stations[:-1, None] + (stations[1:] - stations[:-1])[:, None] * lower).ravel()
    inner = at[np.isin(at, stations, invert=True)]
    _, kind = torsal_partners(rail_a, rail_b, stations, inner)
    interval = np.searchsorted(stations, inner, side="right")
    change = np.flatnonzero((kind[1:] != kind[:-1]) & (interval[1:] == interval[:-1]))
    if not len(change):
        return np.empty(0)
    left, right, first = inner[change], inner[change + 1], kind[change]
    for _ in range(halvings):
        middle = (left + right) / 2
        _, now = torsal_partners(rail_a, rail_b, stations, middle)
        same = now == first
        left, right = np.where(same, middle, left), np.where(same, right, middle)
    return (left + right) / 2


def _unit(vectors: FloatArray) -> FloatArray:
    return vectors / np.maximum(np.linalg.norm(vectors, axis=1), 1e-300)[:, None]
