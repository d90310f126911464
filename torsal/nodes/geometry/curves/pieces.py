"""Curves cut into pieces and pieces joined into curves: sub-curves, poly-curves, join, split, explode.

- :class:`SubCurve` — the part of a curve between two parameters, reparameterised to [0, 1].
- :class:`PolyCurve` — curves end to end as one curve; each piece's share of t is its share
  of the length, so a poly-curve of lines is parameterised as the :class:`Polyline` through
  them is.
- :func:`join` chains curves whose ends meet, :func:`split` cuts a curve at parameters,
  :func:`explode` gives a curve's smooth pieces (a polyline's segments, a poly-curve's
  pieces, a NURBS curve's spans between kinks).

Lines and polylines stay lines and polylines through all three (exact, and what a
Grasshopper user expects to bake); other curves are wrapped in the views below.
"""

from __future__ import annotations

import itertools

import numpy as np
from numpy.typing import ArrayLike
from scipy.spatial import cKDTree

from ..array_types import FloatArray
from ..curve_base import Curve
from .line import Line, Polyline
from .nurbs import NurbsCurve


class SubCurve(Curve):
    """``C(t0 + (t1 − t0)·t)``: the part of ``curve`` from ``t0`` to ``t1`` (``t0 < t1``)."""

    def __init__(self, curve: Curve, t0: float, t1: float) -> None:
        if not 0.0 <= t0 < t1 <= 1.0:
            raise ValueError(f"A sub-curve needs 0 <= t0 < t1 <= 1; got {t0}, {t1}.")
        if isinstance(curve, SubCurve):  # a piece of a piece is a piece of the original
            a, b = curve.t0, curve.t1
            curve, t0, t1 = curve.curve, a + (b - a) * t0, a + (b - a) * t1
        self.curve, self.t0, self.t1 = curve, float(t0), float(t1)
        self.closed = bool(curve.closed and t0 == 0.0 and t1 == 1.0)

    def _outer(self, t: ArrayLike) -> FloatArray:
        return self.t0 + (self.t1 - self.t0) * np.atleast_1d(np.asarray(t, dtype=float)).reshape(-1)

    def _scaled(self, result: list[FloatArray]) -> list[FloatArray]:
        width = self.t1 - self.t0
        return [d * width**k for k, d in enumerate(result)]

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        return self._scaled(self.curve.derivatives(self._outer(t), order))

    @property
    def anchor(self) -> FloatArray:
        return self.curve.anchor

    def local_derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        return self._scaled(self.curve.local_derivatives(self._outer(t), order))

    def _breakpoints(self) -> FloatArray:
        inner = self.curve._breakpoints()
        inside = inner[(inner > self.t0) & (inner < self.t1)]
        return np.concatenate([[0.0], (inside - self.t0) / (self.t1 - self.t0), [1.0]])

    def __repr__(self) -> str:
        return f"SubCurve({self.curve!r}, {self.t0:g}, {self.t1:g})"


class PolyCurve(Curve):
    """``pieces`` end to end as one curve (each piece's start on the previous one's end).

    Piece i runs over ``t`` in ``[breaks[i], breaks[i + 1]]``, a share of [0, 1] equal to
    its share of the total length. Closed when the last piece ends where the first starts
    (within ``tolerance``, a distance).
    """

    def __init__(self, pieces: list[Curve], tolerance: float = 0.0) -> None:
        if not pieces:
            raise ValueError("A poly-curve needs at least one piece.")
        self.pieces = list(pieces)
        lengths = np.array([piece.length for piece in self.pieces])
        if not (np.all(np.isfinite(lengths)) and lengths.sum() > 0):
            raise ValueError("A poly-curve needs pieces of finite, positive total length.")
        self.breaks: FloatArray = np.concatenate([[0.0], np.cumsum(lengths) / lengths.sum()])
        self.breaks[-1] = 1.0
        self._length = float(lengths.sum())
        gap = np.linalg.norm(self.pieces[-1].end_points[1] - self.pieces[0].end_points[0])
        self.closed = bool(len(self.pieces) > 1 and gap <= tolerance)

    @property
    def length(self) -> float:
        return self._length

    def _each(self, t: ArrayLike, order: int, local: bool) -> list[FloatArray]:
        t = np.atleast_1d(np.asarray(t, dtype=float)).reshape(-1)
        index = np.clip(np.searchsorted(self.breaks, t, side="right") - 1, 0, len(self.pieces) - 1)
        result = [np.empty((len(t), 3)) for _ in range(order + 1)]
        for i in np.unique(index):  # one vectorised call per piece that holds a parameter
            rows = index == i
            a, b = self.breaks[i], self.breaks[i + 1]
            width = b - a
            s = np.clip((t[rows] - a) / width, 0.0, 1.0) if width > 0 else np.zeros(rows.sum())
            piece = self.pieces[i]
            values = piece.local_derivatives(s, order) if local else piece.derivatives(s, order)
            if local:
                values[0] = values[0] + piece.anchor - self.anchor
            for k in range(order + 1):
                result[k][rows] = values[k] / (width**k if width > 0 else 1.0)
        return result

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        return self._each(t, order, local=False)

    @property
    def anchor(self) -> FloatArray:
        return self.pieces[0].anchor

    def local_derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        return self._each(t, order, local=True)

    def _breakpoints(self) -> FloatArray:
        spans = [a + (b - a) * piece._breakpoints()
                 for piece, a, b in zip(self.pieces, self.breaks[:-1], self.breaks[1:], strict=True)]
        return np.unique(np.concatenate([self.breaks, *spans]))

    def __repr__(self) -> str:
        return f"PolyCurve({len(self.pieces)} pieces, closed={self.closed})"


