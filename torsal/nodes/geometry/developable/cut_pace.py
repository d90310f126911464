"""Where a cut strip's developable pairing jumps, found on the pairing itself.

Between a strip's rulings each point A(x) of rail A is paired with its developable partner
B(τ(x)) on rail B (:func:`~torsal.nodes.geometry.torsal_pairing.torsal_partners`,
:mod:`.trimmed`'s sheet). τ is not continuous everywhere: where the pairing turns from a
root to a cone (rail B stands still, :func:`~torsal.nodes.geometry.torsal_pairing.
switches`), or next to a ruling that closes a fan and is not exactly torsal itself, τ
jumps, by up to most of its ruling interval: the sheet there is a cone with its apex at
A(x) that sweeps B from one side of the jump to the other (1.4 m of a ring on the double
bump).

The sheet's pace is a monotone cubic through the partners at the lines it samples, so a
jump between two samples became a steep ramp wherever the samples happened to lie:
between whichever two lines the cut had pinned (the corners', the refinement's), so the
cone's apex, and with it the sheet's normals along the swept stretch of B, moved with the
sampling (the same design in millimetres and in metres creased 0.174 and 0.131 rad along
one ring). :func:`jumps` locates each jump by bisection on the pairing itself (to
:data:`BISECTIONS` halvings of the samples' gap) and gives the ramp the pace takes across
it: :data:`RAMP` of the ruling interval either side of it, placed by the geometry alone.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike

from ..array_types import FloatArray
from ..curve_base import Curve

#: Halvings of the gap between two sampled lines to a jump of the pairing (to ~5e-9 of the
#: ruling interval, well inside the ramp; each is a call of the partner search).
BISECTIONS = 24
#: Halvings of the gap between two lines to where an edge turns onto the trim across a
#: ramp (to rounding: the cone sweeps metres of the rail in 1e-5 of the interval).
TURN_BISECTIONS = 60
#: A step of τ larger than this share of its ruling interval between two lines that
#: close (after :data:`BISECTIONS`) is a jump.
STEP = 1e-3
#: The pace crosses a jump between two lines this share of the ruling interval either side
#: of it (the cone's apex moves by that much of rail A).
RAMP = 1e-5
#: After this many bisections only the pairs whose step of τ is still more than this share
#: of their first are followed on (a continuous τ's step shrinks with the gap, ~2^-8).
EARLY, SHRUNK = 8, 0.1
#: Pairs of sampled lines whose τ rises faster than this many times their ruling
#: interval's mean slope are looked into.
STEEP = 2.0
#: Samples of each stretch of a cut strip's edges whose length sets its share of the
#: strip's parameter (:func:`by_length`).
BY_LENGTH = 8
#: Ends of stretches of the pace closer than this (of the strip's parameter) are one.
SAME = 1e-12


def jumps(partners: Callable[[FloatArray], FloatArray], x: FloatArray, tau: FloatArray,
          rulings: FloatArray, skip: np.ndarray) -> FloatArray:
    """The ramps (n, 2) of x across which the pace crosses a jump of ``partners`` (rail B's
    parameter of A(x)'s partner), from its samples ``tau`` at ``x`` (sorted, the
    ``rulings`` among them, their τ their own u); the ruling intervals marked in ``skip``
    (fans: τ = x) have none. Each ramp lies between the two samples either side of its
    jump, within :data:`RAMP` of its interval of the jump's bracket."""
    x, tau = np.asarray(x, dtype=float), np.asarray(tau, dtype=float)
    # a pair of samples is in the interval of its left one (the interval's right ruling too)
    pair = np.clip(np.searchsorted(rulings, 0.5 * (x[:-1] + x[1:]), side="right") - 1, 0, len(rulings) - 2)
    width = rulings[pair + 1] - rulings[pair]
    dx, dtau = np.diff(x), np.abs(np.diff(tau))
    look = ~skip[pair] & (dx > 0.0) & (dtau > STEEP * dx) & (dtau > STEP * width)
    if not look.any():
        return np.empty((0, 2))
    k = np.flatnonzero(look)
    lo, hi = x[k].copy(), x[k + 1].copy()
    t_lo, t_hi = tau[k].copy(), tau[k + 1].copy()
    first = np.abs(t_hi - t_lo)
    for step in range(BISECTIONS):
        if step == EARLY:  # a continuous τ's step has shrunk with the gap by now, a jump's not
            going = np.abs(t_hi - t_lo) > SHRUNK * first
            k, lo, hi, t_lo, t_hi = k[going], lo[going], hi[going], t_lo[going], t_hi[going]
            if not len(k):
                return np.empty((0, 2))
        mid = 0.5 * (lo + hi)
        t_mid = np.asarray(partners(mid), dtype=float)
        left = np.abs(t_mid - t_lo) >= np.abs(t_hi - t_mid)
        lo, t_lo = np.where(left, lo, mid), np.where(left, t_lo, t_mid)
        hi, t_hi = np.where(left, mid, hi), np.where(left, t_mid, t_hi)
    found = np.abs(t_hi - t_lo) > STEP * width[k]
    k, lo, hi = k[found], lo[found], hi[found]
    half = RAMP * width[k]
    return np.column_stack([np.maximum(lo - half, x[k]), np.minimum(hi + half, x[k + 1])])


