"""Surfaces given by a vectorised function f(u, v) → (x, y, z) over a parameter box.

``ParametricSurface`` reparameterises the box [u0, u1] × [v0, v1] to [0, 1]². Its
derivatives are the analytic ones when derivative callables are supplied, otherwise
finite differences good enough for curvature analysis:

* Richardson-extrapolated central differences: the 7-point central stencils,
  equivalent to extrapolating the 3-point formulas over steps h, 2h and 3h (error
  O(h⁶)); steps h₁ = 1e-3 for first and h₂ = 2e-3 for second derivatives (in
  normalised parameter units); the mixed derivative Suv by the same extrapolation
  of the 4-corner formula. The steps balance truncation (∝ h⁶) against rounding
  (∝ ε/h, ε/h²): derivatives are typically accurate to ~1e-12 (first) and ~1e-10
  (second) relative, curvature to ~1e-10 relative even where a normalised
  parameter sweeps several turns of a torus, and ~1e-8 on sharply folded NURBS.
  Rounding grows with the coordinates' magnitude: a surface of size 1 placed 1000
  units from the origin loses three digits (curvature ~1e-8 relative).
* Central stencils reach 3h (≤ 0.006) outside [0, 1] at the boundary: the function
  is evaluated slightly outside its domain, which is exact for analytic expressions.
  Where that gives a non-finite value (sqrt(u) at u = 0 …), or when
  ``extrapolate=False``, one-sided stencils are used instead (8 points for first
  derivatives, 9 for second, their tensor product for Suv; error O(h⁷)), which
  keeps curvature accurate to ~1e-9 at the boundary (~1e-7 for the far-off case).

Factory functions build the usual primitives with analytic derivatives: :func:`sphere`,
:func:`torus`, :func:`cylinder`, :func:`cone` (all with outward normals).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from fractions import Fraction
from functools import cached_property
from math import factorial
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from .array_types import FloatArray
from .surface_base import Surface, broadcast_uv

SurfaceFunction = Callable[[FloatArray, FloatArray], Any]
DerivativeFunction = Callable[[FloatArray, FloatArray], Sequence[Any]]

FIRST_STEP = 1e-3
SECOND_STEP = 2e-3


def _fd_weights(offsets: Sequence[int], order: int) -> FloatArray:
    """Exact finite-difference weights of the ``order``-th derivative on integer
    ``offsets`` (unit step), from the moment conditions Σ w_k o_k^m = m!·δ(m, order),
    solved in rational arithmetic so that the weights are consistent to the last bit."""
    n = len(offsets)
    rows = [
        [Fraction(o) ** m for o in offsets] + [Fraction(factorial(order) if m == order else 0)]
        for m in range(n)
    ]
    for col in range(n):  # Gauss–Jordan elimination, exact
        pivot = next(r for r in range(col, n) if rows[r][col] != 0)
        rows[col], rows[pivot] = rows[pivot], rows[col]
        lead = rows[col][col]
        rows[col] = [x / lead for x in rows[col]]
        for r in range(n):
            if r != col and rows[r][col] != 0:
                factor = rows[r][col]
                rows[r] = [a - factor * b for a, b in zip(rows[r], rows[col], strict=True)]
    return np.array([float(rows[k][n]) for k in range(n)])


def _stencil(offsets: Sequence[int], order: int) -> tuple[FloatArray, FloatArray]:
    return np.array(offsets, dtype=float), _fd_weights(offsets, order)


def _richardson_corners(levels: int) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Mixed-derivative stencil: the 4-corner formula
    D(h) = [f(h,h) − f(h,−h) − f(−h,h) + f(−h,−h)]/(4h²), whose error is even in h,
    Richardson-extrapolated over steps h, 2h, …, ``levels``·h (error O(h^(2·levels)))."""
    k = np.arange(1, levels + 1, dtype=float)
    moments = np.array([k ** (2 * m) for m in range(levels)])  # kill h², h⁴, …
    coef = np.linalg.solve(moments, np.eye(levels)[0])
    signs = [(1, 1, 1.0), (1, -1, -1.0), (-1, 1, -1.0), (-1, -1, 1.0)]
    du = np.array([kk * a for kk in k for a, _, _ in signs])
    dv = np.array([kk * b for kk in k for _, b, _ in signs])
    w = np.array([c * g / (4 * kk * kk) for kk, c in zip(k, coef, strict=True) for _, _, g in signs])
    return du, dv, w