def size_of(curves: list[Curve]) -> float:
    """The diagonal of the box around every curve's ends and middle (a scale for tolerances)."""
    points = np.concatenate([c.point_at(np.array([0.0, 0.5, 1.0])) for c in curves])
    return float(np.linalg.norm(np.ptp(points, axis=0)))


def _is_straight(curve: Curve) -> bool:
    return isinstance(curve, Line | Polyline)


def _vertices(curve: Curve) -> FloatArray:
    return np.asarray(curve.points if isinstance(curve, Polyline) else curve.end_points)


def _joined(chain: list[Curve], tolerance: float) -> Curve:
    """One curve from pieces already oriented end to end: a polyline when all are straight."""
    if len(chain) == 1:
        return chain[0]
    if all(_is_straight(c) for c in chain):
        points = [_vertices(chain[0])] + [_vertices(c)[1:] for c in chain[1:]]
        joined = np.concatenate(points)
        if np.linalg.norm(joined[-1] - joined[0]) <= tolerance:
            joined[-1] = joined[0]  # closed exactly
        return Polyline(joined)
    return PolyCurve(chain, tolerance)


def join(curves: list[Curve], tolerance: float) -> list[Curve]:
    """Chain ``curves`` whose ends lie within ``tolerance`` of each other, in input order.

    Each chain starts at the first curve not yet used and grows at its end, then at its
    start, taking at each step the nearest free end (a piece is reversed when it meets
    the chain end first). Returns one curve per chain.
    """
    count = len(curves)
    ends = np.concatenate([c.end_points for c in curves])  # row 2i: start of curve i, 2i + 1: its end
    tree = cKDTree(ends)
    neighbours = tree.query_ball_point(ends, r=tolerance)
    used = np.zeros(count, dtype=bool)

    def nearest(row: int) -> int | None:
        free = [j for j in neighbours[row] if j // 2 != row // 2 and not used[j // 2]]
        if not free:
            return None
        return min(free, key=lambda j: float(np.linalg.norm(ends[j] - ends[row])))

    chains: list[Curve] = []
    for first in range(count):
        if used[first]:
            continue
        used[first] = True
        chain: list[tuple[int, bool]] = [(first, False)]  # (curve, reversed)
        for grow_end in (True, False):
            while True:
                index, flipped = chain[-1] if grow_end else chain[0]
                # the free end of the chain: the end of its last piece, or the start of its first
                row = 2 * index + (1 if grow_end != flipped else 0)
                found = nearest(row)
                if found is None:
                    break
                other, meets_at_end = found // 2, bool(found % 2)
                used[other] = True
                if grow_end:
                    chain.append((other, meets_at_end))  # its end meets ours: run it backwards
                else:
                    chain.insert(0, (other, not meets_at_end))
            first_start = ends[2 * chain[0][0] + chain[0][1]]
            last_end = ends[2 * chain[-1][0] + 1 - chain[-1][1]]
            if len(chain) > 1 and np.linalg.norm(first_start - last_end) <= tolerance:
                break  # closed: nothing to add at the start
        pieces = [curves[i].reversed() if flipped else curves[i] for i, flipped in chain]
        chains.append(_joined(pieces, tolerance))
    return chains


def split(curve: Curve, parameters: ArrayLike) -> list[Curve]:
    """``curve`` cut at ``parameters`` (t in [0, 1]; outside, repeated or at an end they cut
    nothing): the pieces in order. A closed curve cut at one parameter inside gives two
    pieces, as an open one does."""
    t = np.unique(np.asarray(parameters, dtype=float).reshape(-1))
    t = t[(t > 0.0) & (t < 1.0)]
    cuts = np.concatenate([[0.0], t, [1.0]])
    if isinstance(curve, Line | Polyline):
        return [_straight_piece(curve, a, b) for a, b in itertools.pairwise(cuts)]
    if len(cuts) == 2:
        return [curve]
    return [SubCurve(curve, a, b) for a, b in itertools.pairwise(cuts)]


def _straight_piece(curve: Line | Polyline, a: float, b: float) -> Line | Polyline:
    """The exact part of a line or polyline from t = a to t = b (parameterised by length)."""
    if isinstance(curve, Line):
        return Line(curve.point_at(a), curve.point_at(b))
    inside = (curve.vertex_parameters > a) & (curve.vertex_parameters < b)
    ends = curve.point_at(np.array([a, b]))
    points = np.concatenate([ends[:1], curve.points[inside], ends[1:]])
    return Line(points[0], points[1]) if len(points) == 2 else Polyline(points)


def explode(curve: Curve) -> list[Curve]:
    """The smooth pieces of ``curve``: a polyline's segments, a poly-curve's pieces (each
    exploded in turn), a NURBS curve's spans between kinks (a degree-1 NURBS curve's
    segments); any other curve is one piece."""
    if isinstance(curve, Polyline):
        return [s for s in curve.segments if s.length > 0]
    if isinstance(curve, PolyCurve):
        return [piece for inner in curve.pieces for piece in explode(inner)]
    if isinstance(curve, NurbsCurve) and curve.degree == 1:  # straight between its knots
        corners = curve.point_at(curve._breakpoints())
        return [Line(a, b) for a, b in itertools.pairwise(corners) if np.any(a != b)]
    if isinstance(curve, NurbsCurve):
        kinks = curve.kinks()
        kinks = kinks[kinks > 0.0]  # (not a closed curve's seam: it is already an end)
        if len(kinks):
            return split(curve, kinks)
    return [curve]
