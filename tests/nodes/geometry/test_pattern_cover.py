"""torsal.nodes.geometry.pattern_cover: ring areas against shapely, the cover of a tile against
closed forms, and SurfacePatching's messages from it."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from tests.support.direct_graphs import Chain
from torsal.nodes.geometry.curves.line import Polyline
from torsal.nodes.geometry.parametric_surface import cone
from torsal.nodes.geometry.pattern_cover import pattern_cover
from torsal.nodes.geometry.polygons import ring_areas
from torsal.nodes.patching.surface_patching import SurfacePatching


def star(rng: np.random.Generator, corners: int) -> np.ndarray:
    """A random simple polygon: corners at increasing angles, random radii."""
    angles = np.sort(rng.uniform(0.0, 2 * np.pi, corners))
    radii = rng.uniform(0.5, 2.0, corners)
    return np.column_stack([radii * np.cos(angles), radii * np.sin(angles)])


def square(x0: float, y0: float, side: float) -> np.ndarray:
    return np.array([[x0, y0], [x0 + side, y0], [x0 + side, y0 + side], [x0, y0 + side]])


def test_ring_areas_are_shapelys_for_rings_of_any_length_and_direction():
    rng = np.random.default_rng(7)
    rings = [star(rng, k) for k in (3, 4, 7, 50, 301)]
    rings = [r if i % 2 else r[::-1] for i, r in enumerate(rings)]  # both directions
    expected = [shapely.Polygon(r).area for r in rings]
    np.testing.assert_allclose(ring_areas(rings), expected, rtol=2e-15)


def test_a_repeated_closing_vertex_adds_no_area():
    ring = square(0.0, 0.0, 2.0)
    assert ring_areas([np.vstack([ring, ring[:1]])])[0] == ring_areas([ring])[0] == 4.0


def test_ring_areas_far_from_the_origin_are_those_at_it():
    rng = np.random.default_rng(11)
    far = [star(rng, 40) + 1e7 for _ in range(3)]
    at_origin = [shapely.Polygon(r - 1e7).area for r in far]  # moving back is exact (Sterbenz)
    np.testing.assert_allclose(ring_areas(far), at_origin, rtol=2e-15)


def test_a_running_bond_covers_its_tile_once():
    w, h, offset = 1.2, 0.6, 0.5
    rings = [np.array([[0, 0], [w, 0], [w, h], [0, h]]),
             np.array([[offset, h], [offset + w, h], [offset + w, 2 * h], [offset, 2 * h]])]
    cover = pattern_cover(rings, [0.0, 0.0, w, 2 * h])
    assert cover.share == pytest.approx(1.0, rel=1e-15)
    assert not cover.gaps and not cover.overlaps


def test_a_running_bond_read_with_its_bounding_rectangle_leaves_gaps():
    w, h, offset = 1.2, 0.6, 0.6
    rings = [square(0.0, 0.0, 1.0) * [w, h], square(0.0, 0.0, 1.0) * [w, h] + [offset, h]]
    cover = pattern_cover(rings, [0.0, 0.0, w + offset, 2 * h])
    assert cover.share == pytest.approx(w / (w + offset), rel=1e-15)  # 2wh over (w + o)·2h
    assert cover.gaps and not cover.overlaps


def test_two_panels_on_one_panels_tile_overlap():
    cover = pattern_cover([square(0.0, 0.0, 1.0), square(0.25, 0.0, 1.0)], [0.0, 0.0, 1.0, 1.0])
    assert cover.share == pytest.approx(2.0, rel=1e-15)
    assert cover.overlaps and not cover.gaps


def test_a_tile_without_area_is_refused():
    with pytest.raises(ValueError, match="no area"):
        pattern_cover([square(0.0, 0.0, 1.0)], [0.0, 0.0, 1.0, 0.0])


def test_surface_patching_warns_when_its_panels_overlap_in_their_tile():
    chain = Chain()
    chain.source("surface", cone(1.0, 2.0))
    chain.source("pattern", Polyline(np.column_stack([square(0.0, 0.0, 0.5), np.zeros(4)]), closed=True),
                 Polyline(np.column_stack([square(0.1, 0.0, 0.5), np.zeros(4)]), closed=True))
    chain.source("tile", Polyline(np.column_stack([square(0.0, 0.0, 0.5), np.zeros(4)]), closed=True))
    chain.add("patch", SurfacePatching())
    for name in ("surface", "pattern", "tile"):
        chain.wire(name, "Tree", "patch", name.capitalize())
    chain.solve()
    assert any("add up to 200% of its tile, so repeated panels overlap" in t for t in chain.texts("patch"))
