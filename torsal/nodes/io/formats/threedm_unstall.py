"""A cone's moving rail that does not stand still at its ends (:mod:`.threedm_strips`).

A strip's rail may stand still at a ruling in its own curve's parameter (next to a fan
the boundary curve a strip runs on can have no speed at the fan's point). A cone fitted
over such a rail (its apex at rest on the other rail) has a line across where both rails
stand still: its tangent along u is zero there, and Rhino (finding the Jacobian
degenerate) takes that line's normals from second derivatives and the rounding of the
fit, turning them by up to π between its two ends. :class:`Unstalled` runs the rail over
the same interval of u with its curve parameter moving like a square root from a stalled
end (the curve there moves like the square of its parameter, so the point moves at a
finite, nonzero pace): every line across the cone then has a tangent along u, and its
normals agree along it.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from torsal.nodes.geometry.curve_base import Curve

#: A rail whose speed at an end of an interval is below this fraction of its mean speed
#: over the interval (its chord over the interval's length of u) stands still there.
STALLED = 1e-6


def stalled_ends(rail: Curve, lo: float, hi: float) -> tuple[bool, bool]:
    """Whether ``rail`` stands still at ``lo`` and at ``hi`` (see :data:`STALLED`)."""
    points, slopes = rail.derivatives(np.array([lo, hi]), 1)
    mean = float(np.linalg.norm(points[1] - points[0])) / max(hi - lo, 1e-300)
    speed = np.linalg.norm(slopes, axis=1)
    return bool(speed[0] <= STALLED * mean), bool(speed[1] <= STALLED * mean)


class _Pace(NamedTuple):
    """A monotone map of [0, 1] onto itself: the rail's own x at x, its slope, and its inverse."""

    at: Callable[[np.ndarray], np.ndarray]
    slope: Callable[[np.ndarray], np.ndarray]
    inverse: Callable[[np.ndarray], np.ndarray]


#: The pace by which ends stand still (start, end): √x from a stalled start, 1 − √(1 − x) to
#: a stalled end, arccos(1 − 2x)/π at both, x at neither; each with its inverse (the square,
#: 1 − (1 − h)², ½(1 − cos πh)), one table so the two cannot disagree.
PACES = {
    (True, True): _Pace(lambda x: np.arccos(1.0 - 2.0 * x) / np.pi,
                        lambda x: 1.0 / (np.pi * np.sqrt(x * (1.0 - x))),
                        lambda h: 0.5 * (1.0 - np.cos(np.pi * h))),
    (True, False): _Pace(np.sqrt, lambda x: 0.5 / np.sqrt(x), np.square),
    (False, True): _Pace(lambda x: 1.0 - np.sqrt(1.0 - x), lambda x: 0.5 / np.sqrt(1.0 - x),
                         lambda h: 1.0 - (1.0 - h) ** 2),
    (False, False): _Pace(lambda x: x, np.ones_like, lambda h: h),
}


class Unstalled(Curve):
    """``rail`` over ``lo`` … ``hi`` with its parameter mapped so it does not stand still
    at a stalled end: with x = (u − lo)/(hi − lo), the rail's own x is √x from a stalled
    start, 1 − √(1 − x) to a stalled end, arccos(1 − 2x)/π at both (√-like at each end,
    smooth and monotone between: :data:`PACES`). The same points of the same curve, the
    same ends."""

    def __init__(self, rail: Curve, lo: float, hi: float, start: bool, end: bool) -> None:
        self.rail, self.lo, self.hi = rail, float(lo), float(hi)
        self.stalled = (start, end)
        self.pace = PACES[bool(start), bool(end)]

    def _map(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The rail's parameter at ``t`` and its derivative."""
        width = self.hi - self.lo
        x = np.clip((t - self.lo) / width, 0.0, 1.0)
        with np.errstate(divide="ignore"):
            return self.lo + width * self.pace.at(x), self.pace.slope(x)

    def breaks(self) -> np.ndarray:
        """The wrapped rail's breaks (:meth:`.threedm_rails.Paced.breaks`) at this one's u."""
        inner = self.rail.breaks() if hasattr(self.rail, "breaks") else np.empty(0)
        h = np.clip((np.asarray(inner, dtype=float) - self.lo) / (self.hi - self.lo), 0.0, 1.0)
        return self.lo + (self.hi - self.lo) * self.pace.inverse(h)

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[np.ndarray]:
        if order > 1:  # (a √ pace has no bounded second derivative at a stalled end)
            raise ValueError("an unstalled rail gives its points and first derivatives only")
        t = np.atleast_1d(np.asarray(t, dtype=float)).ravel()
        out = [self.rail.point_at(self._map(t)[0])]
        if order >= 1:
            # at a stalled end itself (0 · ∞): the limit, the rail's second derivative
            # times h·h' (½ for a square root), taken just inside instead
            inside = np.clip(t, self.lo + 1e-12 * (self.hi - self.lo), self.hi - 1e-12 * (self.hi - self.lo))
            at_in, dh_in = self._map(inside)
            slopes = self.rail.derivatives(at_in, 1)[1] * dh_in[:, None]
            out.append(slopes)
        return out


def unstalled(rail: Curve, span: np.ndarray) -> Curve:
    """``rail`` over the interval ``span`` (two parameters), :class:`Unstalled` where it
    stands still at an end, else itself."""
    lo, hi = float(span[0]), float(span[-1])
    start, end = stalled_ends(rail, lo, hi)
    return Unstalled(rail, lo, hi, start, end) if start or end else rail