# Stencil kinds per direction: 0 central, 1 forward (one-sided, inwards from the
# low boundary), 2 backward (mirrors forward). Central stencils are the 7-point
# ones, i.e. Richardson extrapolation of the 3-point formulas over h, 2h, 3h: O(h⁶).
# One-sided ones use 8 (first) and 9 (second derivative) points: O(h⁷).
_FIRST = {0: _stencil([-3, -2, -1, 1, 2, 3], 1), 1: _stencil(list(range(8)), 1)}
_SECOND = {0: _stencil([-3, -2, -1, 0, 1, 2, 3], 2), 1: _stencil(list(range(9)), 2)}
_FIRST[2] = (-_FIRST[1][0], -_FIRST[1][1])
_SECOND[2] = (-_SECOND[1][0], _SECOND[1][1])
_MIXED_CENTRAL = _richardson_corners(3)
_FD_BLOCK = 4096


def _mixed_stencil(ku: int, kv: int) -> tuple[FloatArray, FloatArray, FloatArray]:
    if ku == 0 and kv == 0:
        return _MIXED_CENTRAL
    (ou, wu), (ov, wv) = _FIRST[ku], _FIRST[kv]
    return (
        np.repeat(ou, len(ov)),
        np.tile(ov, len(ou)),
        np.outer(wu, wv).ravel(),
    )


def as_points(value: Any, n: int) -> FloatArray:
    """Coerce a function result to ``(n, 3)``: accepts an (n, 3) array or a triple
    (x, y, z) of arrays/scalars (a constant coordinate may be a plain number)."""
    if isinstance(value, (tuple, list)) and len(value) == 3:
        cols = [np.broadcast_to(np.asarray(c, dtype=float), (n,)) for c in value]
        return np.column_stack(cols)
    arr = np.asarray(value, dtype=float)
    if arr.shape == (n, 3):
        return arr
    if arr.shape == (3, n):
        return np.ascontiguousarray(arr.T)
    if arr.shape == (3,):
        return np.broadcast_to(arr, (n, 3)).copy()
    raise ValueError(f"surface function returned shape {arr.shape}, expected ({n}, 3)")


