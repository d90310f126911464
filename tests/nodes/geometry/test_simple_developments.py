"""Unrolled strips are simple polygons with exactly their four corners: the Kaohsiung
strips (both examples), their cut contours, and a strip made mostly of a fan."""

from __future__ import annotations

from functools import cache
from pathlib import Path

import numpy as np
import pytest
import shapely

from tests.support.node_helpers import out, run, tree
from torsal.app.headless import Run, run_file
from torsal.nodes.analysis.iso_mapping import IsoMapping
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.geometry.unroll import Development, unroll_rulings, unroll_surface
from torsal.nodes.io.formats.cutfiles import surface_outline

EXAMPLES = Path(__file__).resolve().parents[3] / "torsal" / "resources" / "examples"
#: A turn between consecutive outline edges above this is a corner.
CORNER_DEG = 25.0


@cache
def solved(name: str) -> Run:
    return run_file(EXAMPLES / f"{name}.graph")


def corners(outline: np.ndarray) -> int:
    """How many vertices of the closed polygon turn by more than CORNER_DEG, edges of
    zero length (a fan's apex, visited once per ruling) left out."""
    edges = np.diff(np.vstack([outline, outline[:1]]), axis=0)
    length = np.linalg.norm(edges, axis=1)
    edges = edges[length > 1e-9 * np.ptp(outline, axis=0).max()]
    heading = np.arctan2(edges[:, 1], edges[:, 0])
    turn = np.angle(np.exp(1j * (np.roll(heading, -1) - heading)))
    return int(np.count_nonzero(np.abs(turn) > np.deg2rad(CORNER_DEG)))


def assert_simple(outline: np.ndarray) -> None:
    size = np.ptp(outline, axis=0).max()
    keep = np.r_[True, np.linalg.norm(np.diff(outline, axis=0), axis=1) > 1e-9 * size]
    ring = outline[keep]
    assert shapely.Polygon(outline).is_valid
    assert shapely.LinearRing(ring).is_simple


def kaohsiung_developments() -> list[tuple[str, int, Development]]:
    found = []
    cut = solved("kaohsiung-cut-sheets").solver.result("unroll").outputs["Map"].all_items()
    found += [("kaohsiung-cut-sheets", k, d) for k, d in enumerate(cut)]
    strips = solved("kaohsiung-stadium").solver.result("strip").outputs["Surface"].all_items()
    for k, strip in enumerate(strips):
        found.append(("kaohsiung-stadium", k, unroll_surface(strip, len(strip.ruling_lines) - 1)))
    return found


def tips(development: Development) -> int:
    """How many of the strip's two end rulings have zero length (it tapers to a point)."""
    lengths = np.linalg.norm(development.ends3d - development.starts3d, axis=1)
    return int(lengths[0] <= 1e-9) + int(lengths[-1] <= 1e-9)


def test_every_kaohsiung_strip_unrolls_to_a_simple_polygon_with_exactly_four_corners():
    """Four corners; where the strip tapers to a point at a horseshoe's end, two to four
    (its tip, and the far end's corners, which on a thin sliver may turn by under 25°, and
    where the tip's cone meets the rim): never the many turns of a wiggle."""
    developments = kaohsiung_developments()
    assert len(developments) == (16 + 2) + (24 + 4)  # count + 2n strips in each example
    assert sum(tips(d) for _, _, d in developments) > 0
    for name, k, development in developments:
        assert_simple(development.outline)
        assert not development.overlaps, (name, k)
        if tips(development):  # a sliver's blunt corners may turn by less or more than 25°
            assert 2 <= corners(development.outline) <= 4, (name, k)
        else:
            assert corners(development.outline) == 4, (name, k)


def test_every_kaohsiung_cut_contour_is_simple_with_exactly_four_corners():
    layout = solved("kaohsiung-cut-sheets").solver.result("cut").outputs["Layout"].all_items()[0]
    maps = solved("kaohsiung-cut-sheets").solver.result("unroll").outputs["Map"].all_items()
    assert len(layout.parts) == len(maps) == 16 + 2
    for part, development in zip(layout.parts, maps, strict=True):
        assert_simple(part.outline)
        if tips(development):
            assert 2 <= corners(part.outline) <= 4, part.id
        else:
            assert corners(part.outline) == 4, part.id


def fan_heavy_strip() -> tuple[RuledSurface, np.ndarray, slice]:
    """Rulings from an arc A (radius 10 in z = 0) to B: a line at z = 3 for the first
    and last six, and in between 21 rulings through one point of it (a fan)."""
    phi = np.linspace(0.0, 1.4, 33)
    a = np.column_stack([10 * np.cos(phi), 10 * np.sin(phi), 0 * phi])
    x = np.r_[np.linspace(9.0, 7.0, 6), np.full(21, 6.6), np.linspace(6.2, 4.0, 6)]
    b = np.column_stack([x, 2.0 * (9.0 - x), np.full_like(x, 3.0)])
    return RuledSurface.from_rulings(a, b), b[6], slice(6, 27)


