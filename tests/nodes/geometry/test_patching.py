"""SurfacePatching's kernel: a staggered pattern tiled over a development and mapped to 3D."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
import shapely

from torsal.nodes.geometry.parametric_surface import cone
from torsal.nodes.geometry.patching import Pattern, staggered_pattern, tile_pattern
from torsal.nodes.geometry.unroll import unroll_rulings, unroll_surface

R, H, N = 1.0, 2.0, 48


def cylinder_development(turn: float = 2.0 * np.pi):
    phi = np.linspace(0.0, turn, N + 1)
    base = np.column_stack([R * np.cos(phi), R * np.sin(phi), 0 * phi])
    return unroll_rulings(base, base + np.array([0.0, 0.0, H]))


def cone_development():
    return unroll_surface(cone(1.0, math.sqrt(3.0)), 24, 4)


def test_staggered_pattern_is_a_running_bond_with_whole_panels():
    tile = staggered_pattern(2.0, 1.0, 0.5)
    assert len(tile) == 2 and isinstance(tile, Pattern)
    assert np.array_equal(tile.period, [0.0, 0.0, 2.0, 2.0])
    assert np.array_equal(tile[1], tile[0] + [0.5, 1.0])  # the second row, shifted by the offset
    # copies of the tile cover the plane once: a 3 × 3 block of tiles has area 9 tiles
    shifts = [np.array([2.0 * i, 2.0 * j]) for i in range(3) for j in range(3)]
    copies = [shapely.Polygon(p + shift) for p in tile for shift in shifts]
    assert shapely.union_all(copies).area == pytest.approx(sum(c.area for c in copies), rel=1e-15)


@pytest.mark.parametrize("rotation", [0.0, 30.0, 90.0])
def test_panels_mapped_to_3d_and_back_match_the_flat_panels_within_1e_9(rotation):
    dev = cone_development()
    patching = tile_pattern(staggered_pattern(0.3, 0.2, 0.15), dev, rotation_deg=rotation)
    turned = dev.rotated(rotation)
    fine = turned.map.subdivide_many(patching.panels_flat)
    back = turned.map.polylines_to_2d(patching.panels_3d)
    assert len(back) == len(fine) > 100
    for flat, flat_again in zip(fine, back, strict=True):
        assert np.abs(flat_again - flat).max() < 1e-9


@pytest.mark.parametrize("rotation", [0.0, 17.0, 45.0])
def test_panel_areas_add_up_to_the_development_area_when_the_pattern_covers_it(rotation):
    dev = cone_development()
    patching = tile_pattern(staggered_pattern(0.3, 0.2, 0.1), dev, scale=1.5, rotation_deg=rotation)
    assert patching.covered_area == pytest.approx(dev.area_2d, rel=1e-6)
    assert patching.development_area == pytest.approx(dev.area_2d, rel=1e-12)


def test_waste_is_the_cut_off_share_of_the_used_sheets():
    # a 2.5 × 1 planar strip under unit squares: panels of area 1, 1 and ½
    x = np.linspace(0.0, 2.5, 6)
    dev = unroll_rulings(np.column_stack([x, 0 * x, 0 * x]), np.column_stack([x, 0 * x, 1 + 0 * x]))
    square = [np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])]
    patching = tile_pattern(square, dev)
    assert np.allclose(np.sort(patching.areas), [0.5, 1.0, 1.0], rtol=1e-14)
    assert patching.waste == pytest.approx(1.0 - 2.5 / 3.0, rel=1e-14)
    assert patching.ids.tolist() == [0, 1, 2]
    assert patching.tiles[:, 0].tolist() == [0, 1, 2]


def test_panel_ids_run_row_by_row():
    patching = tile_pattern(staggered_pattern(0.5, 0.25, 0.25), cylinder_development())
    assert np.array_equal(patching.ids, np.arange(len(patching.ids)))
    rows = patching.tiles[:, 1] * 2 + patching.pattern_index  # tile row, then bond row
    assert np.all(np.diff(rows) >= 0)
    lowest = np.array([ring[:, 1].min() for ring in patching.panels_flat])
    assert np.all(np.diff(lowest) >= -1e-12)  # bottom row first
    for row in np.unique(rows):  # left to right within a row
        left = np.array([ring[:, 0].min() for ring, r in zip(patching.panels_flat, rows, strict=True)
                         if r == row])
        assert np.all(np.diff(left) > 0)


def test_flat_panels_run_counter_clockwise_from_their_lower_left_corner():
    patching = tile_pattern(staggered_pattern(0.5, 0.25, 0.25), cylinder_development())
    for ring in patching.panels_flat:
        assert np.array_equal(ring[0], ring[-1])
        assert shapely.Polygon(ring).exterior.is_ccw
        assert np.allclose(ring[0], ring.min(axis=0))  # rectangles: the corner itself


def test_scale_multiplies_the_tile():
    dev = cylinder_development()
    one = tile_pattern(staggered_pattern(0.5, 0.25, 0.25), dev, scale=1.0)
    two = tile_pattern(staggered_pattern(0.5, 0.25, 0.25), dev, scale=2.0)
    assert np.array_equal(one.pattern_bounds[2:] - one.pattern_bounds[:2], [0.5, 0.5])
    assert np.array_equal(two.pattern_bounds[2:] - two.pattern_bounds[:2], [1.0, 1.0])
    assert two.full_areas.max() == pytest.approx(4.0 * one.full_areas.max(), rel=1e-14)


def test_rotating_the_development_rotates_the_pattern_on_the_surface():
    dev = cylinder_development()  # flat faces, rulings vertical: developed x is arc along the circle
    for rotation in (0.0, 25.0):
        patching = tile_pattern(staggered_pattern(0.4, 0.3, 0.2), dev, rotation_deg=rotation)
        # every panel edge that runs along the sheet's x, oriented towards +x
        edges = [np.stack([a, b] if a[0] < b[0] else [b, a]) for ring in patching.panels_flat
                 for a, b in itertools.pairwise(ring) if abs(a[1] - b[1]) < 1e-12]
        assert len(edges) > 50
        _, pieces = dev.rotated(rotation).map.polylines_to_3d(edges)
        for piece in pieces:
            rise = np.diff(piece[:, 2])
            travel = np.linalg.norm(np.diff(piece, axis=0), axis=1)
            # on the surface such an edge climbs at −rotation against the horizontal
            assert np.allclose(rise / travel, -math.sin(math.radians(rotation)), atol=1e-12)


def test_3d_panels_depend_only_on_the_total_turn_of_the_development():
    dev = cone_development()
    pattern = staggered_pattern(0.3, 0.2, 0.1)
    direct = tile_pattern(pattern, dev, rotation_deg=40.0)
    turned_first = tile_pattern(pattern, dev.rotated(25.0), rotation_deg=15.0)
    assert len(direct.ids) == len(turned_first.ids)
    assert np.allclose(direct.areas, turned_first.areas, rtol=1e-12)
    to3d_a = dev.rotated(40.0).map
    to3d_b = dev.rotated(25.0).rotated(15.0, pivot=dev.centroid).map
    for a, b in zip(direct.panels_flat, turned_first.panels_flat, strict=True):
        assert np.abs(to3d_a.to_3d(a) - to3d_b.to_3d(b)).max() < 1e-12


def test_a_full_turn_of_the_development_gives_the_same_panels():
    dev = cylinder_development(np.pi)
    a = tile_pattern(staggered_pattern(0.4, 0.3, 0.2), dev)
    b = tile_pattern(staggered_pattern(0.4, 0.3, 0.2), dev, rotation_deg=360.0)
    assert len(a.ids) == len(b.ids)
    for pa, pb in zip(a.panels_3d, b.panels_3d, strict=True):
        assert pa.shape == pb.shape and np.abs(pa - pb).max() < 1e-12
