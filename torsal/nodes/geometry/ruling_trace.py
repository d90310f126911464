"""Valid rulings: the straight lines a surface contains where it is single-curved.

SurfaceAnalysis asks, at each grid point P where the surface is single-curved within
a curvature tolerance (min(|k1|, |k2|) <= tol), whether the straight line through P
along the zero-curvature direction d lies on the surface, and how far. The line
P + s·d is walked outwards in both directions in steps of h, all grid points at
once, and each sample Q(s) is projected onto the surface (Gauss–Newton from the
previous sample's (u, v), so each step costs a few vectorised evaluations). A step
is accepted while

* the foot point is inside the surface: the gap Q − S has no tangential part (at an
  edge the projection stops on the boundary and the gap turns sideways);
* the gap along the normal stays within ½·tol·s², the sag of an arc bent at the
  tolerance curvature: the line hugs the surface as a ruling must;
* the surface stays single-curved within tol at the foot point;
* the warp of the line stays within the warp tolerance: the angle between the
  surface normals at its two ends, 0 to π (the turn of the tangent plane along it,
  as every WarpAngles output measures it: 0 along a ruling of a developable, whose
  tangent plane is the same all along it; a normal that flips over counts as π).

Both sides grow together, one step each per round, so the warp budget is shared
fairly between them; where a side stops, its end is refined by bisection between the last
accepted and the first rejected sample, so a ruling ends on the surface's edge, not
up to a step short of it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Protocol

import numpy as np
import trimesh
from numpy.typing import NDArray

from torsal.nodes.geometry.array_types import BoolArray, FloatArray
from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.vec_ops import dot, position_rounding

if TYPE_CHECKING:
    from torsal.nodes.geometry.surface_base import Surface

#: Walking steps per side: a line can reach the surface's diameter from its grid point.
STEPS = 128
#: Gauss–Newton iterations per projection, at most (from the previous sample: quadratic
#: convergence, usually settled after two).
NEWTON = 4
#: Bisection halvings that place a ruling's end between its last two samples.
BISECTIONS = 32
#: Distances below this share of the surface's diameter are rounding.
ROUNDING = 1e-12


@dataclass(frozen=True)
class Foot:
    """Projections of k query points onto the surface."""

    points: FloatArray  #: (k, 3) foot points
    normals: FloatArray  #: (k, 3) unit normals there
    flatness: FloatArray  #: (k,) min(|k1|, |k2|) there
    state: FloatArray  #: (k, 2) where the foot is, to start the next projection from
    outside: BoolArray  #: (k,) the query lies beyond the surface's boundary


class Projector(Protocol):
    """Projects points onto one surface, starting from a known nearby foot. ``slack`` is
    the distance a line may stray from the surface for reasons of representation
    alone (a mesh's facets), on top of rounding."""

    slack: float

    def project(self, queries: FloatArray, state: FloatArray) -> Foot: ...


class SurfaceProjector:
    """Projection onto a parameterised surface by Gauss–Newton in (u, v).

    The parameters are clamped to [0, 1]² (wrapped across a closed direction), so a
    query beyond an edge lands on the edge: the query is ``outside`` when its foot is
    on an open edge and the gap exceeds rounding, or when the gap still has a
    tangential part (the iteration has not settled: treated like leaving the surface).
    """

    def __init__(self, surface: Surface, size: float) -> None:
        self.surface = surface
        self.eps = ROUNDING * size
        self.slack = 0.0

    def _limit(self, u: FloatArray, v: FloatArray) -> tuple[FloatArray, FloatArray]:
        s = self.surface
        u = np.mod(u, 1.0) if s.closed_u else np.clip(u, 0.0, 1.0)
        v = np.mod(v, 1.0) if s.closed_v else np.clip(v, 0.0, 1.0)
        return u, v

    def project(self, queries: FloatArray, state: FloatArray) -> Foot:
        u, v = self._limit(state[:, 0].copy(), state[:, 1].copy())
        for _ in range(NEWTON):
            s, su, sv = self.surface.derivatives(u, v, 1)
            r = queries - s
            e, f, g = dot(su, su), dot(su, sv), dot(sv, sv)
            bu, bv = dot(su, r), dot(sv, r)
            damp = 1e-14 * (e + g) + 1e-300  # Levenberg: keeps a pole or apex solvable
            e, g = e + damp, g + damp
            det = e * g - f * f
            du, dv = (g * bu - f * bv) / det, (e * bv - f * bu) / det
            u, v = self._limit(u + du, v + dv)
            if not np.max(np.abs(du) + np.abs(dv), initial=0.0) > 1e-15:
                break  # settled everywhere (at once on a plane or a cylinder)
        points = self.surface.point_at(u, v).reshape(-1, 3)
        c = self.surface.curvature(u, v)
        gap = queries - points
        sideways = np.linalg.norm(gap - dot(gap, c.normal)[:, None] * c.normal, axis=1)
        edge = np.zeros(len(u), dtype=bool)
        if not self.surface.closed_u:
            edge |= (u <= 0.0) | (u >= 1.0)
        if not self.surface.closed_v:
            edge |= (v <= 0.0) | (v >= 1.0)
        eps = self.eps + position_rounding(queries)  # far from the origin, gaps round to more
        outside = (edge & (np.linalg.norm(gap, axis=1) > eps)) | ~(sideways <= eps)
        return Foot(points, c.normal, np.minimum(np.abs(c.k1), np.abs(c.k2)),
                    np.column_stack([u, v]), outside)


class MeshProjector:
    """Projection onto a triangle mesh (exact closest points); normals and flatness are
    interpolated from the vertices' (so a line crossing from facet to facet sees the
    normal turn gradually, as on the surface the mesh stands for)."""

    def __init__(self, surface: MeshSurface, flatness: FloatArray, bending: FloatArray, size: float) -> None:
        """``flatness``: min(|k1|, |k2|) per vertex (signed or not); ``bending``:
        max(|k1|, |k2|) per vertex, which with the edge lengths sets ``slack`` to the
        largest sag of a facet below the smooth surface it stands for (l²·|k|/8)."""
        self.surface = surface
        mesh = surface.mesh
        self.flatness = flatness
        edges = np.asarray(mesh.edges_unique)
        lengths = np.asarray(mesh.edges_unique_length)
        bend = np.maximum(np.abs(bending[edges[:, 0]]), np.abs(bending[edges[:, 1]]))
        self.slack = float(np.max(lengths**2 * np.nan_to_num(bend) / 8.0, initial=0.0))
        self.eps = ROUNDING * size
        self.normals = np.asarray(mesh.vertex_normals, dtype=float)
        # which edges of each face are boundary edges (used by that face only)
        # mesh.edges_sorted lists each face's edges (0,1), (1,2), (2,0) in order, sorted
        edges = np.asarray(mesh.edges_sorted)
        boundary = np.zeros(len(edges), dtype=bool)
        boundary[trimesh.grouping.group_rows(edges, require_count=1)] = True
        self.boundary = boundary.reshape(-1, 3)

    def project(self, queries: FloatArray, state: FloatArray) -> Foot:
        found = self.surface.closest_point(queries)
        mesh = self.surface.mesh
        corners = np.asarray(mesh.vertices, dtype=float)[np.asarray(mesh.faces)[found.faces]]
        bary = trimesh.triangles.points_to_barycentric(corners, found.points)
        corner_ids = np.asarray(mesh.faces)[found.faces]
        flat = np.einsum("kj,kj->k", bary, self.flatness[corner_ids])
        normals = np.einsum("kj,kjd->kd", bary, self.normals[corner_ids])
        normals /= np.linalg.norm(normals, axis=1, keepdims=True)
        # A query beyond a boundary edge has its foot on that edge and its gap pointing out
        # across it, within the face's plane: edge (0,1) is opposite corner 2, (1,2)
        # opposite 0, (2,0) opposite 1.
        gap = queries - found.points
        outside = np.zeros(len(queries), dtype=bool)
        for edge, (a, b, c) in enumerate(((0, 1, 2), (1, 2, 0), (2, 0, 1))):
            rows = np.flatnonzero((np.abs(bary[:, c]) <= 1e-9) & self.boundary[found.faces, edge])
            if rows.size == 0:
                continue
            p, q, r = corners[rows, a], corners[rows, b], corners[rows, c]
            along = (q - p) / np.linalg.norm(q - p, axis=1, keepdims=True)
            out = (p - r) - dot(p - r, along)[:, None] * along
            out /= np.linalg.norm(out, axis=1, keepdims=True)
            outside[rows] |= dot(gap[rows], out) > self.eps
        return Foot(found.points, normals, np.abs(flat), state, outside)


@dataclass(frozen=True)
class Traced:
    """Rulings found from m origins: ends ``(m, 3)``, the warp of each (the angle between
    the lines of its end normals, rad) and the lengths of the two halves from the origin."""

    starts: FloatArray
    ends: FloatArray
    warp: FloatArray
    back: FloatArray
    ahead: FloatArray

    @property
    def lengths(self) -> FloatArray:
        return self.back + self.ahead


def trace_rulings(
    projector: Projector,
    origins: FloatArray,
    directions: FloatArray,
    normals: FloatArray,
    states: FloatArray,
    curvature_tolerance: float,
    warp_tolerance: float,
    size: float,
    steps: int = STEPS,
) -> Traced:
    """Walk the lines ``origins + s·directions`` (unit directions) over the surface.

    ``normals`` are the unit normals at the origins and ``states`` where the origins
    are for the projector ((u, v) for a parameterised surface). ``size`` is the
    surface's diameter: steps are ``size / steps`` long. See the module docstring
    for when a step is accepted.
    """
    m = len(origins)
    d = directions / np.linalg.norm(directions, axis=1, keepdims=True)
    h = size / steps
    eps = ROUNDING * size + projector.slack + position_rounding(origins)
    reach = np.zeros((2, m))  # accepted distance on each side
    alive = np.ones((2, m), dtype=bool)
    state = np.stack([states, states]).astype(float)
    previous = state.copy()
    end_normals = np.stack([normals, normals]).astype(float)  # at each side's current end
    warp = np.zeros(m)
    reject = np.full((2, m), np.nan)  # first rejected distance, for the bisection
    sides = (1.0, -1.0)

    def check(
        rows: np.ndarray, side: int, s: FloatArray, guess: FloatArray
    ) -> tuple[BoolArray, Foot, FloatArray]:
        q = origins[rows] + (sides[side] * s)[:, None] * d[rows]
        foot = projector.project(q, guess)
        gap = q - foot.points
        along = dot(gap, foot.normals)
        inside = ~foot.outside
        hugs = np.abs(along) <= 0.5 * curvature_tolerance * s * s + eps
        flat = foot.flatness <= curvature_tolerance
        other = end_normals[1 - side, rows]
        turn = np.arctan2(np.linalg.norm(np.cross(other, foot.normals), axis=1),
                          dot(other, foot.normals))
        ok = inside & hugs & flat & (turn <= warp_tolerance)
        return ok, foot, turn

    for step in range(1, steps + 1):
        for side in (0, 1):
            rows = np.flatnonzero(alive[side])
            if rows.size == 0:
                continue
            s = np.full(rows.size, step * h)
            guess = 2.0 * state[side, rows] - previous[side, rows]  # extrapolate the foot
            ok, foot, turn = check(rows, side, s, guess)
            good, bad = rows[ok], rows[~ok]
            previous[side, good] = state[side, good]
            state[side, good] = foot.state[ok]
            reach[side, good] = step * h
            end_normals[side, good] = foot.normals[ok]
            warp[good] = turn[ok]
            alive[side, bad] = False
            reject[side, bad] = step * h
        if not alive.any():
            break

    # place each stopped end between its last accepted and first rejected sample
    for side in (0, 1):
        rows = np.flatnonzero(np.isfinite(reject[side]))
        if rows.size == 0:
            continue
        lo, hi = reach[side, rows].copy(), reject[side, rows].copy()
        start = state[side, rows]
        normal, turned = end_normals[side, rows].copy(), warp[rows].copy()
        for _ in range(BISECTIONS):
            mid = 0.5 * (lo + hi)
            ok, foot, turn = check(rows, side, mid, start)
            lo = np.where(ok, mid, lo)
            hi = np.where(ok, hi, mid)
            normal[ok], turned[ok] = foot.normals[ok], turn[ok]
        reach[side, rows] = lo
        end_normals[side, rows], warp[rows] = normal, turned

    ahead, back = reach[0], reach[1]
    starts = origins - back[:, None] * d
    ends = origins + ahead[:, None] * d
    return Traced(starts, ends, warp, back, ahead)


def _segment_distance(points: FloatArray, starts: FloatArray, ends: FloatArray) -> FloatArray:
    """Distance of each point ``(k, 3)`` to each segment ``(m, 3)``: ``(k, m)``."""
    axis = ends - starts
    length2 = np.maximum(np.einsum("ij,ij->i", axis, axis), 1e-300)
    rel = points[:, None, :] - starts[None, :, :]
    t = np.clip(np.einsum("kmj,mj->km", rel, axis) / length2, 0.0, 1.0)
    return np.linalg.norm(rel - t[..., None] * axis[None], axis=2)


def on_rulings(
    origins: FloatArray, directions: FloatArray, starts: FloatArray, ends: FloatArray, size: float
) -> NDArray[np.bool_]:
    """Which origins lie on one of the given rulings (to 1e-6 of ``size``) with their
    direction along it (to 1e-3 rad): walking from them would find that ruling again."""
    found = np.zeros(len(origins), dtype=bool)
    if len(starts) == 0 or len(origins) == 0:
        return found
    axis = ends - starts
    unit_axis = axis / np.maximum(np.linalg.norm(axis, axis=1, keepdims=True), 1e-300)
    unit = directions / np.linalg.norm(directions, axis=1, keepdims=True)
    chunk = max(1, 4_000_000 // (3 * len(starts)))
    for lo in range(0, len(origins), chunk):
        rows = slice(lo, lo + chunk)
        near = _segment_distance(origins[rows], starts, ends) <= 1e-6 * size
        sine = np.linalg.norm(np.cross(unit[rows][:, None, :], unit_axis[None]), axis=2)
        found[rows] = np.any(near & (sine <= 1e-3), axis=1)
    return found


def distinct_rulings(starts: FloatArray, ends: FloatArray, size: float, shortest: float) -> NDArray[np.int64]:
    """Indices of the rulings worth drawing, longest first: longer than ``shortest``
    and not lying along a longer one already kept (both ends within 1e-4 of ``size``
    of it: grid points along one ruling all find it, some only part of it)."""
    lengths = np.linalg.norm(ends - starts, axis=1)
    # equal lengths (to 1e-6 of the size: a symmetric surface's) keep the grid's order,
    # not the order rounding gives them, which changes when the surface is moved
    order = np.argsort(-np.round(lengths / (1e-6 * size)), kind="stable")
    order = order[lengths[order] > shortest]
    kept: list[int] = []
    tol = 1e-4 * size
    for i in order:
        if kept:
            ends_i = np.stack([starts[i], ends[i]])
            distance = _segment_distance(ends_i, starts[kept], ends[kept])
            if np.any(np.all(distance <= tol, axis=0)):
                continue
        kept.append(int(i))
    return np.asarray(kept, dtype=np.int64)
