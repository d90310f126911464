"""The contract every kernel surface fulfils: parameters (u, v) in [0, 1]², vectorised.

A subclass implements :meth:`Surface.derivatives` (S and its partial derivatives up to
order 2 with respect to the *normalised* parameters); everything else — normals,
fundamental forms, curvature, isocurves, edges, area, closest point, rulings,
meshing, bounding box — is derived here, generically, from those derivatives.

Edge numbering (used by :meth:`Surface.edges`, SurfaceCoupling and the viewport)
runs counter-clockwise around the parameter square, each edge starting where the
previous one ends::

        v
        1 ┌───── 2 ◄────┐
          │              │
          3              1
          ▼              ▲
        0 └───── 0 ─────►┘
          0              1  u

    edge 0: v = 0, u from 0 to 1
    edge 1: u = 1, v from 0 to 1
    edge 2: v = 1, u from 1 to 0
    edge 3: u = 0, v from 1 to 0

Curvature signs follow :mod:`torsal.nodes.geometry.curvature` (normal ``Su × Sv``).
"""

from __future__ import annotations

import functools
from abc import ABC, abstractmethod
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike
from scipy.spatial import cKDTree

from .area import integrate_unit_square
from .array_types import FloatArray
from .curvature import (
    BLOCK,
    DEGENERATE_RATIO,
    FundamentalForms,
    SurfaceCurvature,
    assign_curvature,
    empty_curvature,
    fundamental_forms,
    principal_curvatures,
    unit_normal,
)
from .curve_base import Curve
from .square_descent import backtrack, pinned_step, step_length
from .surface_box import surface_bounding_box
from .vec_ops import anchor, cross, derivative_noise, dot, extent, position_rounding
from .watch import watch_check

if TYPE_CHECKING:
    import trimesh

#: At a degenerate point (|Su × Sv| below ``DEGENERATE_RATIO``·(|Su|² + |Sv|²): a pole,
#: an apex, a collapsed edge) normals and curvature are taken this step (in
#: parameter units) towards the middle of the parameter square.
DEGENERATE_NUDGE = 1e-6


