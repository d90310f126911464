"""Free-form surfaces: lofts through curves, ruled surfaces between two curves, NURBS
surfaces from point grids, and surfaces from X, Y, Z expressions in u and v."""

from __future__ import annotations

from typing import Any

import numpy as np

from torsal.engine.datatree import DataTree, Path, format_path
from torsal.engine.node import LIST, TREE, In, Node, NodeWarning, Out
from torsal.engine.types import BOOLEAN, DOMAIN, INTEGER, POINT, TEXT
from torsal.engine.values import Domain
from torsal.nodes.common.checks import degree, given, interval, point_list, whole
from torsal.nodes.common.convert import kernel_errors
from torsal.nodes.common.formulas import formula
from torsal.nodes.common.values import CURVE, SURFACE
from torsal.nodes.expressions import ExpressionError
from torsal.nodes.geometry import nurbs_surface, parametric_surface, ruled
from torsal.nodes.geometry.curvature import DEGENERATE_RATIO
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.surface_base import Surface, uv_grid

SAMPLES = 513
"""Points per curve where Loft samples its curves: circles are reproduced to ~1e-8 of their radius
(the kernel's default, 129, leaves ~1e-6 where a NURBS circle's quarter arcs meet)."""


def _same(a: np.ndarray, b: np.ndarray) -> bool:
    """Whether two sampled curves coincide, to 1e-12 of their size."""
    size = float(np.ptp(np.vstack([a, b]), axis=0).max())
    return bool(np.abs(a - b).max() <= 1e-12 * max(size, 1e-300))


def _curve_list(name: str, values: list[Any]) -> list[Curve]:
    if any(v is None for v in values):
        raise NodeWarning(f"{name} contains empty (null) items: remove them or fix what made them")
    return list(values)


class Loft(Node):
    """A smooth surface through several curves, in order: the skin of a ship's frames.

    v runs across the curves (the first curve is the edge v = 0, the last v = 1) and
    u runs along them, following each curve's own direction, so curves that run
    opposite ways give a twisted loft: Flip one. The surface passes through every
    curve (exactly at 513 points along each, and to ~1e-8 of a circle's radius
    between them); across the curves it is cubic (2 curves give a ruled surface, 3 a
    quadratic one).
    Closed curves (circles) give a surface closed smoothly around its seam: circles
    of equal radius at several heights loft to a cylinder.
    """

    type_id = "surfaces.Loft"
    nickname, aliases = "Loft", ("skin", "Loft Curves")
    inputs = (In("Curves", CURVE, "C", "The section curves, in order (at least 2).", access=LIST),)
    outputs = (Out("Surface", SURFACE, "S", "The lofted NURBS surface."),)

    def solve(self, curves: list[Any]) -> Surface:
        sections = _curve_list("Curves", curves)
        if len(sections) < 2:
            raise NodeWarning(f"A loft needs at least 2 curves; got {len(sections)}")
        t = np.linspace(0.0, 1.0, SAMPLES)
        samples = [np.atleast_2d(c.point_at(t)) for c in sections]
        for i in range(len(samples) - 1):
            if _same(samples[i], samples[i + 1]):
                raise NodeWarning(
                    f"Curves {i} and {i + 1} are the same curve: a loft cannot pass through one "
                    "curve twice in a row (remove the duplicate)"
                )
        closed = [bool(getattr(c, "closed", False)) for c in sections]
        if any(closed) and not all(closed):
            self.remark(
                "Some curves are closed and some open: the loft is open, with a seam that is not smooth"
            )
        with kernel_errors():
            return nurbs_surface.Loft(sections, samples=SAMPLES)


