"""Circles and circular arcs as exact rational quadratic NURBS curves.

An arc of sweep φ ≤ 90° is one rational quadratic segment: end points on the circle, the
middle control point where the end tangents meet (at distance r / cos(φ/2) from the
centre) with weight cos(φ/2). Longer arcs are split into equal segments of at most 90°.
The points are exactly on the circle, but ``t`` is not proportional to the angle.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from ..array_types import FloatArray
from ..curve_base import ClosestPoints
from ..vectors import WORLD_XY, Plane, as_points, as_vector
from .nurbs import NurbsCurve


def _arc_arrays(
    plane: Plane, radius: float, start_angle: float, sweep: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Control points, weights and knots of an arc in ``plane`` (angles from its x axis)."""
    segments = max(1, math.ceil(sweep / (math.pi / 2) - 1e-9))
    half = sweep / segments / 2
    angles = start_angle + half * np.arange(2 * segments + 1)
    # odd entries are the tangent-intersection points, farther out by 1 / cos(half)
    distance = np.where(np.arange(2 * segments + 1) % 2 == 1, radius / math.cos(half), radius)
    points = plane.point_at(distance * np.cos(angles), distance * np.sin(angles))
    weights = np.where(np.arange(2 * segments + 1) % 2 == 1, math.cos(half), 1.0)
    interior = np.repeat(np.arange(1, segments) / segments, 2)
    knots = np.concatenate([[0.0] * 3, interior, [1.0] * 3])
    return points, weights, knots


def _parameters_at_angles(angles: FloatArray, sweep: float) -> FloatArray:
    """The curve parameter ``t`` at angles ``0 ≤ angles ≤ sweep`` from the arc's start.

    On each rational quadratic segment (sweep 2h, local parameter u in [0, 1]) the point
    at angle φ from the segment's start has tan((φ − h)/2) = tan(h/2)·(2u − 1)."""
    segments = max(1, math.ceil(sweep / (math.pi / 2) - 1e-9))
    half = sweep / segments / 2
    segment = np.clip(np.floor(angles / (2 * half)), 0, segments - 1)
    phi = angles - segment * 2 * half
    u = 0.5 + 0.5 * np.tan((phi - half) / 2) / math.tan(half / 2)
    return (segment + np.clip(u, 0.0, 1.0)) / segments


def _closest_on_arc(
    plane: Plane, radius: float, start_angle: float, sweep: float, points: FloatArray
) -> ClosestPoints:
    """Closest points on the arc, in closed form: each query projected onto the plane,
    then radially onto the circle; a foot outside the arc goes to the nearer end. A query
    on the axis (every point equally near; to 1e-12 of the radius and height) gets the
    arc's start; a non-finite one gets t = 0."""
    local = plane.to_local(points)
    finite = np.isfinite(local).all(axis=1)
    x, y = np.where(finite, local[:, 0], 0.0), np.where(finite, local[:, 1], 0.0)
    # on the axis to rounding (every point of the circle equally near): the start
    on_axis = np.hypot(x, y) <= 1e-12 * (radius + np.abs(np.where(finite, local[:, 2], 0.0)))
    angle = np.where(on_axis, 0.0, np.mod(np.arctan2(y, x) - start_angle, 2 * math.pi))
    inside = angle <= sweep
    if not inside.all():  # beyond the arc: the nearer end (the start on a tie)
        ends = plane.point_at(radius * np.cos([start_angle, start_angle + sweep]),
                              radius * np.sin([start_angle, start_angle + sweep]))
        to_start = np.linalg.norm(points - ends[0], axis=1)
        to_end = np.linalg.norm(points - ends[1], axis=1)
        angle = np.where(inside, angle, np.where(to_end < to_start, sweep, 0.0))
    angle = np.where(finite, angle, 0.0)
    t = _parameters_at_angles(angle, sweep)
    if sweep >= 2 * math.pi:
        t = np.where(angle >= 2 * math.pi, 0.0, t)
    at = start_angle + angle
    closest = plane.point_at(radius * np.cos(at), radius * np.sin(at))
    return ClosestPoints(t, closest, np.linalg.norm(points - closest, axis=1))


def _check_radius(radius: float) -> float:
    radius = float(radius)
    if not (math.isfinite(radius) and radius > 0):
        raise ValueError(f"A circle's radius must be a positive number; got {radius}.")
    return radius


