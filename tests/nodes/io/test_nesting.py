"""True-shape nesting (sparrow), kerf offsets and the SHEET / REFERENCE layers, checked
independently with shapely on what the DXF and SVG files hold. Budgets are 1-2 s."""

from __future__ import annotations

import itertools
import math
import threading
import time
import xml.etree.ElementTree as ET

import ezdxf
import numpy as np
import pytest
import shapely

from tests.support.io_helpers import random_panels, rectangle
from tests.support.node_helpers import Source, allowed, out, run, texts, tree
from torsal.engine.graph import Graph
from torsal.engine.node import CancelToken
from torsal.engine.solver import OK, Solver
from torsal.nodes.geometry.curves import Circle, Polyline
from torsal.nodes.geometry.nesting import nest, place
from torsal.nodes.io.cutting import ExportCutSheet
from torsal.nodes.io.formats import cutfiles

SVG = "{http://www.w3.org/2000/svg}"


def cut(tmp_path, panels, name="sheet.dxf", **settings):
    inputs = {"Panels": tree({(0,): panels}), "Path": name, "Write": True, "Nesting": "TrueShape",
              "TimeBudget": 1.0, **settings}
    result = run(ExportCutSheet(), writes=allowed(tmp_path), **inputs)
    assert result.state == OK, texts(result)
    return result


def layer(path, name):
    doc = ezdxf.readfile(path)
    found = []
    for entity in doc.modelspace().query(f'LWPOLYLINE[layer=="{name}"]'):
        assert entity.closed
        found.append(np.array([(x, y) for x, y, *_ in entity.get_points()]))
    return doc, found


def check_sheets(files, width, height, margin, gap):
    """Every cut contour simple and inside the sheet less its margin, no two closer than
    the gap less 0.01 mm; returns the contours per sheet."""
    room = shapely.box(margin, margin, width - margin, height - margin)
    sheets = []
    for file in files:
        _, contours = layer(file, "CUT")
        polygons = [shapely.Polygon(c) for c in contours]
        for polygon in polygons:
            assert polygon.is_valid and polygon.exterior.is_simple
            assert room.buffer(1e-9).covers(polygon)
        for a, b in itertools.combinations(polygons, 2):
            assert a.distance(b) >= gap - 0.01
        sheets.append(polygons)
    return sheets


def triangles(count):
    """Right triangles 1.0 × 0.5 m: two make a rectangle, so they nest in pairs."""
    return [Polyline([[2 * i, 0, 0], [2 * i + 1.0, 0, 0], [2 * i, 0.5, 0]], closed=True)
            for i in range(count)]


# ------------------------------------------------------------------ layouts


def test_true_shape_layout_keeps_gap_and_margin_on_every_sheet(tmp_path):
    result = cut(tmp_path, random_panels(24, seed=4), Gap=6.0, Margin=15.0, SheetWidth=1500.0,
                 SheetHeight=1000.0)
    files = out(result, "Paths")[(0,)]
    sheets = check_sheets(files, 1500.0, 1000.0, 15.0, 6.0)
    assert sum(len(s) for s in sheets) == 24


def test_true_shape_pairs_triangles_onto_one_sheet_where_shelf_needs_two(tmp_path):
    shelf = run(ExportCutSheet(), Panels=tree({(0,): triangles(8)}), Nesting="Shelf")
    assert out(shelf, "Layout")[(0,)][0].sheets == 2  # 4 bounding rectangles of 1000 × 500 per sheet
    result = cut(tmp_path, triangles(8), TimeBudget=2.0)
    (file,) = out(result, "Paths")[(0,)]
    check_sheets([file], 2500.0, 1250.0, 10.0, 10.0)


def test_grain_turns_parts_only_by_0_or_180_degrees(tmp_path):
    panels = random_panels(10, seed=8)
    result = cut(tmp_path, panels, Grain=True)
    layout = out(result, "Layout")[(0,)][0]
    for part, panel in zip(layout.parts, panels, strict=True):
        drawn = panel.points[:-1, :2] * 1000.0
        edge, placed = drawn[1] - drawn[0], part.panel[1] - part.panel[0]
        assert np.allclose(placed, edge, atol=1e-6) or np.allclose(placed, -edge, atol=1e-6)


