"""Where a family of boundary curves runs along an asymptotic direction of the design.

The rulings of a strip tangent to the design along a curve run in the direction conjugate
to the curve's tangent t: the direction r with II(t, r) = 0 (Pottmann, Schiftner, Bo et
al. 2008). They turn to run along the curve itself where t is asymptotic, II(t, t) = 0;
where the normal curvature along the curve, II(t, t), changes sign the rulings swing from
leaning one way along the strip to leaning the other, and no torsal strip joins two
neighbouring boundaries there: the strip creases (a zigzag of flat triangles). The one
harmless way through is where II(t, ·) vanishes as a whole — the curve crosses a
parabolic line along its asymptotic direction (a wave's crest line followed across its
inflection): the tangent plane stands still along the curve there and every direction
is conjugate to it.

:func:`asymptotic_crossings` measures how much a family of parameter lines does the
harmful thing: along each line, every sign change of II(t, t) weighted by how far from
harmless it is, |II(t, p)| at the crossing (p the unit tangent across the line),
relative to the design's largest normal curvature. Rationalise tries first the family
with much less of it (:func:`~.rationalise.rationalise`).
"""

from __future__ import annotations

import numpy as np

from ..array_types import FloatArray
from ..surface_base import Surface

#: Samples of the design per direction.
SAMPLES = 41


def _curvatures(design: Surface, family: str, samples: int) -> tuple[FloatArray, FloatArray]:
    """II(t, t) and II(t, p) on a grid, t the unit tangent of the parameter lines along
    ``family`` and p = N × t; rows run along the lines (shape: lines × samples)."""
    g = np.linspace(0.0, 1.0, samples)
    u, v = (a.ravel() for a in np.meshgrid(g, g, indexing="xy" if family == "u" else "ij"))
    _, su, sv, suu, suv, svv = design.derivatives(u, v, 2)
    n = np.cross(su, sv)
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
    second = np.stack([np.einsum("ij,ij->i", d, n) for d in (suu, suv, svv)], axis=1)  # L, M, N
    along = su if family == "u" else sv
    t = along / np.maximum(np.linalg.norm(along, axis=1, keepdims=True), 1e-300)
    p = np.cross(n, t)
    # a tangent vector's coefficients on (Su, Sv): solve the first fundamental form
    e, f, h = (np.einsum("ij,ij->i", a, b) for a, b in ((su, su), (su, sv), (sv, sv)))
    det = e * h - f * f
    det = np.where(np.abs(det) > 0.0, det, np.inf)

    def coefficients(x: FloatArray) -> tuple[FloatArray, FloatArray]:
        a, b = np.einsum("ij,ij->i", su, x), np.einsum("ij,ij->i", sv, x)
        return (h * a - f * b) / det, (e * b - f * a) / det

    (ta, tb), (pa, pb) = coefficients(t), coefficients(p)
    big_l, big_m, big_n = second.T
    tt = ta * ta * big_l + 2 * ta * tb * big_m + tb * tb * big_n
    tp = ta * pa * big_l + (ta * pb + tb * pa) * big_m + tb * pb * big_n
    return tt.reshape(samples, samples), tp.reshape(samples, samples)


def asymptotic_crossings(design: Surface, family: str, samples: int = SAMPLES) -> float:
    """How much the parameter lines along ``family`` ("u": along u) cross asymptotic
    directions harmfully (see the module): the mean over the lines of the sum, over each
    line's sign changes of II(t, t), of |II(t, p)| there (interpolated) over the design's
    largest |II(t, t)| or |II(t, p)| on either family. 0 when no line crosses one."""
    tt, tp = _curvatures(design, family, samples)
    other_tt, other_tp = _curvatures(design, "v" if family == "u" else "u", samples)
    scale = float(max(np.abs(tt).max(), np.abs(tp).max(), np.abs(other_tt).max(), np.abs(other_tp).max()))
    if not np.isfinite(scale) or scale <= 0.0:
        return 0.0
    sign = np.where(np.abs(tt) > 1e-9 * scale, np.sign(tt), 0.0)
    # a sample where II(t, t) is 0 (a line through a grid point of the crossing) takes the
    # sign before it, so the change is counted once, at the sample after it
    last = np.maximum.accumulate(np.where(sign != 0.0, np.arange(samples), 0), axis=1)
    sign = np.take_along_axis(sign, last, axis=1)
    a, b = tt[:, :-1], tt[:, 1:]
    change = sign[:, :-1] * sign[:, 1:] < 0.0
    w = np.where(change, a / np.where(change, a - b, 1.0), 0.0)  # where II(t, t) is 0 between
    at = (1.0 - w) * tp[:, :-1] + w * tp[:, 1:]
    return float(np.where(change, np.abs(at), 0.0).sum(axis=1).mean() / scale)