class ParametricSurface(Surface):
    """S(s, t) = f(u0 + s·(u1 − u0), v0 + t·(v1 − v0)) on (s, t) in [0, 1]².

    ``function(u, v)`` takes equal-length arrays of the *original* parameters and
    returns ``(n, 3)`` points (or a triple of coordinate arrays). Optional
    ``first_derivatives(u, v) → (Su, Sv)`` and ``second_derivatives(u, v) →
    (Suu, Suv, Svv)`` give exact derivatives with respect to the original
    parameters (the chain rule to [0, 1]² is applied here); otherwise finite
    differences are used as the module docstring describes.

    ``closed_u``/``closed_v`` default to a check that the opposite edges coincide.

    Example:
        >>> import numpy as np
        >>> hypar = ParametricSurface(lambda u, v: (u, v, u * v), (-1, 1), (-1, 1))
        >>> float(hypar.gaussian_curvature(0.5, 0.5)[0])  # at x = y = 0
        -1.0
    """

    def __init__(
        self,
        function: SurfaceFunction,
        u_domain: tuple[float, float] = (0.0, 1.0),
        v_domain: tuple[float, float] = (0.0, 1.0),
        first_derivatives: DerivativeFunction | None = None,
        second_derivatives: DerivativeFunction | None = None,
        extrapolate: bool = True,
        closed_u: bool | None = None,
        closed_v: bool | None = None,
        steps: tuple[float, float] = (FIRST_STEP, SECOND_STEP),
    ) -> None:
        self.function = function
        self.u_domain = (float(u_domain[0]), float(u_domain[1]))
        self.v_domain = (float(v_domain[0]), float(v_domain[1]))
        if self.u_domain[0] == self.u_domain[1] or self.v_domain[0] == self.v_domain[1]:
            raise ValueError("parameter domains must not be empty")
        self.first_derivatives = first_derivatives
        self.second_derivatives = second_derivatives
        self.extrapolate = extrapolate
        self.steps = steps
        self._span_u = self.u_domain[1] - self.u_domain[0]
        self._span_v = self.v_domain[1] - self.v_domain[0]
        if closed_u is None or closed_v is None:
            auto_u, auto_v = self._detect_closed()
            closed_u = auto_u if closed_u is None else closed_u
            closed_v = auto_v if closed_v is None else closed_v
        self.closed_u, self.closed_v = bool(closed_u), bool(closed_v)

    def __repr__(self) -> str:
        return f"ParametricSurface(u∈{self.u_domain}, v∈{self.v_domain})"

    def _detect_closed(self) -> tuple[bool, bool]:
        t = np.linspace(0.0, 1.0, 7)
        zeros, ones = np.zeros(7), np.ones(7)
        with np.errstate(all="ignore"):
            pts = self._call(np.concatenate([zeros, ones, t, t]), np.concatenate([t, t, zeros, ones]))
        if not np.all(np.isfinite(pts)):
            return False, False
        size = float(np.ptp(pts, axis=0).max()) or 1.0
        gap_u = np.abs(pts[0:7] - pts[7:14]).max()
        gap_v = np.abs(pts[14:21] - pts[21:28]).max()
        return bool(gap_u <= 1e-10 * size), bool(gap_v <= 1e-10 * size)

    def _call(self, s: FloatArray, t: FloatArray) -> FloatArray:
        """Evaluate the user function at normalised parameters."""
        u = self.u_domain[0] + s * self._span_u
        v = self.v_domain[0] + t * self._span_v
        return as_points(self.function(u, v), len(s))

    def derivatives(self, u: ArrayLike, v: ArrayLike, order: int = 1) -> list[FloatArray]:
        self._check_order(order)
        s, t = broadcast_uv(u, v)
        if order == 0:
            return [self._call(s, t)]
        uu = self.u_domain[0] + s * self._span_u
        vv = self.v_domain[0] + t * self._span_v
        n = len(s)
        first = second = None
        if self.first_derivatives is not None:
            su, sv = self.first_derivatives(uu, vv)
            first = [as_points(su, n) * self._span_u, as_points(sv, n) * self._span_v]
        if order == 2 and self.second_derivatives is not None:
            suu, suv, svv = self.second_derivatives(uu, vv)
            second = [
                as_points(suu, n) * self._span_u**2,
                as_points(suv, n) * (self._span_u * self._span_v),
                as_points(svv, n) * self._span_v**2,
            ]
        if first is not None and (order == 1 or second is not None):
            return [self._call(s, t), *first, *(second or [])]
        fd = self._finite_differences(s, t, order)
        if first is not None:
            fd[1:3] = first
        if second is not None:
            fd[3:6] = second
        return fd

    # ------------------------------------------------------------------ integrals

    @cached_property
    def _difference_noise(self) -> float:
        """The relative rounding error of first derivatives taken by differences: the
        function's values round to ε·|S|, and a difference over the step h divides that
        by h·(the surface's extent). At the origin ~1e-12; far from it (a function of
        site coordinates, 1e6 m) far more, and no integration gets below it."""
        if self.first_derivatives is not None:
            return 0.0
        grid = np.linspace(0.0, 1.0, 5)
        with np.errstate(all="ignore"):
            probe = self._call(*(a.ravel() for a in np.meshgrid(grid, grid)))
        extent = float(np.ptp(probe, axis=0).max()) if np.isfinite(probe).all() else 0.0
        if extent == 0.0:
            return 0.0
        magnitude = float(np.abs(probe).max())
        return 8.0 * float(np.finfo(float).eps) * magnitude / (min(self.steps) * extent)

    def area(self, rtol: float = 1e-11) -> float:
        """Surface area, to ``rtol`` or to the rounding of the derivatives if coarser
        (see :attr:`_difference_noise`: asking for less would refine without end)."""
        return super().area(max(rtol, self._difference_noise))

    def area_and_centroid(self, rtol: float = 1e-11) -> tuple[float, FloatArray]:
        return super().area_and_centroid(max(rtol, self._difference_noise))

    # ------------------------------------------------------------------ differences

    def _finite_differences(self, s: FloatArray, t: FloatArray, order: int) -> list[FloatArray]:
        """All derivatives to ``order`` by differences, in blocks of points so that
        the ~37 stencil evaluations per point never need more than a few MB."""
        n = len(s)
        if n <= _FD_BLOCK:
            return self._finite_difference_block(s, t, order)
        out = [np.empty((n, 3)) for _ in range(3 if order == 1 else 6)]
        for lo in range(0, n, _FD_BLOCK):
            rows = slice(lo, lo + _FD_BLOCK)
            for full, part in zip(out, self._finite_difference_block(s[rows], t[rows], order), strict=True):
                full[rows] = part
        return out

    def _finite_difference_block(self, s: FloatArray, t: FloatArray, order: int) -> list[FloatArray]:
        n = len(s)
        kind_u = np.zeros(n, dtype=np.int8)
        kind_v = np.zeros(n, dtype=np.int8)
        if not self.extrapolate:
            kind_u, kind_v = self._one_sided_kinds(s, t)
        with np.errstate(all="ignore"):
            result = self._differences_by_kind(s, t, kind_u, kind_v, order)
            bad = ~np.all(np.isfinite(np.concatenate(result[1:], axis=1)), axis=1)
            if self.extrapolate and bad.any():
                ku, kv = self._one_sided_kinds(s[bad], t[bad])
                redo = self._differences_by_kind(s[bad], t[bad], ku, kv, order)
                for full, part in zip(result, redo, strict=True):
                    full[bad] = part
        return result

    def _one_sided_kinds(self, s: FloatArray, t: FloatArray) -> tuple[np.ndarray, np.ndarray]:
        """Stencil kind per point: forward near 0, backward near 1, else central."""
        reach = 3.0 * max(self.steps) * (1.0 + 1e-9)  # central stencils reach 3h

        def kinds(x: FloatArray) -> np.ndarray:
            k = np.zeros(len(x), dtype=np.int8)
            k[x - reach < 0.0] = 1
            k[x + reach > 1.0] = 2
            return k

        return kinds(s), kinds(t)

    def _differences_by_kind(
        self, s: FloatArray, t: FloatArray, kind_u: np.ndarray, kind_v: np.ndarray, order: int
    ) -> list[FloatArray]:
        """Finite-difference derivatives with per-point stencil kinds, using a single
        call of the user function for every stencil point of every point."""
        h1, h2 = self.steps
        n = len(s)
        centre = self._call(s, t)
        out = [centre] + [np.zeros((n, 3)) for _ in range(2 if order == 1 else 5)]
        # Per (kind_u, kind_v) group of points: its (output slot, du, dv, weights) terms.
        plans: list[tuple[np.ndarray, list[tuple[int, FloatArray, FloatArray, FloatArray]]]] = []
        chunks_s: list[FloatArray] = []
        chunks_t: list[FloatArray] = []
        group_key = kind_u.astype(np.int16) * 3 + kind_v
        for key in np.unique(group_key):
            idx = np.nonzero(group_key == key)[0]
            ku, kv = int(key) // 3, int(key) % 3
            ou1, wu1 = _FIRST[ku]
            ov1, wv1 = _FIRST[kv]
            terms = [
                (1, ou1 * h1, np.zeros_like(ou1), wu1 / h1),
                (2, np.zeros_like(ov1), ov1 * h1, wv1 / h1),
            ]
            if order == 2:
                ou2, wu2 = _SECOND[ku]
                ov2, wv2 = _SECOND[kv]
                mu, mv, mw = _mixed_stencil(ku, kv)
                terms += [
                    (3, ou2 * h2, np.zeros_like(ou2), wu2 / h2**2),
                    (4, mu * h2, mv * h2, mw / h2**2),
                    (5, np.zeros_like(ov2), ov2 * h2, wv2 / h2**2),
                ]
            plan = []
            for slot, du, dv, w in terms:
                at_centre = (du == 0) & (dv == 0)
                if at_centre.any():  # the centre value is already known
                    out[slot][idx] += w[at_centre].sum() * centre[idx]
                du, dv, w = du[~at_centre], dv[~at_centre], w[~at_centre]
                chunks_s.append((s[idx, None] + du[None, :]).ravel())
                chunks_t.append((t[idx, None] + dv[None, :]).ravel())
                plan.append((slot, du, dv, w))
            plans.append((idx, plan))
        values = self._call(np.concatenate(chunks_s), np.concatenate(chunks_t))
        pos = 0
        for idx, plan in plans:
            for slot, du, _dv, w in plan:
                size = len(idx) * len(du)
                block = values[pos : pos + size].reshape(len(idx), len(du), 3)
                pos += size
                out[slot][idx] += np.einsum("ikc,k->ic", block, w)
        return out