def _circumcentre(a: np.ndarray, b: np.ndarray, c: np.ndarray) -> tuple[Plane, float]:
    """Plane (origin at the circumcentre, x towards ``a``) and radius through three points."""
    ab, ac = b - a, c - a
    normal = np.cross(ab, ac)
    nn = float(normal @ normal)
    if nn <= 1e-24 * max(float(ab @ ab), float(ac @ ac)) ** 2:
        raise ValueError("The three points are on one line; no circle passes through them.")
    # circumcentre relative to a: ((|ab|² ac − |ac|² ab) × n) / (2 |n|²), reordered
    offset = np.cross(float(ab @ ab) * ac - float(ac @ ac) * ab, normal) / (2.0 * nn)
    centre = a + offset
    plane = Plane.from_axes(centre, a - centre, np.cross(normal, a - centre))
    return plane, float(np.linalg.norm(offset))


class Circle(NurbsCurve):
    """The full circle of ``radius`` centred on ``plane``'s origin, in that plane.

    It starts on the plane's x axis and runs counter-clockwise about its normal.

    >>> circle = Circle(radius=2.0)
    >>> round(float(np.linalg.norm(circle.point_at(0.3))), 12)
    2.0
    """

    def __init__(self, plane: Plane = WORLD_XY, radius: float = 1.0) -> None:
        self.plane = plane
        self.radius = _check_radius(radius)
        points, weights, knots = _arc_arrays(plane, self.radius, 0.0, 2 * math.pi)
        self._setup(points, weights, knots, 2, periodic=False)
        self.closed = True

    @property
    def centre(self) -> np.ndarray:
        return self.plane.origin

    @property
    def length(self) -> float:
        """The circumference 2πr, exactly."""
        return 2 * math.pi * self.radius

    def closest_point(self, points: ArrayLike) -> ClosestPoints:
        """Closest points on the circle, in closed form: each point projected onto the
        circle's plane, then radially onto the circle (a point on the axis gets the start)."""
        return _closest_on_arc(self.plane, self.radius, 0.0, 2 * math.pi, as_points(points))

    @classmethod
    def from_three_points(cls, a: ArrayLike, b: ArrayLike, c: ArrayLike) -> Circle:
        """The circle through three points, starting at ``a`` and passing ``b`` then ``c``."""
        plane, radius = _circumcentre(as_vector(a), as_vector(b), as_vector(c))
        return cls(plane, radius)


class Arc(NurbsCurve):
    """A circular arc in ``plane``, centred on its origin, from ``start_angle`` to ``end_angle``.

    Angles are in radians, measured counter-clockwise from the plane's x axis; the sweep
    ``end_angle − start_angle`` must be in (0, 2π].

    >>> arc = Arc(radius=1.0, start_angle=0.0, end_angle=np.pi / 2)
    >>> np.round(arc.end, 12).tolist()
    [0.0, 1.0, 0.0]
    """

    def __init__(
        self,
        plane: Plane = WORLD_XY,
        radius: float = 1.0,
        start_angle: float = 0.0,
        end_angle: float = math.pi / 2,
    ) -> None:
        sweep = float(end_angle) - float(start_angle)
        if not (0 < sweep <= 2 * math.pi * (1 + 1e-12)):
            raise ValueError(f"An arc's sweep angle must be in (0, 2π]; got {sweep}.")
        self.plane = plane
        self.radius = _check_radius(radius)
        self.start_angle = float(start_angle)
        self.end_angle = float(end_angle)
        points, weights, knots = _arc_arrays(plane, self.radius, self.start_angle, sweep)
        self._setup(points, weights, knots, 2, periodic=False)

    @property
    def centre(self) -> np.ndarray:
        return self.plane.origin

    @property
    def sweep(self) -> float:
        """The angle the arc turns through, in radians."""
        return self.end_angle - self.start_angle

    @property
    def length(self) -> float:
        """The arc length r·sweep, exactly."""
        return self.radius * self.sweep

    def closest_point(self, points: ArrayLike) -> ClosestPoints:
        """Closest points on the arc, in closed form: each point projected onto the arc's
        plane, then radially onto its circle; where that foot is off the arc, the nearer
        of the arc's two ends."""
        return _closest_on_arc(self.plane, self.radius, self.start_angle, self.sweep, as_points(points))

    @classmethod
    def from_three_points(cls, start: ArrayLike, through: ArrayLike, end: ArrayLike) -> Arc:
        """The arc from ``start`` through ``through`` to ``end``."""
        a, b, c = as_vector(start), as_vector(through), as_vector(end)
        plane, radius = _circumcentre(a, b, c)
        # the plane's normal is (b − a) × (c − a), so a → b → c runs counter-clockwise
        # about it and the arc sweeps from angle 0 (at a) to the angle of c
        local = plane.to_local(c)
        return cls(plane, radius, 0.0, float(np.mod(np.arctan2(local[1], local[0]), 2 * math.pi)))