def test_rotate_false_keeps_every_part_as_drawn(tmp_path):
    panels = random_panels(6, seed=2)
    layout = out(cut(tmp_path, panels, Rotate=False), "Layout")[(0,)][0]
    for part, panel in zip(layout.parts, panels, strict=True):
        drawn = panel.points[:-1, :2] * 1000.0
        assert np.allclose(part.panel - part.panel[0], drawn - drawn[0], atol=1e-6)


def test_nest_stopped_at_once_still_places_every_part_apart():
    shapes = [np.asarray(p.points[:-1, :2]) * 1000 for p in random_panels(12, seed=6)]
    started = time.perf_counter()
    nested = nest(shapes, 2500.0, 1250.0, 10.0, 10.0, budget=30.0, stop=lambda: True)
    assert nested.stopped and time.perf_counter() - started < 5.0
    polygons = [(s, shapely.Polygon(place(shape, a, t)))
                for shape, s, a, t in zip(shapes, nested.sheet, nested.angle, nested.shift, strict=True)]
    room = shapely.box(10, 10, 2490, 1240).buffer(1e-9)
    assert all(room.covers(p) for _, p in polygons)
    for (s, a), (t, b) in itertools.combinations(polygons, 2):
        assert s != t or a.distance(b) >= 10.0 - 0.01


def test_nest_stopped_midway_keeps_the_best_layout_found_and_reports_progress():
    shapes = [np.asarray(p.points[:-1, :2]) * 1000 for p in random_panels(12, seed=6)]
    started = time.perf_counter()
    fractions: list[float] = []
    nested = nest(shapes, 2500.0, 1250.0, 10.0, 10.0, budget=30.0,
                  stop=lambda: time.perf_counter() - started > 1.5, report=fractions.append)
    assert nested.stopped and time.perf_counter() - started < 5.0
    assert fractions == sorted(fractions) and fractions[-1] == 1.0 and 0 < fractions[0] < 0.2
    assert nested.sheets >= 1 and (nested.sheet >= 0).all()


def test_the_node_keeps_its_best_layout_when_cancelled_and_reports_progress():
    graph = Graph()
    graph.add_node(Source(tree({(0,): random_panels(6, seed=1)})), "panels")
    graph.add_node(ExportCutSheet(), "cut")
    graph.connect("panels", "Tree", "cut", "Panels")
    for name, value in (("Nesting", "TrueShape"), ("TimeBudget", 30.0)):
        graph.set_input_value("cut", name, value)
    token, heard = CancelToken(), []
    threading.Timer(1.5, token.cancel).start()
    started = time.perf_counter()
    solver = Solver(graph)
    solver.solve(token, node_progress=lambda node, f: heard.append((node, f)))
    assert time.perf_counter() - started < 6.0
    result = solver.result("cut")
    assert "Nesting was stopped: this is the best layout found by then" in texts(result)
    assert len(out(result, "Layout")[(0,)][0].parts) == 6
    assert {node for node, _ in heard} == {"cut"} and heard[-1][1] == 1.0


# ------------------------------------------------------------------ kerf


def _kerf_errors(part, half):
    """How far the cut contour is from the mitred offset of the panel by ``half``: each
    contour edge must be parallel to its panel edge (largest sine of the angle between them
    times the edge's length, mm) and lie ``half`` from the panel (error at its midpoint, mm,
    measured by shapely: the midpoint of an offset edge is nearest its own panel edge)."""
    cut, panel = part.outline, part.panel
    assert len(cut) == len(panel)
    cut = np.roll(cut, -int(np.argmin(np.linalg.norm(cut - panel[0], axis=1))), axis=0)  # corner by corner
    cut_edges, panel_edges = np.roll(cut, -1, axis=0) - cut, np.roll(panel, -1, axis=0) - panel
    cross = cut_edges[:, 0] * panel_edges[:, 1] - cut_edges[:, 1] * panel_edges[:, 0]
    skew = float(np.abs(cross / np.linalg.norm(panel_edges, axis=1)).max())
    middles = shapely.points(cut + cut_edges / 2)
    distance = shapely.distance(middles, shapely.Polygon(panel).exterior)
    return skew, float(np.abs(distance - half).max())