# --------------------------------------------------------------------------- primitives

#: ``jet(u, v, order)`` → [S, Su, Sv, Suu, Suv, Svv][: 1, 3 or 6] in the original
#: parameters; lets a primitive share its trigonometry between all derivatives.
Jet = Callable[[FloatArray, FloatArray, int], list[FloatArray]]


def _xyz(x: ArrayLike, y: ArrayLike, z: ArrayLike, n: int) -> FloatArray:
    out = np.empty((n, 3))
    out[:, 0], out[:, 1], out[:, 2] = x, y, z
    return out


class _JetSurface(ParametricSurface):
    """A ParametricSurface whose value and derivatives come from one ``jet`` call."""

    #: Derivatives from the definition, not differences of positions (:func:`.vec_ops.differenced`).
    exact_derivatives = True

    def __init__(
        self,
        jet: Jet,
        u_domain: tuple[float, float],
        v_domain: tuple[float, float],
        closed_u: bool,
        closed_v: bool,
    ) -> None:
        super().__init__(
            lambda u, v: jet(u, v, 0)[0], u_domain, v_domain, closed_u=closed_u, closed_v=closed_v
        )
        self._jet = jet

    #: Analytic derivatives: no difference noise.
    _difference_noise = 0.0

    def derivatives(self, u: ArrayLike, v: ArrayLike, order: int = 1) -> list[FloatArray]:
        self._check_order(order)
        s, t = broadcast_uv(u, v)
        ders = self._jet(self.u_domain[0] + s * self._span_u, self.v_domain[0] + t * self._span_v, order)
        a, b = self._span_u, self._span_v
        factors = (1.0, a, b, a * a, a * b, b * b)
        return [d if f == 1.0 else d * f for d, f in zip(ders, factors, strict=False)]


