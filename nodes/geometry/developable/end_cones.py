"""Closing a strip's ends with one smooth cone instead of a creased pair of triangle fans.

Where the curves' ends admit no torsal ruling (A(0)'s torsal partner would lie before
B(0), say), the strip is closed by triangles from the end of the curves to the first
torsal ruling. Closed one way — a fan through B(0) over A up to the first torsal
*station*, then a fan through that station's point of A over B up to its partner — the
sheet folds along the ruling where the apex changes. But there is a torsal ruling that
passes through B(0) itself: A(s*) → B(0), with s* between the last fan station and the
first torsal one. Closing with the single cone through B(0) over A[0, s*] and joining the
torsal rulings at A(s*) → B(0) leaves no fold: along that ruling the cone's tangent plane
(the ruling and A'(s*)) is the torsal strip's (the ruling, A'(s*) and B'(0)). So the end
is smooth (G1) and exactly developable, and the strip still reaches both curves' ends.

This module finds that ruling (or the one through A(0) over B, whichever the geometry
gives) and rewrites the first run of fan rulings; the last run is done on the reversed
curves. Where the fan run holds a station strictly inside the new torsal stretch (the
solve found no torsal partner for it, so the stretch is not known to be torsal), or no
such ruling exists, the run is left as it was.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq

from ..curve_base import Curve, FloatArray
from .warp import warp_angles

IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]

#: Samples of the coplanarity function used to bracket the end ruling's root.
SAMPLES = 65


@dataclass(frozen=True)
class Rulings:
    """The strip's rulings as parameters: per ruling s, t, the station it is (−1 when
    added) and whether it is a fan ruling."""

    s: FloatArray
    t: FloatArray
    source: IntArray
    fan: BoolArray

    def reversed(self) -> Rulings:
        return Rulings(1.0 - self.s[::-1], 1.0 - self.t[::-1], self.source[::-1], self.fan[::-1])


def smooth_ends(curve_a: Curve, curve_b: Curve, rulings: Rulings) -> Rulings:
    """``rulings`` with each end's run of fans made one cone where that is possible (see
    the module). Not for a closed B, whose partners may run through its seam. Rulings
    away from the ends keep their parameters bit for bit."""
    if curve_b.closed or rulings.fan.all() or not rulings.fan.any():
        return rulings
    fix = _head(curve_a, curve_b, rulings)
    if fix is not None:
        head, k, source_k = fix
        rest = rulings.source[k:].copy()
        rest[0] = source_k
        rulings = Rulings(
            np.concatenate([head.s, rulings.s[k:]]), np.concatenate([head.t, rulings.t[k:]]),
            np.concatenate([head.source, rest]), np.concatenate([head.fan, rulings.fan[k:]]),
        )
    fix = _head(curve_a.reversed(), curve_b.reversed(), rulings.reversed())
    if fix is not None:
        head, k, source_k = fix
        tail = head.reversed()
        m = len(rulings.s) - k  # rulings[m:] are replaced by the tail, rulings[m - 1] gets source_k
        rest = rulings.source[:m].copy()
        rest[-1] = source_k
        rulings = Rulings(
            np.concatenate([rulings.s[:m], tail.s]), np.concatenate([rulings.t[:m], tail.t]),
            np.concatenate([rest, tail.source]), np.concatenate([rulings.fan[:m], tail.fan]),
        )
    return rulings


def _head(curve_a: Curve, curve_b: Curve, r: Rulings) -> tuple[Rulings, int, int] | None:
    """The rulings that replace the first ``k`` (the run of fans before the first torsal
    ruling): a cone's rulings and the torsal ruling through the curve's end point; with
    ``k`` and the station index the first torsal ruling carries from then on. None when
    the start is one cone already or cannot be made one."""
    k = int(np.argmin(r.fan))  # the first torsal ruling
    if k == 0:
        return None
    s0, t0, sk, tk = r.s[0], r.t[0], r.s[k], r.t[k]
    if np.all(r.s[: k + 1] == s0) or np.all(r.t[: k + 1] == t0):
        return None  # already one cone
    run_s, run_t, run_source = r.s[:k], r.t[:k], r.source[:k]
    stations = run_source >= 0
    def on_a(s: FloatArray) -> FloatArray:
        return _coplanarity(curve_a, curve_b, s, t0)

    def on_b(t: FloatArray) -> FloatArray:
        return _coplanarity(curve_a, curve_b, s0, t)

    through_b = _root(on_a, curve_a, curve_b, s0, sk, t0, True)
    if through_b is not None and not np.any(stations & (run_s > through_b) & (run_s < sk)):
        keep = (run_s < through_b) & stations  # the stations the cone through B(t0) covers
        head_s = np.append(run_s[keep], through_b)
        head_t = np.full(len(head_s), t0)
    else:
        through_a = _root(on_b, curve_a, curve_b, t0, tk, s0, False)
        if through_a is None or np.any(stations & (run_s > s0)):
            return None
        keep = (run_t < through_a) & (run_s == s0)  # the cone through A(s0) over B[t0, t*]
        head_s = np.append(run_s[keep], s0)
        head_t = np.append(run_t[keep], through_a)
    head_source = np.append(run_source[keep], -1).astype(np.int64)
    dropped = set(run_source[stations].tolist()) - set(run_source[keep].tolist())
    source_k = int(r.source[k])
    if dropped and source_k < 0:  # a fan ruling of the station at the first torsal ruling's s
        source_k = min(dropped)
    head_fan = np.append(np.ones(int(keep.sum()), dtype=bool), False)
    return Rulings(head_s, head_t, head_source, head_fan), k, source_k


def _coplanarity(curve_a: Curve, curve_b: Curve, s: FloatArray, t: FloatArray) -> FloatArray:
    """det[B(t) − A(s), Â'(s), B̂'(t)] (unit tangents), vectorised over s or t."""
    s, t = np.broadcast_arrays(np.atleast_1d(s), np.atleast_1d(t))
    a, da = curve_a.local_derivatives(s, 1)
    b, db = curve_b.local_derivatives(t, 1)
    ruling = b + (curve_b.anchor - curve_a.anchor) - a
    da = da / np.linalg.norm(da, axis=1, keepdims=True)
    db = db / np.linalg.norm(db, axis=1, keepdims=True)
    return np.einsum("ij,ij->i", ruling, np.cross(da, db))


def _root(
    f, curve_a: Curve, curve_b: Curve, low: float, high: float, fixed: float, moving_a: bool
) -> float | None:
    """The root of ``f`` in (low, high) nearest ``high`` whose ruling has consistently
    oriented normals (signed warp near 0, not near π), or None."""
    if not high > low:
        return None
    x = np.linspace(low, high, SAMPLES)
    with np.errstate(invalid="ignore", divide="ignore"):
        y = f(x)
    if not np.isfinite(y).all():
        return None
    changes = np.flatnonzero(np.sign(y[:-1]) * np.sign(y[1:]) < 0)
    for i in changes[::-1]:
        root = brentq(lambda v: float(f(np.array([v]))[0]), x[i], x[i + 1], xtol=1e-15)
        s, t = (root, fixed) if moving_a else (fixed, root)
        a, da = curve_a.derivatives(np.array([s]), 1)
        b, db = curve_b.derivatives(np.array([t]), 1)
        signed = warp_angles(a, b, da, db, signed=True)[0]
        if np.isfinite(signed) and abs(signed) < 0.5 * np.pi:
            return float(root)
    return None
