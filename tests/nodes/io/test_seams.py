"""Seams on the cut sheets: strips that share a curve are neighbours, each seam's ID is
engraved on both parts with alignment ticks, and its two flat edge lengths are reported."""

from __future__ import annotations

import functools
import itertools
from pathlib import Path

import numpy as np
import pytest
import shapely

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.solver import OK
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.io.cutting import ExportCutSheet
from torsal.nodes.io.formats import cutfiles
from torsal.nodes.io.seams import TICK_MM, edge_polyline, find_seams, length

EXAMPLE = Path(__file__).resolve().parents[3] / "torsal" / "resources" / "examples" / (
    "kaohsiung-cut-sheets.graph"
)


def band(y0: float, y1: float, length: float = 1.0, bend: float = 0.0) -> RuledSurface:
    """A flat band between y = y0 and y = y1 along x (bend > 0 curves it up in z)."""
    x = np.linspace(0.0, length, 9)
    z = bend * (x / length) ** 2
    return RuledSurface.from_rulings(np.column_stack([x, np.full(9, y0), z]),
                                     np.column_stack([x, np.full(9, y1), z]))


def normalised(glyphs):
    every = np.vstack(glyphs)
    low, high = every.min(axis=0), every.max(axis=0)
    return [(g - low) / (high - low)[1] for g in glyphs]


def carries(part, text):
    """Whether the part's seam labels hold ``text``'s letter outlines (any size and place)."""
    expected = normalised(cutfiles.text_outlines(text))
    labels = part.seam_labels
    for start in range(len(labels) - len(expected) + 1):
        run_ = labels[start:start + len(expected)]
        if all(a.shape == b.shape for a, b in zip(run_, expected, strict=True)):
            got = normalised(run_)
            if all(np.allclose(a, b, atol=1e-9) for a, b in zip(got, expected, strict=True)):
                return True
    return False


def test_strips_sharing_an_edge_are_found_as_one_seam_and_others_not():
    strips = [band(0.0, 0.3), band(0.3, 0.5), band(2.0, 2.4)]
    (seam,) = find_seams(strips)
    assert (seam.id, seam.a, seam.b) == ("S1", 0, 1)
    assert {seam.edge_a, seam.edge_b} == {2, 0}  # v = 1 of the first is v = 0 of the second


def test_a_polyline_edge_is_measured_through_its_vertices():
    # a flat strip whose rails are polylines with corners (IsoMapping's Development is one):
    # rail A is a zigzag of 7 legs, each of length hypot(1/7, 0.02) (corners off the
    # tessellation's own dyadic parameters)
    x = np.linspace(0.0, 1.0, 8)
    a = np.column_stack([x, 0.02 * (np.arange(8) % 2), np.zeros(8)])
    strip = RuledSurface.from_rulings(a, a + np.array([0.0, 0.5, 0.0]), degree=1)
    edge = edge_polyline(strip, 0, 1e-3)
    assert length(edge) == pytest.approx(7 * np.hypot(1 / 7, 0.02), rel=1e-12)
    assert length(edge_polyline(strip, 2, 1e-3)) == pytest.approx(7 * np.hypot(1 / 7, 0.02), rel=1e-12)


def test_a_seam_between_flat_bands_has_equal_lengths_an_id_on_both_parts_and_ticks(tmp_path):
    strips = [band(0.0, 0.3), band(0.3, 0.5)]
    result = run(ExportCutSheet(), Surfaces=tree({(0,): strips}), Strips=tree({(0,): strips}),
                 TickSpacing=100.0, TextHeight=20.0)
    assert result.state == OK, texts(result)
    assert out(result, "SeamDifferences")[(0,)] == [pytest.approx(0.0, abs=1e-9)]
    layout = out(result, "Layout")[(0,)][0]
    first, second = layout.parts
    assert carries(first, "S1") and carries(second, "S1")
    # a 1000 mm seam, ticks every 100 mm up to half a spacing from the end: 9 on each part
    for part in layout.parts:
        assert len(part.ticks) == 9
        boundary = shapely.Polygon(part.panel).exterior
        polygon = shapely.Polygon(part.panel)
        for tick in part.ticks:
            assert boundary.distance(shapely.Point(tick[0])) < 1e-6  # on the edge
            assert polygon.contains(shapely.Point(tick[1]))  # pointing in
            assert np.linalg.norm(tick[1] - tick[0]) == pytest.approx(TICK_MM)


def test_ticks_are_at_the_same_distances_from_the_same_end_on_both_parts():
    strips = [band(0.0, 0.3), band(0.3, 0.5)]
    result = run(ExportCutSheet(), Surfaces=tree({(0,): strips}), Strips=tree({(0,): strips}),
                 TickSpacing=130.0, Rotate=False, Nesting="Shelf")
    first, second = out(result, "Layout")[(0,)][0].parts
    # not turned: both bands keep x along the seam, so the ticks' x from the parts' left ends agree
    xs = [np.sort([t[0][0] for t in p.ticks]) - p.panel[:, 0].min() for p in (first, second)]
    assert np.allclose(xs[0], xs[1], atol=1e-6)
    # from the end where the first strip's edge v = 1 starts (u = 1, x = 1000 mm)
    assert np.allclose(xs[0], np.sort(1000.0 - 130.0 * np.arange(1, 8)), atol=1e-6)