@pytest.mark.parametrize("nesting", ["Shelf", "TrueShape"])
def test_kerf_offset_of_a_square_is_exact_to_a_millionth_of_a_mm(tmp_path, nesting):
    result = cut(tmp_path, [rectangle(0, 0, 0.4, 0.4)], Kerf=0.3, Nesting=nesting)
    (file,) = out(result, "Paths")[(0,)]
    _, (contour,) = layer(file, "CUT")
    assert np.ptp(contour, axis=0) == pytest.approx([400.3, 400.3], abs=1e-6)
    part = out(result, "Layout")[(0,)][0].parts[0]
    assert max(_kerf_errors(part, 0.15)) <= 1e-6
    expected = shapely.Polygon(part.panel).buffer(0.15, join_style="mitre")
    assert shapely.Polygon(part.outline).exterior.hausdorff_distance(expected.exterior) <= 1e-6


def test_kerf_offset_of_a_circle_is_exact_to_a_millionth_of_a_mm(tmp_path):
    result = cut(tmp_path, [Circle(radius=0.2)], Kerf=0.25, Nesting="Shelf")
    part = out(result, "Layout")[(0,)][0].parts[0]
    assert max(_kerf_errors(part, 0.125)) <= 1e-6


# ------------------------------------------------------------------ SHEET and REFERENCE layers


def test_dxf_has_an_unplotted_sheet_border_and_optional_reference_outlines(tmp_path):
    result = cut(tmp_path, [rectangle(0, 0, 1, 0.5), rectangle(2, 0, 0.5, 0.5)], Kerf=0.2,
                 Reference=True, SheetWidth=2000.0, SheetHeight=1000.0)
    (file,) = out(result, "Paths")[(0,)]
    doc, (border,) = layer(file, "SHEET")
    assert shapely.Polygon(border).equals(shapely.box(0, 0, 2000, 1000))
    assert doc.layers.get("SHEET").dxf.plot == 0 and doc.layers.get("REFERENCE").dxf.plot == 0
    _, references = layer(file, "REFERENCE")
    assert sorted(round(shapely.Polygon(r).area) for r in references) == [250000, 500000]
    _, contours = layer(file, "CUT")
    for reference in references:  # each drawn outline lies inside its cut contour, kerf/2 away
        polygon = shapely.Polygon(reference)
        (owner,) = [c for c in contours if shapely.Polygon(c).contains(polygon)]
        assert shapely.Polygon(owner).exterior.distance(polygon.exterior) == pytest.approx(0.1, abs=1e-6)


def test_no_reference_layer_entities_unless_asked(tmp_path):
    (file,) = out(cut(tmp_path, [rectangle(0, 0, 1, 0.5)], Kerf=0.2), "Paths")[(0,)]
    assert layer(file, "REFERENCE")[1] == []


def test_svg_has_the_sheet_border_and_reference_groups(tmp_path):
    result = cut(tmp_path, [rectangle(0, 0, 1, 0.5)], name="s.svg", Reference=True, SheetWidth=1200.0,
                 SheetHeight=800.0)
    (file,) = out(result, "Paths")[(0,)]
    groups = {g.get("id"): g for g in ET.parse(file).getroot().findall(f"{SVG}g")}
    assert set(groups) == {"SHEET", "REFERENCE", "CUT", "ENGRAVE"}
    (border,) = groups["SHEET"].findall(f"{SVG}path")
    corners = [tuple(float(x) for x in pair.split(",")) for pair in border.get("d").split() if "," in pair]
    assert sorted(corners) == [(0, 0), (0, 800), (1200, 0), (1200, 800)]
    assert len(groups["REFERENCE"].findall(f"{SVG}path")) == 1


# ------------------------------------------------------------------ settings