class Paced(Curve):
    """``curve`` run at another pace: its parameters ``at`` reached at ``knots`` (both
    increasing, from 0 to 1), linearly between them. ``jumps``: the knots at a ramp's ends
    (:func:`jumps`), where the speeds of a cut strip's two edges change a millionfold
    within a sliver of the parameter (a cone's apex stands still on A while B sweeps): no
    single pace of the two makes both edges' speeds continuous there, and a fitted rail
    wants a triple knot at each (:mod:`torsal.nodes.io.formats.threedm_strips`)."""

    def __init__(self, curve: Curve, at: FloatArray, knots: FloatArray,
                 jumps: FloatArray | None = None) -> None:
        self.curve, self.at, self.knots = curve, at, knots
        self.jumps = np.empty(0) if jumps is None else np.asarray(jumps, dtype=float)

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        t = np.clip(np.atleast_1d(np.asarray(t, dtype=float)), 0.0, 1.0)
        k = np.clip(np.searchsorted(self.knots, t, side="right") - 1, 0, len(self.knots) - 2)
        rate = (self.at[k + 1] - self.at[k]) / (self.knots[k + 1] - self.knots[k])
        out = self.curve.derivatives(self.at[k] + (t - self.knots[k]) * rate, order)
        return [value * rate[:, None] ** d for d, value in enumerate(out)]

    def _breakpoints(self) -> FloatArray:
        inner = np.interp(self.curve._breakpoints(), self.at, self.knots)
        return np.unique(np.clip(np.concatenate([self.knots, inner]), 0.0, 1.0))


def by_length(lower: Curve, upper: Curve, s: FloatArray, breaks: FloatArray, ramps: FloatArray,
              x0: float, x1: float) -> tuple[Paced, Paced, FloatArray]:
    """Both edges of a cut strip (curves linear in the sheet's u from ``x0`` to ``x1``, its
    lines at ``s``) run at one pace by their length instead: between the ``breaks`` (the
    kept lines, the chains' joins) and the ends of the pace's ``ramps``, each stretch takes
    its share of the parameter by the two edges' summed length (:data:`BY_LENGTH` samples a
    stretch), linearly within it. A cone that sweeps 1.4 m of rail B across a jump of the
    pairing in 1e-5 of u so gets its share, and an even grid of the strip's parameters sees
    it (a preview, a coverage check). Returns the two edges and the lines' new parameters.

    Linear within each stretch, not a C1 cubic through the stretches' ends: a stretch
    keeps the smoothness its edges have in the sheet's u, and a fitted rail follows a step
    of speed at a ruling (a face's end, or a double knot) or at a ramp's end (a triple
    knot) exactly. A C1 cubic (scipy's PCHIP) bends the pace inside a stretch next to a much
    steeper one (a short fan) and made the double bump's exported rails miss by 5.3e-5 of
    the size where they now keep within 1.1e-6 (docs/geometry.md)."""
    inside = (ramps[(ramps > x0) & (ramps < x1)] - x0) / (x1 - x0)
    at = np.unique(np.clip(np.concatenate([breaks, inside, [0.0, 1.0]]), 0.0, 1.0))
    # (a chain's join at a kept line may differ from it by a rounding: one end, not a
    # stretch of no length whose pace would stand both edges still)
    at = at[np.concatenate([[True], np.diff(at) > SAME])]
    share = np.linspace(0.0, 1.0, BY_LENGTH + 1)
    c = (at[:-1, None] + np.diff(at)[:, None] * share).ravel()
    steps = sum(np.linalg.norm(np.diff(edge.point_at(c).reshape(len(at) - 1, -1, 3), axis=1), axis=2)
                for edge in (lower, upper)).sum(axis=1)
    steps = np.maximum(steps, 1e-9 * max(float(steps.sum()), 1e-300))  # (no stretch of no length)
    knots = np.concatenate([[0.0], np.cumsum(steps)]) / float(steps.sum())
    knots[-1] = 1.0
    ramp_ends = np.interp(inside, at, knots)
    return Paced(lower, at, knots, ramp_ends), Paced(upper, at, knots, ramp_ends), np.interp(s, at, knots)
