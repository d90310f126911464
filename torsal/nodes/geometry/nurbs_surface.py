"""Tensor-product NURBS surfaces: any degrees, any knot vectors, rational weights.

Evaluation is vectorised over points with B-spline basis *matrices*: for each
parameter the knot span and the p + 1 non-zero basis functions (and their
derivatives) come from per-span polynomial tables (:class:`SpanBasis`, built once by
the Cox–de Boor recurrence); each point's (p + 1) × (q + 1) products of u- and
v-basis values form one row of a sparse matrix whose product with the control net
is the evaluation. Points alone (the common 10⁶-point case: meshing, sampling) take
a faster path: every knot-span patch is converted once to power form, and a point
is one gather of its patch's coefficients and a 2D Horner scheme. Rational surfaces
are evaluated in homogeneous coordinates and their derivatives recovered with the
quotient rule. Work is done in chunks so that 10⁶ points need a bounded amount of
memory.

Knot vectors may live on any interval and need not be clamped; the valid domain
[t_p, t_n] is mapped to [0, 1].
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike
from scipy import sparse
from scipy.interpolate import make_interp_spline

from .area import CHUNK_POINTS, span_gauss, watch_check
from .array_types import FloatArray, IntArray
from .surface_base import Surface, broadcast_uv
from .vec_ops import anchor

if TYPE_CHECKING:
    from .curve_base import Curve

_CHUNK = 8192  # points per evaluation pass: keeps the sparse rows and temporaries in cache
_LOOKUP_LIMIT = 1 << 16  # cells of a knot-span lookup table
_PATCH_LIMIT = 1 << 23  # numbers in a surface's power-form patch table (64 MB)


# --------------------------------------------------------------------------- basis


def clamped_knots(count: int, degree: int) -> FloatArray:
    """Uniform clamped knot vector on [0, 1] for ``count`` control points."""
    inner = np.linspace(0.0, 1.0, count - degree + 1)
    return np.concatenate([np.zeros(degree), inner, np.ones(degree)])


def find_spans(knots: FloatArray, degree: int, count: int, x: FloatArray) -> IntArray:
    """Index i of the knot span [t_i, t_{i+1}) holding each x, kept within the valid
    range [degree, count − 1] so that the domain end (and points slightly outside
    it) use the first/last span."""
    spans = np.searchsorted(knots, x, side="right") - 1
    return np.clip(spans, degree, count - 1)


def _safe_reciprocal(den: FloatArray) -> FloatArray:
    out = np.zeros_like(den)
    np.divide(1.0, den, out=out, where=den != 0.0)
    return out


def basis_functions(
    knots: FloatArray, degree: int, spans: IntArray, x: FloatArray, order: int = 0
) -> FloatArray:
    """Non-zero B-spline basis functions and their derivatives at x.

    Returns ``(order + 1, n, degree + 1)``: entry ``[d, i, k]`` is the d-th
    derivative of N_{spans[i] − degree + k, degree} at x[i].

    Values come from the Cox–de Boor recurrence raised one degree at a time,
    N_{r,j} = (x − t_r)/(t_{r+j} − t_r)·N_{r,j−1} + (t_{r+j+1} − x)/(t_{r+j+1} − t_{r+1})·N_{r+1,j−1},
    keeping every degree's table; the d-th derivative applies the derivative rule
    D N_{r,j} = j·[N_{r,j−1}/(t_{r+j} − t_r) − N_{r+1,j−1}/(t_{r+j+1} − t_{r+1})]
    d times, starting from the degree − d table. 0/0 terms (repeated knots) are 0.
    """
    n = len(x)
    tables = [np.ones((n, 1))]
    for j in range(1, degree + 1):
        prev = tables[-1]
        cur = np.zeros((n, j + 1))
        for k in range(j + 1):
            r = spans - j + k
            if k >= 1:  # N_{r, j-1} is prev[:, k-1]
                left = knots[r]
                cur[:, k] += (x - left) * _safe_reciprocal(knots[r + j] - left) * prev[:, k - 1]
            if k <= j - 1:  # N_{r+1, j-1} is prev[:, k]
                right = knots[r + j + 1]
                cur[:, k] += (right - x) * _safe_reciprocal(right - knots[r + 1]) * prev[:, k]
        tables.append(cur)
    out = np.zeros((order + 1, n, degree + 1))
    out[0] = tables[degree]
    for d in range(1, min(order, degree) + 1):
        vals = tables[degree - d]
        for j in range(degree - d + 1, degree + 1):
            nxt = np.zeros((n, j + 1))
            for k in range(j + 1):
                r = spans - j + k
                if k >= 1:
                    nxt[:, k] += j * _safe_reciprocal(knots[r + j] - knots[r]) * vals[:, k - 1]
                if k <= j - 1:
                    nxt[:, k] -= j * _safe_reciprocal(knots[r + j + 1] - knots[r + 1]) * vals[:, k]
            vals = nxt
        out[d] = vals
    return out


class SpanBasis:
    """Fast evaluation of the B-spline basis of one knot vector, for many parameters.

    At construction the p + 1 basis functions that are non-zero on each knot span
    are converted, once, to polynomials in the local coordinate
    ξ = (x − t_i)/(t_{i+1} − t_i) (the same Cox–de Boor recurrence as
    :func:`basis_functions`, run on polynomial coefficients). Evaluating then costs
    a span search, ξ's powers and one small product per parameter, which is what
    makes 10⁶ surface points take a fraction of a second.
    """

    def __init__(self, knots: FloatArray, degree: int, count: int) -> None:
        p = degree
        self.knots, self.degree = knots, p
        self.breaks = np.unique(knots[p : count + 1])
        spans = len(self.breaks) - 1
        # Knot index i of each span: t_i = breaks[k] < t_{i+1}.
        index = np.searchsorted(knots, self.breaks[:-1], side="right") - 1
        self.index = np.clip(index, p, count - 1)
        self.start = knots[self.index]
        self.length = knots[self.index + 1] - self.start
        poly = np.zeros((spans, 1, p + 1))
        poly[:, 0, 0] = 1.0
        for j in range(1, p + 1):
            new = np.zeros((spans, j + 1, p + 1))
            for k in range(j + 1):
                r = self.index - j + k
                if k >= 1:  # (x − t_r)/(t_{r+j} − t_r) · N_{r,j−1}
                    inv = _safe_reciprocal(knots[r + j] - knots[r])
                    c0, c1 = (self.start - knots[r]) * inv, self.length * inv
                    prev = poly[:, k - 1, :]
                    new[:, k, :] += c0[:, None] * prev
                    new[:, k, 1:] += c1[:, None] * prev[:, :-1]
                if k <= j - 1:  # (t_{r+j+1} − x)/(t_{r+j+1} − t_{r+1}) · N_{r+1,j−1}
                    inv = _safe_reciprocal(knots[r + j + 1] - knots[r + 1])
                    c0, c1 = (knots[r + j + 1] - self.start) * inv, -self.length * inv
                    prev = poly[:, k, :]
                    new[:, k, :] += c0[:, None] * prev
                    new[:, k, 1:] += c1[:, None] * prev[:, :-1]
            poly = new
        coefficients = poly.transpose(0, 2, 1)  # (span, power, function)
        # Coefficients of the first and second ξ-derivatives, for Horner evaluation.
        a = np.arange(p + 1, dtype=float)[None, :, None]
        first = (coefficients * a)[:, 1:]
        second = (first * a[:, :-1])[:, 1:]
        # Stored power-major, (power, span, function), so that gathers are contiguous.
        self._tables = [np.ascontiguousarray(c.transpose(1, 0, 2)) for c in (coefficients, first, second)]
        self._inner_breaks = self.breaks[1:-1]
        # Span lookup table (see locate): cells narrower than the shortest span.
        gaps = np.diff(self.breaks)
        cells = int(np.ceil(1.0 / gaps.min())) + 1 if len(gaps) > 1 else 0
        self._lookup: IntArray | None = None
        if 0 < cells <= _LOOKUP_LIMIT:
            self._lookup = np.searchsorted(self._inner_breaks, np.arange(cells) / cells, side="right")
            self._sentinel_breaks = np.append(self._inner_breaks, np.inf)

    def power_table(self) -> FloatArray:
        """``(span, power, function)`` coefficients of the basis polynomials in ξ."""
        return self._tables[0].transpose(1, 0, 2)

    def locate(self, x: FloatArray) -> tuple[IntArray, FloatArray]:
        """Span number of each x (clamped to the first/last span) and the local
        coordinate ξ in it (outside [0, 1] only for x outside the domain)."""
        if self._lookup is None:
            k = np.searchsorted(self._inner_breaks, x, side="right")
        else:
            # Cell of a uniform grid fine enough to hold at most one break, then one
            # comparison with that break: much faster than a binary search per x.
            cells = len(self._lookup)
            cell = np.clip((x * cells).astype(np.intp), 0, cells - 1)
            k = np.take(self._lookup, cell)
            k += x >= np.take(self._sentinel_breaks, k)
        return k, (x - np.take(self.start, k)) / np.take(self.length, k)

    def evaluate(self, x: FloatArray, order: int) -> tuple[IntArray, FloatArray]:
        """First non-zero function index per x, and ``(order+1, n, p+1)`` values and
        derivatives (with respect to x) of the p + 1 non-zero functions."""
        k, xi = self.locate(x)
        length = np.take(self.length, k)
        xi = xi[:, None]
        out = np.zeros((order + 1, len(x), self.degree + 1))
        for d in range(min(order, self.degree) + 1):
            table = self._tables[d]
            values = np.take(table[-1], k, axis=0)
            for power in range(len(table) - 2, -1, -1):  # Horner in ξ
                values *= xi
                values += np.take(table[power], k, axis=0)
            if d:
                values /= (length**d)[:, None]
            out[d] = values
        return np.take(self.index, k) - self.degree, out


def _validate_knots(knots: ArrayLike | None, count: int, degree: int, name: str) -> FloatArray:
    if degree < 1:
        raise ValueError(f"{name}: degree must be at least 1")
    if count < degree + 1:
        raise ValueError(
            f"{name}: {count} control points are too few for degree {degree} (need at least {degree + 1})"
        )
    if knots is None:
        return clamped_knots(count, degree)
    t = np.asarray(knots, dtype=float).ravel()
    if len(t) != count + degree + 1:
        raise ValueError(
            f"{name}: {len(t)} knots given, {count} control points of degree {degree} "
            f"need {count + degree + 1}"
        )
    if np.any(np.diff(t) < 0):
        raise ValueError(f"{name}: knots must be non-decreasing")
    lo, hi = t[degree], t[count]
    if not hi > lo:
        raise ValueError(f"{name}: knot vector has an empty domain")
    return (t - lo) / (hi - lo)


# --------------------------------------------------------------------------- surface


class NurbsSurface(Surface):
    """A tensor-product NURBS surface on (u, v) in [0, 1]².

    ``control_points`` is an ``(nu, nv, 3)`` grid (first index along u),
    ``weights`` an optional ``(nu, nv)`` array of positive weights. Knot vectors
    default to uniform clamped ones; given ones may be on any interval and are
    normalised so that their valid domain becomes [0, 1].

    Example:
        >>> import numpy as np
        >>> grid = np.array([[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 1]]], float)
        >>> NurbsSurface(grid, 1, 1).point_at(0.5, 0.5)  # bilinear patch
        array([0.5 , 0.5 , 0.25])
    """

    #: Derivatives from the definition, not differences of positions (:func:`.vec_ops.differenced`).
    exact_derivatives = True

    def __init__(
        self,
        control_points: ArrayLike,
        degree_u: int = 3,
        degree_v: int = 3,
        knots_u: ArrayLike | None = None,
        knots_v: ArrayLike | None = None,
        weights: ArrayLike | None = None,
    ) -> None:
        points = np.asarray(control_points, dtype=float)
        if points.ndim != 3 or points.shape[2] != 3:
            raise ValueError(f"control points must be an (nu, nv, 3) grid, got {points.shape}")
        nu, nv = points.shape[:2]
        self.degree_u, self.degree_v = int(degree_u), int(degree_v)
        self.knots_u = _validate_knots(knots_u, nu, self.degree_u, "u")
        self.knots_v = _validate_knots(knots_v, nv, self.degree_v, "v")
        if weights is None:
            w = np.ones((nu, nv))
        else:
            w = np.asarray(weights, dtype=float).reshape(nu, nv)
            if np.any(w <= 0):
                raise ValueError("NURBS weights must be positive")
        self.control_points = points
        self.weights = w
        self.is_rational = bool(np.any(w != w.flat[0]))
        # The net is kept relative to the control points' box centre (added back to
        # positions only): derivatives and areas then round relative to the surface's
        # size, not to its distance from the origin (site coordinates).
        self._anchor = anchor(points.reshape(-1, 3))
        local = points - self._anchor
        # Homogeneous control net (w·P, w), or plain P when all weights are equal.
        self._net = (
            np.concatenate([local * w[..., None], w[..., None]], axis=2)
            if self.is_rational
            else local
        )
        self._basis_u = SpanBasis(self.knots_u, self.degree_u, nu)
        self._basis_v = SpanBasis(self.knots_v, self.degree_v, nv)
        self.closed_u, self.closed_v = self._detect_closed()

    def __repr__(self) -> str:
        nu, nv = self.control_points.shape[:2]
        kind = "rational " if self.is_rational else ""
        return f"NurbsSurface({kind}degrees {self.degree_u}×{self.degree_v}, {nu}×{nv} points)"

    def _detect_closed(self) -> tuple[bool, bool]:
        t = np.linspace(0.0, 1.0, 7)
        zeros, ones = np.zeros(7), np.ones(7)
        pts = self.derivatives(np.concatenate([zeros, ones, t, t]), np.concatenate([t, t, zeros, ones]), 0)[0]
        size = float(np.ptp(self.control_points.reshape(-1, 3), axis=0).max()) or 1.0
        gap_u = np.abs(pts[0:7] - pts[7:14]).max()
        gap_v = np.abs(pts[14:21] - pts[21:28]).max()
        return bool(gap_u <= 1e-10 * size), bool(gap_v <= 1e-10 * size)

    # ------------------------------------------------------------------ evaluation

    def derivatives(self, u: ArrayLike, v: ArrayLike, order: int = 1) -> list[FloatArray]:
        self._check_order(order)
        s, t = broadcast_uv(u, v)
        n = len(s)
        count = (1, 3, 6)[order]
        out = [np.empty((n, 3)) for _ in range(count)]
        for lo in range(0, n, _CHUNK):
            hi = min(lo + _CHUNK, n)
            for slot, value in enumerate(self._evaluate(s[lo:hi], t[lo:hi], order)):
                out[slot][lo:hi] = value
        out[0] += self._anchor
        return out

    def area(self, rtol: float = 1e-11) -> float:
        return self.area_and_centroid(rtol)[0]

    def ruling_kinks(self) -> FloatArray:
        """The inner knots across the rulings of multiplicity ≥ the degree there: the only
        places its edges can turn a corner (elsewhere they are at least C¹)."""
        direction = self.ruling_direction
        if direction is None:
            return np.empty(0)
        knots, degree = (self.knots_u, self.degree_u) if direction == "v" else (self.knots_v, self.degree_v)
        values, counts = np.unique(knots[(knots > 0.0) & (knots < 1.0)], return_counts=True)
        return values[counts >= degree]

    def area_breaks(self) -> tuple[FloatArray | None, FloatArray | None]:
        """The distinct knots in [0, 1] (when there are not too many cells between them)."""
        spans_u, spans_v = (np.unique(np.clip(k, 0.0, 1.0)) for k in (self.knots_u, self.knots_v))
        if (len(spans_u) - 1) * (len(spans_v) - 1) > 100_000:
            return None, None
        return spans_u, spans_v

    def area_and_centroid(self, rtol: float = 1e-11) -> tuple[float, FloatArray]:
        """Area and centroid by a Gauss rule on every knot-span patch.

        |Su × Sv| is smooth inside a patch but not across knots, where the generic
        adaptive cubature on power-of-two cells refines at length: a loft of 512 spans
        takes it ~20 s, this ~0.1 s. Rules of order 8 and 12 must agree to ``rtol``;
        otherwise (a bumpy surface) the adaptive cubature decides, starting from the
        knot grid (:meth:`area_breaks`): a bumpy 24 × 24 bicubic net, 55 s on
        power-of-two cells, takes well under a second.
        """
        spans_u, spans_v = (np.unique(np.clip(k, 0.0, 1.0)) for k in (self.knots_u, self.knots_v))
        if (len(spans_u) - 1) * (len(spans_v) - 1) <= 100_000:
            results = []
            check = watch_check()
            for order in (8, 12):
                (u, wu), (v, wv) = (span_gauss(s[:-1], s[1:], order) for s in (spans_u, spans_v))
                rows = max(1, CHUNK_POINTS // len(v))
                area, moment = 0.0, np.zeros(3)
                for lo in range(0, len(u), rows):  # blocks of rows, checking for cancellation
                    if check is not None:
                        check()
                    uu, vv = np.meshgrid(u[lo:lo + rows], v, indexing="ij")
                    s, su, sv = self.derivatives(uu.ravel(), vv.ravel(), 1)
                    w = np.linalg.norm(np.cross(su, sv), axis=1) * np.outer(wu[lo:lo + rows], wv).ravel()
                    area, moment = area + float(w.sum()), moment + (s * w[:, None]).sum(axis=0)
                results.append((area, moment))
            (coarse, _), (area, moment) = results
            if area > 0 and abs(area - coarse) <= max(rtol, 1e-13) * area:
                return area, moment / area
        return super().area_and_centroid(rtol)

    @cached_property
    def _patches(self) -> FloatArray | None:
        """Power-form coefficients of every knot-span patch, ``(spans_u·spans_v, q+1,
        p+1, dim)``: S = Σ_ab ξ^a η^b C[b, a] on the patch. None when the table would
        exceed ``_PATCH_LIMIT`` numbers (huge nets use the sparse path only)."""
        bu, bv = self._basis_u, self._basis_v
        p, q, dim = self.degree_u, self.degree_v, self._net.shape[2]
        ku, kv = len(bu.length), len(bv.length)
        if ku * kv * (p + 1) * (q + 1) * dim > _PATCH_LIMIT:
            return None
        poly_u = bu.power_table()  # (spans_u, power a, function i)
        poly_v = bv.power_table()
        rows = (bu.index - p)[:, None] + np.arange(p + 1)
        cols = (bv.index - q)[:, None] + np.arange(q + 1)
        local = self._net[rows[:, None, :, None], cols[None, :, None, :]]  # (ku, kv, i, j, c)
        table = np.einsum("kai,lbj,klijc->klbac", poly_u, poly_v, local, optimize=True)
        return np.ascontiguousarray(table.reshape(ku * kv, q + 1, p + 1, dim))

    def _points(self, s: FloatArray, t: FloatArray, table: FloatArray) -> FloatArray:
        """Points only, from the patch table: one gather and a 2D Horner scheme."""
        p, q = self.degree_u, self.degree_v
        span_u, xi = self._basis_u.locate(s)
        span_v, eta = self._basis_v.locate(t)
        coef = np.take(table, span_u * len(self._basis_v.length) + span_v, axis=0)
        inner = coef[:, q].copy()  # Horner in η for every power of ξ: (m, p+1, dim)
        eta = eta[:, None, None]
        for b in range(q - 1, -1, -1):
            inner *= eta
            inner += coef[:, b]
        out = inner[:, p].copy()  # then Horner in ξ
        xi = xi[:, None]
        for a in range(p - 1, -1, -1):
            out *= xi
            out += inner[:, a]
        return out[:, :3] / out[:, 3:] if self.is_rational else out

    def _evaluate(self, s: FloatArray, t: FloatArray, order: int) -> list[FloatArray]:
        if order == 0 and (table := self._patches) is not None:
            return [self._points(s, t, table)]
        p, q = self.degree_u, self.degree_v
        nu, nv, dim = self._net.shape
        first_u, basis_u = self._basis_u.evaluate(s, order)
        first_v, basis_v = self._basis_v.evaluate(t, order)
        m = len(s)
        # Flat indices of the (p+1)(q+1) control points acting on each parameter.
        index_type = np.int32 if nu * nv < 2**31 else np.int64
        base = (first_u * nv + first_v).astype(index_type)
        offsets = (np.arange(p + 1)[:, None] * nv + np.arange(q + 1)).ravel().astype(index_type)
        flat = (base[:, None] + offsets).ravel()
        width = (p + 1) * (q + 1)
        indptr = np.arange(0, m * width + 1, width, dtype=index_type)
        net = self._net.reshape(-1, dim)

        def mixed(a: int, b: int) -> FloatArray:
            # Row i of this sparse matrix holds N_a(u_i)·M_b(v_i) for its 16 (say)
            # control points; its product with the net is the evaluation.
            weights = (basis_u[a][:, :, None] * basis_v[b][:, None, :]).ravel()
            matrix = sparse.csr_matrix((weights, flat, indptr), shape=(m, nu * nv))
            return np.asarray(matrix @ net)

        pairs = [(0, 0), (1, 0), (0, 1), (2, 0), (1, 1), (0, 2)][: (1, 3, 6)[order]]
        homog = [mixed(a, b) for a, b in pairs]
        if not self.is_rational:
            return homog
        return _rational(homog, order)

    # ------------------------------------------------------------------ construction

    @classmethod
    def from_points(
        cls,
        points: ArrayLike,
        degree_u: int = 3,
        degree_v: int = 3,
        u_params: ArrayLike | None = None,
        v_params: ArrayLike | None = None,
    ) -> NurbsSurface:
        """The surface interpolating an ``(m, n, 3)`` grid of points.

        Point ``[i, j]`` lies on the surface at ``(u_params[i], v_params[j])``;
        by default these are chord-length parameters averaged over the rows
        (resp. columns) of the grid. Degrees are lowered when there are too few
        points. Interpolation is global (scipy's ``make_interp_spline``, with
        not-a-knot end conditions), first along u for all columns at once, then
        along v for the resulting control rows.
        """
        grid = np.asarray(points, dtype=float)
        if grid.ndim != 3 or grid.shape[2] != 3 or min(grid.shape[:2]) < 2:
            raise ValueError("from_points needs an (m, n, 3) grid with m, n >= 2")
        control, knots_u, knots_v, du, dv = interpolate_grid(grid, degree_u, degree_v, u_params, v_params)
        return cls(control, du, dv, knots_u, knots_v)


def _rational(homog: list[FloatArray], order: int) -> list[FloatArray]:
    """Quotient rule: derivatives of A/w from those of the homogeneous (A, w)."""
    w = homog[0][:, 3:]
    s = homog[0][:, :3] / w
    if order == 0:
        return [s]
    wu, wv = homog[1][:, 3:], homog[2][:, 3:]
    su = (homog[1][:, :3] - wu * s) / w
    sv = (homog[2][:, :3] - wv * s) / w
    if order == 1:
        return [s, su, sv]
    wuu, wuv, wvv = homog[3][:, 3:], homog[4][:, 3:], homog[5][:, 3:]
    suu = (homog[3][:, :3] - 2.0 * wu * su - wuu * s) / w
    suv = (homog[4][:, :3] - wu * sv - wv * su - wuv * s) / w
    svv = (homog[5][:, :3] - 2.0 * wv * sv - wvv * s) / w
    return [s, su, sv, suu, suv, svv]


def chord_parameters(grid: FloatArray, axis: int) -> FloatArray:
    """Chord-length parameters along ``axis`` of an (m, n, 3) grid, averaged over
    the other axis; rows of zero length (collapsed edges, poles) are left out, and
    if all are, the parameters are uniform."""
    lines = np.moveaxis(grid, axis, 0)  # (count, others, 3)
    steps = np.linalg.norm(np.diff(lines, axis=0), axis=2)  # (count-1, others)
    totals = steps.sum(axis=0)
    keep = totals > 0
    count = lines.shape[0]
    if not keep.any():
        return np.linspace(0.0, 1.0, count)
    cumulative = np.concatenate([np.zeros((1, keep.sum())), np.cumsum(steps[:, keep], axis=0)])
    params = (cumulative / totals[keep]).mean(axis=1)
    params[0], params[-1] = 0.0, 1.0
    return params


def interpolate_grid(
    grid: FloatArray,
    degree_u: int,
    degree_v: int,
    u_params: ArrayLike | None = None,
    v_params: ArrayLike | None = None,
    periodic_u: bool = False,
) -> tuple[FloatArray, FloatArray, FloatArray, int, int]:
    """Control net, knots and degrees of the NURBS surface through a point grid.

    ``periodic_u`` makes the u-interpolation periodic (the last grid row must repeat
    the first; it is set equal to it), which keeps closed sections C² across the seam.
    """
    m, n = grid.shape[:2]
    du, dv = min(int(degree_u), m - 1), min(int(degree_v), n - 1)
    pu = chord_parameters(grid, 0) if u_params is None else np.asarray(u_params, float)
    pv = chord_parameters(grid, 1) if v_params is None else np.asarray(v_params, float)
    if len(pu) != m or len(pv) != n:
        raise ValueError("one parameter per grid row and per grid column is needed")
    if np.any(np.diff(pu) <= 0) or np.any(np.diff(pv) <= 0):
        raise ValueError("grid parameters must be strictly increasing")
    if periodic_u and m >= 4:
        grid = grid.copy()
        grid[-1] = grid[0]
        along_u = make_interp_spline(pu, grid.reshape(m, n * 3), k=du, bc_type="periodic")
    else:
        along_u = make_interp_spline(pu, grid.reshape(m, n * 3), k=du)
    rows = np.asarray(along_u.c).reshape(-1, n, 3)  # (m, n, 3) control rows
    mu = rows.shape[0]
    along_v = make_interp_spline(pv, rows.transpose(1, 0, 2).reshape(n, mu * 3), k=dv)
    control = np.asarray(along_v.c).reshape(-1, mu, 3).transpose(1, 0, 2)
    return control, np.asarray(along_u.t), np.asarray(along_v.t), du, dv


# --------------------------------------------------------------------------- loft


class Loft(NurbsSurface):
    """A NURBS surface through several curves, in order.

    u runs along the curves (each curve is sampled at ``samples`` equally spaced
    parameters t_i, and the loft keeps u = t_i at them), v runs across them: curve
    j is the isocurve v = ``curve_parameters[j]`` (chord-length by default, or
    ``"uniform"``). Interpolation is cubic in u (periodic when every curve is
    closed) and of degree min(``degree``, curves − 1) across, so two curves give a
    ruled loft. The isocurves reproduce the input curves exactly at the samples and
    to the accuracy of cubic interpolation between them: for a circle, ~1e-10 of
    the radius at the default 129 samples (closed), ~2e-7 near the ends of open
    curves (not-a-knot end conditions).
    """

    def __init__(
        self,
        curves: Sequence[Curve],
        samples: int = 129,
        degree: int = 3,
        parameterisation: str = "chord",
    ) -> None:
        if len(curves) < 2:
            raise ValueError("a loft needs at least two curves")
        if samples < 2:
            raise ValueError("a loft needs at least two samples per curve")
        t = np.linspace(0.0, 1.0, samples)
        grid = np.stack([np.atleast_2d(c.point_at(t)) for c in curves], axis=1)
        if parameterisation == "uniform":
            pv = np.linspace(0.0, 1.0, len(curves))
        elif parameterisation == "chord":
            pv = chord_parameters(grid, 1)
        else:
            raise ValueError(f"unknown loft parameterisation {parameterisation!r}")
        closed = all(bool(getattr(c, "closed", False)) for c in curves)
        control, knots_u, knots_v, du, dv = interpolate_grid(grid, 3, degree, t, pv, closed)
        super().__init__(control, du, dv, knots_u, knots_v)
        self.curves = list(curves)
        self.curve_parameters = pv
