"""Straight curves: :class:`Line` (one segment) and :class:`Polyline` (a chain of segments)."""

from __future__ import annotations

from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike

from ..array_types import FloatArray
from ..curve_base import ClosestPoints, Curve
from ..transforms import apply_transform
from ..vec_ops import anchor
from ..vectors import as_points, as_vector
from .nurbs import NurbsCurve


class Line(Curve):
    """The segment from ``start`` to ``end``: ``C(t) = start + t·(end − start)``.

    A zero-length line is allowed (its tangent is the zero vector); nodes that need a
    direction should check :attr:`length`.

    >>> Line([0, 0, 0], [2, 0, 0]).point_at(0.25).tolist()
    [0.5, 0.0, 0.0]
    """

    #: Derivatives from the definition, not differences of positions (:func:`.vec_ops.differenced`).
    exact_derivatives = True

    def __init__(self, start: ArrayLike, end: ArrayLike) -> None:
        self._start = as_vector(start)
        self._end = as_vector(end)
        if not (np.all(np.isfinite(self._start)) and np.all(np.isfinite(self._end))):
            raise ValueError("A line's end points must have finite coordinates.")
        self._start.setflags(write=False)
        self._end.setflags(write=False)
        self.closed = False

    @classmethod
    def many(cls, starts: ArrayLike, ends: ArrayLike) -> list[Line]:
        """One line per row of ``starts`` and ``ends`` (``(n, 3)``), checked once for
        all: several times faster than ``n`` constructor calls, for nodes that output
        hundreds of rulings on every solve.

        >>> [line.end.tolist() for line in Line.many([[0, 0, 0], [1, 0, 0]], [[0, 1, 0], [1, 1, 0]])]
        [[0.0, 1.0, 0.0], [1.0, 1.0, 0.0]]
        """
        a, b = as_points(starts), as_points(ends)
        if a.shape != b.shape:
            raise ValueError(f"Expected as many line ends as starts; got {len(b)} and {len(a)}.")
        if not (np.isfinite(a).all() and np.isfinite(b).all()):
            raise ValueError("A line's end points must have finite coordinates.")
        return cls._of_rows(a, b)

    @classmethod
    def _of_rows(cls, starts: FloatArray, ends: FloatArray) -> list[Line]:
        """:meth:`many` for ``(n, 3)`` float arrays of one shape whose coordinates the
        caller has checked are finite (the lines keep read-only copies)."""
        a, b = starts.copy(), ends.copy()
        a.setflags(write=False)
        b.setflags(write=False)
        lines = []
        for start, end in zip(a, b, strict=True):  # only attribute setting per line
            line = cls.__new__(cls)
            line._start, line._end, line.closed = start, end, False
            lines.append(line)
        return lines

    @property
    def start(self) -> FloatArray:
        return self._start

    @property
    def end(self) -> FloatArray:
        return self._end

    @property
    def direction(self) -> FloatArray:
        """``end − start`` (not normalised)."""
        return self._end - self._start

    @property
    def length(self) -> float:
        return float(np.linalg.norm(self.direction))

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        t = np.atleast_1d(np.asarray(t, dtype=float)).reshape(-1)
        result = [self._start + t[:, None] * self.direction]
        if order >= 1:
            result.append(np.broadcast_to(self.direction, (len(t), 3)).copy())
        result.extend(np.zeros((len(t), 3)) for _ in range(order - 1))
        return result

    @property
    def anchor(self) -> FloatArray:
        """The start (see :meth:`local_derivatives`)."""
        return self._start

    def local_derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        result = self.derivatives(t, order)
        t = np.atleast_1d(np.asarray(t, dtype=float)).reshape(-1)
        result[0] = t[:, None] * self.direction
        return result

    def length_at(self, t: ArrayLike) -> FloatArray:
        return np.asarray(t, dtype=float) * self.length

    def parameter_at_length(self, s: ArrayLike) -> FloatArray:
        length = self.length
        return np.clip(np.asarray(s, dtype=float) / (length if length > 0 else 1.0), 0.0, 1.0)

    def bounding_box(self) -> FloatArray:
        ends = np.stack([self._start, self._end])
        return np.stack([ends.min(axis=0), ends.max(axis=0)])

    def closest_point(self, points: ArrayLike) -> ClosestPoints:
        """Closest points on the segment, in closed form (projection clamped to [0, 1])."""
        p = as_points(points)
        d = self.direction
        dd = float(d @ d)
        t = np.zeros(len(p)) if dd == 0 else np.clip((p - self._start) @ d / dd, 0.0, 1.0)
        closest = self._start + t[:, None] * d
        return ClosestPoints(t, closest, np.linalg.norm(p - closest, axis=1))

    def reversed(self) -> Line:
        return Line(self._end, self._start)

    def transformed(self, matrix: ArrayLike) -> Line:
        start, end = apply_transform(matrix, np.stack([self._start, self._end]))
        return Line(start, end)

    def to_nurbs(self) -> NurbsCurve:
        """The line as a degree-1 NURBS curve with the same parameterisation."""
        return NurbsCurve(np.stack([self._start, self._end]), degree=1)

    def __repr__(self) -> str:
        return f"Line({self._start.tolist()}, {self._end.tolist()})"


