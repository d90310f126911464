"""developable.Rationalise on design surfaces about 10 m across at a 2 cm tolerance.

Every check is recomputed here from closed forms: the designs are height fields
z = f(x, y) given with their exact derivatives, a strip's distance from the design is
found by a Newton iteration on the height field written in this file (from the nearest
of a dense sample grid, cKDTree), warps by the triple product with the design's exact
tangents, areas by triangles of dense samples.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable
from dataclasses import dataclass
from functools import cache

import numpy as np
import pytest
import rhino3dm
import trimesh
from scipy.integrate import dblquad
from scipy.spatial import cKDTree

from tests.support.node_helpers import run, texts, tree
from tests.support.strip_grids import grid, grid_area, items
from torsal.engine.values import Vector
from torsal.nodes.developable.rationalise import Rationalise
from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.parametric_surface import ParametricSurface
from torsal.nodes.geometry.transforms import translation

TOL = 0.02
SIZE = 10.0
HALF = SIZE / 2


@dataclass(frozen=True)
class HeightField:
    """z = f(x, y) on [-5, 5]² with its first and second derivatives."""

    f: Callable
    fx: Callable
    fy: Callable
    fxx: Callable
    fxy: Callable
    fyy: Callable

    def surface(self) -> ParametricSurface:
        square = (-HALF, HALF)
        return ParametricSurface(lambda x, y: np.column_stack([x, y, self.f(x, y)]), square, square)


def _zero(x, y):
    return np.zeros_like(x)


SADDLE = HeightField(lambda x, y: (x**2 - y**2) / 20, lambda x, y: x / 10, lambda x, y: -y / 10,
                     lambda x, y: np.full_like(x, 0.1), _zero, lambda x, y: np.full_like(x, -0.1))
DOME = HeightField(lambda x, y: 3 - (x**2 + y**2) / 20, lambda x, y: -x / 10, lambda x, y: -y / 10,
                   lambda x, y: np.full_like(x, -0.1), _zero, lambda x, y: np.full_like(x, -0.1))
WAVE = HeightField(lambda x, y: 0.6 * np.sin(0.9 * x) + 0.3 * np.sin(0.5 * y),
                   lambda x, y: 0.54 * np.cos(0.9 * x), lambda x, y: 0.15 * np.cos(0.5 * y),
                   lambda x, y: -0.486 * np.sin(0.9 * x), _zero, lambda x, y: -0.075 * np.sin(0.5 * y))
DESIGNS = {"saddle": SADDLE, "dome": DOME, "wave": WAVE}


def distance_to(field: HeightField, points: np.ndarray) -> np.ndarray:
    """Distance from each point to the height field over [-5, 5]² (Newton on ½|S − P|²,
    clamped to the square, from the nearest of 201² samples)."""
    g = np.linspace(-HALF, HALF, 201)
    gx, gy = (a.ravel() for a in np.meshgrid(g, g))
    samples = np.column_stack([gx, gy, field.f(gx, gy)])
    _, index = cKDTree(samples).query(points)
    x, y = gx[index].copy(), gy[index].copy()
    for _ in range(30):
        d = np.column_stack([x, y, field.f(x, y)]) - points
        fx, fy = field.fx(x, y), field.fy(x, y)
        gradient = np.column_stack([d[:, 0] + d[:, 2] * fx, d[:, 1] + d[:, 2] * fy])
        h11 = 1 + fx * fx + d[:, 2] * field.fxx(x, y)
        h12 = fx * fy + d[:, 2] * field.fxy(x, y)
        h22 = 1 + fy * fy + d[:, 2] * field.fyy(x, y)
        det = h11 * h22 - h12 * h12
        x = np.clip(x - (h22 * gradient[:, 0] - h12 * gradient[:, 1]) / det, -HALF, HALF)
        y = np.clip(y - (h11 * gradient[:, 1] - h12 * gradient[:, 0]) / det, -HALF, HALF)
    return np.linalg.norm(np.column_stack([x, y, field.f(x, y)]) - points, axis=1)


@cache
def solved(name: str):
    result = run(Rationalise(), Surface=tree({(0,): [DESIGNS[name].surface()]}), Tolerance=TOL, MaxStrips=40)
    assert result.state == "ok", texts(result)
    return result








@pytest.mark.parametrize("name", DESIGNS)
def test_every_strip_lies_within_the_tolerance_of_the_design(name):
    strips = items(solved(name), "Strips")
    worst = max(distance_to(DESIGNS[name], grid(s).reshape(-1, 3)).max() for s in strips)
    assert worst <= TOL * 1.001


@pytest.mark.parametrize("name", DESIGNS)
def test_every_torsal_ruling_has_warp_below_1e_7_against_the_boundaries_own_tangents(name):
    """The boundaries are lifted off the design (see the node): the tangents are the
    boundary curves' own, by central differences of their points (measured below 1e-8)."""
    from tests.nodes.developable.test_rationalise_freeform import curve_tangents

    result = solved(name)
    rulings, kinds = items(result, "Rulings"), items(result, "Kind")
    boundaries, strips = items(result, "Boundaries"), items(result, "Strips")
    worst, start, torsal = 0.0, 0, 0
    for i, strip in enumerate(strips):
        keep = [j for j in range(start, start + len(strip.ruling_lines)) if kinds[j] == "torsal"]
        a = np.array([rulings[j].start for j in keep], dtype=float)
        b = np.array([rulings[j].end for j in keep], dtype=float)
        n1 = np.cross(b - a, curve_tangents(boundaries[i], a))
        n2 = np.cross(b - a, curve_tangents(boundaries[i + 1], b))
        warp = np.arctan2(np.linalg.norm(np.cross(n1, n2), axis=1), np.einsum("ij,ij->i", n1, n2))
        worst, torsal = max(worst, float(warp.max(initial=0.0))), torsal + len(keep)
        start += len(strip.ruling_lines)
    assert torsal > 10
    assert worst < 1e-7


