"""Arc length of curves: an adaptive Gauss–Legendre length table and its inverse.

scipy's ``quad`` integrates one interval at a time; the curve operations here need the
cumulative length at many parameters (division, equal spacing), so the integration is
written out vectorised: every interval in the table is refined in the same pass.
"""

from __future__ import annotations

import numpy as np
from scipy.special import roots_legendre

from .array_types import FloatArray
from .curve_protocol import ParametricCurve
from .roots import safeguarded_newton
from .vec_ops import derivative_noise

_NODES, _WEIGHTS = roots_legendre(16)

#: An interval whose error estimate is below this share of the length (per unit of
#: parameter) and does not shrink when halved is at the speed's rounding noise: kept.
#: (A smooth interval's estimate falls by orders of magnitude per halving; one too long
#: for the curve's turns has an estimate far above this.)
_NOISE_SHARE = 1e-8


def speed(curve: ParametricCurve, t: FloatArray) -> FloatArray:
    """``|C'(t)|``, the rate at which arc length grows with t."""
    return np.linalg.norm(curve.derivative_at(t, 1), axis=1)


def gauss_length(curve: ParametricCurve, low: FloatArray, high: FloatArray) -> FloatArray:
    """16-point Gauss–Legendre length of the curve over each ``[low, high]``, one call."""
    half = 0.5 * (high - low)
    x = (0.5 * (high + low))[:, None] + half[:, None] * _NODES[None, :]
    s = speed(curve, x.reshape(-1)).reshape(x.shape)
    return half * (s @ _WEIGHTS)


class LengthTable:
    """Cumulative arc length at a set of parameters, accurate to ``rel_tol`` of the total.

    Intervals start at the curve's smooth spans (``curve._breakpoints()``), four per span,
    and are halved wherever the 16-point rule on the whole interval and on its two
    halves disagree by more than the interval's share of the tolerance, or until halving
    no longer shrinks an already small disagreement (rounding noise, which far from the
    origin can exceed the tolerance: the table then stays as short as there). The length
    between table entries is then computed by the same rule, which is exact to rounding
    on such short smooth pieces.
    """

    def __init__(self, curve: ParametricCurve, rel_tol: float = 1e-13, max_rounds: int = 60) -> None:
        self.curve = curve
        breaks = curve._breakpoints()
        # four starting intervals per smooth span
        edges = breaks[:-1, None] + np.linspace(0.0, 1.0, 5)[None, :] * np.diff(breaks)[:, None]
        low, high = edges[:, :-1].reshape(-1), edges[:, 1:].reshape(-1)
        done_low, done_high, done_length = [], [], []
        estimate = float(gauss_length(curve, low, high).sum())
        # the noise an interval may be left at: 1e-8 of the length, or more far from the origin
        share = max(_NOISE_SHARE, derivative_noise(curve.point_at(np.linspace(0.0, 1.0, 9))))
        parent = np.full(len(low), np.inf)  # the error estimate of each interval's parent
        for round_ in range(max_rounds):
            mid = 0.5 * (low + high)
            left = gauss_length(curve, low, mid)
            right = gauss_length(curve, mid, high)
            whole = gauss_length(curve, low, high)
            error = np.abs(whole - left - right)
            # each interval's share of the tolerance, plus a floor for rounding error
            allowed = rel_tol * estimate * (high - low) + 8e-16 * np.abs(whole)
            # an error that halving no longer shrinks, though already small, is the noise
            # of the speed's rounding (a curve evaluated at site coordinates, 1e5 m and
            # more, by finite differences): refining further only multiplies intervals
            noise = (error >= 0.5 * parent) & (error <= share * estimate * (high - low))
            accept = (error <= allowed) | noise | (round_ == max_rounds - 1) | (high - low < 1e-14)
            if len(low) > 200_000:  # a pathological curve: stop refining, keep what we have
                accept[:] = True
            done_low += [low[accept], mid[accept]]
            done_high += [mid[accept], high[accept]]
            done_length += [left[accept], right[accept]]
            refine = ~accept
            if not refine.any():
                break
            low = np.concatenate([low[refine], mid[refine]])
            high = np.concatenate([mid[refine], high[refine]])
            parent = np.concatenate([error[refine], error[refine]])
        order = np.argsort(np.concatenate(done_low))
        lengths = np.concatenate(done_length)[order]
        #: Parameters of the table entries, from 0 to 1.
        self.parameters: FloatArray = np.concatenate([np.concatenate(done_low)[order], [1.0]])
        #: Arc length from t = 0 to each entry.
        self.lengths: FloatArray = np.concatenate([[0.0], np.cumsum(lengths)])

    @property
    def total(self) -> float:
        return float(self.lengths[-1])

    def length_at(self, t: FloatArray) -> FloatArray:
        """Arc length from 0 to each ``t`` (in [0, 1])."""
        t = np.clip(np.asarray(t, dtype=float), 0.0, 1.0)
        i = np.clip(np.searchsorted(self.parameters, t, side="right") - 1, 0, len(self.parameters) - 2)
        return self.lengths[i] + gauss_length(self.curve, self.parameters[i], t)

    def parameter_at(self, s: FloatArray, tol: float = 1e-15) -> FloatArray:
        """Parameters where the arc length from 0 equals ``s`` (clipped to [0, total]).

        Newton on ``length_at(t) − s`` (whose derivative is the speed), safeguarded by the
        table interval that brackets ``s``; converges to ``|Δt| < tol``.
        """
        s = np.clip(np.asarray(s, dtype=float), 0.0, self.total)
        i = np.clip(np.searchsorted(self.lengths, s, side="right") - 1, 0, len(self.lengths) - 2)
        low, high = self.parameters[i], self.parameters[i + 1]
        span = self.lengths[i + 1] - self.lengths[i]
        fraction = np.where(span > 0, (s - self.lengths[i]) / np.where(span > 0, span, 1), 0)
        start = low + fraction * (high - low)

        def residual(x: FloatArray, index: np.ndarray) -> tuple[FloatArray, FloatArray]:
            j = i[index]
            partial = self.lengths[j] + gauss_length(self.curve, self.parameters[j], x)
            return partial - s[index], speed(self.curve, x)

        t = safeguarded_newton(residual, low, high, start, xtol=tol)
        t[s <= 0] = 0.0
        t[s >= self.total] = 1.0
        return t