@pytest.mark.parametrize(
    ("settings", "needle"),
    [
        ({"Nesting": "Best"}, "Nesting is 'Best': use TrueShape or Shelf"),
        ({"TimeBudget": 0.0}, "TimeBudget must be between 1 and 3600 s"),
        ({"Seed": 1.5}, "Seed must be a whole number"),
        ({"Margin": 700.0}, "A margin of 700 mm on each side leaves no room"),
    ],
)
def test_bad_nesting_settings_are_refused_naming_the_input(settings, needle):
    result = run(ExportCutSheet(), Panels=tree({(0,): [rectangle(0, 0, 1, 0.5)]}),
                 **{"Nesting": "TrueShape", **settings})
    assert needle in texts(result)[0]


def test_stock_usage_counts_the_last_sheet_up_to_its_parts(tmp_path):
    layout = out(cut(tmp_path, [rectangle(0, 0, 0.5, 0.5)], Nesting="Shelf"), "Layout")[(0,)][0]
    assert layout.last_length == pytest.approx(510.0)  # 10 mm margin + 500 mm part
    assert layout.stock_usage == pytest.approx(500 * 500 / (510 * 1250))
    assert math.isclose(layout.usage, 500 * 500 / (2500 * 1250))


def test_layout_area_is_kept_under_true_shape_nesting(tmp_path):
    panels = random_panels(10, seed=12)
    layout = out(cut(tmp_path, panels), "Layout")[(0,)][0]
    expected = sorted(shapely.Polygon(p.points[:-1, :2] * 1000).area for p in panels)
    assert np.allclose(sorted(shapely.Polygon(p.outline).area for p in layout.parts), expected, rtol=1e-9)
    assert layout.nesting == cutfiles.TRUE_SHAPE


def test_a_failing_nesting_engine_is_an_error_saying_so(monkeypatch):
    import subprocess

    from torsal.nodes.geometry import sparrow_runs

    real = subprocess.Popen

    def broken(args, **kwargs):  # the worker as it fails without spyrrow installed
        code = "import sys; sys.stdin.read(); raise ModuleNotFoundError(\"No module named 'spyrrow'\")"
        return real([args[0], "-c", code], **kwargs)

    monkeypatch.setattr(sparrow_runs.subprocess, "Popen", broken)
    result = run(ExportCutSheet(), Panels=tree({(0,): [rectangle(0, 0, 1, 0.5)]}), Nesting="TrueShape")
    (message,) = texts(result)
    assert "TrueShape nesting failed: the nesting engine (sparrow) stopped with ModuleNotFound" in message
    assert "Nesting = Shelf still works" in message


RECTANGLES = [rectangle(3 * i, 0, 1.2, 0.6) for i in range(8)]


@pytest.mark.parametrize("panels", [random_panels(30, seed=21), RECTANGLES], ids=["random", "rectangles"])
def test_true_shape_never_takes_more_stock_than_shelf_packing(panels):
    def layout(nesting):
        result = run(ExportCutSheet(), Panels=tree({(0,): panels}), Nesting=nesting, TimeBudget=1.0)
        return out(result, "Layout")[(0,)][0]

    shelf, true = layout("Shelf"), layout("TrueShape")
    assert (true.sheets, true.last_length) <= (shelf.sheets, shelf.last_length + 1e-9)


# ------------------------------------------------------------------ repeatability


def _nested_once(shapes, budget=2.0):
    from torsal.nodes.geometry import nesting

    nesting.PACKED.clear()  # the cache would answer a repeat without searching
    return nest(shapes, 1250.0, 1250.0, 10.0, 10.0, budget=budget, seed=3)


def test_the_same_parts_and_seed_give_the_same_layout_even_on_a_busy_machine():
    """The budget is counted in sparrow's steps, not seconds: a run alone and one beside
    three others that each run a sparrow worker too (so the machine is busy) agree to the bit."""
    shapes = [np.asarray(p.points[:-1, :2]) * 1000 for p in random_panels(16, seed=4)]
    alone = _nested_once(shapes)
    busy: list = []
    threads = [threading.Thread(target=lambda k=k: busy.append(
        nest(shapes, 1250.0, 1250.0, 10.0, 10.0, budget=2.0, seed=3 + k))) for k in range(1, 4)]
    for thread in threads:
        thread.start()
    again = _nested_once(shapes)
    for thread in threads:
        thread.join()
    assert not alone.on_the_clock and not again.on_the_clock
    assert alone.sheets == again.sheets and alone.steps == again.steps
    np.testing.assert_array_equal(alone.sheet, again.sheet)
    np.testing.assert_array_equal(alone.angle, again.angle)
    np.testing.assert_array_equal(alone.shift, again.shift)