class RuledSurface(Node):
    """The surface of straight lines joining CurveA to CurveB, point for point.

    S(u, v) = (1 − v)·A(u) + v·B(u): the isocurve at each u is the straight ruling
    from A(u) to B(u), with v = 0 on CurveA and v = 1 on CurveB. The rulings join
    points at the same curve parameter u, so curves that run opposite ways give a
    twisted, bow-tie surface (Flip one of them). Ruled surfaces include every
    developable: cylinders, cones and tangent surfaces.
    """

    type_id = "surfaces.RuledSurface"
    nickname, aliases = "Rule", ("ruled", "two curve surface")
    inputs = (
        In("CurveA", CURVE, "A", "The first rail: the edge v = 0."),
        In("CurveB", CURVE, "B", "The second rail: the edge v = 1."),
    )
    outputs = (Out("Surface", SURFACE, "S", "The ruled surface, straight along v."),)

    def solve(self, curve_a: Any, curve_b: Any) -> Surface:
        a, b = given("CurveA", curve_a), given("CurveB", curve_b)
        t = np.linspace(0.0, 1.0, SAMPLES)
        pa, pb = np.atleast_2d(a.point_at(t)), np.atleast_2d(b.point_at(t))
        if _same(pa, pb):
            raise NodeWarning("CurveA and CurveB are the same curve, so the ruled surface would have no area")
        if not (getattr(a, "closed", False) or getattr(b, "closed", False)):
            straight = np.linalg.norm(pa[0] - pb[0]) + np.linalg.norm(pa[-1] - pb[-1])
            crossed = np.linalg.norm(pa[0] - pb[-1]) + np.linalg.norm(pa[-1] - pb[0])
            if crossed < straight:  # in a plane: exactly when A0–B0 and A1–B1 cross
                self.remark("CurveA and CurveB run in opposite directions, so the rulings cross: Flip one")
        with kernel_errors():
            return ruled.RuledSurface(a, b)


def _grid_from_list(points: np.ndarray, u_count: int) -> np.ndarray:
    """A flat list, rows of ``u_count`` (2 or more: the port's bound) along u stacked along v,
    as an (nu, nv, 3) grid."""
    if len(points) % u_count:
        raise NodeWarning(
            f"UCount is {u_count} but there are {len(points)} points, not a multiple of {u_count}: "
            f"every row along u needs {u_count} points"
        )
    return points.reshape(-1, u_count, 3).transpose(1, 0, 2)


def _grid_from_rows(rows: list[tuple[Path, np.ndarray]]) -> np.ndarray:
    """Branches, one row along u each, stacked along v, as an (nu, nv, 3) grid."""
    if len(rows) == 1:
        path, row = rows[0]
        raise NodeWarning(
            f"Points has one row ({len(row)} points in branch {format_path(path)}): give UCount to "
            "read it as a grid, or one branch per row"
        )
    length = len(rows[0][1])
    for path, row in rows[1:]:
        if len(row) != length:
            raise NodeWarning(
                f"Every row must have as many points as the first ({length}): branch "
                f"{format_path(path)} has {len(row)}"
            )
    return np.stack([row for _, row in rows], axis=1)


def _check_grid(grid: np.ndarray, du: int, dv: int, interpolate: bool) -> None:
    nu, nv = grid.shape[:2]
    if nu < 2 or nv < 2:
        raise NodeWarning(f"A surface needs a grid of at least 2 × 2 points; got {nu} × {nv}")
    if not interpolate:
        for name, degree, count in (("DegreeU", du, nu), ("DegreeV", dv, nv)):
            if count < degree + 1:
                along = name[-1].lower()
                raise NodeWarning(
                    f"{name} {degree} needs at least {degree + 1} points along {along}; the grid has "
                    f"{count} (lower {name} to {count - 1} or add points)"
                )
        return
    for i in range(nu - 1):
        if np.array_equal(grid[i], grid[i + 1]):
            raise NodeWarning(
                f"Points {i} and {i + 1} of every row are the same: the surface cannot pass through "
                "a point twice in a row"
            )
    for j in range(nv - 1):
        if np.array_equal(grid[:, j], grid[:, j + 1]):
            raise NodeWarning(
                f"Rows {j} and {j + 1} are the same points: the surface cannot pass through a row twice"
            )


