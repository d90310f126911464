"""A NURBS surface fitted to a triangle mesh that is a height field over a plane.

Designs often arrive as meshes (OBJ, STL, PLY from a modeller or a scan). Nodes that need
(u, v) parameters — Rationalise, isocurves — cannot work on a mesh; :func:`fit_mesh` gives
them a bicubic NURBS surface within a set distance of it:

1. the plane: normal to the mesh's vector area (the sum of its triangles' area vectors,
   which depends on its outline only: the plane onto which the outline encloses the
   most area — a roof drawn over a plan gets its plan, however its heights tilt), with
   its axes along the smallest rectangle round the outline there (shapely's
   ``minimum_rotated_rectangle``); the mesh must be a height field over it — every
   triangle facing the same side (a roof, a canopy, a scan of a shell), else it is refused;
2. the heights fitted by least squares with FITPACK's ``LSQBivariateSpline`` on a grid of
   interior knots refined (doubled) until every vertex, every triangle's centroid and the
   midpoint of every edge lie within ``tolerance`` of the surface, measured along the
   plane's normal (an upper bound of the true distance);
3. the spline written as a NURBS surface: x and y run linearly with u and v (their control
   points are the knots' Greville abscissae, which reproduce a linear function exactly),
   z has the fitted coefficients.

The surface spans the outline's rectangle in the plane. Where the outline does not reach
that rectangle's edges to within ``tolerance`` (a curved or slanted edge, a hole), the
surface is trimmed by the outline (a :class:`~torsal.nodes.geometry.trimmed_surface.
TrimmedSurface`, the mesh's boundary loops in (u, v)), so that nodes working inside the
trim (Rationalise) stay on the mesh and cover it to its edges; untrimmed, the surface
reaches at most ``tolerance`` past the outline. A mesh whose footprint leaves much of its
rectangle empty is refused (the fit there would be a guess).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
import trimesh
from scipy.interpolate import LSQBivariateSpline

from .array_types import FloatArray
from .nurbs_surface import NurbsSurface
from .surface_base import Surface
from .trimmed_surface import TrimmedSurface

#: The share of the footprint's bounding rectangle the mesh must cover.
COVERAGE = 0.95

#: The finest knot grid tried (interior knots per direction).
LARGEST_GRID = 64


@dataclass(frozen=True)
class MeshFit:
    """A surface fitted to a mesh and how far the mesh is from it (along the plane's normal)."""

    surface: Surface  #: the NURBS surface, trimmed by the mesh's outline where it is not the rectangle
    deviation: float
    knots: int  #: interior knots per direction
    overhang: float = 0.0  #: how far the untrimmed rectangle reaches past the outline, in the plane


def fit_mesh(mesh: trimesh.Trimesh, tolerance: float) -> MeshFit:
    """The bicubic NURBS surface within ``tolerance`` of ``mesh`` (see the module), or a
    ValueError that says why the mesh cannot be fitted."""
    vertices = np.asarray(mesh.vertices, dtype=float)
    faces = np.asarray(mesh.faces, dtype=np.int64)
    if len(faces) == 0 or not np.isfinite(vertices).all():
        raise ValueError("the mesh has no faces, or a coordinate that is not a finite number")
    centre = vertices.mean(axis=0)
    _, spread, axes = np.linalg.svd(vertices - centre, full_matrices=False)
    if not spread[1] > 1e-9 * spread[0]:
        raise ValueError("the mesh is a line or a point: it spans no plane")
    facing = _facing(vertices - centre, faces, axes[2])
    if facing is None:
        raise ValueError("the mesh folds over itself seen from its mean plane (a wall, an overhang or a "
                         "closed shape): only a mesh that is one height field over a plane can be fitted")
    frame = _plan_frame(vertices - centre, faces, axes)  # rows: along, across, normal
    local = (vertices - centre) @ frame.T
    facing = _facing(local, faces, np.array([0.0, 0.0, 1.0]))
    assert facing is not None  # the plan is the mean plane unless the mesh is a height field over it
    x, y, z = local.T
    lo, hi = local.min(axis=0), local.max(axis=0)
    footprint = float(np.abs(facing).sum()) / 2.0
    rectangle = float((hi[0] - lo[0]) * (hi[1] - lo[1]))
    if footprint < COVERAGE * rectangle:
        raise ValueError(f"the mesh covers {footprint / rectangle:.0%} of its footprint's bounding "
                         f"rectangle (at least {COVERAGE:.0%} is needed): trim it to a rectangle first")
    outline = _outline(local, faces)
    edges = np.asarray(mesh.edges_unique, dtype=np.int64)
    probes = np.vstack([local, local[faces].mean(axis=1), local[edges].mean(axis=1)])
    count = 2
    best: tuple[LSQBivariateSpline, float, int] | None = None
    while True:
        tx = np.linspace(lo[0], hi[0], count + 2)[1:-1]
        ty = np.linspace(lo[1], hi[1], count + 2)[1:-1]
        try:
            spline = LSQBivariateSpline(x, y, z, tx, ty, bbox=[lo[0], hi[0], lo[1], hi[1]], kx=3, ky=3)
        except ValueError:  # too few points for this many knots: the previous grid stands
            break
        off = float(np.abs(spline.ev(probes[:, 0], probes[:, 1]) - probes[:, 2]).max())
        if best is None or off < best[1]:  # a finer grid with cells short of data can fit worse
            best = (spline, off, count)
        if off <= tolerance or count >= LARGEST_GRID:
            break
        count *= 2
    if best is None:
        raise ValueError("the mesh has too few vertices for a bicubic surface (16 at least)")
    spline, deviation, count = best
    full_u, full_v = (np.asarray(k, dtype=float) for k in spline.get_knots())  # full, ends ×4
    greville_u = np.array([full_u[i + 1:i + 4].mean() for i in range(len(full_u) - 4)])
    greville_v = np.array([full_v[j + 1:j + 4].mean() for j in range(len(full_v) - 4)])
    heights = np.asarray(spline.get_coeffs()).reshape(len(greville_u), len(greville_v))
    gu, gv = np.meshgrid(greville_u, greville_v, indexing="ij")
    net = np.stack([gu, gv, heights], axis=-1) @ frame + centre
    surface = NurbsSurface(net, 3, 3, full_u, full_v)
    box = shapely.box(lo[0], lo[1], hi[0], hi[1])
    overhang = float(shapely.hausdorff_distance(box, outline, densify=0.01))
    if overhang <= tolerance:
        return MeshFit(surface, deviation, count, overhang)
    size = hi[:2] - lo[:2]
    to_uv = (lambda ring: (np.asarray(ring.coords)[:, :2] - lo[:2]) / size)  # noqa: E731
    trimmed = TrimmedSurface(surface, to_uv(outline.exterior), [to_uv(r) for r in outline.interiors])
    return MeshFit(trimmed, deviation, count, overhang)


def _facing(points: FloatArray, faces: np.ndarray, normal: FloatArray) -> FloatArray | None:
    """Twice each triangle's area seen along ``normal``, all positive (the side most of them
    face), or None where some triangle faces the other way or is seen edge-on (a fold)."""
    cross = np.cross(points[faces[:, 1]] - points[faces[:, 0]], points[faces[:, 2]] - points[faces[:, 0]])
    facing = cross @ normal
    if np.count_nonzero(facing < 0) > np.count_nonzero(facing > 0):
        facing = -facing
    return facing if np.all(facing > 1e-12 * np.linalg.norm(cross, axis=1).max()) else None


def _plan_frame(points: FloatArray, faces: np.ndarray, axes: FloatArray) -> FloatArray:
    """Rows: the plan's two axes and its normal (see the module, step 1); the mean plane's
    normal (``axes[2]``, the vertices' direction of least spread) where the mesh is not a
    height field over its vector area, or has none (a closed mesh)."""
    corner = points[faces[:, 0]]
    area = 0.5 * np.cross(points[faces[:, 1]] - corner, points[faces[:, 2]] - corner)
    normal = area.sum(axis=0)
    length = float(np.linalg.norm(normal))
    some = length > 1e-6 * np.linalg.norm(area, axis=1).sum()  # a closed mesh's vector area is 0
    over = some and _facing(points, faces, normal / length) is not None
    normal = normal / length if over else axes[2]
    seed = np.eye(3)[int(np.argmin(np.abs(normal)))]
    e1 = np.cross(normal, seed)
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(normal, e1)
    flat = points @ np.column_stack([e1, e2])
    corners = np.asarray(shapely.minimum_rotated_rectangle(shapely.multipoints(flat)).exterior.coords)
    sides = np.diff(corners[:3], axis=0)
    longer = sides[int(np.argmax(np.linalg.norm(sides, axis=1)))]
    along = longer[0] * e1 + longer[1] * e2
    along /= np.linalg.norm(along)
    return np.array([along, np.cross(normal, along), normal])


def _outline(local: FloatArray, faces: np.ndarray) -> shapely.Polygon:
    """The mesh's footprint in the plane (``local``: its vertices in the plan's frame): the
    polygon its boundary edges bound (edges of one triangle only, vertices at the same place
    welded first, as an STL's are not)."""
    _, weld = np.unique(local, axis=0, return_inverse=True)
    weld = weld.reshape(-1)
    edges = np.sort(weld[faces][:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    once = trimesh.grouping.group_rows(edges, require_count=1)
    ends = np.zeros((len(local), 2))
    ends[weld] = local[:, :2]
    area = shapely.build_area(shapely.multilinestrings(ends[edges[once]]))
    parts = [p for p in shapely.get_parts(area) if isinstance(p, shapely.Polygon)]
    merged = shapely.union_all(parts) if parts else shapely.Polygon()
    if not isinstance(merged, shapely.Polygon) or merged.is_empty:
        raise ValueError("the mesh's boundary edges do not bound one piece (the mesh is in several parts, "
                         "or has a gap): join it into one first")
    return merged
