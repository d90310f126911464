"""io.ExportCutSheet: DXF and SVG cut files that a laser or router takes as they are."""

from __future__ import annotations

import itertools
import math
import xml.etree.ElementTree as ET

import ezdxf
import numpy as np
import pytest
import shapely

from tests.support.io_helpers import polygon_area, random_panels, rectangle
from tests.support.node_helpers import allowed, out, run, texts, tree
from torsal.engine.solver import ERROR, OK
from torsal.nodes.geometry.curves import Circle, NurbsCurve, Polyline
from torsal.nodes.geometry.offset2d import offset_polygon
from torsal.nodes.geometry.packing import DoesNotFit, shelf_pack
from torsal.nodes.geometry.vectors import Plane
from torsal.nodes.io.cutting import ExportCutSheet
from torsal.nodes.io.formats import cutfiles

SVG = "{http://www.w3.org/2000/svg}"


def cut(tmp_path, panels, name="sheet.dxf", ids=None, **settings):
    inputs = {"Panels": tree({(0,): panels}), "Path": name, "Write": True, **settings}
    if ids is not None:
        inputs["PanelIDs"] = tree({(0,): ids})
    return run(ExportCutSheet(), writes=allowed(tmp_path), **inputs)


def closed_polylines(path, layer):
    doc = ezdxf.readfile(path)
    found = []
    for entity in doc.modelspace().query(f'LWPOLYLINE[layer=="{layer}"]'):
        assert entity.closed
        found.append(np.array([(x, y) for x, y, *_ in entity.get_points()]))
    return doc, found


# ------------------------------------------------------------------ DXF


def test_dxf_has_one_closed_polyline_per_panel_with_its_area_in_mm(tmp_path):
    panels = random_panels(30)
    result = cut(tmp_path, panels)
    assert result.state == OK, texts(result)
    files = out(result, "Paths")[(0,)]
    contours = []
    for file in files:
        doc, found = closed_polylines(file, "CUT")
        assert doc.dxfversion == "AC1024"  # R2010
        assert doc.header["$INSUNITS"] == 4  # millimetres
        contours += found
    assert len(contours) == len(panels)
    expected = sorted(polygon_area(p.points[:-1, :2]) * 1e6 for p in panels)
    got = sorted(polygon_area(c) for c in contours)
    assert np.allclose(got, expected, rtol=1e-6, atol=0)


def test_panel_areas_match_one_to_one_through_their_ids(tmp_path):
    panels = random_panels(12, seed=3)
    ids = [f"S1-{i}" for i in range(12)]
    result = cut(tmp_path, panels, ids=ids)
    (file,) = out(result, "Paths")[(0,)]
    doc = ezdxf.readfile(file)
    for entity in doc.modelspace().query('LWPOLYLINE[layer=="CUT"]'):
        name = entity.get_xdata("TORSAL")[0].value
        area = polygon_area(np.array([(x, y) for x, y, *_ in entity.get_points()]))
        panel = panels[ids.index(name)]
        assert area == pytest.approx(polygon_area(panel.points[:-1, :2]) * 1e6, rel=1e-6)


def test_no_two_panels_overlap_and_all_stay_on_their_sheet_less_its_margin(tmp_path):
    result = cut(tmp_path, random_panels(60, seed=11), Gap=5.0)
    files = out(result, "Paths")[(0,)]
    assert len(files) >= 2
    room = shapely.box(5, 5, 2495, 1245).buffer(1e-9, join_style="mitre")  # less the margin (the gap)
    for file in files:
        _, contours = closed_polylines(file, "CUT")
        polygons = [shapely.Polygon(c) for c in contours]
        assert all(p.is_valid and room.covers(p) for p in polygons)
        for a, b in itertools.combinations(polygons, 2):
            assert not a.intersects(b)
            assert a.distance(b) >= 5.0 - 1e-9