class NurbsSurface(Node):
    """A NURBS surface from a grid of points: its control points, or points it passes through.

    Give the grid one of two ways:

    * a list and UCount: the first UCount points are the first row, running along u;
      each next UCount points are the next row, one step along v. 12 points with
      UCount 4 make a grid of 4 (along u) × 3 (along v). Each branch is one grid.
    * one branch per row, UCount left empty: each branch holds a row along u, all of
      the same length, and the branches step along v in path order. Branches
      {0;0} {0;1} {0;2} make one grid; {0;…} and {1;…} make two.

    With Interpolate off, the points are control points: the surface starts and ends
    on the grid's corner rows and is pulled towards the others; a degree-d direction
    needs at least d + 1 points. With Interpolate on, the surface passes through every
    point (chord-length parameters; the degree drops, with a remark, where there are
    too few points). Degree 1 in both directions gives flat quads between the points.
    """

    type_id = "surfaces.NurbsSurface"
    nickname, aliases = "SrfGrid", ("Surface From Points", "control point surface")
    inputs = (
        In("Points", POINT, "P", "The grid: a list read with UCount, or one branch per row.",
           access=TREE),
        In("UCount", INTEGER, "U", "Points in each row along u (2 or more); empty when each branch "
           "is a row.", optional=True, min=2),
        In("DegreeU", INTEGER, "Du", "Degree along u: 3 is cubic, 1 is straight between points.",
           default=3),
        In("DegreeV", INTEGER, "Dv", "Degree along v.", default=3),
        In("Interpolate", BOOLEAN, "I", "Whether the surface passes through the points.",
           default=False),
    )
    outputs = (Out("Surface", SURFACE, "S", "One surface per grid, at the grid's path.", access=TREE),)

    def solve(
        self, points: DataTree, u_count: Any, degree_u: Any, degree_v: Any, interpolate: Any
    ) -> DataTree:
        du, dv = degree("DegreeU", degree_u), degree("DegreeV", degree_v)
        count = None if u_count is None else whole("UCount", u_count)
        # Each job is one grid: its output path and its branches (one, or one per row).
        jobs: dict[Path, list[tuple[Path, list[Any]]]] = {}
        for path, branch in points.items():
            key = path if count is not None else (path[:-1] or (0,))
            jobs.setdefault(key, []).append((path, branch))
        result = DataTree()
        for path, branches in jobs.items():
            try:
                rows = [(p, point_list("Points", branch)) for p, branch in branches]
                grid = _grid_from_list(rows[0][1], count) if count is not None else _grid_from_rows(rows)
                _check_grid(grid, du, dv, bool(interpolate))
                result.append(path, self._surface(grid, du, dv, bool(interpolate)))
            except NodeWarning as exc:
                if len(jobs) == 1:
                    raise
                self.warn(f"{format_path(path)}: {exc}")
                result.append(path, None)
        return result

    def _surface(self, grid: np.ndarray, du: int, dv: int, interpolate: bool) -> Surface:
        with kernel_errors():
            if not interpolate:
                return nurbs_surface.NurbsSurface(grid, du, dv)
            surface = nurbs_surface.NurbsSurface.from_points(grid, du, dv)
        for name, asked, got in (("u", du, surface.degree_u), ("v", dv, surface.degree_v)):
            if got != asked:
                count = grid.shape[0 if name == "u" else 1]
                self.remark(
                    f"With {count} points along {name} the surface has degree {got} along {name}, not {asked}"
                )
        return surface


PROBE = 65
"""Grid of PROBE × PROBE parameters where ParametricSurface checks its formulas give points."""