def test_a_strip_that_is_mostly_a_fan_unrolls_to_a_simple_polygon():
    surface, _, _ = fan_heavy_strip()
    development = unroll_surface(surface, 32)
    assert_simple(development.outline)
    assert not development.overlaps
    assert development.max_edge_length_error < 1e-12


def test_the_fan_unrolls_onto_one_point_with_its_rulings_lengths():
    surface, apex, fan = fan_heavy_strip()
    development = unroll_surface(surface, 32, subdivisions=4)
    starts, ends = development.starts2d, development.ends2d
    inside = slice(4 * fan.start, 4 * (fan.stop - 1) + 1)  # every unrolled ruling of the fan
    assert np.ptp(ends[inside], axis=0).max() < 1e-12 * 10
    lengths = np.linalg.norm(development.starts3d[inside] - apex, axis=1)
    assert np.abs(np.linalg.norm(ends[inside] - starts[inside], axis=1) - lengths).max() < 1e-12 * 10


def test_iso_mapping_of_a_fan_heavy_strip_is_silent_and_simple():
    surface, _, _ = fan_heavy_strip()
    result = run(IsoMapping(), Surface=tree({(0,): [surface]}), Segments=32)
    assert result.state == "ok", result.messages
    (development,) = out(result, "Map")[(0,)]
    assert_simple(development.outline)


@pytest.mark.parametrize("name", ["kaohsiung-cut-sheets", "kaohsiung-stadium"])
def test_kaohsiung_strips_have_no_rail_that_doubles_back(name):
    """The root of the wiggles: a loft rail swinging back past a ruling end (each rail
    span must advance along its chord)."""
    for strip in solved(name).solver.result("strip").outputs["Surface"].all_items():
        n = len(strip.ruling_lines)
        u = np.linspace(0.0, 1.0, 64 * (n - 1) + 1)
        lines = strip.ruling_lines
        for rail, ends in ((strip.curve_a, lines[:, 0]), (strip.curve_b, lines[:, 1])):
            points = rail.point_at(u).reshape(-1)[:-3].reshape(n - 1, 64, 3)
            chord = np.diff(ends, axis=0)
            advance = np.einsum("skd,sd->sk", np.diff(points, axis=1), chord)
            assert advance.min() >= -1e-12 * np.square(chord).sum(axis=1).max()


def test_every_kaohsiung_development_surface_outline_is_simple_with_four_corners():
    """The cut outline is traced from IsoMapping's Development surface (as ExportCutSheet
    does), here finer than any cutter: a fan's apex, where the edge stands still, is one point."""
    unrolled = solved("kaohsiung-cut-sheets").solver.result("unroll").outputs
    developments, maps = unrolled["Development"].all_items(), unrolled["Map"].all_items()
    assert len(developments) == 16 + 2
    for k, (development, unrolled_map) in enumerate(zip(developments, maps, strict=True)):
        outline = surface_outline(development, 1e-7).points[:, :2]
        assert_simple(outline)
        if tips(unrolled_map):
            assert 2 <= corners(outline) <= 4, k
        else:
            assert corners(outline) == 4, k


def test_iso_mapping_development_is_the_outline_of_the_unrolled_triangles():
    surface, _, _ = fan_heavy_strip()
    result = run(IsoMapping(), Surface=tree({(0,): [surface]}), Segments=32, Placement=1)  # Map frame
    (flat,) = out(result, "Development")[(0,)]
    (development,) = out(result, "Map")[(0,)]
    count = len(development.starts2d)
    u = np.linspace(0.0, 1.0, count)
    middle = (u[:-1] + u[1:]) / 2
    for v, ends in ((0.0, development.starts2d), (1.0, development.ends2d)):
        assert np.abs(flat.point_at(u, np.full(count, v))[:, :2] - ends).max() < 1e-14 * 40
        halfway = flat.point_at(middle, np.full(count - 1, v))[:, :2]
        assert np.abs(halfway - (ends[:-1] + ends[1:]) / 2).max() < 1e-14 * 40  # straight between
    assert len(flat.ruling_lines) == 33  # its rulings are the requested ones


def test_quads_of_a_fan_are_single_triangles_that_do_not_fold():
    """Even where the apex's samples differ by rounding (here 1e-14), a quad with a
    collapsed edge is one triangle: its fold (hinge angle) is 0, not the angle of a
    rounding-sized triangle's normal."""
    surface, _, fan = fan_heavy_strip()
    starts, ends = surface.ruling_lines[:, 0], surface.ruling_lines[:, 1].copy()
    ends[fan] += np.random.default_rng(5).uniform(-1e-14, 1e-14, ends[fan].shape)
    development = unroll_rulings(starts, ends)
    inside = slice(fan.start, fan.stop - 1)  # the quads between the fan's rulings
    assert np.all(development.hinge_angles[inside] == 0.0)
