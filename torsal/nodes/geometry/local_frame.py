"""Solving near the origin: a frame anchored at the model, for geometry at site coordinates.

A point 1e9 m from the world origin is known to 1.2e-7 m, whatever its object's size.
Work that subtracts positions (a ruling B − A, a closest point, a distance to a design)
done there rounds each position to that, and a search that is sensitive to its inputs
(a torsal partner, a strip's placement by its deviation) turns it into tens or
hundreds of ulps. A :class:`LocalFrame` moves the inputs once to a frame whose origin
is the model's (the rounded centre of its box), the solve runs there as it would at the
world origin, and its outputs are moved back once: only those two translations round.

:func:`translated` moves any kernel curve or surface *exactly on its defining data*
(control points, vertices, rails, the wrapped object of a view): the moved object is the
same kind as the original, and at site coordinates (where the offset and the
coordinates nearly cancel) every coordinate of it is exact (Sterbenz), so the local
model is the world model, moved, to the last bit. Kinds it does not know are wrapped in
their generic transformed view (a function surface evaluates in world coordinates and is
then moved: no better, no worse). Modules with curve kinds of their own register them
(:func:`register`).

Applying it in a node, in three lines::

    frame = LocalFrame.around(curve_a, curve_b)          # no frame near the origin
    result = solve(frame.to_local(curve_a), frame.to_local(curve_b))
    starts, ends = frame.points_to_world(result.starts), frame.points_to_world(result.ends)

Near the world origin (the model's centre within :data:`NEAR` of its extent from it) the
frame is the world itself: the geometry is handed on as it is, and the solve is exactly
what it was without a frame.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from functools import singledispatch
from typing import Any, TypeVar

import numpy as np
from numpy.typing import ArrayLike

from .array_types import FloatArray
from .curve_base import Curve, ReversedCurve, TransformedCurve
from .curve_rail import CurveRail
from .curves.conics import Arc, Circle
from .curves.interpolated import InterpolatedCurve
from .curves.line import Line, Polyline
from .curves.nurbs import NurbsCurve
from .curves.shared_knots import derivative_each
from .nurbs_surface import Loft, NurbsSurface
from .ruled import RuledSurface, SplineRail
from .surface_base import IsoCurve, Surface, TransformedSurface
from .transforms import translation
from .trimmed_surface import TrimmedSurface

#: A model whose box centre is within this many extents of the world origin stays in world
#: coordinates: its coordinates already round relative to its size.
NEAR = 8.0

#: Samples per direction of each object, for the model's box (an anchor need not be exact).
SAMPLES = 9

G = TypeVar("G")


class Mover:
    """One translation by ``offset``, remembering what it has moved (and, for a frame's
    way back, what the moved objects were), so an object shared by several inputs (a
    design under every boundary curve) is moved once and stays shared."""

    def __init__(self, offset: ArrayLike, known: dict[int, tuple[Any, Any]] | None = None) -> None:
        self.offset: FloatArray = np.asarray(offset, dtype=float).reshape(3)
        self.known: dict[int, tuple[Any, Any]] = {} if known is None else known

    def __call__(self, geometry: G) -> G:
        if not self.offset.any():
            return geometry
        seen = self.known.get(id(geometry))
        if seen is not None and seen[0] is geometry:
            return seen[1]
        moved = _translate(geometry, self)
        self.known[id(geometry)] = (geometry, moved)  # (keeps the original alive: its id stays unique)
        return moved

    def points(self, points: ArrayLike) -> FloatArray:
        """Points (any shape ending in 3) moved by the offset."""
        return np.asarray(points, dtype=float) + self.offset


def translated(geometry: G, offset: ArrayLike) -> G:
    """``geometry`` (a kernel curve or surface) moved by ``offset``, as the same kind of
    object, exactly on its defining data (see the module); itself for a zero offset."""
    return Mover(offset)(geometry)


@singledispatch
def _translate(geometry: Any, move: Mover) -> Any:
    raise TypeError(f"cannot move a {type(geometry).__name__}: only curves and surfaces")


def register(kind: type) -> Callable[[Callable[[Any, Mover], Any]], Callable[[Any, Mover], Any]]:
    """Register how a curve or surface kind is moved: ``fn(geometry, move)`` returns the
    moved object, moving what it wraps with ``move(...)`` and points with ``move.points``."""
    return _translate.register(kind)



@_translate.register
def _(curve: Curve, move: Mover) -> Curve:
    return curve.transformed(translation(move.offset))


@_translate.register
def _(surface: Surface, move: Mover) -> Surface:
    return TransformedSurface(surface, translation(move.offset))


@_translate.register
def _(curve: NurbsCurve, move: Mover) -> NurbsCurve:
    weights = curve.weights if curve.is_rational else None
    return NurbsCurve.from_arrays(move.points(curve.control_points), curve.knots, curve.degree, weights,
                                  curve.periodic)


@_translate.register
def _(curve: InterpolatedCurve, move: Mover) -> InterpolatedCurve:
    weights = curve.weights if curve.is_rational else None
    moved = InterpolatedCurve.from_arrays(move.points(curve.control_points), curve.knots, curve.degree,
                                          weights, curve.periodic)
    moved._set_points(move.points(curve.points), curve.parameters)
    return moved


@_translate.register
def _(circle: Circle, move: Mover) -> Circle:
    return Circle(dataclasses.replace(circle.plane, origin=move.points(circle.plane.origin)), circle.radius)


@_translate.register
def _(arc: Arc, move: Mover) -> Arc:
    plane = dataclasses.replace(arc.plane, origin=move.points(arc.plane.origin))
    return Arc(plane, arc.radius, arc.start_angle, arc.end_angle)


@_translate.register
def _(line: Line, move: Mover) -> Line:
    return Line(move.points(line.start), move.points(line.end))


@_translate.register
def _(polyline: Polyline, move: Mover) -> Polyline:
    return Polyline(move.points(polyline.points))


@_translate.register
def _(rail: SplineRail, move: Mover) -> SplineRail:
    return SplineRail(rail.params, move.points(rail.points), rail.closed)


@_translate.register
def _(curve: ReversedCurve, move: Mover) -> ReversedCurve:
    return ReversedCurve(move(curve.curve))


@_translate.register
def _(curve: TransformedCurve, move: Mover) -> TransformedCurve:
    return TransformedCurve(curve.curve, translation(move.offset) @ curve.matrix)


@_translate.register
def _(rail: CurveRail, move: Mover) -> CurveRail:
    return CurveRail(move(rail.curve), rail.params, rail.curve_params)


@_translate.register
def _(curve: IsoCurve, move: Mover) -> IsoCurve:
    return IsoCurve(move(curve.surface), curve.direction, curve.param, curve.reverse)


@_translate.register
def _(surface: TrimmedSurface, move: Mover) -> TrimmedSurface:
    return TrimmedSurface(move(surface.surface), surface.outer, surface.holes)  # the trim is in (u, v)


@_translate.register
def _(surface: TransformedSurface, move: Mover) -> Surface:
    matrix = translation(move.offset) @ surface.matrix
    if np.array_equal(matrix, np.eye(4)):
        return surface.surface
    return TransformedSurface(surface.surface, matrix)


@_translate.register
def _(surface: NurbsSurface, move: Mover) -> NurbsSurface:
    weights = surface.weights if surface.is_rational else None
    moved = NurbsSurface(move.points(surface.control_points), surface.degree_u, surface.degree_v,
                         surface.knots_u, surface.knots_v, weights)
    if isinstance(surface, Loft):  # a loft keeps the curves it was made through
        moved.__class__ = Loft
        moved.curves = [move(c) for c in surface.curves]
        moved.curve_parameters = surface.curve_parameters
    return moved


@_translate.register
def _(surface: RuledSurface, move: Mover) -> RuledSurface:
    moved = RuledSurface.__new__(RuledSurface)
    lines = surface.ruling_lines
    both = surface._both
    if both is not None:  # a loft of given rulings: its rails share one spline, through both's points
        # (not ruling_lines: those are the rulings drawn, which may be fewer than the rails')
        a, b = move.points(both.points[:, :3]), move.points(both.points[:, 3:])
        rails = SplineRail._pair(both.params, a, b, surface.closed_u, both.degree)
    else:
        rails = move(surface.curve_a), move(surface.curve_b)
    moved._setup(*rails, surface.closed_u)
    moved.ruling_parameters = surface.ruling_parameters
    moved.ruling_lines = None if lines is None else move.points(lines)
    return moved


def _samples(geometry: Any) -> FloatArray:
    """A few points of ``geometry`` (a curve, a surface or an array of points), for its box."""
    if isinstance(geometry, Curve):
        return np.atleast_2d(geometry.point_at(_UNIT.copy()))
    if isinstance(geometry, Surface):
        u, v = np.meshgrid(_UNIT, _UNIT, indexing="ij")
        return geometry.point_at(u.ravel(), v.ravel())
    return np.asarray(geometry, dtype=float).reshape(-1, 3)


def _curve_samples(curves: Sequence[Curve]) -> list[FloatArray]:
    """:func:`_samples` of every curve of ``curves``, bit for bit: each distinct curve once
    (a roof's edge is two strips' curve), those that share knots evaluated together
    (:func:`.curves.shared_knots.derivative_each`: ``point_at`` is the derivative of order 0)."""
    distinct = list({id(curve): curve for curve in curves}.values())
    found = derivative_each(distinct, [_UNIT.copy() for _ in distinct], 0)
    by_id = {id(curve): points for curve, points in zip(distinct, found, strict=True)}
    return [by_id[id(curve)] for curve in curves]


#: The parameters of a curve's :data:`SAMPLES` samples (read-only: each curve gets a copy).
_UNIT = np.linspace(0.0, 1.0, SAMPLES)
_UNIT.setflags(write=False)


def frame_origin(points: ArrayLike) -> FloatArray:
    """Where a frame around ``points`` (``(n, 3)``) is anchored: the centre of their box,
    rounded to a multiple of the power of two at or above its extent (so a model moved by
    a round offset keeps its local coordinates, bit for bit); the world origin when the
    centre is within :data:`NEAR` extents of it, or the points are not all finite."""
    p = np.asarray(points, dtype=float).reshape(-1, 3)
    return frame_origins(p, [len(p)])[0]


def frame_origins(points: FloatArray, counts: Sequence[int]) -> FloatArray:
    """:func:`frame_origin` of each group of ``points`` (``(n, 3)``, group after group, of
    ``counts`` points each), their boxes found at once: ``(len(counts), 3)``."""
    counts = np.asarray(counts, dtype=np.int64)
    origins = np.zeros((len(counts), 3))
    has = np.flatnonzero(counts)
    if len(has) == 0:
        return origins
    starts = (np.cumsum(counts) - counts)[has]
    finite = np.logical_and.reduceat(np.isfinite(points).all(axis=1), starts).tolist()
    low, high = np.minimum.reduceat(points, starts), np.maximum.reduceat(points, starts)
    with np.errstate(invalid="ignore"):  # (not finite: the world origin)
        centre = 0.5 * (low + high)
        sizes, reaches = (high - low).max(axis=1).tolist(), np.abs(centre).max(axis=1).tolist()
    for k, (group, ok, size, reach) in enumerate(zip(has.tolist(), finite, sizes, reaches, strict=True)):
        if not ok or reach <= NEAR * size or reach == 0.0:
            continue
        step = 2.0 ** math.ceil(math.log2(size)) if size > 0.0 else float(np.spacing(reach))
        origins[group] = np.round(centre[k] / step) * step
    return origins


class LocalFrame:
    """A frame whose origin is at the model: :meth:`to_local` moves inputs there,
    :meth:`to_world` and :meth:`points_to_world` move results back (see the module).

    An object moved back that the frame moved in the first place comes back as the very
    original; so do the objects built on it (an isocurve of the moved design, moved back,
    is an isocurve of the design itself)."""

    def __init__(self, origin: ArrayLike) -> None:
        self.origin: FloatArray = np.asarray(origin, dtype=float).reshape(3)
        self._in = Mover(-self.origin)
        self._out = Mover(self.origin)

    @classmethod
    def around(cls, *geometry: Any) -> LocalFrame:
        """The frame around curves, surfaces or point arrays (``None`` items are skipped)."""
        return cls.around_each([geometry])[0]

    @classmethod
    def around_each(cls, groups: Sequence[Sequence[Any]]) -> list[LocalFrame]:
        """:meth:`around` of each group of geometry, the groups' boxes found at once (the
        curves' samples too: :func:`_curve_samples`)."""
        kept = [[g for g in group if g is not None] for group in groups]
        curves = iter(_curve_samples([g for group in kept for g in group if isinstance(g, Curve)]))
        parts = [[next(curves) if isinstance(g, Curve) else _samples(g) for g in group] for group in kept]
        counts = [sum(len(part) for part in group) for group in parts]
        points = np.concatenate([part for group in parts for part in group] or [np.empty((0, 3))])
        return [cls(origin) for origin in frame_origins(points, counts)]

    @property
    def is_world(self) -> bool:
        """True when the frame is the world's own (nothing is moved)."""
        return not self.origin.any()

    def to_local(self, geometry: G) -> G:
        """``geometry`` in the frame (moved by −origin)."""
        local = self._in(geometry)
        if local is not geometry:
            self._out.known[id(local)] = (local, geometry)  # moved back, it is the original
        return local

    def to_world(self, geometry: G) -> G:
        """``geometry`` made in the frame, in world coordinates."""
        return self._out(geometry)

    def points_to_world(self, points: ArrayLike) -> FloatArray:
        """Points (any shape ending in 3) made in the frame, in world coordinates."""
        return self._out.points(points)
