"""A strip cut to a region keeps the region's corners (torsal/nodes/geometry/developable/
trimmed.py, ``cut_strip`` with ``corners``; the regions and their corners from rings.py).

The design is the cylinder z = (x − 5)²/50 over [0, 10] × [0, 4], its plan (x, y); the
strip lies between its parameter lines y = 1 and y = 3, so its rulings are the cylinder's
generators x = const and the strip is the band 1 ≤ y ≤ 3 of the design exactly. Cut to a
polygon in the plan, it must be band ∩ polygon (shapely), with each corner of the polygon
inside the band on the cut strip's edge. The whole double bump at 1, 2 and 5 cm is in
tests/benchmarks/bench_rationalise_freeform.py.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from tests.support.freeform_designs import Design
from torsal.nodes.geometry.curve_rail import ruled_between
from torsal.nodes.geometry.developable.guided import IsoBoundaries
from torsal.nodes.geometry.developable.rationalise import Strip
from torsal.nodes.geometry.developable.rings import region_corners, region_inside
from torsal.nodes.geometry.developable.ruling import ruling_developable
from torsal.nodes.geometry.developable.trim_region import sharp_corners
from torsal.nodes.geometry.developable.trimmed import cut_strip


def _cylinder(x, y):
    zero = 0 * x
    return (x - 5) ** 2 / 50, (x - 5) / 25, zero, 1 / 25 + zero, zero, zero


DESIGN = Design("cylinder", _cylinder, (0.0, 10.0), (0.0, 4.0))
SCALE = np.array([10.0, 4.0])  # the plan is (x, y)
BAND = shapely.box(0.0, 1.0, 10.0, 3.0)
TOLERANCE = 0.01
#: A run's end line keeps 2e-3 of its neighbour's length (trimmed.TIP): where the band's
#: rail meets the region's edge, the cut strip stops that short of the corner (2 mm of 1.2 m).
CLOSE = 3e-3

REGIONS = {
    "a convex corner": (shapely.Polygon([(2, -1), (8, -1), (5.13, 2.2)]), (5.13, 2.2)),
    "a concave corner": (shapely.box(0, 0, 10, 4).difference(shapely.Polygon([(3, 4.5), (7, 4.5),
                                                                               (4.87, 1.8)])), (4.87, 1.8)),
}


def _strip() -> Strip:
    surface = DESIGN.surface()
    boundaries = IsoBoundaries(surface, "u")
    a, b = boundaries.at(0.25), boundaries.at(0.75)  # y = 1 and y = 3
    result = ruling_developable(a, b, 24, 1e-7)
    return Strip(0.25, 0.75, result, ruled_between(a, result.s, b, result.t), np.zeros(len(result.s)), 0.0,
                 np.zeros(3))


def _outline(pieces) -> shapely.Geometry:
    """The cut strips' outline in the plan, from 4,001 points along each edge and its rulings'
    ends (a corner of the region is a ruling's)."""
    parts = []
    for piece in pieces:
        t = np.union1d(np.linspace(0.0, 1.0, 4001), piece.surface.ruling_parameters)
        lower = piece.surface.point_at(t, 0 * t)[:, :2]
        upper = piece.surface.point_at(t, 0 * t + 1)[:, :2]
        parts.append(shapely.Polygon(np.vstack([lower, upper[::-1]])))
    return shapely.union_all(parts)


def test_sharp_corners_are_the_vertices_where_the_outline_turns():
    # a vertex where the outline runs straight on, and one repeated
    square = shapely.Polygon([(0, 0), (1, 0), (2, 0), (2, 2), (2, 2), (0, 2)])
    found = sharp_corners(square)
    assert sorted(map(tuple, found.tolist())) == [(0.0, 0.0), (0.0, 2.0), (2.0, 0.0), (2.0, 2.0)]
    circle = shapely.Point(0, 0).buffer(1.0, quad_segs=32)  # turns by 2π/128 at each vertex
    assert len(sharp_corners(circle)) == 0


@pytest.mark.parametrize("name", list(REGIONS))
def test_a_cut_strip_keeps_the_regions_corner_inside_the_band(name):
    region, corner = REGIONS[name]
    surface = DESIGN.surface()
    inside = region_inside(surface, region, SCALE)
    corners = region_corners(surface, region, SCALE)
    assert np.abs(corners[:, :2] - corner).sum(axis=1).min() <= 1e-12  # the corner, on the design
    pieces = cut_strip(_strip(), inside, surface, TOLERANCE, corners)
    assert len(pieces) == 1
    got = _outline(pieces)
    expected = BAND.intersection(region)
    # the corner lies on the cut strip's edge, and the strip lies inside the region
    assert got.boundary.distance(shapely.Point(corner)) <= 1e-8 * DESIGN.size
    edge = np.asarray(got.boundary.segmentize(0.005).coords)
    assert shapely.distance(expected, shapely.points(edge)).max() <= 1e-6 * DESIGN.size
    assert shapely.hausdorff_distance(got.boundary, expected.boundary, densify=0.01) <= CLOSE


def test_without_its_corners_the_cut_rounds_the_corner_off():
    region, corner = REGIONS["a convex corner"]
    surface = DESIGN.surface()
    pieces = cut_strip(_strip(), region_inside(surface, region, SCALE), surface, TOLERANCE)
    assert _outline(pieces).boundary.distance(shapely.Point(corner)) > 1e-3


def test_a_regions_corners_with_a_margin_are_where_it_meets_the_designs_edge():
    surface = DESIGN.surface()
    # grown by 0.5 inside the design, its own corners are rounded off: none are left
    assert len(region_corners(surface, shapely.box(2.0, 1.0, 6.0, 3.0), SCALE, margin=0.5)) == 0
    # the left half, grown by 0.5 past x = 5 and cut at the design's edge: its corners there
    found = region_corners(surface, shapely.box(0.0, 0.0, 5.0, 4.0), SCALE, margin=0.5)
    expected = [(0.0, 0.0), (0.0, 4.0), (5.5, 0.0), (5.5, 4.0)]
    assert sorted(map(tuple, np.round(found[:, :2], 9).tolist())) == expected
    assert np.allclose(found[:, 2], DESIGN.height(found[:, 0], found[:, 1]), atol=1e-12)  # on the design