def broadcast_uv(u: ArrayLike, v: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """Broadcast u and v against each other and flatten them to equal-length 1-D arrays."""
    uu, vv = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
    return np.ascontiguousarray(uu.ravel()), np.ascontiguousarray(vv.ravel())


def uv_grid(nu: int, nv: int) -> tuple[FloatArray, FloatArray]:
    """Flattened parameters of an ``nu × nv`` grid on [0, 1]², u-major.

    Point ``(i, j)`` (u_i, v_j) is at flat index ``i * nv + j``.
    """
    uu, vv = np.meshgrid(np.linspace(0.0, 1.0, nu), np.linspace(0.0, 1.0, nv), indexing="ij")
    return uu.ravel(), vv.ravel()


@functools.lru_cache(maxsize=32)
def _uv_grid(nu: int, nv: int) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """:func:`uv_grid` and each of its points a step inwards (where a degenerate normal is
    re-taken, see :meth:`Surface._regular_derivatives`), made once per size (read-only)."""
    u, v = uv_grid(nu, nv)
    grid = (
        u, v, u + np.where(u < 0.5, DEGENERATE_NUDGE, -DEGENERATE_NUDGE),
        v + np.where(v < 0.5, DEGENERATE_NUDGE, -DEGENERATE_NUDGE),
    )
    for axis in grid:
        axis.flags.writeable = False
    return grid


@functools.lru_cache(maxsize=32)
def _grid_triangles(nu: int, nv: int) -> np.ndarray:
    i, j = np.meshgrid(np.arange(nu - 1), np.arange(nv - 1), indexing="ij")
    a = (i * nv + j).ravel()
    b, c, d = a + nv, a + nv + 1, a + 1  # (i+1, j), (i+1, j+1), (i, j+1)
    faces = np.concatenate([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    faces.flags.writeable = False
    return faces


def grid_triangles(nu: int, nv: int) -> np.ndarray:
    """Triangles ``(2 (nu-1)(nv-1), 3)`` of an ``nu × nv`` vertex grid numbered as in
    :func:`uv_grid`, oriented with u × v (a copy: callers may change it)."""
    return _grid_triangles(nu, nv).copy()


@dataclass(frozen=True)
class ClosestPoint:
    """Result of :meth:`Surface.closest_point` for m query points."""

    parameters: FloatArray  #: (m, 2) the (u, v) of the closest points
    points: FloatArray  #: (m, 3) the closest points on the surface
    distances: FloatArray  #: (m,) distances from the query points


class Surface(ABC):
    """A 3D surface parameterised on (u, v) in [0, 1]².

    Subclasses set ``closed_u``/``closed_v`` when the surface joins itself across
    u = 0 ≡ 1 (resp. v) — closest-point searches then wrap instead of clamping.
    """

    closed_u: bool = False
    closed_v: bool = False

    # ------------------------------------------------------------------ contract

    @abstractmethod
    def derivatives(self, u: ArrayLike, v: ArrayLike, order: int = 1) -> list[FloatArray]:
        """Return S and its partial derivatives at (u, v), each an ``(n, 3)`` array.

        ``order=0``: ``[S]``; ``order=1``: ``[S, Su, Sv]``; ``order=2``:
        ``[S, Su, Sv, Suu, Suv, Svv]``. ``u`` and ``v`` are scalars or arrays,
        broadcast against each other (see :func:`broadcast_uv`); derivatives are
        with respect to the normalised parameters.
        """

    @staticmethod
    def _check_order(order: int) -> None:
        if order not in (0, 1, 2):
            raise ValueError(f"surface derivatives are available to order 2, not {order}")

    # ------------------------------------------------------------------ evaluation

    def point_at(self, u: ArrayLike, v: ArrayLike) -> FloatArray:
        """Points S(u, v): ``(n, 3)``, or ``(3,)`` when u and v are both scalars."""
        scalar = np.ndim(u) == 0 and np.ndim(v) == 0
        points = self.derivatives(u, v, 0)[0]
        return points[0] if scalar else points

    def _regular_derivatives(
        self, u: ArrayLike, v: ArrayLike, order: int, bad: np.ndarray | None = None
    ) -> list[FloatArray]:
        """Derivatives, re-taken a tiny step inwards at degenerate points (poles).

        ``bad`` marks the degenerate rows when the caller already knows them;
        otherwise they are found from |Su × Sv| (see ``DEGENERATE_RATIO``).
        """
        uu, vv = broadcast_uv(u, v)
        ders = self.derivatives(uu, vv, order)
        if bad is None:
            su, sv = ders[1], ders[2]
            cross = np.linalg.norm(np.cross(su, sv), axis=1)
            bad = ~(cross > DEGENERATE_RATIO * (dot(su, su) + dot(sv, sv)))
        if bad.any():
            nudged_u = uu[bad] + np.where(uu[bad] < 0.5, DEGENERATE_NUDGE, -DEGENERATE_NUDGE)
            nudged_v = vv[bad] + np.where(vv[bad] < 0.5, DEGENERATE_NUDGE, -DEGENERATE_NUDGE)
            fixed = self.derivatives(nudged_u, nudged_v, order)
            for full, part in zip(ders[1:], fixed[1:], strict=True):
                full[bad] = part
        return ders

    def normal_at(self, u: ArrayLike, v: ArrayLike) -> FloatArray:
        """Unit normals ``Su × Sv / |Su × Sv|`` at (u, v), ``(n, 3)``.

        At degenerate points (a sphere's poles, a cone's apex) the normal is the
        limit taken from a point 1e-6 inside the parameter square.
        """
        ders = self._regular_derivatives(u, v, 1)
        return unit_normal(ders[1], ders[2])

    def frame_at(self, u: ArrayLike, v: ArrayLike) -> tuple[FloatArray, ...]:
        """Orthonormal frames ``(origin, x, y, z)``, each ``(n, 3)``.

        x is the unit u-tangent, z the unit normal and y = z × x.
        """
        ders = self._regular_derivatives(u, v, 1)
        z = unit_normal(ders[1], ders[2])
        x = ders[1] / np.linalg.norm(ders[1], axis=1, keepdims=True)
        return ders[0], x, np.cross(z, x), z

    def fundamental_forms(self, u: ArrayLike, v: ArrayLike) -> FundamentalForms:
        """First and second fundamental forms (E, F, G, L, M, N) and the unit normal."""
        ders = self._regular_derivatives(u, v, 2)
        return fundamental_forms(*ders[1:])

    def curvature(self, u: ArrayLike, v: ArrayLike) -> SurfaceCurvature:
        """Principal curvatures k1 >= k2, principal directions (3D unit vectors),
        Gaussian and mean curvature and the normal at (u, v), from exact derivatives.

        At umbilics the directions are still an orthonormal tangent pair (the unit
        u-tangent and its perpendicular).
        """
        uu, vv = broadcast_uv(u, v)
        if len(uu) <= BLOCK:
            return self._curvature_block(uu, vv)
        # Cache-sized blocks: derivatives and curvature of one block stay in cache.
        result = empty_curvature(len(uu))
        for lo in range(0, len(uu), BLOCK):
            rows = slice(lo, lo + BLOCK)
            assign_curvature(result, rows, self._curvature_block(uu[rows], vv[rows]))
        return result

    def _curvature_block(self, uu: FloatArray, vv: FloatArray) -> SurfaceCurvature:
        result = principal_curvatures(*self.derivatives(uu, vv, 2)[1:])
        bad = np.isnan(result.k1)
        if bad.any():
            ders = self._regular_derivatives(uu[bad], vv[bad], 2, bad=np.ones(bad.sum(), bool))
            assign_curvature(result, bad, principal_curvatures(*ders[1:]))
        return result

    def gaussian_curvature(self, u: ArrayLike, v: ArrayLike) -> FloatArray:
        """Gaussian curvature K = k1·k2 = (LN − M²)/(EG − F²), ``(n,)``."""
        return self.curvature(u, v).gaussian

    # ------------------------------------------------------------------ curves

    def isocurve(self, direction: str | int, param: float) -> IsoCurve:
        """The curve of constant parameter that runs along ``direction``.

        ``direction="u"`` (or 0): t ↦ S(t, param), the curve along u at v = param;
        ``direction="v"`` (or 1): t ↦ S(param, t), the curve along v at u = param.
        """
        return IsoCurve(self, direction, param)

    def edges(self) -> list[IsoCurve]:
        """The four boundary curves, numbered and oriented as in the module docstring:
        0: v=0 (u 0→1), 1: u=1 (v 0→1), 2: v=1 (u 1→0), 3: u=0 (v 1→0)."""
        return [
            IsoCurve(self, "u", 0.0),
            IsoCurve(self, "v", 1.0),
            IsoCurve(self, "u", 1.0, reverse=True),
            IsoCurve(self, "v", 0.0, reverse=True),
        ]

    # ------------------------------------------------------------------ integrals

    def area(self, rtol: float = 1e-11) -> float:
        """Surface area ∫∫ |Su × Sv| du dv by adaptive Gauss–Legendre cubature."""

        def element(u: FloatArray, v: FloatArray) -> FloatArray:
            _, su, sv = self.derivatives(u, v, 1)
            return np.linalg.norm(np.cross(su, sv), axis=1)

        bu, bv = self.area_breaks()
        noise = derivative_noise(self._probe())
        return float(integrate_unit_square(element, rtol=rtol, breaks_u=bu, breaks_v=bv, noise=noise)[0])

    def _probe(self) -> FloatArray:
        """A 5 × 5 grid of the surface's points: where it is and how big, for the cubature's
        rounding floor (:func:`~.vec_ops.derivative_noise`)."""
        grid = np.linspace(0.0, 1.0, 5)
        return self.point_at(*(a.ravel() for a in np.meshgrid(grid, grid)))

    def area_breaks(self) -> tuple[FloatArray | None, FloatArray | None]:
        """Parameters in u and v where the area element may not be smooth (knots), or
        None: the area cubature starts from their grid, so no cell straddles one."""
        return None, None

    def area_and_centroid(self, rtol: float = 1e-11) -> tuple[float, FloatArray]:
        """Area and area centroid ∫∫ S |Su × Sv| / area, by the same cubature.

        The moment is integrated about a point of the surface and in units of its size,
        so that the cubature's tolerance (relative to the largest component) is set by
        the area wherever the surface sits, not by its distance from the origin."""
        probe = self._probe()
        origin = anchor(probe)
        size = float(np.linalg.norm(extent(probe))) or 1.0

        def integrand(u: FloatArray, v: FloatArray) -> FloatArray:
            s, su, sv = self.derivatives(u, v, 1)
            w = np.linalg.norm(np.cross(su, sv), axis=1)
            return np.column_stack([w, (s - origin) * (w / size)[:, None]])

        bu, bv = self.area_breaks()
        result = integrate_unit_square(integrand, rtol=rtol, breaks_u=bu, breaks_v=bv,
                                       noise=derivative_noise(probe))
        return float(result[0]), origin + size * result[1:] / result[0]

    # ------------------------------------------------------------------ queries

    def closest_point(
        self,
        points: ArrayLike,
        seeds: int = 32,
        candidates: int = 4,
        tolerance: float = 1e-13,
        max_iterations: int = 60,
    ) -> ClosestPoint:
        """Closest points on the surface to ``points`` (``(m, 3)`` or ``(3,)``).

        Each query starts from its ``candidates`` nearest samples of a
        ``(seeds+1)²`` grid and runs a safeguarded Newton iteration on
        f(u, v) = ½|S(u, v) − P|², all queries at once: the exact Hessian when it
        is positive definite, else the Gauss–Newton one; a backtracking line search
        that never lets the distance grow; coordinates pinned at the boundary
        (an active set) when the minimum lies on an edge, and wrapped across a seam
        of a closed direction. Iteration stops when the parameter step is below
        ``tolerance``; the best candidate wins.
        """
        query = np.atleast_2d(np.asarray(points, dtype=float))
        gu, gv = uv_grid(seeds + 1, seeds + 1)
        samples = self.derivatives(gu, gv, 0)[0]
        k = min(candidates, len(gu))
        _, idx = cKDTree(samples).query(query, k=k)
        idx = np.asarray(idx).reshape(len(query), k)
        rep = np.repeat(query, k, axis=0)
        u, v = self._newton_closest(rep, gu[idx.ravel()], gv[idx.ravel()], tolerance, max_iterations)
        found = self.derivatives(u, v, 0)[0]
        dist = np.linalg.norm(found - rep, axis=1).reshape(len(query), k)
        best = np.argmin(dist, axis=1)
        pick = np.arange(len(query)) * k + best
        return ClosestPoint(
            parameters=np.column_stack([u[pick], v[pick]]),
            points=found[pick],
            distances=dist[np.arange(len(query)), best],
        )

    def _newton_closest(
        self, query: FloatArray, u: FloatArray, v: FloatArray, tolerance: float, max_iter: int
    ) -> tuple[FloatArray, FloatArray]:
        u, v = u.copy(), v.copy()
        active = np.arange(len(u))
        check = watch_check()

        def distance(pending: np.ndarray, pu: FloatArray, pv: FloatArray) -> FloatArray:
            """Half the squared distance to the queries of the active starts ``pending``."""
            dd = self.derivatives(pu, pv, 0)[0] - query[active[pending]]
            return 0.5 * dot(dd, dd)

        for _ in range(max_iter):
            if check:
                check()
            if active.size == 0:
                break
            ua, va, pa = u[active], v[active], query[active]
            s, su, sv, suu, suv, svv = self.derivatives(ua, va, 2)
            d = s - pa
            g_u, g_v = dot(d, su), dot(d, sv)
            e, f, g = dot(su, su), dot(su, sv), dot(sv, sv)
            h_uu, h_uv, h_vv = e + dot(d, suu), f + dot(d, suv), g + dot(d, svv)
            det = h_uu * h_vv - h_uv * h_uv
            indefinite = (h_uu <= 0) | (det <= 1e-14 * (e * g + 1e-300))
            # Gauss–Newton (first fundamental form), lightly damped, where indefinite.
            damp = 1e-12 * (e + g)
            h_uu = np.where(indefinite, e + damp, h_uu)
            h_vv = np.where(indefinite, g + damp, h_vv)
            h_uv = np.where(indefinite, f, h_uv)
            du, dv = pinned_step(ua, va, g_u, g_v, h_uu, h_uv, h_vv, self.closed_u, self.closed_v)
            # backtracking: never let the distance grow
            new_u, new_v = backtrack(distance, 0.5 * dot(d, d), ua, va, du, dv, self.closed_u,
                                     self.closed_v, halvings=40, slack=1e-14, floor=1e-300)
            moved = step_length(ua, va, new_u, new_v, self.closed_u, self.closed_v)
            u[active], v[active] = new_u, new_v
            active = active[moved > tolerance]
        return u, v

    def bounding_box(self, samples: int = 32) -> FloatArray:
        """Axis-aligned bounding box ``[[xmin, ymin, zmin], [xmax, ymax, zmax]]``, tight.

        Each extreme is at a corner, on an edge where the coordinate's derivative along
        it is zero, or inside where both its partial derivatives are: the edges' own
        boxes and a Newton search on the gradient from the best of a
        ``(samples + 1)²`` grid find them, to the rounding of the surface's positions
        wherever it is (see :mod:`.surface_box`).
        """
        return surface_bounding_box(self, samples)

    # ------------------------------------------------------------------ rulings

    @cached_property
    def ruling_direction(self) -> str | None:
        """``"v"`` if every v-isocurve (u constant) is a straight segment, else ``"u"``
        if every u-isocurve is, else ``None``. Checked on a 9 × 9 sample to 1e-9 of
        the surface's size; subclasses that know (RuledSurface) override it."""
        t = np.array([0.0, 0.11, 0.23, 0.37, 0.5, 0.61, 0.74, 0.88, 1.0])
        uu, vv = np.meshgrid(t, t, indexing="ij")
        pts = self.derivatives(uu.ravel(), vv.ravel(), 0)[0].reshape(9, 9, 3)
        size = float(np.linalg.norm(pts.max(axis=(0, 1)) - pts.min(axis=(0, 1))))
        if size == 0.0:
            return None

        def straight(lines: FloatArray) -> bool:  # lines: (rows, samples, 3)
            a, b = lines[:, :1], lines[:, -1:]
            axis = b - a
            length = np.linalg.norm(axis, axis=2, keepdims=True)
            unit = np.divide(axis, length, out=np.zeros_like(axis), where=length > 0)
            rel = lines - a
            off = rel - np.sum(rel * unit, axis=2, keepdims=True) * unit
            # to 1e-9 of the size, or to the rounding of positions far from the origin
            return bool(np.max(np.linalg.norm(off, axis=2)) <= 1e-9 * size + position_rounding(pts))

        if straight(pts):
            return "v"
        if straight(pts.transpose(1, 0, 2)):
            return "u"
        return None

    @property
    def is_ruled(self) -> bool:
        """True when one family of isocurves is straight (see :attr:`ruling_direction`)."""
        return self.ruling_direction is not None

    def rulings(self, count: int) -> FloatArray:
        """``count`` rulings, evenly spaced in the other parameter, as a
        ``(count, 2, 3)`` array of [start, end] points.

        Raises ValueError for a surface without straight rulings.
        """
        direction = self.ruling_direction
        if direction is None:
            raise ValueError("surface has no straight rulings")
        t = np.linspace(0.0, 1.0, count)
        zeros, ones = np.zeros(count), np.ones(count)
        if direction == "v":
            start, end = self.point_at(t, zeros), self.point_at(t, ones)
        else:
            start, end = self.point_at(zeros, t), self.point_at(ones, t)
        return np.stack([start, end], axis=1)

    def ruling_kinks(self) -> FloatArray:
        """Increasing parameters across the rulings (u when ``ruling_direction`` is
        ``"v"``) where an edge may turn a corner (a rail's kink): a chord polyline of the
        edge samples a ruling on each, or its length converges only like 1/n
        (:mod:`.edge_sampling`). None here; ruled and NURBS surfaces know theirs."""
        return np.empty(0)

    def transformed(self, matrix: ArrayLike) -> TransformedSurface:
        """This surface moved by an affine 4 × 4 matrix (see :class:`TransformedSurface`)."""
        return TransformedSurface(self, matrix)

    # ------------------------------------------------------------------ meshing

    def to_mesh(self, nu: int = 33, nv: int = 33) -> trimesh.Trimesh:
        """A triangle mesh on an ``nu × nv`` vertex grid of (u, v).

        Vertex ``i * nv + j`` is S(u_i, v_j) (see :func:`uv_grid`), so per-point
        values computed on the same grid colour it directly. Seams of closed
        surfaces are not welded (the grid stays intact); triangles are oriented
        with the surface normal, which is stored as the vertex normals.
        """
        import trimesh

        points, faces, normals = self.mesh_arrays(nu, nv)
        return trimesh.Trimesh(points, faces.copy(), vertex_normals=normals, process=False)

    def mesh_arrays(self, nu: int = 33, nv: int = 33) -> tuple[FloatArray, np.ndarray, FloatArray]:
        """:meth:`to_mesh` as plain arrays, for drawing: the ``(nu·nv, 3)`` points, the
        triangles (shared and read-only: the same array for every surface on this grid)
        and the unit normals (:meth:`normal_at`'s) on the grid of :func:`uv_grid`, without
        the cost of a mesh object."""
        if nu < 2 or nv < 2:
            raise ValueError("to_mesh needs at least 2 × 2 vertices")
        grid = _uv_grid(nu, nv)
        ders = self.derivatives(grid[0].copy(), grid[1].copy(), 1)
        return ders[0], _grid_triangles(nu, nv), self._grid_normals(grid, ders[1], ders[2])

    def _grid_normals(self, grid: tuple[FloatArray, ...], su: FloatArray, sv: FloatArray) -> FloatArray:
        """:meth:`normal_at` on a grid of :func:`_uv_grid` from the derivatives there
        (points where the normal degenerates re-taken a step inwards, as
        :meth:`_regular_derivatives` does), with one cross product where ``normal_at``
        takes two."""
        normal = cross(su, sv)
        length = np.sqrt(dot(normal, normal))
        bad = ~(length > DEGENERATE_RATIO * (dot(su, su) + dot(sv, sv)))
        if bad.any():
            fixed = self.derivatives(grid[2][bad], grid[3][bad], 1)
            retaken = cross(fixed[1], fixed[2])
            normal[bad] = retaken
            length[bad] = np.sqrt(dot(retaken, retaken))
        found = length > 0.0
        np.divide(normal, length[:, None], out=normal, where=found[:, None])
        if not found.all():
            normal[~found] = np.nan  # (no normal, as normal_at says)
        return normal


class CurveOnSurface(Curve):
    """A curve evaluated through a surface: :meth:`_eval` gives its exact derivatives to
    order 2 (from the surface's); order 3 (for torsion) is Richardson-extrapolated central
    differences of the second (~1e-8 relative)."""

    def _eval(self, t: FloatArray, order: int) -> list[FloatArray]:
        raise NotImplementedError

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        t = np.atleast_1d(np.asarray(t, dtype=float)).ravel()
        if order < 0 or order > 3:
            raise ValueError("derivatives of a curve on a surface are available to order 3")
        ders = self._eval(t, min(order, 2))
        if order == 3:
            h = 1e-3
            d2 = [self._eval(t + k * h, 2)[2] for k in (-2, -1, 1, 2)]
            ders.append((d2[0] - 8.0 * d2[1] + 8.0 * d2[2] - d2[3]) / (12.0 * h))
        return ders


class IsoCurve(CurveOnSurface):
    """A parameter line of a surface, as a :class:`Curve` on t in [0, 1].

    ``direction="u"``: C(t) = S(t, param); ``direction="v"``: C(t) = S(param, t);
    ``reverse=True`` runs it from t = 1 to 0. Derivatives up to order 2 are the
    surface's exact ones; order 3 (for torsion) uses Richardson-extrapolated
    central differences of the second derivative (~1e-8 relative).
    """

    def __init__(self, surface: Surface, direction: str | int, param: float, reverse: bool = False) -> None:
        key = {"u": "u", "v": "v", 0: "u", 1: "v"}.get(direction)  # type: ignore[call-overload]
        if key is None:
            raise ValueError(f"isocurve direction must be 'u' or 'v', not {direction!r}")
        self.surface = surface
        self.direction = key
        self.param = float(param)
        self.reverse = reverse
        self.closed = surface.closed_u if key == "u" else surface.closed_v

    def __repr__(self) -> str:
        return f"IsoCurve({self.direction}, {self.param:g}, reverse={self.reverse})"

    def _eval(self, t: FloatArray, order: int) -> list[FloatArray]:
        s = 1.0 - t if self.reverse else t
        c = np.full_like(s, self.param)
        if self.direction == "u":
            ders = self.surface.derivatives(s, c, order)
            picked = [ders[k] for k in (0, 1, 3)[: order + 1]]  # S, Su, Suu
        else:
            ders = self.surface.derivatives(c, s, order)
            picked = [ders[k] for k in (0, 2, 5)[: order + 1]]  # S, Sv, Svv
        if self.reverse and order >= 1:
            picked[1] = -picked[1]
        return picked

    def _breakpoints(self) -> FloatArray:
        """The surface's knots along the curve (NURBS), so that sampling-based curve
        operations put samples on every span."""
        knots = getattr(self.surface, "knots_u" if self.direction == "u" else "knots_v", None)
        if knots is None:
            return super()._breakpoints()
        inside = np.unique(np.clip(np.asarray(knots, dtype=float), 0.0, 1.0))
        return np.sort(1.0 - inside) if self.reverse else inside



class TransformedSurface(Surface):
    """A surface moved by an affine 4 × 4 matrix: S'(u, v) = R·S(u, v) + t.

    Derivatives transform with R; a rotation/translation keeps curvature, a
    uniform scale by s divides it by s. Projective matrices are rejected.
    """

    def __init__(self, surface: Surface, matrix: ArrayLike) -> None:
        m = np.asarray(matrix, dtype=float)
        if m.shape != (4, 4) or not np.allclose(m[3], [0.0, 0.0, 0.0, 1.0]):
            raise ValueError("an affine 4 × 4 matrix with last row (0, 0, 0, 1) is needed")
        self.surface = surface
        self.matrix = m
        self.closed_u, self.closed_v = surface.closed_u, surface.closed_v

    def __repr__(self) -> str:
        return f"TransformedSurface({self.surface!r})"

    def derivatives(self, u: ArrayLike, v: ArrayLike, order: int = 1) -> list[FloatArray]:
        self._check_order(order)
        linear, shift = self.matrix[:3, :3], self.matrix[:3, 3]
        ders = self.surface.derivatives(u, v, order)
        return [ders[0] @ linear.T + shift] + [d @ linear.T for d in ders[1:]]

    @cached_property
    def ruling_direction(self) -> str | None:
        """The wrapped surface's: an affine map takes straight lines to straight lines."""
        return self.surface.ruling_direction

    def ruling_kinks(self) -> FloatArray:
        """The wrapped surface's: an affine map keeps corners and parameters."""
        return self.surface.ruling_kinks()

    def _area_scale(self) -> float | None:
        """k² when the matrix is a similarity (rotation, mirror, uniform scale k and a
        move): areas then scale by k² and the surface's own integrator is kept."""
        linear = self.matrix[:3, :3]
        gram = linear.T @ linear
        k2 = float(np.trace(gram)) / 3.0
        if k2 > 0.0 and np.abs(gram - k2 * np.eye(3)).max() <= 1e-12 * k2:
            return k2
        return None

    def area(self, rtol: float = 1e-11) -> float:
        k2 = self._area_scale()
        return k2 * self.surface.area(rtol) if k2 is not None else super().area(rtol)

    def area_and_centroid(self, rtol: float = 1e-11) -> tuple[float, FloatArray]:
        k2 = self._area_scale()
        if k2 is None:
            return super().area_and_centroid(rtol)
        area, centroid = self.surface.area_and_centroid(rtol)
        return k2 * area, self.matrix[:3, :3] @ centroid + self.matrix[:3, 3]