@pytest.mark.parametrize("name", DESIGNS)
def test_fan_rulings_share_an_apex_with_a_neighbour(name):
    """A flat fan's rulings pass through one point of a boundary (a flat triangle)."""
    rulings, kinds = items(solved(name), "Rulings"), items(solved(name), "Kind")
    for i, kind in enumerate(kinds):
        if kind == "fan":
            here = np.array([rulings[i].start, rulings[i].end], dtype=float)
            near = [np.array([rulings[j].start, rulings[j].end], dtype=float)
                    for j in (i - 1, i + 1) if 0 <= j < len(rulings)]
            assert any(np.abs(here - n).max(axis=1).min() < 1e-12 * SIZE for n in near)


@pytest.mark.parametrize("name", DESIGNS)
def test_neighbouring_strips_share_their_boundary(name):
    """Both edges along a boundary run on that boundary curve, end to end; the boundary is
    lifted off the design by at most 0.8 of the tolerance."""
    from tests.nodes.developable.test_rationalise_freeform import project

    strips, boundaries = items(solved(name), "Strips"), items(solved(name), "Boundaries")
    assert len(strips) >= 2
    for i, (lower, upper) in enumerate(itertools.pairwise(strips)):
        top, bottom = grid(lower)[:, -1], grid(upper)[:, 0]
        assert np.abs(top[[0, -1]] - bottom[[0, -1]]).max() <= 1e-12 * SIZE
        curve = boundaries[i + 1]
        for edge in (top, bottom):
            assert np.linalg.norm(curve.point_at(project(curve, edge)) - edge, axis=1).max() <= 1e-9 * SIZE
        assert distance_to(DESIGNS[name], curve.point_at(np.linspace(0, 1, 201))).max() <= 0.8 * TOL * 1.0001