def test_a_sheet_is_cut_where_the_strip_holds_the_most_part_area():
    """Three 100 mm squares at x = 0, 300 and 600 along a strip, a 500 mm sheet with a
    10 mm margin: from 0 the sheet holds the first two (from x = 290 too, but later); a
    120 mm square at 900 makes the stretches holding the third and it the best, the first
    of them ending where the big one ends plus the margin: 1020 + 10 - 500 = 530."""
    from torsal.nodes.geometry.nesting import _window

    def squares(*corners_and_sides):
        return {k: shapely.box(x, 10, x + side, 10 + side) for k, (x, side) in enumerate(corners_and_sides)}

    small = squares((10, 100), (300, 100), (600, 100))
    assert _window(small, np.array([1e4, 1e4, 1e4]), 500.0, 10.0) == 0.0
    big = squares((10, 100), (300, 100), (600, 100), (900, 120))
    assert _window(big, np.array([1e4, 1e4, 1e4, 14400]), 500.0, 10.0) == pytest.approx(530.0)


def test_a_sheets_parts_are_chosen_largest_first_each_that_keeps_within_its_target():
    """Areas 50, 40, 30, 22 and 5. Towards 100: 50 + 40, the 30 and the 22 would pass 100,
    the 5 not: 95. Towards 117: 50 + 40, the 30 would pass, the 22 and the 5 not: 117."""
    from torsal.nodes.geometry.nesting import _choose

    area = np.array([50.0, 40.0, 30.0, 22.0, 5.0])
    assert _choose(range(5), area, 100.0) == [0, 1, 4]
    assert _choose(range(5), area, 117.0) == [0, 1, 3, 4]
    assert _choose([2, 3, 4], area, 1.0) == [2]  # at least the largest


def _in_a_row(first_seed_from: float | None = None, first_seed_gap: float | None = None):  # type: ignore[no-untyped-def]
    """A stand-in for sparrow's strip packing: the parts in a row along the strip's middle,
    ``spacing`` apart from x = ``spacing`` (seed 0's from ``first_seed_from``, ``first_seed_gap``
    apart, when given), odd seeds' in reverse order."""

    def row(shapes, members, height, spacing, orientations, steps, seed, budget, enough=0.0, failures=1,
            better=None, halt=None, counted=True, turn=0.0, workers=None):
        budget.spend(10 if counted else 0)
        spread = seed == 0 and first_seed_gap is not None
        gap = first_seed_gap if spread else spacing
        placed, x = {}, first_seed_from if spread else spacing
        for i in (members if seed % 2 == 0 else list(members)[::-1]):
            w = float(np.ptp(shapes[i][:, 0]))
            placed[i] = (0.0, (x + w / 2, height / 2))
            x += w + gap
        if better is not None:
            better(placed)
        return placed

    return row