class Polyline(Curve):
    """A chain of straight segments through ``points``, parameterised by arc length.

    ``t`` is the fraction of the total length travelled, so :meth:`point_at` at evenly
    spaced ``t`` gives evenly spaced points; :attr:`vertex_parameters` holds the ``t`` of
    each vertex. With ``closed=True`` a last segment back to the first point is added
    (unless the last point already repeats the first). A polyline whose ends coincide is
    closed either way.

    >>> Polyline([[0, 0], [1, 0], [1, 3]]).vertex_parameters.tolist()
    [0.0, 0.25, 1.0]
    """

    #: Derivatives from the definition, not differences of positions (:func:`.vec_ops.differenced`).
    exact_derivatives = True

    def __init__(self, points: ArrayLike, closed: bool = False) -> None:
        p = as_points(points)
        if len(p) < 2:
            raise ValueError(f"A polyline needs at least 2 points; got {len(p)}.")
        if not np.all(np.isfinite(p)):
            raise ValueError("A polyline point has a non-finite coordinate.")
        if closed and not np.array_equal(p[0], p[-1]):
            p = np.concatenate([p, p[:1]])
        segment_lengths = np.linalg.norm(np.diff(p, axis=0), axis=1)
        total = segment_lengths.sum()
        if total == 0:
            raise ValueError("A polyline needs at least two distinct points.")
        self.points: FloatArray = p
        self.vertex_parameters: FloatArray = np.concatenate([[0.0], np.cumsum(segment_lengths) / total])
        self.vertex_parameters[-1] = 1.0
        self._length = float(total)
        self.closed = bool(np.array_equal(p[0], p[-1]))
        for array in (self.points, self.vertex_parameters):
            array.setflags(write=False)

    @classmethod
    def from_curve(cls, curve: Curve, tolerance: float) -> Polyline:
        """A polyline within ``tolerance`` (a distance) of ``curve``, by adaptive subdivision
        (:meth:`Curve.tessellate`)."""
        return cls(curve.point_at(curve.tessellate(tolerance)))

    @property
    def length(self) -> float:
        return self._length

    @property
    def segments(self) -> list[Line]:
        """The segments as :class:`Line` objects."""
        return [Line(a, b) for a, b in zip(self.points[:-1], self.points[1:], strict=True)]

    def _segment_index(self, t: FloatArray) -> FloatArray:
        # side="right" skips zero-length segments; t = 1 falls in the last segment.
        index = np.searchsorted(self.vertex_parameters, t, side="right") - 1
        return np.clip(index, 0, len(self.points) - 2)

    @property
    def anchor(self) -> FloatArray:
        """The centre of the vertices' bounding box (see :meth:`local_derivatives`)."""
        return self._local[0]

    @cached_property
    def _local(self) -> tuple[FloatArray, FloatArray]:
        """The anchor and the vertices relative to it (exact, as in ``vec_ops.anchor``)."""
        origin = anchor(self.points)
        return origin, self.points - origin

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        result = self.local_derivatives(t, order)
        result[0] = result[0] + self._local[0]
        return result

    def local_derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        """Points relative to :attr:`anchor` (rounded to the polyline's size, not to its
        position) and derivatives."""
        t = np.atleast_1d(np.asarray(t, dtype=float)).reshape(-1)
        points = self._local[1]
        i = self._segment_index(t)
        t0, t1 = self.vertex_parameters[i], self.vertex_parameters[i + 1]
        width = t1 - t0
        safe = np.where(width > 0, width, 1.0)
        segment = points[i + 1] - points[i]
        local = np.where(width > 0, (t - t0) / safe, 0.0)
        result = [points[i] + local[:, None] * segment]
        if order >= 1:
            result.append(np.where(width[:, None] > 0, segment / safe[:, None], 0.0))
        result.extend(np.zeros((len(t), 3)) for _ in range(order - 1))
        return result

    def _breakpoints(self) -> FloatArray:
        return np.unique(self.vertex_parameters)

    def length_at(self, t: ArrayLike) -> FloatArray:
        return np.clip(np.asarray(t, dtype=float), 0.0, 1.0) * self._length

    def parameter_at_length(self, s: ArrayLike) -> FloatArray:
        return np.clip(np.asarray(s, dtype=float) / self._length, 0.0, 1.0)

    def bounding_box(self) -> FloatArray:
        return np.stack([self.points.min(axis=0), self.points.max(axis=0)])

    def closest_point(self, points: ArrayLike) -> ClosestPoints:
        """Closest points, in closed form: every segment is tried, in memory-bounded chunks."""
        p = as_points(points)
        a = self.points[:-1]
        d = self.points[1:] - a
        dd = np.einsum("ij,ij->i", d, d)
        safe = np.where(dd > 0, dd, 1.0)
        best_t = np.empty(len(p))
        best_points = np.empty((len(p), 3))
        best_distance = np.empty(len(p))
        chunk = max(1, 2_000_000 // len(a))
        for start in range(0, len(p), chunk):  # chunks bound memory, not a per-point loop
            q = p[start : start + chunk]
            s = np.clip(np.einsum("mij,ij->mi", q[:, None, :] - a, d) / safe, 0.0, 1.0)
            s = np.where(dd > 0, s, 0.0)
            foot = a + s[..., None] * d
            dist2 = np.sum((q[:, None, :] - foot) ** 2, axis=2)
            j = np.argmin(dist2, axis=1)
            rows = np.arange(len(q))
            t0, t1 = self.vertex_parameters[j], self.vertex_parameters[j + 1]
            best_t[start : start + chunk] = t0 + s[rows, j] * (t1 - t0)
            best_points[start : start + chunk] = foot[rows, j]
            best_distance[start : start + chunk] = np.sqrt(dist2[rows, j])
        return ClosestPoints(best_t, best_points, best_distance)

    def reversed(self) -> Polyline:
        return Polyline(self.points[::-1])

    def transformed(self, matrix: ArrayLike) -> Polyline:
        return Polyline(apply_transform(matrix, self.points))

    def to_nurbs(self) -> NurbsCurve:
        """The polyline as a degree-1 NURBS curve with the same parameterisation."""
        # zero-length segments would repeat a knot twice in a degree-1 curve: drop them
        keep = np.concatenate([[True], np.diff(self.vertex_parameters) > 0])
        knots = np.concatenate([[0.0], self.vertex_parameters[keep], [1.0]])
        return NurbsCurve(self.points[keep], degree=1, knots=knots)

    def __repr__(self) -> str:
        return f"Polyline({len(self.points)} points, closed={self.closed})"
