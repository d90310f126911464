"""Where rulings start: stations spaced evenly along a curve, and a fast arc-length map.

The developable nodes place their ``Segments + 1`` rulings at stations spaced evenly in
arc length along the base curve, as Grasshopper's *Divide Curve* does (the thesis
divides the curve that way); ``spacing="parameter"`` spaces them evenly in t instead.

The arc length here is a light table: Gauss–Legendre on a partition of every smooth span,
its pieces checked in pairs against a rule of higher order and split where they disagree
(a knot the curve does not report, as in a NURBS run as t²), read back by the integral
of the quintic through each piece's six speeds (its ends and Gauss nodes), and inverted
by Newton steps on that same quintic from the inverse of the piece's Hermite cubic, until
they stand still: t → ℓ → t comes back to rounding, so two ways of reaching one point of
a curve agree, and a strip does not depend on how its curves are parameterised (the same
curve run as t² or backwards gives the same stations, fans and closing triangles to
~1e-11 of its size). It is still several times cheaper than the curve's own
:class:`~..arclength.LengthTable`, which matters when a slider rebuilds the curve on
every solve.
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import lru_cache
from typing import TYPE_CHECKING, Literal, NamedTuple

import numpy as np
from numpy.polynomial.legendre import legvander
from numpy.typing import ArrayLike
from scipy.special import roots_legendre

from ..array_types import IntArray
from ..curve_base import FloatArray
from ..curves.shared_knots import derivative_each
from ..vec_ops import dot
from .stack import Stack

if TYPE_CHECKING:
    from ..curve_base import Curve

Spacing = Literal["length", "parameter"]

_NODES, _WEIGHTS = roots_legendre(4)
#: The speeds at a piece's start, its 4 Gauss nodes and its end (in the piece's own
#: coordinate u in [0, 1]) to the coefficients of the degree-5 polynomial through them.
_POWERS = np.arange(7.0)
_FIT = np.linalg.inv(np.vander(np.concatenate([[0.0], 0.5 * (_NODES + 1.0), [1.0]]), 6, increasing=True))
#: The same six speeds to the coefficients of u¹…u⁶ of the arc length from the piece's start.
_INTEGRAL = _FIT.T / _POWERS[None, 1:]

#: Where two neighbouring pieces (a *pair*, as [0, 1]) have their 11 speeds: its start, the
#: first piece's Gauss nodes, its middle, the second's Gauss nodes and its end.
_PAIR_AT = np.concatenate([[0.0], 0.25 * (_NODES + 1.0), [0.5], 0.25 * (_NODES + 3.0), [1.0]])
#: Those 11 speeds to (the integral over the pair by the rule through all of them, exact to
#: degree 11) − (the two pieces' Gauss rules, exact to degree 7 on each), per half width:
#: the Gauss rules' error, for a speed smooth at the pair's scale. (The weights solved in the
#: Legendre basis, where the system is well conditioned.)
_PAIR_CHECK = np.linalg.solve(legvander(2.0 * _PAIR_AT - 1.0, 10).T, 2.0 * np.eye(11)[0]) - np.concatenate(
    [[0.0], 0.5 * _WEIGHTS, [0.0], 0.5 * _WEIGHTS, [0.0]]
)
#: The weights of :data:`_PAIR_CHECK` for the pair's two pieces' Gauss nodes, as they lie.
_PAIR_INNER = _PAIR_CHECK[np.r_[1:5, 6:10]]
#: A pair of pieces is split in two pairs while its estimated error exceeds this share of the
#: curve's length ...
PAIR_TOLERANCE = 1e-13
#: ... for at most this many rounds, and while the pairs are at most this many times as many
#: as at the start (a speed that is noisy everywhere must not split without end).
ROUNDS, GROWTH = 24, 8
#: At most this many Newton steps polish :meth:`LengthMap.parameter_at` (1 or 2, measured).
_POLISH = 8


@lru_cache(maxsize=64)
def _layout(breaks: tuple[float, ...], intervals: int) -> tuple[FloatArray, ...]:
    """Where a :class:`LengthMap` evaluates the speed (depends only on the breakpoints, so
    curves rebuilt with the same knots on every solve share it).

    Returns the piece ends ``nodes``, the 4 Gauss nodes of every piece (flat), the pieces'
    half widths, the index of the last piece of every span, and all the parameters at
    which the speed is needed: the Gauss nodes, the piece ends and points just before
    every breakpoint (the speed may jump at a knot).
    """
    edges = np.array(breaks)
    widths = np.diff(edges)
    # pieces in proportion to each span's share of the parameter, at least eight per span and
    # an even number (they are checked in pairs: :func:`_refined`)
    counts = np.maximum(8, np.ceil(intervals * widths).astype(int))
    counts += counts % 2
    span = np.repeat(np.arange(len(widths)), counts)
    local = np.arange(len(span)) - np.repeat(np.cumsum(counts) - counts, counts)
    low = edges[span] + widths[span] * local / counts[span]
    nodes = np.append(low, 1.0)
    half = 0.5 * (nodes[1:] - low)
    gauss = ((0.5 * (nodes[1:] + low))[:, None] + half[:, None] * _NODES[None, :]).reshape(-1)
    at = np.concatenate([gauss, nodes, edges[1:] - 1e-12 * widths])
    arrays = (nodes, gauss, half, np.cumsum(counts) - 1, at)
    for array in arrays:
        array.setflags(write=False)
    return arrays


class LengthMap:
    """Arc length along a curve as a function of t, and its inverse (vectorised).

    About ``intervals`` pieces are spread over the curve's smooth spans in proportion to
    their parameter width (at least eight per span);
    each piece is integrated with the 4-point Gauss–Legendre rule (its error falls as the 8th
    power of the pieces' length: exact to rounding where the speed is smooth at their
    scale), and neighbouring pieces whose rule is not (a knot the curve does not report,
    a sharp bend; see :func:`_refined`) are split until it is. Within a piece ℓ(t) is
    the integral of the quintic through the piece's six speeds, kept as its coefficients
    in the piece's own coordinate u.
    """

    def __init__(self, curve: Curve, intervals: int = 128) -> None:
        self._set(curve, *_tables([curve], intervals)[0])

    @classmethod
    def many(cls, curves: Sequence[Curve], intervals: int = 128) -> list[LengthMap]:
        """The map of each of ``curves``, each the one it gets alone (bit for bit), their
        tables made together (:func:`_tables`); none for no curves."""
        if not curves:
            return []
        maps = []
        for curve, tables in zip(curves, _tables(curves, intervals), strict=True):
            length_map = cls.__new__(cls)
            length_map._set(curve, *tables)
            maps.append(length_map)
        return maps

    def _set(
        self, curve: Curve, nodes: FloatArray, lengths: FloatArray, start_speeds: FloatArray,
        end_speeds: FloatArray, width: FloatArray, rise: FloatArray, inverse: FloatArray, poly: FloatArray,
        stacked: _Stacked, first_piece: int, first_node: int,
    ) -> None:
        self.curve = curve
        #: the tables of the maps made together, one map after another (this map's arrays
        #: are views of them), and where its pieces and nodes start there: read by the
        #: searches of many maps at once without joining their tables again
        self._stacked, self._first_piece, self._first_node = stacked, first_piece, first_node
        self.nodes: FloatArray = nodes
        self.lengths: FloatArray = lengths
        #: |C'| at the start and at the end of each piece: the slopes of ℓ(t) there
        self.start_speeds: FloatArray = start_speeds
        self.end_speeds: FloatArray = end_speeds
        #: Total arc length of the curve.
        self.total: float = float(lengths[-1])
        self._width, self._rise = width, rise
        #: per piece, du/dv at its ends for v = (ℓ − ℓ0)/its length (inf where the speed is 0)
        self._inverse = inverse
        #: per piece, the coefficients of u⁰…u⁶ of ℓ − ℓ0 (row 0) and of its slope (row 1)
        self._poly = poly

    def length_at(self, t: ArrayLike) -> FloatArray:
        """Arc length from t = 0 to each ``t``."""
        t = np.minimum(np.maximum(np.asarray(t, dtype=float), 0.0), 1.0)
        k = np.minimum(np.searchsorted(self.nodes, t, side="right") - 1, len(self._rise) - 1)
        u = (t - self.nodes[k]) / self._width[k]
        return self.lengths[k] + self._rises(k, u)

    def _rises(self, k: IntArray, u: FloatArray) -> FloatArray:
        """ℓ − ℓ0 at ``u`` on pieces ``k``: the integral of the speed's polynomial of degree 5
        through the six speeds each piece has (its ends and Gauss nodes), exact to ~h⁷
        where the Hermite cubic alone is to ~h⁴ (1e-9 of the length on a wavy curve:
        enough for stations to move by that when the curve's parameter changes)."""
        return np.einsum("...j,...j->...", u[..., None] ** _POWERS, self._poly[k, 0])

    def parameter_near(self, length: ArrayLike) -> FloatArray:
        """:meth:`parameter_at` read linearly between the pieces' ends (to ~1e-5 of the
        length, for a tenth of the work: enough to place samples that are not rulings)."""
        return np.interp(length, self.lengths, self.nodes)

    def parameter_at(self, length: ArrayLike) -> FloatArray:
        """The t at which the arc length from the start equals ``length`` (clipped to the
        curve), to rounding."""
        length = np.asarray(length, dtype=float)
        return _parameters_at([self], length.reshape(-1), Stack([length.size]))[0].reshape(length.shape)


def _tables(curves: Sequence[Curve], intervals: int) -> list[tuple[FloatArray, ...]]:
    """The tables of a :class:`LengthMap` of each of ``curves`` (what :meth:`LengthMap._set`
    takes after the curve), each the one the curve gets alone, bit for bit: each curve's
    speed is evaluated on its own, its pieces refined on their own (:func:`_refined`), and
    so are its pieces' Gauss sums, their running total and the quintics' coefficients (a
    matrix product's and a cumulative sum's rounding depend on what else is in the array:
    the curves with one layout are stacked along a new first axis, each its own row of
    every product and sum, as :func:`_layout_rows` does); the rest runs once for all of them."""
    layouts = []
    for curve in curves:
        breaks = tuple(curve._breakpoints().tolist())
        layout = _layout if len(breaks) <= 64 else _layout.__wrapped__  # long keys cost more than they save
        layouts.append(layout(breaks, int(intervals)))
    stacked = np.concatenate(derivative_each(curves, [layout[4] for layout in layouts], 1))
    stacked = np.sqrt(dot(stacked, stacked))  # ((x² + y²) + z², as np.add.reduce along the rows sums)
    first = np.cumsum([0] + [len(layout[4]) for layout in layouts])
    # each curve's pieces: their ends, half widths, speeds at their Gauss nodes, starts and ends
    own: list[tuple[FloatArray, ...]] = [()] * len(curves)
    by_layout: dict[int, list[int]] = {}
    for index, layout in enumerate(layouts):  # (a cached layout is one object for every curve)
        by_layout.setdefault(id(layout), []).append(index)
    for members in by_layout.values():
        layout = layouts[members[0]]
        rows = stacked[first[members][:, None] + np.arange(len(layout[4]))]
        for index, (pieces, total, bad) in zip(members, _layout_rows(layout, rows), strict=True):
            nodes, _, inner, start, end, _ = pieces
            refined = _refined(curves[index], nodes, inner, start, end, total) if bad else None
            if refined is None:
                own[index] = pieces
            else:  # (some pieces were split: their widths differ)
                nodes, inner, start, end = refined
                half = 0.5 * (nodes[1:] - nodes[:-1])
                own[index] = (nodes, half, inner, start, end, half * (inner @ _WEIGHTS))
    all_nodes, halves, gauss, starts, ends, pieces = zip(*own, strict=True)
    counts = [len(piece) for piece in pieces]
    # each curve's nodes and running lengths (a node more than pieces each), curve after curve
    at_node = np.cumsum([0, *counts]) + np.arange(len(counts) + 1)
    all_lengths = np.empty(at_node[-1])
    for piece, low in zip(pieces, at_node[:-1].tolist(), strict=True):
        all_lengths[low] = 0.0
        np.cumsum(piece, out=all_lengths[low + 1 : low + 1 + len(piece)])
    nodes_stack = np.concatenate(all_nodes)
    rise = np.concatenate(pieces)
    h = 2.0 * np.concatenate(halves)
    d0, d1 = np.concatenate(starts) * h, np.concatenate(ends) * h
    samples = np.empty((len(rise), 6))
    samples[:, 0], samples[:, 5] = d0, d1
    np.multiply(np.concatenate(gauss), h[:, None], out=samples[:, 1:5])
    with np.errstate(divide="ignore", invalid="ignore"):
        inverse = np.column_stack([rise / d0, rise / d1])
    poly = np.zeros((len(rise), 2, 7))
    bounds = np.cumsum([0, *counts])
    by_count: dict[int, list[int]] = {}
    for index, count in enumerate(counts):
        by_count.setdefault(count, []).append(index)
    for count, members in by_count.items():  # (each curve's rows one matrix of the stack)
        rows = bounds[members][:, None] + np.arange(count)
        poly[rows, 0, 1:] = samples[rows] @ _INTEGRAL
    poly[:, 1, :6] = poly[:, 0, 1:] * _POWERS[1:]
    stacked = _Stacked(h, rise, inverse, poly, nodes_stack, all_lengths)
    nodes_at = at_node[:-1].tolist()
    return [(nodes_stack[node : node + count + 1], all_lengths[node : node + count + 1], start, end,
             *(x[low:high] for x in (h, rise, inverse, poly)), stacked, low, node)
            for start, end, low, high, node, count in zip(
                starts, ends, bounds[:-1].tolist(), bounds[1:].tolist(), nodes_at, counts, strict=True)]


class _Stacked(NamedTuple):
    """The tables of maps made together (:func:`_tables`), one map after another: per piece
    its width, rise, inverse slopes and polynomials; per node (a node more than pieces
    each map) where it lies and the length to it."""

    width: FloatArray
    rise: FloatArray
    inverse: FloatArray
    poly: FloatArray
    nodes: FloatArray
    lengths: FloatArray


def _tables_of(maps: Sequence[LengthMap]) -> tuple[_Stacked, IntArray, IntArray]:
    """The tables of ``maps`` one map after another and where each map's first piece and
    first node lie in them: the stack they were made in together when they share one (no
    copy), else their own tables joined."""
    stacked = maps[0]._stacked
    if all(m._stacked is stacked for m in maps):
        return (stacked, np.array([m._first_piece for m in maps], dtype=np.int64),
                np.array([m._first_node for m in maps], dtype=np.int64))
    joined = _Stacked(*(np.concatenate([getattr(m, name) for m in maps])
                        for name in ("_width", "_rise", "_inverse", "_poly", "nodes", "lengths")))
    pieces = Stack([len(m._rise) for m in maps])
    return joined, pieces.starts, pieces.starts + np.arange(len(maps))


def _layout_rows(
    layout: tuple[FloatArray, ...], speeds: FloatArray
) -> list[tuple[tuple[FloatArray, ...], float, bool]]:
    """The pieces of each curve of one ``layout`` (:func:`_layout`) from its ``speeds``
    there (one row a curve): its pieces' ends ``nodes`` and half widths, the speeds at their
    Gauss nodes, starts and ends (one-sided at a breakpoint) and their lengths by their
    Gauss rule; the curve's length by them; and whether any pair of its pieces fails the
    check of :func:`_refined`. Each curve's row gets what it gets alone: a matrix product of
    stacked rows runs row by row, as a sum and a cumulative sum do along the last axis."""
    nodes, nodes_gauss, half, last, _ = layout
    g, m = len(nodes_gauss), len(nodes)
    inner = speeds[:, :g].reshape(len(speeds), -1, 4)
    start = speeds[:, g : g + m - 1]
    end = speeds[:, g + 1 : g + m].copy()
    end[:, last] = speeds[:, g + m :]
    pieces = half * (inner @ _WEIGHTS)
    totals = pieces.sum(axis=1)
    bad = (_pair_errors(nodes, inner, start, end) > (2.0 * PAIR_TOLERANCE * totals)[:, None]).any(axis=1)
    return [((nodes, half, inner[k], start[k], end[k], pieces[k]), float(totals[k]), bool(bad[k]))
            for k in range(len(speeds))]


def _pair_errors(nodes: FloatArray, inner: FloatArray, start: FloatArray, end: FloatArray) -> FloatArray:
    """The Gauss rules' error estimate of every pair of neighbouring pieces (see
    :func:`_refined`), of the speeds ``inner`` (``(..., pieces, 4)``), ``start`` and ``end``
    (``(..., pieces)``) of pieces ending at ``nodes``."""
    width = nodes[2::2] - nodes[:-2:2]
    pairs = inner.reshape(*inner.shape[:-2], -1, 8)  # (every pair's speeds as they lie, not gathered)
    rule = pairs @ _PAIR_INNER + start[..., ::2] * _PAIR_CHECK[0] + end[..., ::2] * _PAIR_CHECK[5]
    return np.abs(width * (rule + end[..., 1::2] * _PAIR_CHECK[10]))


def _parameters_at(maps: Sequence[LengthMap], length: FloatArray, stack: Stack) -> list[FloatArray]:
    """:meth:`LengthMap.parameter_at` of each map of ``maps`` at its rows of ``length`` (as
    ``stack`` says), run once for all of them, each map's rows getting what they get alone,
    bit for bit (each map's search on its own rows, and its Newton steps stop when its own
    rows stand still)."""
    totals = np.array([m.total for m in maps])
    target = np.minimum(np.maximum(length, 0.0), stack.repeat(totals))
    bounds = stack.offsets.tolist()
    k = np.concatenate([m.lengths.searchsorted(target[low:high], side="right") - 1
                        for m, low, high in zip(maps, bounds[:-1], bounds[1:], strict=True)])
    k = np.minimum(k, stack.repeat(np.array([len(m._rise) for m in maps]) - 1))
    tables, first_piece, first_node = _tables_of(maps)
    on_piece = k + stack.repeat(first_piece)  # (each map's pieces among all of them)
    on_node = k + stack.repeat(first_node)
    rise, width, nodes, lengths = tables.rise, tables.width, tables.nodes, tables.lengths
    inverse, poly = tables.inverse[on_piece], tables.poly[on_piece]
    gap = target - lengths[on_node]
    v = gap / np.maximum(rise[on_piece], 1e-300)
    # u(v) on the piece as the cubic with u' = ℓ_piece/ℓ'(u) at its ends (the inverse of
    # ℓ's Hermite cubic, to the same order), or v itself where the speed is 0 there
    w = 1.0 - v
    with np.errstate(invalid="ignore"):  # (0·inf where the speed is 0: v is taken there)
        u = v * (w * (w * inverse[:, 0] - v * inverse[:, 1]) + v * (3.0 - 2.0 * v))
    u = np.minimum(np.maximum(np.where(np.isfinite(u), u, v), 0.0), 1.0)
    # then Newton on the quintic's integral (:meth:`LengthMap._rises`, the length
    # :meth:`LengthMap.length_at` reads back) with its own slope, the quintic speed, until it
    # stands still: from the cubic one step mostly reaches rounding, but not where the speed
    # changes fast within a piece (a rational rail, a curve run as t²: 1e-6 of the length was
    # left). Each map stops when its own rows' steps are all within 1e-9 (Newton's error
    # squares at every step: after one under 1e-9 the next is rounding).
    floor = stack.repeat(1e-12 * np.maximum(totals, 1e-300))
    moving = stack.counts > 0  # (the maps still stepping)
    rows = np.arange(stack.rows)
    for _ in range(_POLISH):
        if len(maps) > 1:
            rows = np.flatnonzero(stack.repeat(moving))
        at, step_poly, step_floor = u[rows], poly[rows], floor[rows]
        powers = at[:, None] ** _POWERS
        value = (step_poly[:, 0, :] * powers).sum(axis=-1) - gap[rows]
        slope = (step_poly[:, 1, :] * powers).sum(axis=-1)
        step = np.where(slope > step_floor, value / np.maximum(slope, step_floor), 0.0)
        u[rows] = np.minimum(np.maximum(at - step, 0.0), 1.0)
        largest = np.zeros(len(maps))
        np.maximum.at(largest, np.searchsorted(stack.offsets, rows, side="right") - 1, np.abs(step))
        moving &= largest > 1e-9
        if not moving.any():
            break
    # (the whole length is the curve's end exactly, not a rounding short of it)
    whole = target < stack.repeat(totals)
    return stack.split(np.where(whole, np.minimum(nodes[on_node] + u * width[on_piece], 1.0), 1.0))


def parameters_at(maps: Sequence[LengthMap], lengths: Sequence[FloatArray]) -> list[FloatArray]:
    """:meth:`LengthMap.parameter_at` of each map of ``maps`` at its ``lengths`` (1-d), for
    every map at once: each gets what it gets alone, bit for bit."""
    if not len(maps):
        return []
    stack = Stack.of(lengths)
    joined = np.concatenate(lengths) if len(lengths) else np.empty(0)
    return _parameters_at(maps, joined.astype(float, copy=False), stack)


def lengths_at(maps: Sequence[LengthMap], ts: Sequence[FloatArray]) -> list[FloatArray]:
    """:meth:`LengthMap.length_at` of each map of ``maps`` at its ``ts`` (1-d), for every map
    at once: each gets what it gets alone, bit for bit (each map's search on its own rows,
    the rest row by row)."""
    if not len(maps):
        return []
    stack = Stack.of(ts)
    t = np.minimum(np.maximum(np.concatenate(ts).astype(float, copy=False), 0.0), 1.0)
    bounds = stack.offsets.tolist()
    k = np.concatenate([np.minimum(m.nodes.searchsorted(t[low:high], side="right") - 1, len(m._rise) - 1)
                        for m, low, high in zip(maps, bounds[:-1], bounds[1:], strict=True)])
    tables, first_piece, first_node = _tables_of(maps)
    on_piece = k + stack.repeat(first_piece)
    on_node = k + stack.repeat(first_node)
    width, poly, nodes, lengths = tables.width, tables.poly, tables.nodes, tables.lengths
    u = (t - nodes[on_node]) / width[on_piece]
    rises = np.einsum("...j,...j->...", u[..., None] ** _POWERS, poly[on_piece, 0])  # (LengthMap._rises)
    return stack.split(lengths[on_node] + rises)


def spaced_parameters(maps: Sequence[LengthMap], counts: Sequence[int]) -> list[FloatArray]:
    """``counts[i]`` (at least 2) parameters from t = 0 to t = 1 evenly spaced in arc length
    along the curve of ``maps[i]`` (of positive length), for every map at once; the ends
    are exactly 0 and 1."""
    stack = Stack(counts)
    step = np.array([m.total for m in maps]) / (stack.counts - 1)
    local = np.arange(stack.rows) - stack.repeat(stack.starts)
    found = _parameters_at(maps, local * stack.repeat(step), stack)
    for t in found:
        t[0], t[-1] = 0.0, 1.0
    return [np.maximum.accumulate(t) for t in found]

def _refined(
    curve: Curve, nodes: FloatArray, inner: FloatArray, start: FloatArray, end: FloatArray, total: float
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray] | None:
    """The pieces of a :class:`LengthMap` split until each one's Gauss rule is exact to
    :data:`PAIR_TOLERANCE` of the curve's length (``total``, as they measure it), or None
    where all of them are already.

    The pieces (ends ``nodes``, speeds at their Gauss nodes ``inner``, at their ``start``
    and ``end``) are checked in pairs of neighbours within a span: the rule through the
    pair's 11 speeds is exact to degree 11 where the two Gauss rules are to degree 7, so
    their difference (:data:`_PAIR_CHECK`) is the Gauss rules' error wherever the speed is
    smooth at the pair's scale, and where it is not (a knot inside a piece: a NURBS run as
    t², whose parameter no longer reports where its knots are) the difference is of the
    error's size. Each piece of a pair that fails becomes a pair of its own (9 new speeds:
    its middle and its halves' Gauss nodes), checked again; a piece's end at a breakpoint
    keeps its speed from the left. Returns the new ``nodes, inner, start, end``.
    """
    low, width = nodes[:-2:2], nodes[2::2] - nodes[:-2:2]
    tolerance = 2.0 * PAIR_TOLERANCE * total
    bad = _pair_errors(nodes, inner, start, end) > tolerance
    if not bad.any():
        return None
    samples = np.column_stack([start[::2], inner[::2], end[::2], inner[1::2], end[1::2]])
    budget = GROWTH * len(low)
    for _ in range(ROUNDS):
        if not bad.any() or len(low) + np.count_nonzero(bad) > budget:
            break
        # the two halves of every failing pair, as pairs: their ends are known, the rest new
        halves = np.repeat(0.5 * width[bad], 2)
        starts = np.column_stack([low[bad], low[bad] + 0.5 * width[bad]]).ravel()
        at = starts[:, None] + halves[:, None] * _PAIR_AT[None, 1:-1]
        d1 = curve.derivative_at(at.reshape(-1), 1)
        new = np.empty((len(starts), 11))
        new[:, 1:-1] = np.sqrt(dot(d1, d1)).reshape(len(starts), 9)
        new[:, [0, -1]] = samples[bad][:, [0, 5, 5, 10]].reshape(-1, 2)
        low = np.concatenate([low[~bad], starts])
        width = np.concatenate([width[~bad], halves])
        samples = np.concatenate([samples[~bad], new])
        bad = np.concatenate([np.zeros(len(bad) - np.count_nonzero(bad), dtype=bool),
                              np.abs(halves * (new @ _PAIR_CHECK)) > tolerance])
    order = np.argsort(low, kind="stable")
    low, width, samples = low[order], width[order], samples[order]
    # back to pieces: each pair's two halves
    nodes = np.append(np.column_stack([low, low + 0.5 * width]).ravel(), nodes[-1])
    inner = samples[:, np.r_[1:5, 6:10]].reshape(-1, 4)
    return nodes, inner, samples[:, [0, 5]].reshape(-1), samples[:, [5, 10]].reshape(-1)


def station_parameters(
    curve: Curve, count: int, spacing: Spacing = "length", length_map: LengthMap | None = None
) -> FloatArray:
    """``count`` parameters from t = 0 to t = 1, evenly spaced in arc length or in t.

    The ends are exactly 0 and 1 (a closed curve gets both: its first and last ruling
    coincide, which closes a loft).
    """
    if count < 2:
        raise ValueError(f"At least 2 stations are needed; got {count}.")
    if spacing == "parameter":
        return np.linspace(0.0, 1.0, count)
    if spacing != "length":
        raise ValueError(f"Station spacing must be 'length' or 'parameter'; got {spacing!r}.")
    lengths = length_map or LengthMap(curve)
    if lengths.total <= 0.0:
        raise ValueError("The curve has zero length, so rulings cannot be spaced along it.")
    return spaced_parameters([lengths], [count])[0]
