"""Intersections and closest approaches: lines with lines, planes and curves.

Lines are given by two points each (``start``, ``end``: ``(3,)`` or ``(n, 3)``, broadcast)
and treated as infinite; parameters are fractions of ``end − start`` from ``start``, as
in :class:`~.curves.Line`. Results for many lines come back as arrays, one row per line.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .array_types import BoolArray, FloatArray
from .closest import sample_parameters
from .roots import roots_in_samples
from .vec_ops import dot
from .vectors import Plane

if TYPE_CHECKING:
    from .curve_base import Curve


class LineLineClosest(NamedTuple):
    """Closest points between pairs of infinite lines (one row per pair)."""

    points_a: FloatArray  #: (n, 3) on line a
    points_b: FloatArray  #: (n, 3) on line b
    parameters_a: FloatArray  #: (n,) with points_a = a_start + s (a_end − a_start)
    parameters_b: FloatArray  #: (n,)
    distances: FloatArray  #: (n,) |points_a − points_b|
    parallel: BoolArray  #: (n,) no unique pair: parallel lines or a zero-length line


def line_line_closest_points(
    a_start: ArrayLike,
    a_end: ArrayLike,
    b_start: ArrayLike,
    b_end: ArrayLike,
    parallel_tolerance: float = 1e-12,
) -> LineLineClosest:
    """Closest points of pairs of infinite lines, vectorised over the pairs.

    With ``u = a_end − a_start``, ``v = b_end − b_start``, ``w = a_start − b_start`` the
    closest pair solves ``(w + s·u − t·v)·u = 0`` and ``(w + s·u − t·v)·v = 0``:
    ``s = (b·e − c·d) / D``, ``t = (a·e − b·d) / D`` with ``a = u·u``, ``b = u·v``,
    ``c = v·v``, ``d = u·w``, ``e = v·w``, ``D = ac − b²``. Lines count as parallel when
    ``D <= parallel_tolerance · a·c`` (sin² of their angle below the tolerance); then
    ``s = 0`` and ``t`` is the foot of ``a_start`` on line b (any pair would do). A
    zero-length line is flagged the same way and reduces to a point.
    """
    p = np.atleast_2d(np.asarray(a_start, dtype=float))
    u = np.atleast_2d(np.asarray(a_end, dtype=float)) - p
    q = np.atleast_2d(np.asarray(b_start, dtype=float))
    v = np.atleast_2d(np.asarray(b_end, dtype=float)) - q
    p, u, q, v = np.broadcast_arrays(p, u, q, v)
    w = p - q
    a, b, c, d, e = dot(u, u), dot(u, v), dot(v, v), dot(u, w), dot(v, w)
    denominator = a * c - b * b
    parallel = denominator <= parallel_tolerance * a * c
    safe = np.where(parallel, 1.0, denominator)
    s = np.where(parallel, 0.0, (b * e - c * d) / safe)
    t = np.where(parallel, np.where(c > 0, e / np.where(c > 0, c, 1.0), 0.0), (a * e - b * d) / safe)
    # a zero-length line a is the point a_start; a zero-length b, the point b_start
    point_b_only = (c == 0) & (a > 0)
    s = np.where(point_b_only, -d / np.where(a > 0, a, 1.0), s)
    t = np.where(c == 0, 0.0, t)
    points_a = p + s[:, None] * u
    points_b = q + t[:, None] * v
    return LineLineClosest(points_a, points_b, s, t, np.linalg.norm(points_a - points_b, axis=1), parallel)


def line_plane_intersection(
    start: ArrayLike, end: ArrayLike, plane: Plane, parallel_tolerance: float = 1e-12
) -> tuple[FloatArray, FloatArray, BoolArray]:
    """Where infinite lines cross ``plane``: ``(points (n, 3), parameters (n,), parallel (n,))``.

    ``t = n·(origin − start) / n·(end − start)``. Lines within ``parallel_tolerance``
    (sine of the angle) of parallel to the plane get NaN points and parameters and are
    flagged in ``parallel``.
    """
    p = np.atleast_2d(np.asarray(start, dtype=float))
    u = np.atleast_2d(np.asarray(end, dtype=float)) - p
    p, u = np.broadcast_arrays(p, u)
    along = u @ plane.z
    parallel = np.abs(along) <= parallel_tolerance * np.linalg.norm(u, axis=1)
    t = np.where(parallel, np.nan, (plane.origin - p) @ plane.z / np.where(parallel, 1.0, along))
    return p + t[:, None] * u, t, parallel


def plane_plane_intersection(
    a: Plane, b: Plane, parallel_tolerance: float = 1e-12
) -> tuple[FloatArray, FloatArray] | None:
    """The line where two planes meet, as ``(point, unit direction)``; ``None`` if parallel.

    The direction is ``a.z × b.z`` normalised; the point is the one on the line nearest
    ``a.origin`` (it solves both plane equations and ``direction·x = direction·a.origin``).
    """
    direction = np.cross(a.z, b.z)
    sine = float(np.linalg.norm(direction))
    if sine <= parallel_tolerance:
        return None
    direction = direction / sine
    system = np.stack([a.z, b.z, direction])
    rhs = np.array([a.z @ a.origin, b.z @ b.origin, direction @ a.origin])
    return np.linalg.solve(system, rhs), direction


class CurvePlaneHits(NamedTuple):
    """Where a curve meets a plane, in increasing t."""

    parameters: FloatArray  #: (k,)
    points: FloatArray  #: (k, 3)


def curve_plane_intersections(
    curve: Curve, plane: Plane, tolerance: float = 1e-10, samples_per_span: int = 32
) -> CurvePlaneHits:
    """All points where ``curve`` crosses or touches ``plane``.

    The signed distance ``g(t) = (C(t) − origin)·n`` is sampled on every smooth span
    (``samples_per_span``, and finer where the curve turns);
    each sign change is refined to rounding by a bracketed solver. Touching points
    (g has a zero minimum or maximum, no sign change) are found as roots of ``g'`` where
    ``|g| <= tolerance``. A stretch of curve lying in the plane gives its sampled points.
    Crossings closer together than a sampling interval can be missed.
    """
    per_span = sample_parameters(curve, per_span=samples_per_span, minimum=256)
    samples = np.union1d(per_span, curve._search_parameters)

    # measured from the curve's anchor: far from the origin the distances then round
    # relative to the curve's size, not to its coordinates
    normal = np.asarray(plane.z, dtype=float)
    height = float((np.asarray(curve.anchor, dtype=float) - np.asarray(plane.origin, dtype=float)) @ normal)

    def distance(t: FloatArray) -> FloatArray:
        local = curve.local_derivatives(np.ravel(t), 0)[0]
        return (local @ normal + height).reshape(np.shape(t))

    def rate(t: FloatArray) -> FloatArray:
        return (curve.derivatives(np.ravel(t), 1)[1] @ plane.z).reshape(np.shape(t))

    crossings = roots_in_samples(distance, samples)
    extremes = roots_in_samples(rate, samples)
    touching = extremes[np.abs(distance(extremes)) <= tolerance]
    lying = samples[np.abs(distance(samples)) <= tolerance]
    t = np.sort(np.concatenate([crossings, touching, lying]))
    if len(t):
        keep = np.concatenate([[True], np.diff(t) > 1e-10])
        t = t[keep]
        if curve.closed and len(t) > 1 and t[0] <= 1e-10 and t[-1] >= 1 - 1e-10:
            t = t[:-1]  # t = 0 and t = 1 are the same point of a closed curve
    return CurvePlaneHits(t, curve.point_at(t))