def _centred(center: ArrayLike) -> FloatArray:
    return np.asarray(center, dtype=float).reshape(3)


def sphere(radius: float = 1.0, center: ArrayLike = (0.0, 0.0, 0.0)) -> ParametricSurface:
    """Sphere with u = longitude in [0, 2π], v = latitude in [−π/2, π/2]; outward
    normal; poles on the edges v = 0 and v = 1. Analytic derivatives."""
    c = _centred(center)
    r = float(radius)

    def jet(u: FloatArray, v: FloatArray, order: int) -> list[FloatArray]:
        n = len(u)
        cu, su, cv, sv = np.cos(u), np.sin(u), r * np.cos(v), r * np.sin(v)
        out = [_xyz(c[0] + cu * cv, c[1] + su * cv, c[2] + sv, n)]
        if order >= 1:
            out += [_xyz(-su * cv, cu * cv, 0.0, n), _xyz(-cu * sv, -su * sv, cv, n)]
        if order == 2:
            out += [
                _xyz(-cu * cv, -su * cv, 0.0, n),
                _xyz(su * sv, -cu * sv, 0.0, n),
                _xyz(-cu * cv, -su * cv, -sv, n),
            ]
        return out

    return _JetSurface(jet, (0.0, 2 * np.pi), (-np.pi / 2, np.pi / 2), True, False)


