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

Curves that share their knots are also made together (:func:`polynomial_curves`: a node that
makes dozens of edge curves on every solve pays each step of their set-up once).
"""

from __future__ import annotations

import operator
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from contextvars import ContextVar
from functools import cached_property
from typing import TypeVar

import numpy as np
from scipy.interpolate import BSpline

from ..array_types import FloatArray, IntArray
from ..curve_base import Curve
from .nurbs import NurbsCurve, quotient_rule


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
    counts = np.diff(bounds)
    # polynomial curves that share knots and parameters: one evaluation of all of them
    for group, rows, t in _sharing_parameters(curves, x, bounds):
        values = _at_shared_parameters(group, t, range(order + 1), local)
        out[:, rows] = values.reshape(order + 1, len(rows), 3)
        counts[group.members] = 0  # (done: no rows left for what follows)
    together, alone = _groups(curves, counts)
    for i in alone:
        evaluate = curves[i].local_derivatives if local else curves[i].derivatives
        out[:, bounds[i] : bounds[i + 1]] = evaluate(x[bounds[i] : bounds[i + 1]], order)
    for group in together:
        rows, which = _rows(bounds, group.members)
        out[:, rows] = _group_derivatives(group, which, x[rows], order)
        if not local:
            out[0, rows] += group.anchors[which]
    return out


N = TypeVar("N", bound=NurbsCurve)


def polynomial_curves(kind: type[N], points: FloatArray, knots: FloatArray, degree: int) -> list[N]:
    """Open polynomial (non-rational) curves of class ``kind`` (one that evaluates as
    :class:`.NurbsCurve` does, :func:`_groupable`) through the control points ``points[i]``
    (``(curves, count, 3)``, finite) on the shared full ``knots`` (checked) of ``degree``:
    each what :meth:`.NurbsCurve._setup` makes of it alone, bit for bit, their boxes,
    anchors and local coefficients found at once and their end points (which say whether
    each is closed) evaluated together (:func:`derivative_each`)."""
    # each curve's box reduced along its coordinate rows, as vec_ops.bounds reduces one curve's
    columns = np.ascontiguousarray(points.transpose(0, 2, 1))
    low, high = columns.min(axis=2), columns.max(axis=2)
    anchors = 0.5 * (high + low)
    local = points - anchors[:, None]
    curves = []
    for row, anchor, coefficients in zip(points, anchors, local, strict=True):
        curve = kind.__new__(kind)
        curve._set_spline(row, None, knots, degree, False, anchor, coefficients)
        curves.append(curve)
    ends = derivative_each(curves, [_ENDS] * len(curves), 0)
    for curve, end_points, span in zip(curves, ends, (high - low).max(axis=1).tolist(), strict=True):
        end_points.setflags(write=False)
        vars(curve)["end_points"] = end_points  # (where the cached property keeps them)
        curve._set_closed(span)
    return curves


#: The parameters of a curve's end points.
_ENDS = np.array([0.0, 1.0])
_ENDS.setflags(write=False)


def derivative_each(curves: Sequence[Curve], ts: Sequence[FloatArray], order: int = 1) -> list[FloatArray]:
    """``curve.derivative_at(t, order)`` of every curve of ``curves`` at its 1-D array ``t``
    of ``ts``, bit for bit, the curves that share knots evaluated together as in
    :func:`derivatives_together` (a polynomial curve's lower orders are not evaluated)."""
    out: list[FloatArray | None] = [None] * len(curves)
    counts = np.array([len(t) for t in ts], dtype=np.int64)
    # polynomial curves that share knots and parameters: one evaluation of all of them
    for group in _partition(curves)[0]:
        listed = group.members.tolist()
        first = ts[listed[0]]
        if len(listed) > 1 and not group.curves[0].is_rational and all(
                ts[i] is first or _same_bits(ts[i], first) for i in listed[1:]):
            for i, values in zip(listed, _at_shared_parameters(group, first, [order])[0], strict=True):
                out[i] = values
            counts[group.members] = 0  # (done: no rows left for what follows)
    bounds = np.zeros(len(ts) + 1, dtype=np.int64)
    np.cumsum(counts, out=bounds[1:])
    together, alone = _groups(curves, counts)
    for i in alone:
        out[i] = curves[i].derivative_at(ts[i], order)
    for group in together:
        listed = group.members.tolist()
        x = np.concatenate([np.asarray(ts[i], dtype=float) for i in listed])
        which = np.repeat(np.arange(len(listed)), np.diff(bounds)[group.members])
        values = _group_derivatives(group, which, x, order, lowest=order)[order]
        if order == 0:  # (the points: derivative_at adds the anchor to them alone)
            values += group.anchors[which]
        low = 0
        for i in listed:
            high = low + len(ts[i])
            out[i] = values[low:high]
            low = high
    return out  # type: ignore[return-value]  (every curve's is filled in)


def _sharing_parameters(
    curves: Sequence[Curve], x: FloatArray, bounds: IntArray
) -> Iterator[tuple[_Group, IntArray, FloatArray]]:
    """The groups of polynomial curves sharing knots (two or more) whose rows of ``x`` (curve
    ``i`` has ``x[bounds[i]:bounds[i + 1]]``) are the same parameters, with those rows and
    the parameters."""
    counts = np.diff(bounds)
    for group in _partition(curves)[0]:
        members = group.members
        own = counts[members]
        if len(members) < 2 or group.curves[0].is_rational or not own[0] or (own != own[0]).any():
            continue
        rows, _ = _rows(bounds, members)
        each = x[rows].reshape(len(members), -1)
        if (each.view(np.int64) == each[0].view(np.int64)).all():  # (bit for bit: a −0.0 is not 0.0)
            yield group, rows, each[0]


def _same_bits(a: FloatArray, b: FloatArray) -> bool:
    """Whether two arrays of parameters are the same numbers, bit for bit."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return a.shape == b.shape and a.tobytes() == b.tobytes()


def _at_shared_parameters(
    group: _Group, t: FloatArray, orders: Sequence[int], local: bool = False
) -> FloatArray:
    """The derivatives of ``orders`` of every curve of ``group`` (polynomial curves of one
    degree and knots) at the same parameters ``t``, ``(orders, curves, len(t), 3)``: what
    ``curve.derivative_at(t, k)`` gives each (or, with ``local``, ``local_derivatives``:
    its points relative to its anchor), bit for bit. One scipy spline whose coefficients
    are every curve's side by side (``3 × curves`` columns) evaluates each column as it
    evaluates a curve's own three (the basis at each ``t`` once, then each column's sum on
    its own)."""
    first = group.curves[0]
    u, scale = first._knot_parameters(t)
    curves, n = len(group.curves), len(u)
    out = np.zeros((len(orders), curves, n, 3))  # (zero above the degree)
    side_by_side = np.concatenate([curve._coefficients for curve in group.curves], axis=1)
    spline = BSpline.construct_fast(first.knots, side_by_side, first.degree)
    for row, order in enumerate(orders):
        if order > first.degree:
            continue
        values = out[row]
        values[...] = spline(u, nu=order).reshape(n, curves, 3).transpose(1, 0, 2)
        if order and scale != 1.0:  # (as NurbsCurve._polynomial_derivative)
            values *= scale**order
        if order == 0 and not local:
            values += group.anchors[:, None, :]
    return out


def _groups(curves: Sequence[Curve], counts: IntArray) -> tuple[list[_Group], list[int]]:
    """The curves of ``curves`` evaluated together, as :class:`_Group` (NURBS curves of one
    degree, knots and rationality, while they have at most :data:`ROWS_PER_CURVE` of their
    ``counts`` rows each on average), and the indices of those evaluated alone (the curves
    without rows in neither)."""
    grouped, others = _partition(curves)
    together, alone = [], [i for i in others if counts[i] > 0]
    for group in grouped:
        has_rows = counts[group.members] > 0
        if not has_rows.all():
            kept = np.flatnonzero(has_rows).tolist()
            group = _Group(group.members[kept], [group.curves[k] for k in kept])
        members = group.members
        if len(members) > 1 and counts[members].sum() <= ROWS_PER_CURVE * len(members):
            together.append(group)
        else:
            alone += members.tolist()
    return together, alone


class _Group:
    """Curves of one basis evaluated together: their indices among the curves asked for, the
    curves, and what evaluating them takes that depends on them alone (made when first
    needed, and kept with their partition: :func:`_partition`)."""

    def __init__(self, members: IntArray, curves: list[NurbsCurve]) -> None:
        self.members, self.curves = members, curves

    @cached_property
    def basis(self) -> BSpline:
        """scipy's basis of the curves' knots, with ``k + 1`` columns of coefficients:
        coefficient ``j`` is the unit vector of column ``j mod (k + 1)`` (the module's
        docstring)."""
        first = self.curves[0]
        count, width = len(first.control_points), first.degree + 1
        return BSpline.construct_fast(first.knots, np.eye(width)[np.arange(count) % width], first.degree)

    @cached_property
    def coefficients(self) -> FloatArray:
        """Every curve's coefficients one curve after another, as coordinate rows: ``(3 or
        4, curves × count)``."""
        return np.concatenate([curve._coefficients for curve in self.curves]).T

    @cached_property
    def anchors(self) -> FloatArray:
        """Every curve's anchor, ``(curves, 3)``."""
        return np.array([curve._anchor for curve in self.curves])


