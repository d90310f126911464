"""Interpolating splines: a smooth curve that passes exactly through given points."""

from __future__ import annotations

from functools import lru_cache
from math import comb

import numpy as np
from numpy.typing import ArrayLike
from scipy.interpolate import make_interp_spline

from ..vec_ops import anchor
from ..vectors import as_points, normalise
from .nurbs import NurbsCurve
from .shared_knots import polynomial_curves


def chord_length_parameters(points: ArrayLike) -> np.ndarray:
    """Parameters in [0, 1] proportional to the cumulative distance between points."""
    p = as_points(points)
    return _chord_parameters(p[1:] - p[:-1])


def _chord_parameters(steps: np.ndarray) -> np.ndarray:
    """:func:`chord_length_parameters` from the steps between consecutive points."""
    return _cumulative_parameters(_chord_lengths(steps))


def _chord_lengths(steps: np.ndarray) -> np.ndarray:
    """The lengths of the steps between consecutive points."""
    return np.linalg.norm(steps, axis=1)


def _cumulative_parameters(lengths: np.ndarray) -> np.ndarray:
    """Parameters from 0 to 1 proportional to the running sum of ``lengths``."""
    cumulative = np.empty(len(lengths) + 1)
    cumulative[0] = 0.0
    np.cumsum(lengths, out=cumulative[1:])
    return cumulative / cumulative[-1]


class InterpolatedCurve(NurbsCurve):
    """A cubic spline through ``points`` with chord-length parameterisation.

    Point ``i`` sits at ``t = (chord length up to i) / (total chord length)``; those
    parameters are kept in :attr:`parameters`. The spline is solved by scipy's
    ``make_interp_spline`` and stored as a (non-rational) :class:`NurbsCurve`.

    Args:
        points: at least 2 points (3 when closed); consecutive points must differ.
        closed: join the last point back to the first with a periodic spline, smooth
            (C²) across the seam. A last point equal to the first is dropped first.
        start_tangent, end_tangent: optional end directions (open curves only). Only
            the direction counts: the derivative there is scaled to the chord length.
            Without them the ends are "not-a-knot"; with one, the other end is natural.
        degree: 3 by default; 1 gives the polyline through the points.

    With fewer than ``degree + 1`` open points the degree drops (two points give the
    straight line, three a parabola).

    >>> curve = InterpolatedCurve([[0, 0], [1, 1], [2, 0], [3, 1]])
    >>> bool(np.allclose(curve.point_at(curve.parameters), curve.points))
    True
    """

    def __init__(
        self,
        points: ArrayLike,
        closed: bool = False,
        start_tangent: ArrayLike | None = None,
        end_tangent: ArrayLike | None = None,
        degree: int = 3,
    ) -> None:
        p = as_points(points)
        if not np.isfinite(p).all():
            raise ValueError("An interpolation point has a non-finite coordinate.")
        if int(degree) != degree or degree < 1:
            raise ValueError(f"The degree must be a whole number >= 1; got {degree}.")
        degree = int(degree)
        if closed:
            if start_tangent is not None or end_tangent is not None:
                raise ValueError("A closed interpolating curve has no ends to give tangents to.")
            if len(p) > 1 and np.array_equal(p[0], p[-1]):
                p = p[:-1]
            if len(p) < 3:
                raise ValueError(f"A closed interpolating curve needs 3 points; got {len(p)}.")
            p = np.concatenate([p, p[:1]])
        elif len(p) < 2:
            raise ValueError(f"An interpolating curve needs at least 2 points; got {len(p)}.")
        steps = p[1:] - p[:-1]
        lengths = _chord_lengths(steps)
        # a step with every coordinate 0 has length 0: only where one has (or one too short
        # to square) are the coordinates themselves tested
        if not np.minimum.reduce(lengths) > 0.0 and (steps == 0).all(axis=1).any():
            raise ValueError(
                "Two consecutive points coincide; the curve cannot pass through one point twice in a row."
            )
        u = _cumulative_parameters(lengths)
        # solved on the points relative to their box's centre: the spline's coefficients
        # are then as accurate far from the origin as at it (see vec_ops.anchor)
        origin = anchor(p)
        local = p - origin

        if closed:
            k = degree
            spline = make_interp_spline(u, local, k=k, bc_type="periodic")
        elif start_tangent is not None or end_tangent is not None:
            # dC/dt at an end: the given direction, with length equal to the chord length
            # (the speed of a chord-length parameterisation there).
            total_chord = float(np.sum(np.linalg.norm(steps, axis=1)))

            def end(tangent: ArrayLike | None, which: str) -> list[tuple[int, np.ndarray]]:
                if tangent is None:
                    return [(2, np.zeros(3))]
                return [(1, total_chord * normalise(tangent, f"{which} tangent"))]

            k = 3
            spline = make_interp_spline(
                u, local, k=k, bc_type=(end(start_tangent, "start"), end(end_tangent, "end"))
            )
        else:
            k = min(degree, len(p) - 1)
            if len(p) == k + 1:  # one polynomial span: a small Bernstein system
                self._set_points(p, u)
                control = _bezier_through(local, u) + origin
                self._setup(control, None, _bezier_knots(k), k, closed)
                return
            spline = make_interp_spline(u, local, k=k)
        self._set_points(p, u)
        self._setup(np.asarray(spline.c, float) + origin, None, np.asarray(spline.t, float), k, closed)

    @classmethod
    def beziers(cls, points: np.ndarray) -> list[InterpolatedCurve]:
        """The open curves with free ends through each ``points[i]`` (``(calls, count, 3)``,
        finite, ``count`` ≥ 2) of degree ``count − 1``, one polynomial span each, as the
        constructor makes each of them with a degree of ``count − 1`` or more: their chord
        parameters, boxes and Bernstein systems solved at once (each curve's values, bit
        for bit: LAPACK solves each system on its own). A curve through one point twice in
        a row is left to the constructor (its message)."""
        p = np.asarray(points, dtype=float)
        k = p.shape[1] - 1
        steps = p[:, 1:] - p[:, :-1]
        lengths = np.linalg.norm(steps, axis=2)
        if not (lengths > 0.0).all():
            return [cls(row, degree=max(k, 1)) for row in p]
        cumulative = np.empty((len(p), k + 1))
        cumulative[:, 0] = 0.0
        np.cumsum(lengths, axis=1, out=cumulative[:, 1:])
        u = cumulative / cumulative[:, -1:]
        # solved on the points relative to their box's centre (see vec_ops.anchor)
        origin = 0.5 * (p.max(axis=1) + p.min(axis=1))
        j, j_reversed, binomial = _bernstein_terms(k)
        column = u[:, :, None]
        basis = binomial * column**j * (1.0 - column) ** j_reversed
        control = np.linalg.solve(basis, p - origin[:, None]) + origin[:, None]
        curves = polynomial_curves(cls, control, _bezier_knots(k), k)  # (their set-up at once)
        for curve, row, parameters in zip(curves, p, u, strict=True):
            curve._set_points(row, parameters)
        return curves

    def _set_points(self, points: np.ndarray, parameters: np.ndarray) -> None:
        self.points = points
        self.parameters = parameters
        self.points.setflags(write=False)
        self.parameters.setflags(write=False)


