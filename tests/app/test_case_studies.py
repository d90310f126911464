"""The shipped case-study graphs solve headless, with the figures a designer would check."""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import numpy as np
import pytest
import shapely

from torsal.app.headless import Run, run_file
from torsal.engine.solver import ERROR

EXAMPLES = Path(__file__).resolve().parents[2] / "torsal" / "resources" / "examples"


def solved(name: str, *assignments: str) -> Run:
    run = run_file(EXAMPLES / f"{name}.graph", list(assignments))
    errors = {n: r.messages for n, r in run.solver.results.items() if r.state == ERROR}
    assert errors == {}
    return run


def items(run: Run, node_id: str, port: str) -> list:
    return run.solver.result(node_id).outputs[port].all_items()


def test_guggenheim_rings_are_frustums_with_the_closed_form_area_and_no_warp():
    run = solved("guggenheim-ny")
    rings = items(run, "rings_surface", "Surface")
    assert len(rings) == 5
    h, d, r = 3.2, 1.1, 14.0
    for k, ring in enumerate(rings):
        r1, r2 = r + k * d, r + (k + 1) * d
        assert ring.area() == pytest.approx(math.pi * (r1 + r2) * math.hypot(h, d), rel=1e-6)
    assert max(items(run, "rings_surface", "WarpAngles")) < 1e-10
    shaft = items(run, "shaft", "Surface")[0]
    assert shaft.area() == pytest.approx(2 * math.pi * 3.0 * (5 * 3.2 + 2), rel=1e-6)


def test_guggenheim_ring_count_follows_its_slider():
    run = solved("guggenheim-ny", "rings=8")
    assert len(items(run, "rings_surface", "Surface")) == 8


def test_zve_roof_edge_is_developable_with_two_triangle_fans_in_the_middle():
    run = solved("zve-roof-edge")
    warp = items(run, "edge", "WarpAngles")
    assert max(warp) < 1e-14  # developable: 0 to rounding (measured 3.0e-16)
    assert all(items(run, "edge", "Valid"))
    rulings = items(run, "edge", "Rulings")
    assert len(rulings) > 41  # 41 station rulings plus the fans through the corners
    assert run.solver.result("edge").state == "ok"


def test_kaohsiung_makes_one_developable_strip_per_pair_of_neighbouring_edges():
    run = solved("kaohsiung-stadium")
    strips = items(run, "strip", "Surface")
    count, shift = 24, 2
    assert len(strips) == count + 2 * shift  # edges j = 0 … count + 2n
    valid = np.array(items(run, "strip", "Valid"))
    warp = np.array(items(run, "strip", "WarpAngles"))
    kinds = np.array(items(run, "strip", "Kind"))
    lengths = np.array([line.length for line in items(run, "strip", "Rulings")])
    tips = lengths <= 1e-9  # where the edges gather at the horseshoe's ends, strips taper to a point
    assert np.isnan(warp[tips]).all() and not valid[tips].any()
    # where the edges end on the rims their end points have no torsal partner: a smooth cone
    # through the end point closes each end (Kind = "fan"); every other ruling is torsal
    torsal = (kinds == "torsal") & ~tips
    assert valid[torsal].all()
    assert torsal.mean() > 0.75  # 322 of 422 measured (0.763): the rest are the ends' fans
    result = run.solver.result("strip")
    assert result.state == "ok", [m.text for m in result.messages]
    # the strips in the middle close their ends by smooth cones; the tapering ones near the
    # horseshoe's ends keep a few creased triangles (under 2 % of their area, FanLimit 10 %)
    middle = [m.text for m in result.messages if "closed by" in m.text][4:-4]
    assert middle and all("smooth cones" in text for text in middle)


@pytest.mark.parametrize("name", ["kaohsiung-stadium", "kaohsiung-cut-sheets"])
def test_kaohsiung_examples_solve_with_no_warning(name):
    run = solved(name)
    warnings = {n: [m.text for m in r.messages] for n, r in run.solver.results.items() if r.state != "ok"}
    assert warnings == {}


def plane_angle(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """The angle between the planes with normals ``a`` and ``b``, in [0, π/2]."""
    return np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), np.abs(np.einsum("ij,ij->i", a, b)))


