"""The regions of the ring layout (torsal/nodes/geometry/developable/ring_layout.py) on the
double bump: its two tops found where scipy finds the maxima of its closed form, each
top's cell the half of the plan nearer it, split in two halves along the line through
both tops, and a cap round each top inside a ring of curvature (the whole run is in the
freeform benchmark, tests/benchmarks/bench_rationalise_freeform.py)."""

from __future__ import annotations

import numpy as np
import shapely
from scipy.optimize import minimize

from tests.support.freeform_designs import DESIGNS
from torsal.nodes.geometry.developable.curvature_lines import plan_scale
from torsal.nodes.geometry.developable.ring_layout import bump_centres, layout_regions

DESIGN = DESIGNS["bumps"]


def _tops() -> np.ndarray:
    """The maxima of the closed form, by scipy from either side."""
    found = []
    for x0 in (-4.0, 4.0):
        best = minimize(lambda p: -DESIGN.height(np.array([p[0]]), np.array([p[1]]))[0], [x0, 0.5],
                        jac=lambda p: -np.array([DESIGN.height(np.array([p[0]]), np.array([p[1]]), k)[0]
                                                  for k in (1, 2)]))
        found.append(best.x)
    return np.array(found)


def _plan_to_xy(points, scale):
    (x0, x1), (y0, y1) = DESIGN.x, DESIGN.y
    uv = np.asarray(points) / scale
    return np.column_stack([x0 + uv[:, 0] * (x1 - x0), y0 + uv[:, 1] * (y1 - y0)])


def test_the_double_bump_has_two_tops_where_scipy_finds_its_maxima():
    surface = DESIGN.surface()
    scale = plan_scale(surface)
    centres = _plan_to_xy(bump_centres(surface, scale), scale)
    tops = _tops()
    assert len(centres) == 2
    assert np.abs(np.sort(centres[:, 0]) - np.sort(tops[:, 0])).max() <= 0.5 * 18.0 / 40  # half a sample
    assert np.abs(centres[:, 1] - 0.0).max() <= 0.5 * 12.0 / 40


def test_each_top_gets_a_cap_and_two_halves_that_tile_the_design():
    surface = DESIGN.surface()
    scale = plan_scale(surface)
    centres = bump_centres(surface, scale)
    layout = layout_regions(surface, centres, scale)
    assert len(layout.caps) == 2 and len(layout.halves) == 4
    pieces = [*layout.caps, *(h.region for h in layout.halves)]
    outline = shapely.box(0.0, 0.0, *scale)
    union = shapely.union_all(pieces)
    assert abs(union.area - outline.area) <= 1e-9 * outline.area
    assert abs(sum(p.area for p in pieces) - outline.area) <= 1e-9 * outline.area  # no overlaps
    for cap, c in zip(layout.caps, centres, strict=True):
        assert cap.contains(shapely.Point(c))
    for half in layout.halves:  # each half lies on one side of the line through both tops, x = 0 apart
        xy = _plan_to_xy(np.asarray(half.region.exterior.coords), scale)
        assert np.ptp(np.sign(np.round(xy[:, 1], 9))[np.abs(xy[:, 1]) > 1e-6]) == 0
        assert np.ptp(np.sign(np.round(xy[:, 0], 9))[np.abs(xy[:, 0]) > 1e-6]) == 0
