"""Many NURBS curves evaluated together: one B-spline basis for the curves that share a knot
vector.

A strip solve evaluates the two curves of each of its strips at their own parameters; the
edge curves of a roof all have the same knots (the flagship's 56 are single-span
quadratics). A curve's value at ``u`` is ``Σₐ c[i − k + a]·Nₐ(u)`` over the ``k + 1``
basis functions ``Nₐ`` that are non-zero on the knot span ``i`` holding ``u``; the basis
depends on the knots alone. :func:`derivatives_together` therefore asks scipy for the basis
of every parameter of a group of curves sharing knots in one call per derivative order,
and combines each row with its own curve's coefficients — the sum scipy forms, term by
term in the same order, so each curve gets what :meth:`.NurbsCurve.derivatives` gives it
alone, bit for bit (checked against scipy in
``tests/nodes/geometry/curves/test_shared_knots.py``). The rational quotient rule, the
domain's chain rule and the anchor then run row-wise, as they do per curve.

The basis comes from scipy's public :class:`~scipy.interpolate.BSpline` with ``k + 1``
columns of coefficients, coefficient ``j`` being the unit vector of column ``j mod (k + 1)``:
on span ``i`` the basis functions ``i − k … i`` fall in distinct columns, so each column
holds exactly one of them (added to zeros, which changes no bit).
"""

from __future__ import annotations

from collections.abc import Sequence
from math import comb

import numpy as np
from scipy.interpolate import BSpline

from ..array_types import FloatArray, IntArray
from ..curve_base import Curve
from .nurbs import NurbsCurve


def derivatives_together(
    curves: Sequence[Curve], x: FloatArray, bounds: IntArray, order: int, local: bool = False
) -> FloatArray:
    """Points and derivatives up to ``order``, ``(order + 1, len(x), 3)``, of curve ``i`` at
    its parameters ``x[bounds[i]:bounds[i + 1]]``: what ``curve.derivatives`` (or, with
    ``local``, ``curve.local_derivatives``) gives each curve alone, bit for bit. NURBS
    curves that share a degree, knots and rationality are evaluated together (while they
    have at most :data:`ROWS_PER_CURVE` parameters each on average); any other curve on its
    own."""
    out = np.empty((order + 1, len(x), 3))
    groups: dict[tuple, list[int]] = {}
    lows, highs = bounds[:-1].tolist(), bounds[1:].tolist()
    for i, curve in enumerate(curves):
        if highs[i] <= lows[i]:
            continue
        if _groupable(curve):
            key = (curve.degree, curve.is_rational, curve.knots.tobytes())
            groups.setdefault(key, []).append(i)
        else:
            evaluate = curve.local_derivatives if local else curve.derivatives
            out[:, lows[i] : highs[i]] = evaluate(x[lows[i] : highs[i]], order)
    for members in groups.values():
        group = [curves[i] for i in members]
        starts = bounds[:-1][members]
        counts = bounds[1:][members] - starts
        if len(members) == 1 or counts.sum() > ROWS_PER_CURVE * len(members):
            for i in members:
                evaluate = curves[i].local_derivatives if local else curves[i].derivatives
                out[:, lows[i] : highs[i]] = evaluate(x[lows[i] : highs[i]], order)
            continue
        rows = np.arange(counts.sum()) + np.repeat(starts - (np.cumsum(counts) - counts), counts)
        out[:, rows] = _group_derivatives(group, np.repeat(np.arange(len(group)), counts), x[rows], order)
        if not local:
            out[0, rows] += np.repeat(np.array([curve._anchor for curve in group]), counts, axis=0)
    return out


def derivative_each(curves: Sequence[Curve], ts: Sequence[FloatArray], order: int = 1) -> list[FloatArray]:
    """``curve.derivative_at(t, order)`` of every curve of ``curves`` at its 1-D array ``t``
    of ``ts``, bit for bit, the curves that share knots evaluated together
    (:func:`derivatives_together`)."""
    out: list[FloatArray | None] = [None] * len(curves)
    grouped = []
    for i, (curve, t) in enumerate(zip(curves, ts, strict=True)):
        if _groupable(curve):
            grouped.append(i)
        else:
            out[i] = curve.derivative_at(t, order)
    if grouped:
        x = [np.asarray(ts[i], dtype=float) for i in grouped]
        bounds = np.zeros(len(x) + 1, dtype=np.int64)
        np.cumsum([len(t) for t in x], out=bounds[1:])
        # (the points are relative to each curve's anchor: derivative_at adds it to order 0 alone)
        values = derivatives_together(
            [curves[i] for i in grouped], np.concatenate(x), bounds, order, local=order > 0
        )
        for i, low, high in zip(grouped, bounds[:-1].tolist(), bounds[1:].tolist(), strict=True):
            out[i] = values[order, low:high]
    return out  # type: ignore[return-value]  (every curve's is filled in)