def torus(
    major_radius: float = 2.0, minor_radius: float = 0.5, center: ArrayLike = (0.0, 0.0, 0.0)
) -> ParametricSurface:
    """Torus around the z axis: u around the axis, v around the tube, both in [0, 2π];
    v = 0 is the outer equator. Outward normal; analytic derivatives.

    Closed forms: K = cos v / (r (R + r cos v)); principal curvatures −1/r and
    −cos v / (R + r cos v) (negative: the surface bends away from the normal).
    """
    c = _centred(center)
    big, small = float(major_radius), float(minor_radius)

    def jet(u: FloatArray, v: FloatArray, order: int) -> list[FloatArray]:
        n = len(u)
        cu, su, cv, sv = np.cos(u), np.sin(u), small * np.cos(v), small * np.sin(v)
        ring = big + cv
        out = [_xyz(c[0] + ring * cu, c[1] + ring * su, c[2] + sv, n)]
        if order >= 1:
            out += [_xyz(-ring * su, ring * cu, 0.0, n), _xyz(-sv * cu, -sv * su, cv, n)]
        if order == 2:
            out += [
                _xyz(-ring * cu, -ring * su, 0.0, n),
                _xyz(sv * su, -sv * cu, 0.0, n),
                _xyz(-cv * cu, -cv * su, -sv, n),
            ]
        return out

    return _JetSurface(jet, (0.0, 2 * np.pi), (0.0, 2 * np.pi), True, True)


def cylinder(
    radius: float = 1.0, height: float = 1.0, center: ArrayLike = (0.0, 0.0, 0.0)
) -> ParametricSurface:
    """Cylinder around the z axis from the base circle at ``center`` (v = 0) up to
    ``height`` (v = 1); u around the axis; outward normal; analytic derivatives."""
    c = _centred(center)
    r, h = float(radius), float(height)

    def jet(u: FloatArray, v: FloatArray, order: int) -> list[FloatArray]:
        n = len(u)
        cu, su = r * np.cos(u), r * np.sin(u)
        out = [_xyz(c[0] + cu, c[1] + su, c[2] + h * v, n)]
        if order >= 1:
            out += [_xyz(-su, cu, 0.0, n), _xyz(0.0, 0.0, h, n)]
        if order == 2:
            out += [_xyz(-cu, -su, 0.0, n), np.zeros((n, 3)), np.zeros((n, 3))]
        return out

    return _JetSurface(jet, (0.0, 2 * np.pi), (0.0, 1.0), True, False)


def cone(radius: float = 1.0, height: float = 1.0, center: ArrayLike = (0.0, 0.0, 0.0)) -> ParametricSurface:
    """Cone around the z axis from the base circle (v = 0, at ``center``) to the apex
    ``height`` above it (v = 1); outward normal; analytic derivatives."""
    c = _centred(center)
    r, h = float(radius), float(height)

    def jet(u: FloatArray, v: FloatArray, order: int) -> list[FloatArray]:
        n = len(u)
        cu, su = r * np.cos(u), r * np.sin(u)
        w = 1.0 - v
        out = [_xyz(c[0] + w * cu, c[1] + w * su, c[2] + h * v, n)]
        if order >= 1:
            out += [_xyz(-w * su, w * cu, 0.0, n), _xyz(-cu, -su, h, n)]
        if order == 2:
            out += [_xyz(-w * cu, -w * su, 0.0, n), _xyz(su, -cu, 0.0, n), np.zeros((n, 3))]
        return out

    return _JetSurface(jet, (0.0, 2 * np.pi), (0.0, 1.0), True, False)