@pytest.mark.parametrize("name", DESIGNS)
def test_summed_strip_area_is_within_a_hundredth_of_the_designs(name):
    """Within 1 % (the strips stay within the tolerance of the design, to both sides)."""
    field = DESIGNS[name]
    design, _ = dblquad(lambda y, x: np.sqrt(1 + field.fx(x, y) ** 2 + field.fy(x, y) ** 2),
                        -HALF, HALF, -HALF, HALF, epsabs=1e-9)
    strips = sum(grid_area(grid(s, 241, 21)) for s in items(solved(name), "Strips"))
    assert abs(strips - design) <= 1e-2 * design


@pytest.mark.parametrize("name", DESIGNS)
def test_every_ruling_is_valid_and_the_remark_gives_the_count_and_deviation(name):
    result = solved(name)
    assert all(items(result, "Valid"))
    count = len(items(result, "Strips"))
    assert any(f"{count} strips" in t and "deviation at most" in t for t in texts(result))
    assert max(items(result, "Deviation")) <= TOL


def test_a_cylinder_patch_comes_back_as_one_strip_on_the_cylinder():
    radius = 6.0
    cylinder = ParametricSurface(lambda a, y: np.column_stack([radius * np.sin(a), y, radius * np.cos(a)]),
                                 (-0.8, 0.8), (-HALF, HALF))
    result = run(Rationalise(), Surface=tree({(0,): [cylinder]}), Tolerance=TOL, MaxStrips=40)
    strips = items(result, "Strips")
    assert len(strips) == 1
    p = grid(strips[0]).reshape(-1, 3)
    assert np.abs(np.hypot(p[:, 0], p[:, 2]) - radius).max() <= 1e-9 * SIZE


def test_too_few_strips_warn_with_the_deviation_reached():
    result = run(Rationalise(), Surface=tree({(0,): [DOME.surface()]}), Tolerance=TOL, MaxStrips=3)
    assert len(items(result, "Strips")) == 3
    reached = max(items(result, "Deviation"))
    assert reached > TOL
    warning = [t for t in texts(result) if "Tolerance 0.02 is not met" in t]
    assert len(warning) == 1 and f"{reached:.4g}" in warning[0] and "raise MaxStrips (now 3)" in warning[0]
    assert "within the tolerance" not in warning[0]  # no message contradicts it
    where = items(result, "Where")
    assert len(where) == 4 and "the design's edge is" in warning[0]  # each strip's farthest point, the edge's


def test_a_surface_closed_across_the_strips_asks_to_be_cut():
    tube = ParametricSurface(lambda a, y: np.column_stack([3 * np.cos(a), 3 * np.sin(a), y]),
                             (0, 2 * np.pi), (0, 10))
    result = run(Rationalise(), Surface=tree({(0,): [tube]}), Tolerance=TOL, MaxStrips=40,
                 Direction=Vector(0.0, 0.0, 1.0))
    assert result.state == "warning"
    assert any("cut it open" in t for t in texts(result))


def test_a_mesh_surface_is_refused_naming_the_input():
    mesh = MeshSurface(trimesh.creation.box())
    result = run(Rationalise(), Surface=tree({(0,): [mesh]}), Tolerance=TOL)
    assert result.state == "error"
    assert any("Surface" in t and "mesh" in t.lower() for t in texts(result))