def test_several_sheets_are_numbered_files(tmp_path):
    result = cut(tmp_path, random_panels(60, seed=11), name="facade.dxf")
    files = out(result, "Paths")[(0,)]
    assert [f.rsplit("/", 1)[1] for f in files] == [f"facade-{i}.dxf" for i in range(1, len(files) + 1)]
    assert len(out(result, "Sheets")[(0,)]) == len(files)


def test_one_sheet_is_written_to_the_path_as_given(tmp_path):
    result = cut(tmp_path, [rectangle(0, 0, 1, 0.5)], name="one.dxf")
    assert out(result, "Paths") == {(0,): [str(tmp_path / "one.dxf")]}


def test_ids_are_engraved_inside_their_panels_as_closed_outlines(tmp_path):
    panels = [rectangle(0, 0, 1.2, 0.4), rectangle(3, 0, 0.5, 0.3)]
    result = cut(tmp_path, panels, ids=["A-01", "B-02"], TextHeight=20.0)
    (file,) = out(result, "Paths")[(0,)]
    _, contours = closed_polylines(file, "CUT")
    _, letters = closed_polylines(file, "ENGRAVE")
    assert len(letters) == len(cutfiles.text_outlines("A-01")) + len(cutfiles.text_outlines("B-02"))
    parts = [shapely.Polygon(c) for c in contours]
    for letter in letters:
        assert any(part.contains(shapely.Polygon(letter)) for part in parts)
    heights = sorted(np.ptp(np.vstack(letters), axis=0))
    assert heights[0] > 15.0  # cap height 20 mm: letters span more than 15 mm


def test_no_engraving_with_text_height_zero(tmp_path):
    result = cut(tmp_path, [rectangle(0, 0, 1, 1)], TextHeight=0.0)
    (file,) = out(result, "Paths")[(0,)]
    assert closed_polylines(file, "ENGRAVE")[1] == []


def test_narrow_panel_gets_a_smaller_label_or_a_remark(tmp_path):
    result = cut(tmp_path, [rectangle(0, 0, 1, 0.002)], ids=["LONG-NAME-1"])
    assert result.state == OK
    assert "Panel LONG-NAME-1 is too narrow for its ID at 2 mm: not engraved" in texts(result)


def test_curved_panels_are_flattened_within_a_hundredth_of_a_mm(tmp_path):
    disc = Circle(radius=0.3)
    result = cut(tmp_path, [disc])
    (file,) = out(result, "Paths")[(0,)]
    _, (contour,) = closed_polylines(file, "CUT")
    assert polygon_area(contour) == pytest.approx(math.pi * 300.0**2, rel=2 * 0.01 / 300)


def test_flat_panel_in_a_tilted_plane_is_laid_flat(tmp_path):
    tilted = Plane.from_axes(np.array([0.0, 0.0, 5.0]), np.array([1.0, 0.0, 1.0]), np.array([0.0, 1.0, 0.0]))
    uv = [(0, 0), (0.8, 0), (0.8, 0.3), (0, 0.3)]
    corners = [tilted.origin + a * tilted.x + b * tilted.y for a, b in uv]
    result = cut(tmp_path, [Polyline(corners, closed=True)])
    (file,) = out(result, "Paths")[(0,)]
    _, (contour,) = closed_polylines(file, "CUT")
    assert polygon_area(contour) == pytest.approx(800 * 300, rel=1e-9)


def test_degree_1_nurbs_panels_keep_their_exact_corners(tmp_path):
    square = NurbsCurve([[0, 0, 0], [0.5, 0, 0], [0.5, 0.5, 0], [0, 0.5, 0], [0, 0, 0]], degree=1)
    result = cut(tmp_path, [square])
    _, (contour,) = closed_polylines(out(result, "Paths")[(0,)][0], "CUT")
    assert len(contour) == 4 and polygon_area(contour) == pytest.approx(250000.0, rel=1e-12)


