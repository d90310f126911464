"""The shipped case-study graphs solve headless, with the figures a designer would check."""

from __future__ import annotations

import itertools
import math
from pathlib import Path

import numpy as np
import pytest

from app.headless import Run, run_file
from engine.solver import ERROR

EXAMPLES = Path(__file__).resolve().parent.parent / "resources" / "examples"


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
    assert max(warp) < 1e-7
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
    assert warp[torsal].max() < 0.01
    assert valid[torsal].all()
    assert torsal.mean() > 0.7  # 0.74 measured: the rest are the ends' cones
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
    assert max(items(run, "cylinder", "WarpAngles")) < 1e-9
    assert min(items(run, "helicoid", "WarpAngles")[1:-1]) > 0.05
    assert max(items(run, "mobius", "WarpAngles")) > 0.01


def test_textbook_hyperbolic_paraboloid_is_nowhere_and_torus_partly_single_curved():
    run = solved("textbook-ruled-surfaces")
    assert items(run, "hypar_analysis", "DevelopableFraction") == [0.0]
    gaussian = np.array(items(run, "torus_analysis", "Gaussian"))
    assert (gaussian > 1e-6).any() and (gaussian < -1e-6).any() and (np.abs(gaussian) < 1e-9).any()
    assert 0.0 < items(run, "torus_analysis", "DevelopableFraction")[0] < 0.05


def test_paper_strip_unrolls_with_no_length_error():
    run = solved("paper-strip")
    assert items(run, "unroll", "EdgeError")[0] < 1e-12
    assert abs(items(run, "unroll", "AreaError")[0]) < 1e-4
    assert len(items(run, "strip", "Rulings")) == 41


def test_spline_approximation_optimises_the_warp_away_and_the_finished_strip_is_developable():
    run = solved("spline-approximation")
    assert items(run, "approx", "Fitness")[0] < 0.01
    assert all(items(run, "finish", "Valid"))
    assert max(items(run, "finish", "WarpAngles")) < 1e-3


def test_panels_cover_the_development_and_have_ids():
    run = solved("development-and-panels")
    ids = items(run, "patching", "PanelIDs")
    areas = items(run, "patching", "PanelAreas")
    assert len(ids) == len(set(ids)) == len(areas) > 10
    development_area = items(run, "unroll", "AreaDevelopment")[0]
    assert sum(areas) == pytest.approx(development_area, rel=1e-6)
    assert items(run, "unroll", "EdgeError")[0] < 1e-12
    assert 0.0 <= items(run, "patching", "Waste")[0] < 1.0


def test_kaohsiung_cut_sheets_export_headless_as_dxf_svg_and_3dm(tmp_path, monkeypatch):
    import ezdxf
    import rhino3dm

    from app.cli import main

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