def _partition(curves: Sequence[Curve]) -> tuple[list[_Group], list[int]]:
    """The indices of ``curves`` that can be evaluated together, by basis (NURBS curves of
    one degree, knots and rationality: :func:`_groupable`), and the others. A solve's steps
    evaluate the same curves again and again (every Newton step of a search): inside a
    :func:`partitions_kept` block each list's partition is made once, kept by the curves
    themselves (a list of other curves with the same ids, those of curves since
    collected, is not taken for one of them)."""
    kept = _KEPT.get()
    ids = tuple(map(id, curves)) if kept is not None else ()
    if kept is not None:
        known = kept.get(ids)
        if known is not None and all(map(operator.is_, known[0], curves)):
            return known[1]
    groups: dict[tuple, list[int]] = {}
    others = []
    for i, curve in enumerate(curves):
        if _groupable(curve):
            groups.setdefault(curve.basis_key, []).append(i)
        else:
            others.append(i)
    made = [_Group(np.array(members), [curves[i] for i in members]) for members in groups.values()]
    partition = made, others
    if kept is not None:
        kept[ids] = (tuple(curves), partition)
    return partition


@contextmanager
def partitions_kept() -> Iterator[None]:
    """Within the block (a solve, in this thread), the partition of each list of curves
    evaluated (:func:`_partition`) is made once and kept, with the curves; it is dropped
    with the block. Blocks nest: an inner one keeps its partitions in the outer one's."""
    if _KEPT.get() is not None:
        yield
        return
    token = _KEPT.set({})
    try:
        yield
    finally:
        _KEPT.reset(token)


