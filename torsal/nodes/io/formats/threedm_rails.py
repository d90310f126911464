"""The rails a face of an exported strip is fitted between (:mod:`.threedm_strips`).

- :class:`Rails`: two curves to fit a ruled face between, the strip's own or others;
- :class:`AtRest`: a rail at rest, one point (a cone's apex);
- :class:`Paced`: a strip's rail run at an even pace along its curve between the rulings
  (the strip's own pace can change several-fold within an interval: an even one costs a
  fit fewer control points);
- :func:`smooth_partners`: the developable pairing of two rails
  (:mod:`torsal.nodes.geometry.torsal_pairing`) as a smooth function;
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.interpolate import PchipInterpolator, make_lsq_spline

from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curve_rail import CurveRail
from torsal.nodes.geometry.torsal_pairing import torsal_partners

#: Spans of the smoothed developable pairing per interval between rulings (and its kinks).
PARTNER_SPANS = 8


def between(parameters: np.ndarray, per: int) -> np.ndarray:
    """``per`` evenly spaced parameters in each interval of ``parameters``, ends included."""
    steps = np.linspace(0.0, 1.0, per + 1)[:-1]
    inner = parameters[:-1, None] + (parameters[1:] - parameters[:-1])[:, None] * steps
    return np.concatenate([inner.ravel(), parameters[-1:]])


@dataclass(frozen=True)
class Rails:
    """Two rails to fit a face between (the strip's own, or one of them at rest)."""

    curve_a: Curve
    curve_b: Curve


class AtRest(Curve):
    """A rail at rest: one point (a cone's apex)."""

    def __init__(self, point: np.ndarray) -> None:
        self.point = np.asarray(point, dtype=float)

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[np.ndarray]:
        count = len(np.atleast_1d(np.asarray(t, dtype=float)))
        return [np.tile(self.point, (count, 1))] + [np.zeros((count, 3)) for _ in range(order)]


class Paced(Curve):
    """A rail over the ruling intervals of ``span`` run at an even pace along its curve in
    each (the strip's pace is a cubic of u that may change several-fold within an
    interval): the same points at the rulings, the same curve between, a parameterisation
    a cubic fits in few spans (the curve parameter a monotone cubic of u through its
    values at the rulings, C1 at them: PCHIP). A cone's face may take it: a cone is
    developable whatever its rail's pace; so may a face whose rail B is paired with A by
    the developable pairing."""

    def __init__(self, rail: Curve, span: np.ndarray) -> None:
        self.rail = rail
        self.span = np.asarray(span, dtype=float)
        self.lo, self.hi = float(span[0]), float(span[-1])
        if isinstance(rail, CurveRail):
            self.at = np.interp(self.span, rail.params, rail.curve_params)
            # the curve parameter at u: monotone, C1 at the rulings (a fit's double knot
            # there follows it), linear over a single interval
            self.pace = PchipInterpolator(self.span, self.at)

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[np.ndarray]:
        t = np.atleast_1d(np.asarray(t, dtype=float)).ravel()
        rail = self.rail
        if not isinstance(rail, CurveRail):
            return rail.derivatives(t, order)
        pace = [self.pace(t, j) for j in range(min(order, 2) + 1)]
        values = rail.curve.derivatives(rail._wrapped(pace[0]), order)
        out = [values[0]]
        if order >= 1:
            out.append(values[1] * pace[1][:, None])
        if order >= 2:
            out.append(values[2] * pace[1][:, None] ** 2 + values[1] * pace[2][:, None])
        return out

    def breaks(self) -> np.ndarray:
        """The parameters strictly inside the span where the curve has a break (a knot of
        the design it runs on, a joint of a joined curve: the curve's own breakpoints)."""
        rail = self.rail
        if not isinstance(rail, CurveRail):
            return np.empty(0)
        inner = rail.curve._breakpoints()
        at, span = (self.at, self.span) if self.at[-1] >= self.at[0] else (self.at[::-1], self.span[::-1])
        if rail.curve.closed:
            turns = np.arange(np.floor(at[0]), np.ceil(at[-1]) + 1.0)
            inner = (turns[:, None] + inner[None, :]).ravel()
        inner = inner[(inner > at[0]) & (inner < at[-1])]
        found = np.interp(inner, at, span)  # the pace's inverse: from its chords, then Newton
        for _ in range(4):
            with np.errstate(divide="ignore", invalid="ignore"):
                step = (self.pace(found) - inner) / self.pace(found, 1)
            found = np.clip(found - np.where(np.isfinite(step), step, 0.0), self.lo, self.hi)
        return np.sort(found)


def smooth_partners(strip: Rails, span: np.ndarray,
                     kinks: np.ndarray) -> Callable[[np.ndarray], np.ndarray]:
    """The developable partners on rail B of rail A's parameters over ``span``, as a cubic
    least-squares spline of the partner parameter (:data:`PARTNER_SPANS` spans per interval
    between the rulings and the ``kinks``, C0 at those, exact at their ends). The partner
    parameter is a root found where a determinant of the rails' tangents vanishes, so it
    jitters by up to ~1e-7 of an interval where that root is shallow: a fit to the raw
    partners needs a knot at every jitter (a face's rails tens of control points per
    interval), while the smoothed ones pair points still on rail B's curve, whose twist
    :mod:`.threedm_untwist` then takes out."""
    breaks = np.unique(np.concatenate([span, kinks]))
    steps = np.linspace(0.0, 1.0, PARTNER_SPANS + 1)[1:-1]
    inner = (breaks[:-1, None] + np.diff(breaks)[:, None] * steps).ravel()
    knots = np.sort(np.concatenate([np.repeat(breaks[[0, -1]], 4), np.repeat(breaks[1:-1], 3), inner]))
    at = between(np.unique(knots), 6)
    partners = torsal_partners(strip.curve_a, strip.curve_b, span, at)[0]
    try:
        spline = make_lsq_spline(at, partners, knots, 3)
    except (ValueError, np.linalg.LinAlgError):
        return lambda where: torsal_partners(strip.curve_a, strip.curve_b, span, where)[0]
    exact = torsal_partners(strip.curve_a, strip.curve_b, span, breaks)[0]
    miss = exact - spline(breaks)

    def paired(where: np.ndarray) -> np.ndarray:
        where = np.asarray(where, dtype=float)
        return np.clip(spline(where) + np.interp(where, breaks, miss), span[0], span[-1])

    return paired