def test_a_sheet_takes_the_first_seeds_packing_when_it_fits_and_the_rest_fill_the_last(monkeypatch):
    """With a stand-in for sparrow that lays the parts in a row, 1 mm apart, in the order
    asked (reversed for odd seeds): full-height bars 200, 150, 120, 100 and 60 mm wide,
    a sheet with 500 mm of room (502 × 102, margin and gap 1). The sheet's set towards
    ``SHEET_TARGET`` of its area (0.72 × 502 × 102 = 36,867 mm², each bar 100 mm tall):
    200 + 150 (35,000); the 120, 100 and 60 would each pass it. Those three (28,000 mm²,
    within 0.8 of the 500 × 100 usable sheet) are the last sheet, packed beside it, on one
    thread (the set on sparrow's usual two)."""
    from torsal.nodes.geometry import nesting, sparrow_runs

    row, threads = _in_a_row(), {}

    def counted_row(shapes, members, *args, workers=None, **kwargs):  # type: ignore[no-untyped-def]
        threads[tuple(members)] = workers
        return row(shapes, members, *args, **kwargs)

    monkeypatch.setattr(sparrow_runs, "strip", counted_row)
    monkeypatch.setattr(nesting, "strip", counted_row)
    bars = [np.array([[0, 0], [w, 0], [w, 100], [0, 100]], dtype=float) for w in (200, 150, 120, 100, 60)]
    nested = nest(bars, 502.0, 102.0, margin=1.0, spacing=1.0, budget=10.0)
    assert nested.sheet.tolist() == [0, 0, 1, 1, 1]
    assert threads == {(0, 1): None, (2, 3, 4): 1}  # None: sparrow_runs.WORKERS
    first = [place(bars[i], nested.angle[i], nested.shift[i])[:, 0].min() for i in (0, 1)]
    assert first == pytest.approx([1.0, 202.0])  # the first seed's order (the odd one's is reversed)


@pytest.mark.parametrize("gap", [None, 150.0])
def test_many_sheets_take_sparrows_first_packing_cut_into_sheets_when_it_fills_them_to_the_target(
        monkeypatch, gap):
    """Twenty bars 100 × 100 mm (four sheets' worth of the 500 × 100 mm of room on a 502 × 102
    sheet, margin and gap 1) from a stand-in for sparrow that lays them in a row. 1 mm apart, the
    first packing cut into sheets holds four bars a sheet, the last sheet to its bars' reach
    (404 mm): 200,000 mm² over 4 × 502 × 102 + 405 × 102 mm², 81 % of the stock, above
    ``SHEET_TARGET``: that is the layout, asked with no step of sparrow's search. 150 mm apart,
    two bars a sheet (39 %): the same strip (the same seed) is searched on."""
    from torsal.nodes.geometry import nesting, sparrow_runs

    row, asked = _in_a_row(first_seed_from=1.0, first_seed_gap=gap), []

    def recorded(shapes, members, height, spacing, orientations, steps, seed, *args, **kwargs):  # type: ignore[no-untyped-def]
        asked.append((steps, seed))
        return row(shapes, members, height, spacing, orientations, steps, seed, *args, **kwargs)

    monkeypatch.setattr(sparrow_runs, "strip", recorded)
    monkeypatch.setattr(nesting, "strip", recorded)
    bars = [np.array([[0, 0], [100, 0], [100, 100], [0, 100]], dtype=float) for _ in range(20)]
    nested = nest(bars, 502.0, 102.0, margin=1.0, spacing=1.0, budget=10.0, seed=0)
    if gap is None:
        assert asked == [(0, 0)]
        assert nested.sheets == 5 and np.bincount(nested.sheet).tolist() == [4, 4, 4, 4, 4]
    else:
        assert asked[0] == (0, 0) and asked[1][0] >= sparrow_runs.FEWEST and asked[1][1] == 0


def test_a_strip_is_cut_into_sheets_where_no_part_crosses_a_sheet_end():
    """Squares 100 mm wide in a strip at x = 10, 120, 230, 340 and 450 cut into sheets of 300
    with a 10 mm margin: the first sheet starts at 0 and holds the parts ending by 290 (two);
    the next starts 10 before the first part left (220) and holds those ending by 510 (two);
    the last starts at 440."""
    from torsal.nodes.geometry.nesting import _cut

    squares = {k: shapely.box(x, 10, x + 100, 110) for k, x in enumerate((10, 120, 230, 340, 450))}
    assert _cut(squares, 300.0, 10.0) == [(0.0, [0, 1]), (220.0, [2, 3]), (440.0, [4])]
    longer = {0: shapely.box(10, 10, 400, 110)}
    assert _cut(longer, 300.0, 10.0) == []


