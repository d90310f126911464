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

from ..curve_base import Curve, FloatArray
from .warp import warp_angles

IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]

#: Samples of the coplanarity function used to bracket the end ruling's root.
SAMPLES = 33


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
    through_b = _root(_Pencil(curve_a, curve_b, t0, fixed_a=False), s0, sk)
    if through_b is not None and not np.any(stations & (run_s > through_b) & (run_s < sk)):
        keep = (run_s < through_b) & stations  # the stations the cone through B(t0) covers
        head_s = np.append(run_s[keep], through_b)
        head_t = np.full(len(head_s), t0)
    else:
        through_a = _root(_Pencil(curve_a, curve_b, s0, fixed_a=True), t0, tk)
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


class _Pencil:
    """The rulings from a fixed point of one curve (``A(s)`` when ``fixed_a``, else
    ``B(t)``) to the points of the other: the fixed end is evaluated once."""

    def __init__(self, curve_a: Curve, curve_b: Curve, fixed: float, fixed_a: bool) -> None:
        self.curve_a, self.curve_b, self.fixed_a = curve_a, curve_b, fixed_a
        self.offset = curve_b.anchor - curve_a.anchor
        still = curve_a if fixed_a else curve_b
        self.point, self.tangent = still.local_derivatives(np.array([fixed]), 1)

    def values(self, x: FloatArray, warp: bool = True) -> tuple[FloatArray, FloatArray | None]:
        """The coplanarity det[B − A, Â', B̂'] and (with ``warp``) the signed warp (−π…π) of
        the rulings to the moving curve's parameters ``x``."""
        moving = self.curve_b if self.fixed_a else self.curve_a
        p, dp = moving.local_derivatives(np.atleast_1d(x), 1)
        q, dq = np.broadcast_to(self.point, p.shape), np.broadcast_to(self.tangent, p.shape)
        a, da, b, db = (q, dq, p, dp) if self.fixed_a else (p, dp, q, dq)
        b = b + self.offset
        ua = da / np.linalg.norm(da, axis=1, keepdims=True)
        ub = db / np.linalg.norm(db, axis=1, keepdims=True)
        f = np.einsum("ij,ij->i", b - a, np.cross(ua, ub))
        return f, warp_angles(a, b, da, db, signed=True) if warp else None


def _root(pencil: _Pencil, low: float, high: float) -> float | None:
    """The parameter in (low, high), nearest ``high``, of the moving end of a torsal ruling
    of ``pencil`` with consistently oriented normals (signed warp near 0, not near π), or
    None: bracketed on :data:`SAMPLES` samples (one vectorised evaluation, which also tells
    the orientation), then refined by the Illinois variant of regula falsi."""
    if not high > low:
        return None
    x = np.linspace(low, high, SAMPLES)
    with np.errstate(invalid="ignore", divide="ignore"):
        y, signed = pencil.values(x)
    if not np.isfinite(y).all():
        return None
    oriented = np.isfinite(signed) & (np.abs(signed) < 0.5 * np.pi)
    changes = np.flatnonzero((np.sign(y[:-1]) * np.sign(y[1:]) < 0) & (oriented[:-1] | oriented[1:]))
    for i in changes[::-1]:
        def f(v: float) -> float:
            return float(pencil.values(np.array([v]), warp=False)[0][0])

        root = _illinois(f, x[i], x[i + 1], y[i], y[i + 1], first=_inverse_cubic(x, y, i))
        _, at_root = pencil.values(np.array([root]))
        if np.isfinite(at_root[0]) and abs(at_root[0]) < 0.5 * np.pi:
            return float(root)
    return None


def _inverse_cubic(x: FloatArray, y: FloatArray, i: int) -> float | None:
    """Where the cubic through the samples around the sign change between ``i`` and
    ``i + 1`` (as x of y) crosses zero: the refinement's first trial (None where the
    samples there do not run one way)."""
    j = min(max(i - 1, 0), len(x) - 4)
    ys, xs = y[j : j + 4], x[j : j + 4]
    if len(ys) < 4 or not (np.all(np.diff(ys) > 0) or np.all(np.diff(ys) < 0)):
        return None
    # Lagrange interpolation of x as a function of y, at y = 0
    total = 0.0
    for m in range(4):
        others = np.delete(ys, m)
        total += xs[m] * float(np.prod(others / (others - ys[m])))
    return total if x[i] < total < x[i + 1] else None


def _illinois(
    f, x0: float, x1: float, f0: float, f1: float, first: float | None = None, iterations: int = 60
) -> float:
    """A root of ``f`` in the bracket [x0, x1] (f0, f1 of opposite signs) to rounding,
    trying ``first`` before the first secant step."""
    side = 0
    for step in range(iterations):
        x = first if step == 0 and first is not None else x1 - f1 * (x1 - x0) / (f1 - f0)
        if not (min(x0, x1) <= x <= max(x0, x1)):
            x = 0.5 * (x0 + x1)
        fx = f(x)
        if fx == 0.0 or abs(x1 - x0) <= 4.0 * np.finfo(float).eps * max(abs(x), 1.0):
            return x
        if np.sign(fx) == np.sign(f1):
            x1, f1 = x, fx
            if side == 1:
                f0 *= 0.5
            side = 1
        else:
            x0, f0 = x, fx
            if side == -1:
                f1 *= 0.5
            side = -1
    return x
