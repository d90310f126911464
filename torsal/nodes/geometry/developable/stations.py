"""Where rulings start: stations spaced evenly along a curve, and a fast arc-length map.

The developable nodes place their ``Segments + 1`` rulings at stations spaced evenly in
arc length along the base curve, as Grasshopper's *Divide Curve* does (the thesis
divides the curve that way); ``spacing="parameter"`` spaces them evenly in t instead.

The arc length here is a light table: Gauss–Legendre on a fixed partition of every
smooth span, read back by cubic Hermite interpolation (the speed |C'| is the exact slope
of the length at each node), inverted by Newton steps from a linear guess, and the
stations then polished by one Newton step on the integral of the quintic through each
piece's six speeds (its ends and Gauss nodes). The cubic alone spaces stations evenly to
about 1e-9 of the length on a wavy curve — not enough for a strip that must not depend
on how its curve is parameterised (the same curve run as t² moved its stations by that);
the quintic to about 1e-15. It is still several times cheaper than the curve's own
:class:`~..arclength.LengthTable`, which matters when a slider rebuilds the curve on
every solve.
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import lru_cache
from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import ArrayLike
from scipy.special import roots_legendre

from ..array_types import IntArray
from ..curve_base import FloatArray
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
    # pieces in proportion to each span's share of the parameter, at least eight per span
    counts = np.maximum(8, np.ceil(intervals * widths).astype(int))
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
    each piece is integrated with the 4-point Gauss–Legendre rule (exact to rounding on
    pieces this short: its error falls as the 8th power of their length). Between the
    piece ends ℓ(t) is the cubic with the right values and slopes (the speed), kept as
    ℓ = ℓ0 + u·(d0 + u·(c2 + u·c3)) in the piece's own coordinate u.
    """

    def __init__(self, curve: Curve, intervals: int = 128) -> None:
        self._set(curve, *_tables([curve], intervals)[0])

    @classmethod
    def many(cls, curves: Sequence[Curve], intervals: int = 128) -> list[LengthMap]:
        """The map of each of ``curves``, each the one it gets alone (bit for bit), their
        tables made together (:func:`_tables`)."""
        maps = []
        for curve, tables in zip(curves, _tables(curves, intervals), strict=True):
            length_map = cls.__new__(cls)
            length_map._set(curve, *tables)
            maps.append(length_map)
        return maps

    def _set(
        self, curve: Curve, nodes: FloatArray, lengths: FloatArray, start_speeds: FloatArray,
        end_speeds: FloatArray, width: FloatArray, rise: FloatArray, d0: FloatArray, c2: FloatArray,
        c3: FloatArray, samples: FloatArray,
    ) -> None:
        self.curve = curve
        self.nodes: FloatArray = nodes
        self.lengths: FloatArray = lengths
        #: |C'| at the start and at the end of each piece: the slopes of ℓ(t) there
        self.start_speeds: FloatArray = start_speeds
        self.end_speeds: FloatArray = end_speeds
        #: Total arc length of the curve.
        self.total: float = float(lengths[-1])
        self._width, self._rise = width, rise
        self._d0, self._c2, self._c3 = d0, c2, c3
        # the speeds at each piece's ends and Gauss nodes (in its own coordinate u), for the
        # read-back of :meth:`_rises`
        self._samples = samples

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
        return np.einsum("...j,...j->...", u[..., None] ** _POWERS[1:], self._samples[k] @ _INTEGRAL)

    def parameter_at(self, length: ArrayLike) -> FloatArray:
        """The t at which the arc length from the start equals ``length`` (clipped to the curve)."""
        length = np.asarray(length, dtype=float)
        return _parameters_at([self], length.reshape(-1), Stack([length.size]))[0].reshape(length.shape)