def test_a_development_surface_is_cut_along_its_boundary(tmp_path):
    from torsal.nodes.analysis.iso_mapping import IsoMapping
    from torsal.nodes.geometry.ruled import RuledSurface

    theta = np.linspace(0.0, 2.0, 9)
    ring = np.column_stack([np.cos(theta), np.sin(theta), np.zeros_like(theta)])
    cone = RuledSurface.from_rulings(ring, 0.5 * ring + np.array([0.0, 0.0, 0.6]))
    unrolled = run(IsoMapping(), Surface=tree({(0,): [cone]}), Segments=8)
    (development,) = out(unrolled, "Development")[(0,)]
    result = run(ExportCutSheet(), Surfaces=tree({(0,): [development]}), Path="d.dxf",
                 Write=True, writes=allowed(tmp_path))
    assert result.state == OK, texts(result)
    _, (contour,) = closed_polylines(out(result, "Paths")[(0,)][0], "CUT")
    assert polygon_area(contour) == pytest.approx(development.area() * 1e6, rel=1e-7)


# ------------------------------------------------------------------ kerf


def test_kerf_moves_the_cut_out_by_half_its_width_with_sharp_corners(tmp_path):
    result = cut(tmp_path, [rectangle(0, 0, 1, 0.5)], Kerf=0.2)
    _, (contour,) = closed_polylines(out(result, "Paths")[(0,)][0], "CUT")
    assert np.ptp(contour, axis=0).tolist() == pytest.approx([1000.2, 500.2], abs=1e-9)
    assert len(contour) == 4  # mitre joins: still a rectangle
    assert (out(result, "Layout")[(0,)][0]).kerf == 0.2


def test_offset_polygon_keeps_corners_sharp_and_area_grows_by_perimeter_times_offset():
    square = [[0, 0], [10, 0], [10, 10], [0, 10]]
    grown = offset_polygon(square, 0.5)
    assert grown.tolist() == [[-0.5, -0.5], [10.5, -0.5], [10.5, 10.5], [-0.5, 10.5]]
    assert polygon_area(offset_polygon(square, -1.0)) == pytest.approx(64.0)
    with pytest.raises(ValueError, match="does not leave one piece"):
        offset_polygon(square, -6.0)


# ------------------------------------------------------------------ SVG


def test_svg_is_xml_in_mm_with_red_hairline_cuts_and_blue_engraving(tmp_path):
    panels = random_panels(8, seed=5)
    result = cut(tmp_path, panels, name="sheet.svg", SheetWidth=1200.0, SheetHeight=800.0)
    assert result.state == OK, texts(result)
    files = out(result, "Paths")[(0,)]
    count = 0
    for file in files:
        root = ET.parse(file).getroot()
        assert root.tag == f"{SVG}svg"
        size = (root.get("width"), root.get("height"), root.get("viewBox"))
        assert size == ("1200mm", "800mm", "0 0 1200 800")
        groups = {g.get("id"): g for g in root.findall(f"{SVG}g")}
        cut_group, engrave_group = groups["CUT"], groups["ENGRAVE"]
        style = (cut_group.get("id"), cut_group.get("stroke"), cut_group.get("fill"))
        assert style == ("CUT", "#ff0000", "none")
        assert (engrave_group.get("stroke"), engrave_group.get("fill")) == ("#0000ff", "none")
        # a hairline: one pixel at any zoom (docs/cut-sheets.md)
        assert cut_group.get("vector-effect") == "non-scaling-stroke"
        assert float(cut_group.get("stroke-width")) == 1.0
        for path in cut_group.findall(f"{SVG}path"):
            numbers = np.array([[float(x) for x in pair.split(",")] for pair in path.get("d").split()
                                if "," in pair])
            assert numbers.min() >= 0 and numbers[:, 0].max() <= 1200 and numbers[:, 1].max() <= 800
            count += 1
    assert count == len(panels)


