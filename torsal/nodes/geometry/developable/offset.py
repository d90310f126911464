"""Boundaries lifted off the design by up to the tolerance, so that strips may be √2 wider.

A strip whose two boundary curves lie on the design deviates from it on one side only:
its straight rulings cut under the design's bend, by about k·w²/8 in the middle of a
strip w wide whose rulings bend with normal curvature k, and not at all at its edges. The
tolerance allows the other side too. Lifting every boundary off the design by δ towards
the side the rulings bend away from (against the sag) makes the deviation run from δ at
the edges to δ − k·w²/8 in the middle; with |δ| just under the tolerance T the strip may
sag by nearly 2T, so it is √2 as wide and the design needs about 1/√2 as many strips.

δ(u, v) = −τ·tanh(k(u, v)/k_s), with τ = :data:`LIFT`·T, k the design's normal
curvature across the boundaries (along the rulings' way) signed by the design's normal,
and k_s a fifth of its largest magnitude (at least the bend 8T/D² under which a strip
the design's size D sags T; no lift at all where nothing bends more): so δ changes side
smoothly where the bend across changes sign (a wave's inflection), where the sag is small
anyway. δ is a bicubic spline fitted to its samples (scipy's ``RectBivariateSpline``,
evaluated as an ``NdBSpline``) so that its derivatives are exact. A boundary is
C(t) = S(p(t)) + δ(p(t))·N(p(t)) along the parameter line p(t), its derivatives by the
chain rule with the normal's derivatives from Weingarten's (N_u, N_v from S's second
derivatives; its second derivative along the curve by central differences of the first,
which only Newton's slope in the rulings' solve uses). Neighbouring strips still share
their boundary exactly: it is the same curve.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.interpolate import NdBSpline, RectBivariateSpline

from ..array_types import FloatArray
from ..curve_base import Curve
from ..surface_base import CurveOnSurface, Surface

#: |δ| as a share of the tolerance.
LIFT = 0.8
#: Samples per direction of δ.
SAMPLES = 41
#: Step (in t) of the central differences for the boundary's second derivative.
STEP = 1e-5


def _normal_jet(ders: list[FloatArray]) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The unit normal and its partial derivatives N_u, N_v from S's derivatives to order 2."""
    _, su, sv, suu, suv, svv = ders
    m = np.cross(su, sv)
    length = np.linalg.norm(m, axis=1, keepdims=True)
    n = m / length
    out = [n]
    for dm in (np.cross(suu, sv) + np.cross(su, suv), np.cross(suv, sv) + np.cross(su, svv)):
        out.append((dm - n * np.einsum("ij,ij->i", n, dm)[:, None]) / length)
    return out[0], out[1], out[2]


@dataclass(frozen=True)
class Lift:
    """δ(u, v) of the module, as a spline with exact derivatives."""

    spline: NdBSpline | None
    height: float = 0.0  #: the largest |δ|

    def __call__(self, u: FloatArray, v: FloatArray, du: int = 0, dv: int = 0) -> FloatArray:
        if self.spline is None:
            return np.zeros_like(u)
        at = np.column_stack([np.clip(u, 0.0, 1.0), np.clip(v, 0.0, 1.0)])
        return self.spline(at, nu=(du, dv))


def lift_for(design: Surface, family: str, tolerance: float) -> Lift:
    """δ for boundaries running along ``family`` ("u": along u, so the rulings run along v)."""
    g = np.linspace(0.0, 1.0, SAMPLES)
    u, v = (a.ravel() for a in np.meshgrid(g, g, indexing="ij"))
    _, su, sv, suu, _, svv = design.derivatives(u, v, 2)
    n = np.cross(su, sv)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    first, second = (sv, svv) if family == "u" else (su, suu)
    k = np.einsum("ij,ij->i", second, n) / np.einsum("ij,ij->i", first, first)
    k = np.nan_to_num(k)
    points = design.derivatives(u, v, 0)[0]
    size = float(np.linalg.norm(np.ptp(points, axis=0)))
    # a bend under which even a strip the design's size sags less than the tolerance is no
    # bend (a cylinder's straight way, a difference's noise): no lift there
    scale = max(0.2 * float(np.abs(k).max()), 8.0 * tolerance / max(size, 1e-300) ** 2)
    if not np.abs(k).max() * size**2 > 8.0 * tolerance:
        return Lift(None)
    delta = -LIFT * tolerance * np.tanh(k / scale)
    fitted = RectBivariateSpline(g, g, delta.reshape(SAMPLES, SAMPLES), kx=3, ky=3, s=0)
    tu, tv = fitted.get_knots()
    coefficients = fitted.get_coeffs().reshape(len(tu) - 4, len(tv) - 4)
    return Lift(NdBSpline((tu, tv), coefficients, 3), LIFT * tolerance)


class LiftedIsoCurve(CurveOnSurface):
    """The parameter line of ``design`` along ``family`` at ``level``, lifted by δ."""

    def __init__(self, design: Surface, family: str, level: float, lift: Lift) -> None:
        self.surface = design
        self.family = family
        self.level = float(level)
        self.lift = lift

    def __repr__(self) -> str:
        return f"LiftedIsoCurve({self.family}, {self.level:g})"

    def _uv(self, t: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        fixed = np.full_like(t, self.level)
        if self.family == "u":
            return t, fixed, np.ones_like(t), np.zeros_like(t)
        return fixed, t, np.zeros_like(t), np.ones_like(t)

    def _first(self, t: FloatArray) -> tuple[FloatArray, FloatArray, list[FloatArray]]:
        u, v, du, dv = self._uv(t)
        ders = self.surface.derivatives(u, v, 2)
        n, nu, nv = _normal_jet(ders)
        d = self.lift(u, v)[:, None]
        dd = (self.lift(u, v, 1, 0) * du + self.lift(u, v, 0, 1) * dv)[:, None]
        point = ders[0] + d * n
        du, dv = du[:, None], dv[:, None]
        tangent = ders[1] * du + ders[2] * dv + dd * n + d * (nu * du + nv * dv)
        return point, tangent, ders

    def _breakpoints(self) -> FloatArray:
        """The design's knots along the line (a NURBS design: the line is only as smooth
        as the design there), so that sampling-based operations put samples on every span."""
        knots = getattr(self.surface, "knots_u" if self.family == "u" else "knots_v", None)
        if knots is None:
            return super()._breakpoints()
        return np.unique(np.clip(np.asarray(knots, dtype=float), 0.0, 1.0))

    def _eval(self, t: FloatArray, order: int) -> list[FloatArray]:
        t = np.asarray(t, dtype=float)
        point, tangent, _ = self._first(t)
        out = [point]
        if order >= 1:
            out.append(tangent)
        if order >= 2:
            ahead, behind = self._first(t + STEP)[1], self._first(t - STEP)[1]
            out.append((ahead - behind) / (2.0 * STEP))
        return out


@dataclass(frozen=True)
class LiftedBoundaries:
    """The design's parameter lines along ``family``, lifted by δ (see the module)."""

    design: Surface
    family: str
    lift: Lift

    @property
    def levels(self) -> FloatArray:
        return np.array([0.0, 1.0])

    @property
    def height(self) -> float:
        return self.lift.height

    def at(self, level: float) -> Curve:
        return LiftedIsoCurve(self.design, self.family, level, self.lift)