def _tables(curves: Sequence[Curve], intervals: int) -> list[tuple[FloatArray, ...]]:
    """The tables of a :class:`LengthMap` of each of ``curves`` (what :meth:`LengthMap._set`
    takes after the curve), each the one the curve gets alone, bit for bit: each curve's
    speed is evaluated on its own, and so are its pieces' Gauss sums and their running total
    (a matrix product's and a cumulative sum's rounding depend on what else is in the
    array); the rest runs once for all of them."""
    layouts, speeds = [], []
    for curve in curves:
        breaks = tuple(curve._breakpoints().tolist())
        layout = _layout if len(breaks) <= 64 else _layout.__wrapped__  # long keys cost more than they save
        layouts.append(layout(breaks, int(intervals)))
        speeds.append(curve.derivative_at(layouts[-1][4], 1))
    stacked = np.concatenate(speeds)
    stacked = np.sqrt(dot(stacked, stacked))  # ((x² + y²) + z², as np.add.reduce along the rows sums)
    # each curve's speeds: at its Gauss nodes, its piece ends, just before its breakpoints
    pieces, lengths, starts, ends, gauss = [], [], [], [], []
    offset = 0
    for nodes, nodes_gauss, half, last, at in layouts:
        g, m = len(nodes_gauss), len(nodes)
        own = stacked[offset : offset + len(at)]
        offset += len(at)
        gauss.append(own[:g].reshape(-1, 4))
        pieces.append(half * (gauss[-1] @ _WEIGHTS))
        lengths.append(np.empty(m))
        lengths[-1][0] = 0.0
        np.cumsum(pieces[-1], out=lengths[-1][1:])
        starts.append(own[g : g + m - 1])
        ends.append(own[g + 1 : g + m].copy())
        ends[-1][last] = own[g + m :]
    rise = np.concatenate(pieces)
    h = 2.0 * np.concatenate([layout[2] for layout in layouts])
    d0, d1 = np.concatenate(starts) * h, np.concatenate(ends) * h
    c2 = 3.0 * rise - 2.0 * d0 - d1
    c3 = d0 + d1 - 2.0 * rise
    samples = np.empty((len(rise), 6))
    samples[:, 0], samples[:, 5] = d0, d1
    np.multiply(np.concatenate(gauss), h[:, None], out=samples[:, 1:5])
    tables = []
    low = 0
    for layout, length, start, end in zip(layouts, lengths, starts, ends, strict=True):
        high = low + len(start)
        own = (h, rise, d0, c2, c3, samples)
        tables.append((layout[0], length, start, end, *(x[low:high] for x in own)))
        low = high
    return tables


def _parameters_at(maps: Sequence[LengthMap], length: FloatArray, stack: Stack) -> list[FloatArray]:
    """:meth:`LengthMap.parameter_at` of each map of ``maps`` at its rows of ``length`` (as
    ``stack`` says), run once for all of them (each map's search and matrix product on its
    own rows: each gets what it gets alone, bit for bit)."""
    totals = np.array([m.total for m in maps])
    target = np.minimum(np.maximum(length, 0.0), stack.repeat(totals))
    pieces = Stack([len(m._rise) for m in maps])
    bounds = stack.offsets.tolist()
    k = np.concatenate([m.lengths.searchsorted(target[low:high], side="right") - 1
                        for m, low, high in zip(maps, bounds[:-1], bounds[1:], strict=True)])
    k = np.minimum(k, stack.repeat(pieces.counts - 1))
    on_piece = k + stack.repeat(pieces.starts)  # (each map's pieces among all of them)
    on_node = k + stack.repeat(pieces.starts + np.arange(len(maps)))  # (a node more than pieces each)
    d0, c2, c3, rise, width, nodes, lengths = (np.concatenate([getattr(m, name) for m in maps]) for name in (
        "_d0", "_c2", "_c3", "_rise", "_width", "nodes", "lengths"))
    d0, c2, c3 = d0[on_piece], c2[on_piece], c3[on_piece]
    gap = target - lengths[on_node]
    u = gap / np.maximum(rise[on_piece], 1e-300)
    # two Newton steps on the piece's cubic ℓ(u) − target from the linear guess
    floor = stack.repeat(1e-12 * np.maximum(totals, 1e-300))
    c2_twice = 2.0 * c2
    for _ in range(2):
        slope = d0 + u * (c2_twice + 3.0 * u * c3)
        step = (u * (d0 + u * (c2 + u * c3)) - gap) / np.maximum(slope, floor)
        u = np.minimum(np.maximum(u - np.where(slope > floor, step, 0.0), 0.0), 1.0)
    # then one on the quintic's integral (:meth:`LengthMap._rises`; the cubic's slope is the
    # speed to ~1e-9): the cubic's root is within ~1e-9 of the length of its, so one step
    # reaches rounding
    integrals = np.concatenate([m._samples[k[low:high]] @ _INTEGRAL
                                for m, low, high in zip(maps, bounds[:-1], bounds[1:], strict=True)])
    rises = np.einsum("...j,...j->...", u[..., None] ** _POWERS[1:], integrals)
    step = (rises - gap) / np.maximum(slope, floor)
    u = np.minimum(np.maximum(u - np.where(slope > floor, step, 0.0), 0.0), 1.0)
    return stack.split(np.minimum(nodes[on_node] + u * width[on_piece], 1.0))


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