class ParametricSurface(Node):
    """A surface from three formulas in u and v: the point (X(u, v), Y(u, v), Z(u, v)).

    u runs over UDomain and v over VDomain. The formulas use the language of the
    Expression node (``sin cos sqrt pi`` ..., angles in radians). The defaults,
    X = ``u``, Y = ``v``, Z = ``u * v`` over −1 to 1, give the saddle z = xy (a
    hyperbolic paraboloid); X = ``cos(u) * cos(v)``, Y = ``sin(u) * cos(v)``,
    Z = ``sin(v)`` over 0 to 2π and −π/2 to π/2 give the unit sphere.

    Like every surface the result is reparameterised to (u, v) in [0, 1]²: its
    (0.5, 0.5) is the middle of both domains. A reversed domain runs that direction
    backwards, which turns the normal over. Derivatives (normals, curvature) are
    taken by high-order finite differences, good to about 1e-10 of the curvature,
    except within a hair of a pole (a point where a whole edge meets, like a sphere's),
    where curvature is only a few per cent accurate: use the Sphere node for an exact one.
    """

    type_id = "surfaces.ParametricSurface"
    nickname, aliases = "ParSrf", ("function surface",)
    inputs = (
        In("X", TEXT, "X", "Formula in u and v for the X coordinate.", default="u"),
        In("Y", TEXT, "Y", "Formula in u and v for the Y coordinate.", default="v"),
        In("Z", TEXT, "Z", "Formula in u and v for the Z coordinate.", default="u * v"),
        In("UDomain", DOMAIN, "U", "The values of u the surface runs over.", default=Domain(-1.0, 1.0)),
        In("VDomain", DOMAIN, "V", "The values of v the surface runs over.", default=Domain(-1.0, 1.0)),
    )
    outputs = (Out("Surface", SURFACE, "S", "The surface traced by (X, Y, Z) over both domains."),)

    def solve(self, x: Any, y: Any, z: Any, u_domain: Any, v_domain: Any) -> Surface:
        formulas = [formula(name, text, ("u", "v")) for name, text in (("X", x), ("Y", y), ("Z", z))]
        u_range, v_range = interval("UDomain", u_domain, "u"), interval("VDomain", v_domain, "v")
        fx, fy, fz = formulas

        def function(u: np.ndarray, v: np.ndarray) -> tuple[Any, Any, Any]:
            return fx(u=u, v=v), fy(u=u, v=v), fz(u=u, v=v)

        s, t = uv_grid(PROBE, PROBE)
        u = u_range[0] + s * (u_range[1] - u_range[0])
        v = v_range[0] + t * (v_range[1] - v_range[0])
        try:
            values = parametric_surface.as_points(function(u, v), len(u))
        except ExpressionError as exc:  # refused when evaluated: the formulas' fault, as one value
            raise NodeWarning(f"The formulas X, Y, Z cannot be evaluated: {exc}") from None
        bad = ~np.all(np.isfinite(values), axis=1)
        if bad.any():
            k = int(np.argmax(bad))
            raise NodeWarning(
                f"The formulas give no finite point at u = {u[k]:g}, v = {v[k]:g} "
                "(division by zero, or a square root of a negative number?)"
            )
        with kernel_errors():
            surface = parametric_surface.ParametricSurface(function, u_range, v_range)
        _check_spans_area(surface)
        return surface


def _check_spans_area(surface: Surface) -> None:
    """Refuse formulas that trace a point or a curve: Su × Sv vanishes everywhere."""
    s, t = uv_grid(9, 9)
    _, su, sv = surface.derivatives(s, t, 1)
    lu, lv = np.linalg.norm(su, axis=1).max(), np.linalg.norm(sv, axis=1).max()
    if lu == 0 and lv == 0:
        raise NodeWarning("The formulas give the same point for every u and v, not a surface")
    for name, length, other in (("u", lu, lv), ("v", lv, lu)):
        if length <= 1e-12 * other:
            raise NodeWarning(f"The formulas do not change with {name}, so they trace a curve, not a surface")
    cross = np.linalg.norm(np.cross(su, sv), axis=1)
    if np.all(cross <= DEGENERATE_RATIO * (np.sum(su * su, axis=1) + np.sum(sv * sv, axis=1))):
        raise NodeWarning(
            "The formulas trace a curve, not a surface: the u and v directions are parallel everywhere"
        )