def test_svg_areas_match_the_panels(tmp_path):
    panels = random_panels(5, seed=9)
    result = cut(tmp_path, panels, name="a.svg")
    (file,) = out(result, "Paths")[(0,)]
    cut_group = ET.parse(file).getroot().find(f"{SVG}g[@id='CUT']")
    areas = []
    for path in cut_group.findall(f"{SVG}path"):
        pairs = [pair for pair in path.get("d").split() if "," in pair]
        areas.append(polygon_area(np.array([[float(x) for x in pair.split(",")] for pair in pairs])))
    expected = [polygon_area(p.points[:-1, :2]) * 1e6 for p in panels]
    assert np.allclose(sorted(areas), sorted(expected), rtol=1e-6)


# ------------------------------------------------------------------ units and outputs


def test_model_units_are_converted_to_mm(tmp_path):
    result = cut(tmp_path, [rectangle(0, 0, 100, 50)], Units="cm")
    _, (contour,) = closed_polylines(out(result, "Paths")[(0,)][0], "CUT")
    assert np.ptp(contour, axis=0).tolist() == pytest.approx([1000, 500])


def test_preview_outputs_are_in_model_units_and_nothing_is_written_while_write_is_false(tmp_path):
    target = tmp_path / "never.dxf"
    result = run(ExportCutSheet(), Panels=tree({(0,): [rectangle(0, 0, 1, 0.5)]}), Path=str(target))
    assert result.state == OK
    assert not target.exists()
    assert out(result, "Paths") == {(0,): []}
    (contour,) = out(result, "Cuts")[(0,)]
    (sheet,) = out(result, "Sheets")[(0,)]
    assert np.ptp(contour.points, axis=0)[:2].tolist() == pytest.approx([1.0, 0.5])
    assert np.ptp(sheet.points, axis=0)[:2].tolist() == pytest.approx([2.5, 1.25])
    assert out(result, "Usage")[(0,)][0] == pytest.approx(0.5 / (2.5 * 1.25))


def test_panels_from_several_branches_go_into_one_layout(tmp_path):
    panels = tree({(0,): [rectangle(0, 0, 1, 0.5)], (1,): [rectangle(0, 1, 1, 0.5), rectangle(2, 0, 1, 1)]})
    result = run(ExportCutSheet(), Panels=panels, Path="x.dxf", Write=True, writes=allowed(tmp_path))
    assert result.state == OK, texts(result)
    layout = out(result, "Layout")[(0,)][0]
    assert [p.id for p in layout.parts] == ["P-001", "P-002", "P-003"]


# ------------------------------------------------------------------ the pre-export check


@pytest.mark.parametrize(
    ("panels", "ids", "needle"),
    [
        ([rectangle(0, 0, 1, 1), Polyline([[0, 0, 0], [1, 0, 0], [1, 1, 0]])], ["A", "B"],
         "Panel B is open: its ends are 1414 mm apart"),
        ([Polyline([[0, 0, 0], [1, 1, 0], [1, 0, 0], [0, 1, 0]], closed=True)], ["Bow-tie"],
         "Panel Bow-tie's outline crosses or touches itself at (500, 500) mm"),
        ([rectangle(0, 0, 1, 1), rectangle(2, 0, 1, 1)], ["P-7", "P-7"], "are both called P-7"),
        ([rectangle(0, 0, 1, 1), rectangle(0, 0, 1, 1)], ["P-1", "P-2"],
         "Panels P-1 and P-2 are the same outline in the same place"),
        ([rectangle(0, 0, 1, 1), rectangle(0, 0, 2.6, 0.2)], ["ok", "Long"],
         "Panel Long is 2600.0 × 200.0 mm, larger than the 2500 × 1250 mm sheet"),
        ([Polyline([[0, 0, 0], [1, 0, 0], [1, 1, 0.5], [0, 1, 0]], closed=True)], ["Twisted"],
         "Panel Twisted is not flat"),
        ([rectangle(0, 0, 1, 1)], ["A", "B"], "There are 2 panel IDs for 1 panels"),
    ],
)
def test_pre_export_check_refuses_bad_panels_naming_them(tmp_path, panels, ids, needle):
    target = tmp_path / "refused.dxf"
    result = cut(tmp_path, panels, name="refused.dxf", ids=ids)
    assert result.state == ERROR
    (message,) = texts(result)
    assert needle in message
    assert not target.exists()