def test_the_parts_kept_are_those_a_pairwise_check_keeps():
    """200 random squares, some closer than the spacing, some off the room: the parts kept
    (measured only against near ones, an STRtree) are those a check of every pair keeps,
    largest first."""
    from torsal.nodes.geometry.sparrow_runs import valid as _valid

    rng = np.random.default_rng(7)
    corners, sides = rng.uniform(0, 1000, (200, 2)), rng.uniform(5, 40, 200)
    polygons = {k: shapely.box(x, y, x + s, y + s)
                for k, ((x, y), s) in enumerate(zip(corners, sides, strict=True))}
    room = shapely.box(0, 0, 1000, 1000)
    kept: list[int] = []
    for i in sorted(polygons, key=lambda k: -polygons[k].area):
        if room.covers(polygons[i]) and all(polygons[i].distance(polygons[j]) >= 10.0 for j in kept):
            kept.append(i)
    assert 20 < len(kept) < 200
    assert _valid(polygons, room, 10.0) == kept


def test_a_better_layout_too_close_to_the_last_told_is_told_once_the_search_settles(monkeypatch):
    """A stand-in for sparrow finds three bars spread along a strip, then the same with the
    last bar 1 mm nearer (0.1 % less stock: less than ``TELL`` better), then searches on for
    3 s without bettering. The second layout is told about ``SETTLE`` s after it was found,
    not only when the search ends."""
    from torsal.nodes.geometry import nesting, sparrow_runs

    def spread(shapes, members, height, spacing, orientations, steps, seed, budget, enough=0.0, failures=1,
               better=None, halt=None, counted=True, turn=0.0):
        first = {i: (0.0, (60.0 + 420.0 * k, height / 2)) for k, i in enumerate(members)}
        last = {**first, members[-1]: (0.0, (60.0 + 420.0 * 2 - 1.0, height / 2))}
        better(first)
        time.sleep(0.2)
        better(last)
        time.sleep(3.0)
        budget.spend(10)
        return last

    monkeypatch.setattr(sparrow_runs, "strip", spread)
    monkeypatch.setattr(nesting, "strip", spread)
    bars = [np.array([[0, 0], [100, 0], [100, 100], [0, 100]], dtype=float) + 500 * k for k in range(3)]
    started = time.perf_counter()
    told: list[tuple[float, float]] = []  # (seconds, the last bar's right end)

    def found(layout):  # type: ignore[no-untyped-def]
        end = place(bars[2], layout.angle[2], layout.shift[2])[:, 0].max()
        told.append((time.perf_counter() - started, end))

    nested = nest(bars, 2000.0, 102.0, margin=1.0, spacing=1.0, budget=10.0, found=found)
    ended = time.perf_counter() - started
    assert len(told) == 2 and told[0][1] - told[1][1] == pytest.approx(1.0)
    assert told[1][0] - told[0][0] >= nesting.SETTLE and told[1][0] < ended - 1.5
    assert place(bars[2], nested.angle[2], nested.shift[2])[:, 0].max() == pytest.approx(told[1][1])


def test_a_set_that_does_not_fit_sets_the_next_seeds_target_at_the_density_its_strip_reached(monkeypatch):
    """The stand-in for sparrow of the test above, but the first seed spreads its row: from x = 40,
    160 mm between parts. Bars 200, 150, 120, 100 and 60 mm wide, 100 tall, on a 502 × 102 sheet
    (margin and gap 1): the first set, towards 0.72 of the sheet, is the 200 and 150 (35,000 mm²);
    spread, no sheet holds both, and its strip reaches x = 550 (551 mm long with the far gap:
    density 35,000 / (551 × 102) = 0.6228).
    The second seed's set is chosen at 0.98 of that (31,251 mm²): the 200 and the 100 (30,000);
    it fits, and the 150, 120 and 60 make the last sheet."""
    from torsal.nodes.geometry import nesting, sparrow_runs

    row = _in_a_row(first_seed_from=40.0, first_seed_gap=160.0)
    monkeypatch.setattr(sparrow_runs, "strip", row)
    monkeypatch.setattr(nesting, "strip", row)
    bars = [np.array([[0, 0], [w, 0], [w, 100], [0, 100]], dtype=float) for w in (200, 150, 120, 100, 60)]
    nested = nest(bars, 502.0, 102.0, margin=1.0, spacing=1.0, budget=10.0)
    assert nested.sheet.tolist() == [0, 1, 1, 0, 1]