#: the partitions kept by the :func:`partitions_kept` block under way in this thread (None
#: outside one), by the ids of their curves, with the curves (which keeps their ids from
#: being reused while they are kept)
_KEPT: ContextVar[dict[tuple[int, ...], tuple[tuple[Curve, ...], tuple[list[_Group], list[int]]]] | None] = (
    ContextVar("torsal_curve_partitions", default=None))


def _rows(bounds: IntArray, members: IntArray) -> tuple[IntArray, IntArray]:
    """The rows of curves ``members`` (curve ``i`` has rows ``bounds[i]:bounds[i + 1]``), and
    for each of them which of ``members`` it is on."""
    starts = bounds[:-1][members]
    counts = bounds[1:][members] - starts
    rows = np.arange(counts.sum()) + np.repeat(starts - (np.cumsum(counts) - counts), counts)
    return rows, np.repeat(np.arange(len(members)), counts)


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
            and kind.derivative_at is NurbsCurve.derivative_at
        )
    return nurbs_like and not curve.periodic


def _group_derivatives(
    group: _Group, which: IntArray, t: FloatArray, order: int, lowest: int = 0
) -> FloatArray:
    """:meth:`.NurbsCurve.local_derivatives` of the ``group``'s curves (same degree, knots and
    rationality) at ``t``, row ``r`` on curve ``which[r]``: ``(order + 1, len(t), 3)`` (of a
    polynomial curve the orders from ``lowest`` up alone: the others are left zero).

    The sums run on coordinate rows (``(3 or 4, len(t))``), along contiguous rows."""
    first = group.curves[0]
    degree, knots = first.degree, first.knots
    u, scale = first._knot_parameters(t)  # (the same for all: the domain is the knots')
    count, width, n = len(first.control_points), first.degree + 1, len(u)
    # each row's knot span, as scipy finds it (the last span holds the domain's end, and
    # parameters outside the domain extrapolate the end spans)
    span = np.minimum(np.maximum(np.searchsorted(knots, u, side="right") - 1, degree), count - 1)
    basis = group.basis
    # the coefficients each row combines: c[span − degree + a] of its own curve, for every a
    stacked = group.coefficients  # (3 or 4, curves × count)
    first_row = which * count + span - degree
    terms = [stacked.take(first_row + a, axis=1) for a in range(width)]
    # where each row's N_{span − degree + a} lies among the basis's columns (in order where
    # every span is the first: a single-span curve)
    single = count == width
    place = None
    if not single:
        place = (np.arange(n) * width)[:, None] + (span[:, None] - degree + np.arange(width)) % width
    sums = np.zeros((order + 1, len(stacked), n))
    for k in range(0 if first.is_rational else lowest, min(order, degree) + 1):
        weights = basis(u, nu=k)
        weights = (weights if single else weights.reshape(-1).take(place)).T.copy()  # (width, n)
        total = sums[k]
        for a in range(width):  # (scipy's sum, term by term from 0)
            total = total + terms[a] * weights[a]
        sums[k] = total
    if first.is_rational:  # as NurbsCurve.local_derivatives runs it
        sums = np.stack(quotient_rule(sums, order))
    if scale != 1.0:  # (the chain rule; a factor of 1 changes no bit)
        for k in range(1, order + 1):
            sums[k] *= scale**k
    return sums.transpose(0, 2, 1)