def test_kerf_counts_when_checking_the_sheet_size(tmp_path):
    result = cut(tmp_path, [rectangle(0, 0, 2.47, 0.2)], Kerf=1.0)
    assert result.state == OK  # 2470 + 1 + 2 × 10 fits in 2500
    result = cut(tmp_path, [rectangle(0, 0, 2.47, 0.2)], Kerf=1.0, Gap=15.0)
    assert result.state == ERROR
    assert "with its kerf" in texts(result)[0]


def test_panel_too_long_one_way_is_turned_to_fit(tmp_path):
    result = cut(tmp_path, [rectangle(0, 0, 1.1, 0.2)], SheetWidth=1000.0, SheetHeight=1250.0)
    assert result.state == OK, texts(result)
    _, (contour,) = closed_polylines(out(result, "Paths")[(0,)][0], "CUT")
    assert np.ptp(contour, axis=0).tolist() == pytest.approx([200, 1100])


def test_a_bad_extension_is_an_error(tmp_path):
    result = cut(tmp_path, [rectangle(0, 0, 1, 1)], name="sheet.pdf")
    assert result.state == ERROR
    assert "written as .dxf or .svg, not .pdf" in texts(result)[0]


# ------------------------------------------------------------------ kernel: packing


def test_shelf_packing_places_tallest_first_in_rows_without_overlap():
    sheet, corner = shelf_pack([[4, 2], [3, 1], [5, 2]], (10, 6), gap=0.5)
    assert sheet.tolist() == [0, 0, 0]
    assert corner.tolist() == [[0.5, 3.0], [6.0, 0.5], [0.5, 0.5]]


def test_shelf_packing_refuses_a_part_larger_than_the_sheet():
    with pytest.raises(DoesNotFit) as caught:
        shelf_pack([[1, 1], [11, 1]], (10, 6), gap=0.0)
    assert caught.value.index == 1


# ------------------------------------------------------------------ panels far larger than a sheet


@pytest.mark.parametrize("radius", [1.0, 1e12])
def test_a_flat_annulus_outline_stays_within_its_relative_tolerance_and_a_few_thousand_points(radius):
    # a flat half annulus between two concentric arcs: its outline points lie on the two
    # circles exactly; a 1e12 m one (a fuzzed site) must not be sampled to 0.01 mm
    from torsal.nodes.geometry.curves import Arc
    from torsal.nodes.geometry.ruled import RuledSurface

    outer = Arc(radius=2.0 * radius, start_angle=0.0, end_angle=math.pi)
    inner = Arc(radius=radius, start_angle=0.0, end_angle=math.pi)
    outline = cutfiles.surface_outline(RuledSurface(outer, inner), cutfiles.FLATTEN_MM / 1000.0)
    points = np.asarray(outline.points)
    curved = np.abs(points[:, 1]) > 1e-9 * radius  # the two straight ends lie on y = 0
    r = np.linalg.norm(points[curved, :2], axis=1)
    on_a_circle = np.minimum(np.abs(r - radius), np.abs(r - 2.0 * radius))
    assert on_a_circle.max() <= 1e-12 * radius
    # chords of sagitta 1e-7 of the 4r-wide panel: pi / sqrt(8e-7 * 4r / 2r) ~ 2,500 on
    # the outer arc, halving rounds up to 4,096; the inner arc half that
    assert len(points) <= 4097 + 2049 + 8