def test_strips_exported_to_3dm_read_back_as_ruled_faces_degree_1_across_on_the_strips_edges(tmp_path):
    """Each strip goes out as ruled faces (Breps, degree 1 across), its rails fitted to 1e-6 of
    the strip's size (docs/rhino.md): every ruled face's rail points lie on one of the strip's
    edges. (A lone fan triangle goes out as a trimmed plane, whose untrimmed corners lie off
    the strip: only its degree is checked.)"""
    from torsal.app.exports import export_tree
    from torsal.engine.datatree import DataTree

    strips = items(solved("wave"), "Strips")
    path = export_tree(DataTree.from_branches([strips]), tmp_path / "r.3dm")[0]
    objects = list(rhino3dm.File3dm.Read(str(path)).Objects)
    assert len(objects) >= len(strips)
    u = np.linspace(0, 1, 4001)
    polylines = [strip.point_at(u, np.full(len(u), v)) for strip in strips for v in (0.0, 1.0)]
    starts = np.vstack([line[:-1] for line in polylines])
    steps = np.vstack([np.diff(line, axis=0) for line in polylines])
    for obj in objects:
        assert isinstance(obj.Geometry, rhino3dm.Brep)
        for face in obj.Geometry.Faces:
            surface = face.UnderlyingSurface().ToNurbsSurface()
            across = 0 if surface.Degree(0) == 1 else 1
            assert surface.Degree(across) == 1
            if surface.Degree(1 - across) == 1:  # a plane (a fan triangle, trimmed)
                continue
            domain = surface.Domain(1 - across)
            rails = []
            for t in np.linspace(domain.T0, domain.T1, 9):
                for end in (surface.Domain(across).T0, surface.Domain(across).T1):
                    p = surface.PointAt(end, t) if across == 0 else surface.PointAt(t, end)
                    rails.append([p.X, p.Y, p.Z])
            # distance from each rail point to the nearest segment of the edges' polylines
            rel = np.asarray(rails)[:, None, :] - starts[None, :, :]
            squared = (steps * steps).sum(axis=1)  # (0 where an edge stands still: a cone's apex)
            along = np.clip((rel * steps).sum(axis=2) / np.where(squared > 0, squared, 1.0), 0.0, 1.0)
            gaps = np.linalg.norm(rel - along[..., None] * steps[None], axis=2).min(axis=1)
            assert gaps.max() <= 1e-6 * SIZE  # 3.3e-7 measured


def kaohsiung_roof():
    """The Kaohsiung roof of the example as one surface: a loft through its horseshoe base
    curve, that curve 14 m up and that copy scaled by 0.72 about (0, 0, 28)."""
    from torsal.nodes.geometry.curves import InterpolatedCurve
    from torsal.nodes.geometry.nurbs_surface import Loft

    angles = np.radians(np.arange(40, 321, 35))
    base = np.column_stack([60 * np.cos(angles), 42 * np.sin(angles), np.zeros(len(angles))])
    top = base + np.array([0.0, 0.0, 14.0])
    inner = (top - [0, 0, 28]) * 0.72 + [0, 0, 28]
    return Loft([InterpolatedCurve(p, degree=3) for p in (base, top, inner)], degree=2)


def distance_to_surface(surface, points: np.ndarray, grid_size: int = 401) -> np.ndarray:
    """Distance from each point to ``surface``: the nearest of a dense grid of its points
    (cKDTree), refined by Gauss–Newton on |S(u, v) − P|² with the surface's derivatives,
    clamped to the unit square."""
    g = np.linspace(0, 1, grid_size)
    gu, gv = (a.ravel() for a in np.meshgrid(g, g))
    _, index = cKDTree(surface.point_at(gu, gv)).query(points)
    u, v = gu[index].copy(), gv[index].copy()
    for _ in range(20):
        s, su, sv = surface.derivatives(u, v, 1)
        d = s - points
        a11, a12, a22 = (np.einsum("ij,ij->i", x, y) for x, y in ((su, su), (su, sv), (sv, sv)))
        b1, b2 = np.einsum("ij,ij->i", su, d), np.einsum("ij,ij->i", sv, d)
        det = a11 * a22 - a12 * a12
        u = np.clip(u - (a22 * b1 - a12 * b2) / det, 0, 1)
        v = np.clip(v - (a11 * b2 - a12 * b1) / det, 0, 1)
    return np.linalg.norm(surface.point_at(u, v) - points, axis=1)


@cache
def kaohsiung_solved():
    result = run(Rationalise(), Surface=tree({(0,): [kaohsiung_roof()]}), Tolerance=TOL, MaxStrips=40)
    assert result.state == "ok", texts(result)
    return result