#: Curves are evaluated together while they have at most this many parameters each on
#: average: together they pay scipy's fixed cost per call once, but each row costs more (the
#: basis is combined with the coefficients by numpy); alone is cheaper from ~70 rows a curve
#: (measured on 28 quadratics, first and second derivatives).
ROWS_PER_CURVE = 48

#: per class, whether its curves evaluate as :class:`.NurbsCurve` does (:func:`_groupable`)
_NURBS_LIKE: dict[type, bool] = {}


def _groupable(curve: Curve) -> bool:
    """Whether ``curve`` evaluates as :class:`.NurbsCurve` does (a subclass that keeps its
    evaluation: :class:`.InterpolatedCurve`, the conics), on an open knot vector (a
    periodic curve wraps its parameters first: it is evaluated on its own)."""
    kind = type(curve)
    nurbs_like = _NURBS_LIKE.get(kind)
    if nurbs_like is None:
        nurbs_like = _NURBS_LIKE[kind] = (
            issubclass(kind, NurbsCurve)
            and kind.local_derivatives is NurbsCurve.local_derivatives
            and kind.derivatives is NurbsCurve.derivatives
        )
    return nurbs_like and not curve.periodic


def _group_derivatives(curves: list[NurbsCurve], which: IntArray, t: FloatArray, order: int) -> FloatArray:
    """:meth:`.NurbsCurve.local_derivatives` of ``curves`` (same degree, knots and
    rationality) at ``t``, row ``r`` on curve ``which[r]``: ``(order + 1, len(t), 3)``.

    The sums run on coordinate rows (``(3 or 4, len(t))``), along contiguous rows."""
    first = curves[0]
    degree, knots = first.degree, first.knots
    u, scale = first._knot_parameters(t)  # (the same for all: the domain is the knots')
    count, width, n = len(first.control_points), first.degree + 1, len(u)
    # each row's knot span, as scipy finds it (the last span holds the domain's end, and
    # parameters outside the domain extrapolate the end spans)
    span = np.minimum(np.maximum(np.searchsorted(knots, u, side="right") - 1, degree), count - 1)
    basis = BSpline.construct_fast(knots, np.eye(width)[np.arange(count) % width], degree)
    # the coefficients each row combines: c[span − degree + a] of its own curve, for every a
    stacked = np.concatenate([curve._coefficients for curve in curves]).T  # (3 or 4, curves × count)
    first_row = which * count + span - degree
    terms = [stacked.take(first_row + a, axis=1) for a in range(width)]
    # where each row's N_{span − degree + a} lies among the basis's columns (in order where
    # every span is the first: a single-span curve)
    single = count == width
    place = None
    if not single:
        place = (np.arange(n) * width)[:, None] + (span[:, None] - degree + np.arange(width)) % width
    sums = np.zeros((order + 1, len(stacked), n))
    for k in range(min(order, degree) + 1):
        weights = basis(u, nu=k)
        weights = (weights if single else weights.reshape(-1).take(place)).T.copy()  # (width, n)
        total = sums[k]
        for a in range(width):  # (scipy's sum, term by term from 0)
            total = total + terms[a] * weights[a]
        sums[k] = total
    if first.is_rational:  # the quotient rule, as NurbsCurve.local_derivatives runs it
        w = sums[:, 3]
        w0 = w[0]
        result = [sums[0, :3] / w0]
        for k in range(1, order + 1):
            numerator = sums[k, :3] - (w[1] if k == 1 else k * w[1]) * result[k - 1]
            for i in range(2, k + 1):
                factor = comb(k, i)
                numerator -= (w[i] if factor == 1 else factor * w[i]) * result[k - i]
            result.append(numerator / w0)
        sums = np.stack(result)
    if scale != 1.0:  # (the chain rule; a factor of 1 changes no bit)
        for k in range(1, order + 1):
            sums[k] *= scale**k
    return sums.transpose(0, 2, 1)