def test_the_seams_are_engraved_in_the_dxf(tmp_path):
    from tests.support.node_helpers import allowed

    strips = [band(0.0, 0.3), band(0.3, 0.5)]
    result = run(ExportCutSheet(), Surfaces=tree({(0,): strips}), Strips=tree({(0,): strips}),
                 Path="s.dxf", Write=True, writes=allowed(tmp_path), TickSpacing=100.0)
    import ezdxf

    (file,) = out(result, "Paths")[(0,)]
    engraved = ezdxf.readfile(file).modelspace().query('LWPOLYLINE[layer=="ENGRAVE"]')
    assert sum(1 for e in engraved if not e.closed) == 18  # the ticks, open polylines


@functools.cache
def kaohsiung():
    from torsal.app.headless import run_file

    solved = run_file(EXAMPLE)
    strips = solved.solver.result("strip").outputs["Surface"].all_items()
    developments = solved.solver.result("unroll").outputs["Development"].all_items()
    if not strips or len(strips) != len(developments):
        pytest.skip("the Kaohsiung example gives no strips here")
    result = run(ExportCutSheet(), Surfaces=tree({(0,): developments}), Strips=tree({(0,): strips}),
                 SheetWidth=100000.0, SheetHeight=50000.0, TextHeight=200.0)  # 1:1, in mm
    assert result.state == OK, texts(result)
    return out(result, "Layout")[(0,)][0]


def test_kaohsiung_neighbouring_strips_meet_at_a_seam_each_with_its_id_on_both_parts():
    layout = kaohsiung()
    assert len(layout.seams) == len(layout.parts) - 1  # a row of strips, each meeting the next
    parts = {p.id: p for p in layout.parts}
    for seam in layout.seams:
        assert carries(parts[seam.part_a], seam.id) and carries(parts[seam.part_b], seam.id)


def test_kaohsiung_seams_close_to_a_hundredth_of_a_mm_at_full_size():
    seams = kaohsiung().seams
    assert len(seams) == len(kaohsiung().parts) - 1
    assert max(s.difference for s in seams) <= 0.01


def test_kaohsiung_seams_are_as_long_flat_as_the_shared_curve_in_3d():
    """Each flat side of a seam is as long as the 3D edge it was unrolled from: the arc length
    of the shared curve, integrated here with scipy's Gauss–Legendre rule on pieces between
    the rail's kinks (not the unroller's chords), at 1:1 in mm."""
    from itertools import pairwise

    from scipy.integrate import fixed_quad

    from torsal.app.headless import run_file

    solved = run_file(EXAMPLE)
    strips = solved.solver.result("strip").outputs["Surface"].all_items()
    layout = kaohsiung()
    parts = {p.id: i for i, p in enumerate(layout.parts)}
    for seam, found in zip(layout.seams, find_seams(strips), strict=True):
        curve = strips[found.a].edges()[found.edge_a]
        # pieces end where the rail is not smooth: its rulings and where it crosses a knot
        rail = strips[found.a].curve_a if found.edge_a == 0 else strips[found.a].curve_b
        kinks = rail._breakpoints() if found.edge_a == 0 else 1.0 - rail._breakpoints()
        breaks = np.unique(np.concatenate([np.linspace(0.0, 1.0, 257), kinks]))

        def speed(t: np.ndarray, curve=curve) -> np.ndarray:  # type: ignore[no-untyped-def]
            return np.linalg.norm(curve.derivatives(np.ravel(t), 1)[1], axis=1).reshape(np.shape(t))

        arc = 1000.0 * sum(fixed_quad(speed, lo, hi, n=16)[0] for lo, hi in pairwise(breaks))
        assert parts[seam.part_a] == found.a
        assert seam.length_a == pytest.approx(arc, abs=0.005)
        assert seam.length_b == pytest.approx(arc, abs=0.005)


def _label_boxes(part, seam_ids):
    """The envelope of each label on a part: its ID, then each of its seams' IDs in order."""
    boxes = [shapely.MultiPolygon([shapely.Polygon(g) for g in part.label]).envelope] if part.label else []
    glyphs = list(part.seam_labels)
    for seam_id in seam_ids:
        count = len(cutfiles.text_outlines(seam_id))
        these, glyphs = glyphs[:count], glyphs[count:]
        boxes.append(shapely.MultiPolygon([shapely.Polygon(g) for g in these]).envelope)
    assert not glyphs
    return boxes


@pytest.mark.parametrize("width", [0.025, 0.04, 0.08])
def test_labels_on_narrow_parts_never_overlap_and_every_seam_is_labelled_on_both_parts(width):
    """A narrow strip between two wide ones (the canopy's 4-12 cm strips at 1:1): its ID and
    both its seams' IDs are engraved, none on top of another or of a tick."""
    strips = [band(0.0, 0.3), band(0.3, 0.3 + width), band(0.3 + width, 0.6 + width)]
    result = run(ExportCutSheet(), Surfaces=tree({(0,): strips}), Strips=tree({(0,): strips}),
                 TickSpacing=50.0, TextHeight=10.0)
    assert result.state == OK, texts(result)
    assert not [t for t in texts(result) if "does not fit" in t or "too narrow" in t], texts(result)
    layout = out(result, "Layout")[(0,)][0]
    assert [s.id for s in layout.seams] == ["S1", "S2"]
    seams_of = {p.id: [s.id for s in layout.seams if p.id in (s.part_a, s.part_b)] for p in layout.parts}
    for part in layout.parts:
        assert part.label, part.id
        boxes = _label_boxes(part, seams_of[part.id])
        assert len(boxes) == 1 + len(seams_of[part.id])
        for a, b in itertools.combinations(boxes, 2):
            assert not a.intersects(b), part.id
        ticks = shapely.MultiLineString([t for t in part.ticks])
        assert not any(box.intersects(ticks) for box in boxes), part.id
        assert all(shapely.Polygon(part.panel).contains(box) for box in boxes)