def _bezier_through(points: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Control points of the degree n − 1 Bézier curve through ``n`` points at parameters
    ``u`` (from 0 to 1): what ``make_interp_spline`` gives when there are no interior
    knots, without its overhead (a tenth of a millisecond per curve, which a slider
    rebuilding dozens of short edge curves pays on every solve)."""
    j, j_reversed, binomial = _bernstein_terms(len(points) - 1)
    column = u[:, None]
    basis = binomial * column**j * (1.0 - column) ** j_reversed
    return np.linalg.solve(basis, points)


@lru_cache(maxsize=16)
def _bezier_knots(k: int) -> np.ndarray:
    """The knots of a degree-k Bézier curve on [0, 1], read-only (shared by the curves of that degree)."""
    knots = np.repeat([0.0, 1.0], k + 1)
    knots.setflags(write=False)
    return knots


@lru_cache(maxsize=16)
def _bernstein_terms(k: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The exponents 0 … k and k … 0 and the binomial coefficients C(k, j) of the degree-k
    Bernstein basis, read-only. The exponents are floats: ``power`` runs on doubles either
    way (integer exponents are cast to them first), so the values are the same, uncast."""
    j = np.arange(k + 1.0)
    j_reversed = j[::-1].copy()
    binomial = np.array([comb(k, i) for i in range(k + 1)], dtype=float)
    for array in (j, j_reversed, binomial):
        array.setflags(write=False)
    return j, j_reversed, binomial