def test_kaohsiung_torsal_rulings_are_torsal_by_the_tangents_of_their_curves():
    """A torsal ruling R from P on CurveA to Q on CurveB has one tangent plane all along it:
    the planes through R and each curve's tangent, at P and at Q, agree. Measured with the
    curves' own tangents: the angle between them is under the file's WarpTolerance (0.01 rad,
    what makes a ruling torsal; measured 0.0029) and is the node's WarpAngle (to 6e-16)."""
    run = solved("kaohsiung-stadium")
    outputs = run.solver.result("strip").outputs
    curves_a, curves_b = items(run, "left", "Item"), items(run, "right", "Item")
    warps, differences = [], []
    for k, path in enumerate(outputs["Rulings"].paths):
        rulings = outputs["Rulings"].branch(path)
        p, q = np.array([r.start for r in rulings]), np.array([r.end for r in rulings])
        on_a, on_b = curves_a[k].closest_point(p), curves_b[k].closest_point(q)
        assert max(on_a.distances.max(), on_b.distances.max()) < 1e-13 * 100.0  # measured 8.7e-15
        torsal = (np.array(outputs["Kind"].branch(path)) == "torsal") & (np.linalg.norm(q - p, axis=1) > 1e-9)
        r = (q - p)[torsal]
        warp = plane_angle(np.cross(curves_a[k].tangent_at(on_a.parameters)[torsal], r),
                           np.cross(curves_b[k].tangent_at(on_b.parameters)[torsal], r))
        warps.append(warp)
        differences.append(np.abs(warp - np.array(outputs["WarpAngles"].branch(path), dtype=float)[torsal]))
    assert sum(len(w) for w in warps) > 300  # 320 or so of the 422 rulings
    assert np.concatenate(warps).max() < 0.01
    assert np.concatenate(differences).max() < 1e-12


def test_kaohsiung_roof_reaches_both_ends_of_the_horseshoe():
    run = solved("kaohsiung-stadium")
    strips = items(run, "strip", "Surface")
    corners = np.vstack([s.point_at([0.0, 0.0, 1.0, 1.0], [0.0, 1.0, 0.0, 1.0]) for s in strips])
    for node_id, port in (("base", "Curve"), ("inner", "Geometry")):
        (curve,) = items(run, node_id, port)
        for end in curve.point_at(np.array([0.0, 1.0])):
            assert np.linalg.norm(corners - end, axis=1).min() <= 1e-9 * 100.0


def test_kaohsiung_neighbouring_strips_share_their_boundary_curve():
    """Strip k's edge on CurveB and strip k + 1's edge on CurveA both lie on the one edge curve
    between them, all along it, and run over the same stretch of it (end to end)."""
    run = solved("kaohsiung-stadium")
    strips = items(run, "strip", "Surface")
    right = items(run, "right", "Item")
    u = np.linspace(0.0, 1.0, 301)
    for k, (strip, neighbour) in enumerate(itertools.pairwise(strips)):
        edge = right[k]
        size = float(np.ptp(edge.point_at(u), axis=0).max())
        for points in (strip.point_at(u, np.ones_like(u)), neighbour.point_at(u, np.zeros_like(u))):
            gap = edge.closest_point(points).distances.max()
            assert gap <= 1e-9 * size, f"strip {k}: {gap}"
        ends = [strip.point_at([0.0, 1.0], [1.0, 1.0]), neighbour.point_at([0.0, 1.0], [0.0, 0.0])]
        assert np.abs(ends[0] - ends[1]).max() <= 1e-9 * size


def test_textbook_cylinder_is_developable_and_helicoid_and_mobius_are_not():
    run = solved("textbook-ruled-surfaces")
    assert max(items(run, "cylinder", "WarpAngles")) < 1e-14  # measured 0
    # helicoid C = (−3.5, 0, 0.4u), a = (cos u, sin u, 0), v in [−1, 1]: the normals at a
    # ruling's ends are (−0.4 sin u, 0.4 cos u, ∓s), s the factor sin(h)/h that the node's
    # central differences of step h = 2π/48 give the edge tangents; warp 2·atan(s / 0.4)
    # (2.3786; the smooth helicoid's is 2·atan(1 / 0.4) = 2.3806); measured to 2e-15
    h = 2 * math.pi / 48
    helicoid = np.array(items(run, "helicoid", "WarpAngles"))
    assert len(helicoid) == 49
    assert np.abs(helicoid - 2 * math.atan(math.sin(h) / h / 0.4)).max() < 1e-13
    assert max(items(run, "mobius", "WarpAngles")) > 0.01