def test_the_kaohsiung_roof_as_one_surface_is_covered_within_the_tolerance():
    roof = kaohsiung_roof()
    strips = items(kaohsiung_solved(), "Strips")
    worst = max(distance_to_surface(roof, grid(s, 241, 9).reshape(-1, 3)).max() for s in strips)
    assert worst <= TOL * 1.001
    assert all(items(kaohsiung_solved(), "Valid"))


def test_the_kaohsiung_strips_run_along_the_horseshoe_and_cover_its_area():
    roof = kaohsiung_roof()
    strips = items(kaohsiung_solved(), "Strips")
    assert len(strips) <= 30  # slicing across the 250 m horseshoe would take ~90
    design = grid_area(roof.point_at(*(a.ravel() for a in np.meshgrid(
        np.linspace(0, 1, 801), np.linspace(0, 1, 81), indexing="ij"))).reshape(801, 81, 3))
    assert abs(sum(grid_area(grid(s, 401, 9)) for s in strips) - design) <= 0.01 * design


def hypar_solved():
    hypar = ParametricSurface(lambda x, y: np.column_stack([x, y, x * y / 10]), (-HALF, HALF), (-HALF, HALF))
    return run(Rationalise(), Surface=tree({(0,): [hypar]}), Tolerance=TOL, MaxStrips=40)


def test_a_hyperbolic_paraboloid_between_its_straight_lines_gives_flat_triangles_with_a_warning():
    """Two skew straight lines bound no torsal strip: the strips are flat triangles, each a
    ruling pair through one point (so coplanar), still within the tolerance."""
    result = hypar_solved()
    assert any("crease the sheet" in t for t in texts(result))
    rulings = items(result, "Rulings")
    assert set(items(result, "Kind")) <= {"fan", "crease"}
    pairs = 0
    for first, second in itertools.pairwise(rulings):
        p = np.array([first.start, first.end, second.start, second.end], dtype=float)
        if abs(p[0, 1] - p[2, 1]) > 1e-12 or abs(p[1, 1] - p[3, 1]) > 1e-12:
            continue  # the next strip (its boundaries are the lines y = const)
        pairs += 1
        volume = np.linalg.det(np.stack([p[1] - p[0], p[2] - p[0], p[3] - p[0]]))
        assert abs(volume) <= 1e-9 * SIZE**3
    assert pairs >= len(rulings) - len(items(result, "Strips"))
    field = HeightField(lambda x, y: x * y / 10, lambda x, y: y / 10, lambda x, y: x / 10,
                        _zero, lambda x, y: np.full_like(x, 0.1), _zero)
    worst = max(distance_to(field, grid(s).reshape(-1, 3)).max() for s in items(result, "Strips"))
    assert worst <= TOL * 1.001


def test_the_hyperbolic_paraboloids_triangles_fold_where_their_apex_changes_side():
    """Between the lines y = c0 and y = c1 of z = x·y/10 (tangents (1, 0, c/10)), a triangle
    through a point of one line beside one through a point of the other meet at an angle:
    the planes of the ruling R and each line's tangent, R × (1, 0, c0/10) and R × (1, 0, c1/10).
    Those rulings are creases with that angle as WarpAngles, never Valid; a ruling whose
    neighbours share its end on one line is inside a fan (a flat cone): a fan, Valid."""
    result = hypar_solved()
    rulings, kinds = items(result, "Rulings"), items(result, "Kind")
    warps, valid = items(result, "WarpAngles"), items(result, "Valid")
    ends = np.array([[r.start, r.end] for r in rulings], dtype=float)
    creases = 0
    for i in range(1, len(rulings) - 1):
        before, here, after = ends[i - 1], ends[i], ends[i + 1]
        if abs(before[0, 1] - here[0, 1]) > 1e-12 or abs(after[0, 1] - here[0, 1]) > 1e-12:
            continue  # a strip's end ruling (one side only)
        shares = [np.abs(other - here).max(axis=1) <= 1e-12 * SIZE for other in (before, after)]
        if (shares[0][0] and shares[1][1]) or (shares[0][1] and shares[1][0]):  # the apex changes side
            r = here[1] - here[0]
            n0 = np.cross(r, [1.0, 0.0, here[0, 1] / 10])
            n1 = np.cross(r, [1.0, 0.0, here[1, 1] / 10])
            fold = np.arctan2(np.linalg.norm(np.cross(n0, n1)), n0 @ n1)
            assert fold > 1e-3
            assert kinds[i] == "crease" and not valid[i]
            assert warps[i] == pytest.approx(fold, rel=1e-6)
            creases += 1
        elif (shares[0][0] and shares[1][0]) or (shares[0][1] and shares[1][1]):  # inside one fan
            assert kinds[i] == "fan" and valid[i]
    assert creases > 10
    assert any(f"{creases} rulings of flat triangles are creases" in t for t in texts(result))


