"""analysis.SurfaceAnalysis: curvature, single-curved regions and valid rulings of a surface."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, fields
from typing import Any

import numpy as np
import trimesh
from numpy.typing import NDArray

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import GENERIC, INTEGER, NUMBER, POINT
from torsal.nodes.analysis.colours import colour_table, colours
from torsal.nodes.analysis.single_curved import area_fraction, signed_flatness
from torsal.nodes.common.checks import angle, finite, whole
from torsal.nodes.common.convert import points
from torsal.nodes.common.geometry_checks import surface_or_mesh
from torsal.nodes.common.values import LINE, MESH
from torsal.nodes.geometry.array_types import FloatArray
from torsal.nodes.geometry.curvature import DEGENERATE_RATIO, SurfaceCurvature
from torsal.nodes.geometry.curves.line import Line
from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.ruling_trace import (
    MeshProjector,
    Projector,
    SurfaceProjector,
    distinct_rulings,
    on_rulings,
    trace_rulings,
)
from torsal.nodes.geometry.surface_base import Surface, uv_grid
from torsal.nodes.limits import MAX_DENSITY

#: Vertices per direction of the coloured mesh, at least (finer when the grid is finer).
MESH_GRID = 65
#: Rulings shorter than this share of the surface's size are not drawn.
SHORTEST = 1e-3


@dataclass(frozen=True)
class Sampled:
    """Curvature at the analysis points and the coloured mesh of one surface."""

    points: FloatArray  #: (n, 3) analysis points
    curvature: SurfaceCurvature  #: at the analysis points
    states: FloatArray  #: (n, 2) where the points are, for the ruling projector
    mesh: trimesh.Trimesh  #: the mesh to colour
    flatness: FloatArray  #: sign(K)·min(|k1|, |k2|) at the mesh's vertices
    projector: Projector
    size: float  #: the surface's diameter
    regular: NDArray[np.bool_]  #: (n,) not at a pole or apex (where no ruling is traced)
    seeds: NDArray[np.bool_]  #: (n,) traced first: one grid point per ruling of a ruled surface


def _grid(n: int, closed: bool) -> FloatArray:
    """n parameters over [0, 1]: both edges included, or for a closed direction the
    seam once (n evenly spaced around)."""
    return np.arange(n) / n if closed else np.linspace(0.0, 1.0, n)


def _flatness(c: SurfaceCurvature) -> FloatArray:
    return np.minimum(np.abs(c.k1), np.abs(c.k2))


def _signed(c: SurfaceCurvature) -> FloatArray:
    return signed_flatness(c.k1, c.k2)


#: Grid points whose curvature is evaluated in one call (then cancellation is checked).
CURVATURE_CHUNK = 8192


def _curvature(
    s: Surface, u: FloatArray, v: FloatArray, check: Callable[[], None] | None
) -> SurfaceCurvature:
    """``s.curvature(u, v)`` in chunks, calling ``check`` between them (it raises to stop)."""
    if len(u) <= CURVATURE_CHUNK:
        if check is not None:
            check()
        return s.curvature(u, v)
    parts = []
    for lo in range(0, len(u), CURVATURE_CHUNK):
        if check is not None:
            check()
        parts.append(s.curvature(u[lo:lo + CURVATURE_CHUNK], v[lo:lo + CURVATURE_CHUNK]))
    return SurfaceCurvature(*(
        np.concatenate([getattr(part, f.name) for part in parts]) for f in fields(SurfaceCurvature)
    ))


def sample_surface(
    s: Surface, nu: int, nv: int, check: Callable[[], None] | None = None
) -> Sampled:
    """Exact curvature on the nu × nv grid and on a finer mesh grid (u-major); ``check``
    is called between chunks of the grid (a node's ``check_cancelled``)."""
    uu, vv = np.meshgrid(_grid(nu, s.closed_u), _grid(nv, s.closed_v), indexing="ij")
    u, v = uu.ravel(), vv.ravel()
    mu, mv = max(MESH_GRID, nu), max(MESH_GRID, nv)
    mesh = s.to_mesh(mu, mv)
    gu, gv = uv_grid(mu, mv)
    size = float(np.linalg.norm(np.ptp(np.asarray(mesh.vertices), axis=0)))
    p, su, sv = s.derivatives(u, v, 1)
    span = np.linalg.norm(np.cross(su, sv), axis=1)
    # On a ruled surface the grid points along one ruling all find it: trace one row
    # across the rulings first, and from the others only what that did not find.
    seeds = np.zeros(len(u), dtype=bool)
    if s.ruling_direction == "v":
        seeds = (np.arange(len(u)) % nv) == nv // 2
    elif s.ruling_direction == "u":
        seeds = (np.arange(len(u)) // nv) == nu // 2
    return Sampled(
        points=p,
        curvature=_curvature(s, u, v, check),
        states=np.column_stack([u, v]),
        mesh=mesh,
        flatness=_signed(_curvature(s, gu, gv, check)),
        projector=SurfaceProjector(s, size),
        size=size,
        regular=span > DEGENERATE_RATIO * (np.einsum("ij,ij->i", su, su) + np.einsum("ij,ij->i", sv, sv)),
        seeds=seeds,
    )


def spread_vertices(vertices: FloatArray, area: float, count_: int) -> NDArray[np.int64]:
    """About ``count_`` vertices spread evenly over a mesh of the given area: the first
    vertex in each cell of a cubic grid whose cells hold about area / count_ each."""
    if len(vertices) <= count_:
        return np.arange(len(vertices))
    cell = float(np.sqrt(area / count_)) if area > 0 else 1.0
    keys = np.floor((vertices - vertices.min(axis=0)) / cell).astype(np.int64)
    _, first = np.unique(keys, axis=0, return_index=True)
    return np.sort(first)


def sample_mesh(m: MeshSurface, nu: int, nv: int) -> Sampled:
    """Discrete curvature at about nu·nv vertices; the mesh itself is coloured."""
    c = m.curvature()
    flat = _signed(c)
    vertices = m.points
    pick = spread_vertices(vertices, m.area(), nu * nv)
    picked = SurfaceCurvature(*(np.asarray(getattr(c, f))[pick] for f in (
        "k1", "k2", "direction1", "direction2", "gaussian", "mean", "normal")))
    size = float(np.linalg.norm(np.ptp(vertices, axis=0)))
    return Sampled(
        points=vertices[pick],
        curvature=picked,
        states=np.zeros((len(pick), 2)),
        mesh=m.to_mesh(),
        flatness=flat,
        projector=MeshProjector(m, flat, np.maximum(np.abs(c.k1), np.abs(c.k2)), size),
        size=size,
        regular=np.ones(len(pick), dtype=bool),
        seeds=np.zeros(len(pick), dtype=bool),
    )


def curvature_lines(p: FloatArray, c: SurfaceCurvature, scale: float, cap: float) -> list[Line]:
    """Two lines per point, centred on it: along direction 1, |k1|·scale long, then along
    direction 2, |k2|·scale long (each capped at ``cap``)."""
    lines: list[Line] = []
    halves = [0.5 * np.minimum(np.nan_to_num(np.abs(k) * scale), cap) for k in (c.k1, c.k2)]
    dirs = [np.nan_to_num(c.direction1), np.nan_to_num(c.direction2)]
    ends = [(p - h[:, None] * d, p + h[:, None] * d) for h, d in zip(halves, dirs, strict=True)]
    for i in range(len(p)):
        for a, b in ends:
            lines.append(Line(a[i], b[i]))
    return lines


def coloured(mesh: trimesh.Trimesh, flatness: FloatArray, tolerance: float) -> trimesh.Trimesh:
    """``mesh`` coloured per vertex by min(|k1|, |k2|) against the tolerance; the value
    also goes to ``vertex_attributes`` and, with the colour bar's range and table, to
    ``metadata`` for the viewport."""
    mesh.visual = trimesh.visual.ColorVisuals(mesh, vertex_colors=colours(flatness / tolerance))
    mesh.vertex_attributes["min_abs_curvature"] = flatness
    mesh.metadata.update({
        "scalars": flatness,
        "scalar_name": "min(|k1|, |k2|), 1/m",
        "clim": (0.0, 2.0 * tolerance),
        "cmap": colour_table(),
        "curvature_tolerance": tolerance,
    })
    return mesh


#: What one analysis costs besides its grid, in grid samples (0.15 s at 10 x 10, 0.24 s at
#: 50 x 50, 3.5 s at 200 x 200 measured on a loaded two-core machine).
_CALL_SAMPLES = 2_500


class SurfaceAnalysis(Node):
    """Where is a surface single-curved, and where could it be bent from a flat sheet?

    A sheet bends in one direction at a time: at each point of a developable surface
    one principal curvature is 0 and the surface contains a straight line, a ruling,
    along that direction. This node measures the principal curvatures k1 ≥ k2 on a
    UDensity × VDensity grid (from the surface's exact derivatives; for a mesh, from
    a quadric fitted to each vertex's neighbours) and shows:

    * CurvatureLines — at each grid point a cross of two lines along the principal
      directions, |k|·Scale long (the k1 line, then the k2 line, per point; capped
      at the surface's size, which only matters next to an apex or pole);
    * ColouredMesh — bright pink where min(|k1|, |k2|) is below CurvatureTolerance
      (single-curved: locally developable), dark purple above (double-curved), with
      a colour bar from 0 to twice the tolerance;
    * ValidRulings — from each grid point that is single-curved, the straight line
      along its flat direction, as far as it stays on the surface (within the sag
      of an arc bent at the tolerance curvature), single-curved, and twisting its
      normal by at most WarpTolerance radians along its length; a ruling found from
      several grid points is drawn once;
    * DevelopableFraction — the share of the surface's area that is single-curved.

    A mesh (or mesh surface) has no grid: about UDensity·VDensity of its vertices,
    spread evenly over it, are the analysis points, and its rulings follow the
    discrete estimator's flat directions (within about 0.1° on a fine mesh).

    Curvature is in 1/model unit (1/m when you model in metres): 0.01 /m accepts
    anything bent less than a 100 m radius as flat. A cylinder is 100 % pink with a
    ruling along every generator; a hyperbolic paraboloid or a sphere is purple
    everywhere. If nothing is pink, raise CurvatureTolerance; if rulings stop short,
    raise WarpTolerance (e.g. 0.1 rad/m times the ruling length, for a sheet with a
    warp factor of 0.1 rad/m).
    """

    type_id = "analysis.SurfaceAnalysis"
    nickname, aliases = "SrfA", ("developability", "single curved", "gaussian map")
    inputs = (
        In("Surface", GENERIC, "S", "The surface to analyse: any surface, a mesh or a mesh surface."),
        In("UDensity", INTEGER, "U", "Grid points across u (2 or more; a closed direction is not "
           "sampled twice at its seam).", default=10, min=2, max=MAX_DENSITY),
        In("VDensity", INTEGER, "V", "Grid points across v (2 or more).", default=10,
           min=2, max=MAX_DENSITY),
        In("Scale", NUMBER, "Sc", "Curvature line length per unit of curvature: |k|·Scale.",
           default=1.0),
        In("CurvatureTolerance", NUMBER, "Kt", "Below this min(|k1|, |k2|), in 1/m, the surface counts "
           "as single-curved (0.01 /m: radii above 100 m are flat).", default=0.01),
        In("WarpTolerance", NUMBER, "Wt", "How far (rad) the tangent plane may turn along a ruling for "
           "it to be valid: the angle between the surface normals at its two ends, as WarpAngles "
           "measure it.", default=0.01),
    )
    outputs = (
        Out("CurvatureLines", LINE, "L", "Per grid point the k1 line then the k2 line, centred on it, "
            "|k|·Scale long.", access=LIST),
        Out("ColouredMesh", MESH, "M", "The surface coloured by min(|k1|, |k2|): pink within the "
            "tolerance, purple above."),
        Out("ValidRulings", LINE, "R", "Straight lines on the surface where it is single-curved and "
            "twists within WarpTolerance.", access=LIST),
        Out("Gaussian", NUMBER, "K", "Gaussian curvature k1·k2 per grid point (0 on a developable).",
            access=LIST),
        Out("Mean", NUMBER, "H", "Mean curvature (k1 + k2)/2 per grid point.", access=LIST),
        Out("K1", NUMBER, "k1", "The larger principal curvature per grid point.", access=LIST),
        Out("K2", NUMBER, "k2", "The smaller principal curvature per grid point.", access=LIST),
        Out("DevelopableFraction", NUMBER, "F", "Share of the area (0 to 1) that is single-curved "
            "within CurvatureTolerance."),
        Out("Points", POINT, "P", "The grid points, u-major (point i·VDensity + j is (u_i, v_j)).",
            access=LIST, preview=False),
    )

    # a list of densities (or of surfaces) multiplies the capped work of one analysis: one
    # solve does at most two analyses at the cap's grid, or ~100 at 10 x 10 (each call also
    # costs about what 2,500 samples do)
    max_work = 2 * (MAX_DENSITY**2 + _CALL_SAMPLES)
    work_unit = "grid samples"

    def call_work(self, value: Any, u_density: Any, v_density: Any, *rest: Any) -> int:
        def counted(density: Any) -> int:  # a density solve refuses counts as 1
            return density if isinstance(density, int) and 2 <= density <= MAX_DENSITY else 1

        return counted(u_density) * counted(v_density) + _CALL_SAMPLES

    def solve(self, value: Any, u_density: Any, v_density: Any, scale: Any, curvature_tolerance: Any,
              warp_tolerance: Any) -> tuple[Any, ...]:
        target = surface_or_mesh("Surface", value, "surface to analyse")
        nu, nv = whole("UDensity", u_density), whole("VDensity", v_density)  # bounded on the ports
        factor = finite("Scale", scale)
        if factor < 0:
            raise NodeWarning(f"Scale must be 0 or more, not {factor:g}: it sets the lines' length per "
                              "unit of curvature")
        tol = finite("CurvatureTolerance", curvature_tolerance)
        if tol <= 0:
            raise NodeWarning(f"CurvatureTolerance must be positive, in 1/m (e.g. 0.01), not {tol:g}")
        warp = angle("WarpTolerance", warp_tolerance, "0.01")

        if isinstance(target, MeshSurface):
            data = sample_mesh(target, nu, nv)
        else:
            data = sample_surface(target, nu, nv, self.check_cancelled)
        self.progress(0.4)
        c = data.curvature
        if not np.all(np.isfinite(c.k1) & np.isfinite(c.k2)):
            bad = int(np.count_nonzero(~(np.isfinite(c.k1) & np.isfinite(c.k2))))
            self.warn(f"{bad} grid points have no curvature (the surface is degenerate there); "
                      "their values are NaN")

        mesh = coloured(data.mesh, np.abs(data.flatness), tol)
        fraction = area_fraction(data.flatness, mesh.faces, mesh.area_faces, tol)

        self.progress(0.5)
        rulings = self._rulings(data, tol, warp)
        self.progress(1.0)
        self.remark(f"{100 * fraction:.3g} % of the area is single-curved within {tol:g} /m; "
                    f"{len(rulings)} valid rulings")
        return (
            curvature_lines(data.points, c, factor, data.size),
            mesh,
            rulings,
            c.gaussian.tolist(),
            c.mean.tolist(),
            c.k1.tolist(),
            c.k2.tolist(),
            fraction,
            points(data.points),
        )

    def _rulings(self, data: Sampled, tol: float, warp: float) -> list[Line]:
        c = data.curvature
        flat = _flatness(c)
        direction = np.where((np.abs(c.k1) <= np.abs(c.k2))[:, None], c.direction1, c.direction2)
        usable = (flat <= tol) & data.regular & np.isfinite(direction).all(axis=1) & np.isfinite(
            c.normal).all(axis=1)
        if not usable.any() or data.size == 0:
            return []
        starts, ends = np.empty((0, 3)), np.empty((0, 3))
        for phase in (usable & data.seeds, usable & ~data.seeds):
            rows = np.flatnonzero(phase)
            rows = rows[~on_rulings(data.points[rows], direction[rows], starts, ends, data.size)]
            if rows.size == 0:
                continue
            origins = data.points[rows]
            # the normal at each origin as the projector sees it (interpolated, on a mesh)
            foot = data.projector.project(origins, data.states[rows])
            traced = trace_rulings(data.projector, origins, direction[rows], foot.normals, foot.state,
                                   tol, warp, data.size)
            starts, ends = np.vstack([starts, traced.starts]), np.vstack([ends, traced.ends])
            self.check_cancelled()
            self.progress(0.75)
        keep = distinct_rulings(starts, ends, data.size, SHORTEST * data.size)
        return [Line(starts[i], ends[i]) for i in keep]
