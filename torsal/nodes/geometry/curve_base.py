"""The contract every kernel curve fulfils: parameter t in [0, 1], vectorised evaluation.

A subclass implements :meth:`Curve.derivatives`; everything else (tangent, curvature,
frames, length, division, closest point ...) is derived generically here or overridden
where a closed form is faster or exact. :class:`ReversedCurve` and
:class:`TransformedCurve`, the generic views :meth:`Curve.reversed` and
:meth:`Curve.transformed` return, live here too, so the base class needs no import from
the modules of its subclasses.

Every method that takes ``t`` accepts a scalar or a 1-D array: an array gives arrays
with one row per parameter, a scalar gives a single value or a ``(3,)`` vector.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from functools import cached_property
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike

from .arclength import LengthTable
from .array_types import FloatArray
from .closest import SearchSamples, closest_parameters, search_parameters, search_samples
from .roots import roots_in_samples
from .spline_eval import evaluation_parameters
from .tessellate import tessellation_parameters
from .transforms import check_matrix, is_affine
from .vec_ops import cross, dot, extent, linalg_norm
from .vectors import Plane, as_points, perpendicular, unit


class ClosestPoints(NamedTuple):
    """Result of :meth:`Curve.closest_point`, one row per query point."""

    parameters: FloatArray  #: (n,) curve parameters t
    points: FloatArray  #: (n, 3) closest points on the curve
    distances: FloatArray  #: (n,) distances from the query points


class Frames(NamedTuple):
    """Frenet frames along a curve, one row per parameter (all ``(n, 3)``)."""

    origins: FloatArray
    tangents: FloatArray
    normals: FloatArray  #: towards the centre of curvature
    binormals: FloatArray  #: tangent × normal


def _parameters(t: ArrayLike) -> tuple[FloatArray, bool]:
    """``t`` as a 1-D float array, and whether it was a scalar."""
    return evaluation_parameters(t), np.ndim(t) == 0


class Curve(ABC):
    """A 3D curve parameterised on t in [0, 1].

    ``domain`` is the parameter interval the curve was defined on (knot domain, the
    user's ``(a, b)``); ``t = (u − a) / (b − a)``, and derivatives are with respect to t.
    """

    closed: bool = False
    domain: tuple[float, float] = (0.0, 1.0)

    @abstractmethod
    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        """Return ``[C(t), C'(t), ..., C^(order)(t)]``, each an ``(n, 3)`` array.

        ``t`` is a scalar or a 1-D array of parameters in [0, 1]; derivatives are with
        respect to that normalised parameter.
        """

    @property
    def anchor(self) -> FloatArray:
        """A point near the curve that :meth:`local_derivatives` measures positions from
        (the world origin unless the curve keeps its coefficients relative to one)."""
        return np.zeros(3)

    def local_derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        """:meth:`derivatives` with the points relative to :attr:`anchor`.

        Where positions are subtracted (a ruling ``B − A``, a chord), the local points of
        a curve that keeps an anchor carry rounding relative to its size, not to its
        distance from the origin."""
        result = self.derivatives(t, order)
        result[0] = result[0] - self.anchor
        return result

    def point_at(self, t: ArrayLike) -> FloatArray:
        """Points at parameters ``t``: ``(n, 3)`` for an array, ``(3,)`` for a scalar."""
        scalar = np.ndim(t) == 0
        points = self.derivatives(np.atleast_1d(np.asarray(t, dtype=float)), 0)[0]
        return points[0] if scalar else points

    def derivative_at(self, t: ArrayLike, order: int = 1) -> FloatArray:
        """The ``order``-th derivative alone, ``C⁽ᵒʳᵈᵉʳ⁾(t)``: ``(n, 3)`` for an array, ``(3,)``
        for a scalar. Subclasses that can skip the lower orders do."""
        scalar = np.ndim(t) == 0
        d = self.derivatives(np.atleast_1d(np.asarray(t, dtype=float)), order)[order]
        return d[0] if scalar else d

    # -- parameters ---------------------------------------------------------------------

    def _breakpoints(self) -> FloatArray:
        """Increasing t values, 0 and 1 included, between which the curve is smooth.

        Sampling-based operations put samples on every span; NURBS curves return their
        distinct knots, polylines their vertices.
        """
        return np.array([0.0, 1.0])

    def kinks(self) -> FloatArray:
        """Increasing t values where the tangent turns (the curve is only C0 there): the
        inner breakpoints where it turns by more than :data:`KINK_ANGLE`, and 0 first
        for a closed curve whose seam is a corner.

        A chord polyline across a kink falls short of the arc length by a share of its
        chord whatever the sampling, so chord sums converge like 1/n instead of 1/n²;
        sampled on every kink they converge like 1/n² again (:mod:`.edge_sampling`).
        Found once per curve (curves do not change) and handed out read-only."""
        kinks = self.__dict__.get("_kinks")
        if kinks is None:
            kinks = self._find_kinks()
            kinks.setflags(write=False)
            self._kinks = kinks
        return kinks

    def _find_kinks(self) -> FloatArray:
        """:meth:`kinks`, found: subclasses that know where corners can be look only there."""
        inner = self._breakpoints()
        return turning_points(self, inner[(inner > 0.0) & (inner < 1.0)])

    @cached_property
    def end_points(self) -> FloatArray:
        """The points at t = 0 and t = 1, ``(2, 3)``, read-only: evaluated once per curve
        (curves do not change), for the checks that compare the ends of many curves."""
        ends = self.point_at(np.array([0.0, 1.0]))
        ends.setflags(write=False)
        return ends

    @property
    def start(self) -> FloatArray:
        """The point at t = 0."""
        return self.point_at(0.0)

    @property
    def end(self) -> FloatArray:
        """The point at t = 1."""
        return self.point_at(1.0)

    # -- differential geometry ------------------------------------------------------------

    def tangent_at(self, t: ArrayLike) -> FloatArray:
        """Unit tangents. Where C' vanishes (a stationary point) the direction of C''
        is used, its limit; where both vanish the tangent is the zero vector."""
        ts, scalar = _parameters(t)
        _, d1, d2 = self.derivatives(ts, 2)
        speed = np.linalg.norm(d1, axis=1)
        scale = np.maximum(np.linalg.norm(d2, axis=1), 1e-300)
        stationary = speed <= 1e-12 * scale
        tangent = unit(np.where(stationary[:, None], d2, d1))
        return tangent[0] if scalar else tangent

    def curvature_vector_at(self, t: ArrayLike) -> FloatArray:
        """Curvature vectors κN = (C'' − (C''·T)T) / |C'|², pointing to the centre of
        curvature with length κ. Zero where the speed is zero."""
        ts, scalar = _parameters(t)
        _, d1, d2 = self.derivatives(ts, 2)
        speed2 = dot(d1, d1)
        moving = speed2 > 0
        safe = np.where(moving, speed2, 1.0)
        normal_part = d2 - (dot(d2, d1) / safe)[:, None] * d1
        k = np.where(moving[:, None], normal_part / safe[:, None], 0.0)
        return k[0] if scalar else k

    def curvature_at(self, t: ArrayLike) -> FloatArray:
        """Curvature κ = |C' × C''| / |C'|³ (1 / radius of the osculating circle)."""
        ts, scalar = _parameters(t)
        _, d1, d2 = self.derivatives(ts, 2)
        speed = np.linalg.norm(d1, axis=1)
        moving = speed > 0
        safe = np.where(moving, speed, 1.0)
        kappa = np.where(moving, np.linalg.norm(cross(d1, d2), axis=1) / safe**3, 0.0)
        return kappa[0] if scalar else kappa

    def torsion_at(self, t: ArrayLike) -> FloatArray:
        """Torsion τ = (C' × C'')·C''' / |C' × C''|², 0 where the curvature vanishes."""
        ts, scalar = _parameters(t)
        _, d1, d2, d3 = self.derivatives(ts, 3)
        b = cross(d1, d2)
        bb = dot(b, b)
        # the torsion is undefined on straight stretches; report 0 rather than noise
        straight = bb <= 1e-24 * dot(d1, d1) ** 3
        tau = np.where(straight, 0.0, dot(b, d3) / np.where(straight, 1.0, bb))
        return tau[0] if scalar else tau

    def frames_at(self, t: ArrayLike) -> Frames:
        """Frenet frames (origin, tangent T, normal N, binormal B = T × N) at ``t``.

        Where the curvature vanishes N is undefined; there it is a fixed unit vector
        perpendicular to T (:func:`~.vectors.perpendicular`), so the frame stays valid.
        """
        ts, _ = _parameters(t)
        origins, d1, d2 = self.derivatives(ts, 2)
        tangents = self.tangent_at(ts)
        # straight where C'' is parallel to C' (sine of their angle below 1e-12) or zero
        sine_area = np.linalg.norm(cross(d1, d2), axis=1)
        flat = sine_area <= 1e-12 * np.linalg.norm(d1, axis=1) * np.linalg.norm(d2, axis=1)
        flat |= sine_area == 0
        normals = np.where(flat[:, None], perpendicular(tangents), unit(self.curvature_vector_at(ts)))
        return Frames(origins, tangents, normals, cross(tangents, normals))

    def plane_at(self, t: float) -> Plane:
        """The Frenet frame at one parameter as a :class:`~.vectors.Plane`
        (x = tangent, y = normal, z = binormal)."""
        frames = self.frames_at(np.array([float(t)]))
        return Plane(frames.origins[0], frames.tangents[0], frames.normals[0], frames.binormals[0])

    # -- length and division --------------------------------------------------------------

    @cached_property
    def _length_table(self) -> LengthTable:
        return LengthTable(self)

    @property
    def length(self) -> float:
        """Arc length, by adaptive Gauss–Legendre quadrature (relative error ~1e-13)."""
        return self._length_table.total

    def length_at(self, t: ArrayLike) -> FloatArray:
        """Arc length from t = 0 to each ``t``."""
        ts, scalar = _parameters(t)
        s = self._length_table.length_at(ts)
        return s[0] if scalar else s

    def parameter_at_length(self, s: ArrayLike) -> FloatArray:
        """Parameters where the arc length from the start equals ``s`` (clipped to the curve)."""
        ss, scalar = _parameters(s)
        t = self._length_table.parameter_at(ss)
        return t[0] if scalar else t

    def divide_by_count(self, count: int) -> FloatArray:
        """Parameters dividing the curve into ``count`` pieces of equal arc length.

        ``count + 1`` parameters from 0 to 1 on an open curve; ``count`` on a closed one
        (the end would repeat the start).
        """
        if int(count) != count or count < 1:
            raise ValueError(f"The number of pieces must be a whole number >= 1; got {count}.")
        count = int(count)
        t = self.parameter_at_length(np.linspace(0.0, self.length, count + 1))
        t[0], t[-1] = 0.0, 1.0
        return t[:-1] if self.closed else t

    def divide_by_length(self, length: float) -> FloatArray:
        """Parameters at arc lengths 0, L, 2L, ... along the curve.

        The end is included only when the total length is a whole multiple of L (to
        within 1e-9 relative); on a closed curve the start is not repeated.
        """
        if not (np.isfinite(length) and length > 0):
            raise ValueError(f"The division length must be a positive number; got {length}.")
        total = self.length
        count = int(np.floor(total / length * (1 + 1e-9)))
        targets = np.arange(count + 1) * length
        t = self.parameter_at_length(np.minimum(targets, total))
        if self.closed and len(t) > 1 and abs(targets[-1] - total) <= 1e-9 * total:
            t = t[:-1]
        return t

    @cached_property
    def _search_parameters(self) -> FloatArray:
        """Samples for closest points, bounds and intersections (see ``closest.py``)."""
        return search_parameters(self)

    @cached_property
    def _search_samples(self) -> SearchSamples:
        """The search samples' points, tangents and k-d tree (see ``closest.py``)."""
        return search_samples(self)

    # -- closest point --------------------------------------------------------------------

    def closest_point(self, points: ArrayLike) -> ClosestPoints:
        """Closest points on the curve to each of ``points`` (``(n, 3)`` or one point).

        The global minimum of the distance: samples that turn by at most a few degrees
        apiece bound where it can be (every stretch of curve that could hold it is
        examined), then Newton's method on ``(C − P)·C' = 0``, safeguarded by a bracket,
        converges to rounding in each (see ``closest.py``). Always returns arrays (one
        row per query point).
        """
        p = as_points(points)
        t = closest_parameters(self, p)
        c = self.point_at(t)
        return ClosestPoints(t, c, np.linalg.norm(p - c, axis=1))

    # -- whole-curve operations --------------------------------------------------------------

    def reversed(self) -> Curve:
        """The same curve traversed from end to start: ``C_rev(t) = C(1 − t)``."""
        return ReversedCurve(self)

    def transformed(self, matrix: ArrayLike) -> Curve:
        """The curve under an affine 4×4 transform (NURBS curves also take projective ones)."""
        return TransformedCurve(self, matrix)

    def bounding_box(self) -> FloatArray:
        """Axis-aligned bounding box ``[[xmin, ymin, zmin], [xmax, ymax, zmax]]``, tight.

        Extremes are at the ends or where a coordinate of C' changes sign; those roots
        are bracketed on a dense sampling and refined (scipy's vectorised solver).
        """
        samples = self._search_parameters
        candidates = [np.array([0.0, 1.0]), samples]
        for axis in range(3):

            def coordinate_speed(t: FloatArray, axis: int = axis) -> FloatArray:
                return self.derivatives(np.ravel(t), 1)[1][:, axis].reshape(np.shape(t))

            candidates.append(roots_in_samples(coordinate_speed, samples))
        points = self.point_at(np.concatenate(candidates))
        return np.stack([points.min(axis=0), points.max(axis=0)])

    def tessellate(self, tolerance: float) -> FloatArray:
        """Parameters of a polyline within ``tolerance`` (a distance) of the curve."""
        return tessellation_parameters(self, tolerance)


# -- generic views (NURBS curves, lines and polylines override them with exact curves) --


#: Smallest turn of the tangent (rad) :meth:`Curve.kinks` reports: a corner this sharp
#: missed by a chord of length h costs it at most h·KINK_ANGLE²/8 of the arc length.
KINK_ANGLE = np.radians(1e-3)
#: How far (in t) on either side of a breakpoint :func:`turning_points` looks.
KINK_STEP = 1e-9


def turning_points(curve: Curve, t: FloatArray) -> FloatArray:
    """Those of the inner parameters ``t`` where ``curve``'s tangent turns by more than
    :data:`KINK_ANGLE` (the unit tangents of :meth:`Curve.tangent_at` a step either side;
    where one is zero no turn can be told and the point counts, where the curve stands
    still on both sides it turns no corner), with
    0 first when the curve is closed and its tangent turns at the seam."""
    t = np.asarray(t, dtype=float)
    if curve.closed:
        t = np.concatenate([[0.0], t])
    if not len(t):
        return t
    sides = np.where(t > 0.0, np.maximum(t - KINK_STEP, 0.0), 1.0 - KINK_STEP), np.minimum(t + KINK_STEP, 1.0)
    (p0, d0), (p1, d1) = (curve.derivatives(side, 1) for side in sides)
    # a curve that stands still on both sides (a rail held on a cone's apex) turns no corner:
    # still means slower than 1e-9 of its extent per unit t (its derivatives' rounding)
    scale = float(extent(np.vstack([p0, p1, curve.end_points])).max())
    still = (linalg_norm(d0) <= 1e-9 * scale) & (linalg_norm(d1) <= 1e-9 * scale)
    before, after = (curve.tangent_at(side) for side in sides)
    return t[~(dot(before, after) >= np.cos(KINK_ANGLE)) & ~still]  # (a zero tangent on one side counts)


class ReversedCurve(Curve):
    """``C(1 − t)`` for a wrapped curve C; the k-th derivative gains a factor (−1)^k."""

    def __init__(self, curve: Curve) -> None:
        self.curve = curve
        self.closed = curve.closed
        a, b = curve.domain
        self.domain = (-b, -a)

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        t = np.atleast_1d(np.asarray(t, dtype=float)).reshape(-1)
        values = self.curve.derivatives(1.0 - t, order)
        return [v if k % 2 == 0 else -v for k, v in enumerate(values)]

    @property
    def anchor(self) -> FloatArray:
        return self.curve.anchor

    def local_derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        t = np.atleast_1d(np.asarray(t, dtype=float)).reshape(-1)
        values = self.curve.local_derivatives(1.0 - t, order)
        return [v if k % 2 == 0 else -v for k, v in enumerate(values)]

    def _breakpoints(self) -> FloatArray:
        return np.sort(1.0 - self.curve._breakpoints())

    def reversed(self) -> Curve:
        return self.curve

    def __repr__(self) -> str:
        return f"ReversedCurve({self.curve!r})"


class TransformedCurve(Curve):
    """``A·C(t) + b`` for a wrapped curve C and an affine 4×4 transform [A b; 0 1].

    Derivatives are ``A·C⁽ᵏ⁾``. A perspective transform is rejected here: it is exact
    only for NURBS curves (:meth:`NurbsCurve.transformed`).
    """

    def __init__(self, curve: Curve, matrix: ArrayLike) -> None:
        m = check_matrix(matrix)
        if not is_affine(m):
            raise ValueError("Perspective transforms apply only to NURBS curves.")
        self.curve = curve
        self.matrix = m
        self.closed = curve.closed
        self.domain = curve.domain

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        values = self.curve.derivatives(t, order)
        linear = self.matrix[:3, :3].T
        out = [v @ linear for v in values]
        out[0] = out[0] + self.matrix[:3, 3]
        return out

    @property
    def anchor(self) -> FloatArray:
        return self.matrix[:3, :3] @ self.curve.anchor + self.matrix[:3, 3]

    def local_derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        linear = self.matrix[:3, :3].T
        return [v @ linear for v in self.curve.local_derivatives(t, order)]

    def _breakpoints(self) -> FloatArray:
        return self.curve._breakpoints()

    def transformed(self, matrix: ArrayLike) -> Curve:
        return TransformedCurve(self.curve, check_matrix(matrix) @ self.matrix)

    def __repr__(self) -> str:
        return f"TransformedCurve({self.curve!r})"