def test_textbook_hyperbolic_paraboloid_is_nowhere_and_torus_partly_single_curved():
    run = solved("textbook-ruled-surfaces")
    assert items(run, "hypar_analysis", "DevelopableFraction") == [0.0]
    gaussian = np.array(items(run, "torus_analysis", "Gaussian"))
    assert (gaussian > 1e-6).any() and (gaussian < -1e-6).any() and (np.abs(gaussian) < 1e-9).any()
    assert 0.0 < items(run, "torus_analysis", "DevelopableFraction")[0] < 0.05


def test_paper_strip_unrolls_with_no_length_or_area_error():
    """The spec: the paper strip's unfolding has zero area and length error, to rounding.
    AreaError sums the areas of the Map's n = 321 strips (measured 3.7e-16); an edge keeps
    its length to ~n rounding units, the flat frames composed one after another (measured
    2.4e-14)."""
    run = solved("paper-strip")
    rulings = len(items(run, "unroll", "Map")[0].starts2d)
    assert items(run, "unroll", "EdgeError")[0] < 1e-15 * rulings
    assert abs(items(run, "unroll", "AreaError")[0]) < 1e-14
    assert len(items(run, "strip", "Rulings")) == 41


def test_spline_approximation_optimises_the_warp_away_and_the_finished_strip_is_developable():
    run = solved("spline-approximation")
    assert items(run, "approx", "Fitness")[0] < 0.005  # measured 0.0033
    assert all(items(run, "finish", "Valid"))
    assert max(items(run, "finish", "WarpAngles")) < 2.5e-4  # measured 1.2e-4


def test_panels_cover_the_development_and_have_ids():
    run = solved("development-and-panels")
    ids = items(run, "patching", "PanelIDs")
    areas = items(run, "patching", "PanelAreas")
    assert len(ids) == len(set(ids)) == len(areas) > 10
    # the panels (shapely polygons) tile the development's outline (the polygon through its
    # flat rulings' ends) without gap or overlap, to rounding (measured 1.6e-16 and 1.1e-15)
    development = items(run, "unroll", "Map")[0]
    # both nodes lay the development beside the model by one translation (Placement)
    laid = np.asarray(items(run, "unroll", "Rulings")[0].start, dtype=float)[:2] - development.starts2d[0]
    outline = shapely.Polygon(np.vstack([development.starts2d, development.ends2d[::-1]]) + laid)
    panels = [shapely.Polygon(np.asarray(c.points)[:, :2]) for c in items(run, "patching", "PanelsFlat")]
    assert np.abs(np.array([p.area for p in panels]) - areas).max() < 1e-14 * max(areas)
    union = shapely.union_all(panels)
    assert outline.symmetric_difference(union).area < 1e-14 * outline.area
    assert sum(areas) == pytest.approx(union.area, rel=1e-14)
    assert items(run, "unroll", "EdgeError")[0] < 1e-12  # measured 5.4e-13 (1,569 rulings)
    assert 0.0 <= items(run, "patching", "Waste")[0] < 1.0


def test_kaohsiung_cut_sheets_export_headless_as_dxf_svg_and_3dm(tmp_path, monkeypatch):
    import ezdxf
    import rhino3dm

    from torsal.app.cli import main

    monkeypatch.chdir(tmp_path)
    graph = str(EXAMPLES / "kaohsiung-cut-sheets.graph")
    exports = ["--export", "cut.Layout=roof.dxf", "--export", "cut.Layout=roof.svg",
               "--export", "cut.Layout=roof.3dm"]
    assert main(["run", graph, *exports]) == 0
    strips = len(run_file(graph).solver.result("strip").outputs["Surface"].all_items())
    dxfs = sorted(tmp_path.glob("roof-*.dxf"))
    assert dxfs and len(sorted(tmp_path.glob("roof-*.svg"))) == len(dxfs)
    closed = 0
    for path in dxfs:
        document = ezdxf.readfile(path)
        assert document.header["$INSUNITS"] == 4  # millimetres
        closed += sum(1 for e in document.modelspace().query('LWPOLYLINE[layer=="CUT"]') if e.closed)
        assert len(document.modelspace().query('*[layer=="ENGRAVE"]')) > 0
    assert closed == strips
    model = rhino3dm.File3dm.Read(str(tmp_path / "roof.3dm"))
    assert len(model.Objects) >= strips