def test_direction_makes_the_boundaries_run_along_it():
    for guide, fixed in ((Vector(1.0, 0.0, 0.0), 1), (Vector(0.0, 1.0, 0.0), 0)):
        result = run(Rationalise(), Surface=tree({(0,): [SADDLE.surface()]}), Tolerance=TOL, MaxStrips=40,
                     Direction=guide)
        for boundary in items(result, "Boundaries"):
            assert np.ptp(boundary.point_at(np.linspace(0, 1, 9))[:, fixed]) <= 1e-9 * SIZE


def test_progress_rises_to_one_as_the_strips_cover_the_design():
    from torsal.nodes.geometry.developable.rationalise import rationalise

    seen: list[float] = []
    result = rationalise(DOME.surface(), 0.05, 40, progress=seen.append)
    assert len(seen) == len(result.strips)
    assert np.all(np.diff(seen) > 0) and seen[-1] == 1.0


def test_too_many_rulings_at_once_are_refused_naming_maxstrips_and_segments():
    result = run(Rationalise(), Surface=tree({(0,): [DOME.surface()]}), Tolerance=TOL, MaxStrips=200,
                 Segments=200)
    assert result.state == "error"
    assert any("MaxStrips 200" in t and "Segments" in t for t in texts(result))


def test_a_design_1e9_m_out_gives_the_strips_at_the_origin_moved_to_one_rounding():
    """The saddle moved by 1e9 m (as transform.Move moves it) is solved in a frame at the
    design: rulings, boundaries and strips are the origin's moved, to the half ulp
    (6e-8 m) of moving them back, and the deviations and warps are the origin's exactly.
    Solved in world coordinates the rulings' ends moved by 280 ulps (3.3e-5 m) and the
    warps by 2.7e-6 rad (measured)."""
    far_away = np.full(3, 1e9)
    half_ulp = 0.5 * np.spacing(1e9) * 1.01
    near = solved("saddle")
    moved = SADDLE.surface().transformed(translation(far_away))
    far = run(Rationalise(), Surface=tree({(0,): [moved]}), Tolerance=TOL, MaxStrips=40)
    ends_near = np.array([[line.start, line.end] for line in items(near, "Rulings")])
    ends_far = np.array([[line.start, line.end] for line in items(far, "Rulings")])
    assert ends_far.shape == ends_near.shape
    assert np.abs(ends_far - far_away - ends_near).max() <= half_ulp
    assert items(far, "Deviation") == items(near, "Deviation")
    assert items(far, "WarpAngles") == items(near, "WarpAngles")
    t = np.linspace(0.0, 1.0, 9)
    for boundary_far, boundary_near in zip(items(far, "Boundaries"), items(near, "Boundaries"), strict=True):
        assert np.abs(boundary_far.point_at(t) - far_away - boundary_near.point_at(t)).max() <= half_ulp
    for strip_far, strip_near in zip(items(far, "Strips"), items(near, "Strips"), strict=True):
        assert np.abs(strip_far.point_at(t, t) - far_away - strip_near.point_at(t, t)).max() <= 2 * half_ulp
