"""Strips run on past the design's edge and cut by it (torsal.nodes.geometry.developable.outline_cut).

On the saddle turned 30° (tests/support/freeform_designs.py) the strip between two of
its parameter lines has rulings at 30° to them, so the plain strip ends in cones over a
fifth of its area. Trimmed, it must have no fan at all and still be what a strip must be;
every figure is recomputed here from the strip's own surface and the design's closed
form: warps from the surface's normals 1 % in from each end of every ruling (its own first
derivatives, none of the kernel's warp code), distances by the design's
own Newton iteration, the strip's edges against dense samples of the boundary curves.
"""

from __future__ import annotations

from functools import cache

import numpy as np

from tests.support.freeform_designs import DESIGNS
from tests.support.strip_grids import distance_to_strip, gaps_to_edge
from torsal.nodes.geometry.developable.offset import LiftedBoundaries, lift_for
from torsal.nodes.geometry.developable.rationalise import strip_between
from torsal.nodes.geometry.developable.ruling import ruling_developable

TOL = 0.02
LO, HI = 0.33, 0.49  # a strip about 1.3 m wide, 12 m long, in the middle of the saddle


@cache
def strip():
    design = DESIGNS["saddle"]
    surface = design.surface()
    boundaries = LiftedBoundaries(surface, "u", lift_for(surface, "u", TOL))
    return design, boundaries, strip_between(surface, boundaries, LO, HI, tolerance=TOL)


def test_the_plain_strip_ends_in_cones_the_trimmed_one_has_none():
    _, boundaries, trimmed = strip()
    plain = ruling_developable(boundaries.at(LO), boundaries.at(HI), 24, 1e-7)
    assert plain.fan[[0, -1]].all() and plain.fan_share > 0.15  # measured 0.20: two end cones
    # the only fan "rulings" are the two points the strip tapers to, at the design's edge
    fan = trimmed.result.fan
    lengths = np.linalg.norm(trimmed.result.ends - trimmed.result.starts, axis=1)
    assert np.flatnonzero(fan).tolist() == [0, len(fan) - 1] and lengths[fan].max() == 0.0
    assert trimmed.result.fan_share < 2e-6 and trimmed.result.creased_share == 0.0  # measured 9e-7


def test_every_ruling_is_torsal_on_the_strips_own_surface():
    """The surface's normals 1 % in from each end of each ruling agree (from its own first
    derivatives, none of the kernel's warp code): its tangent plane is one along the whole
    ruling, cut ones at the design's edge included."""
    _, _, trimmed = strip()
    surface = trimmed.surface
    torsal = ~trimmed.result.fan  # (the two tips: a point has no plane, its warp is NaN)
    u = np.asarray(surface.ruling_parameters, dtype=float)[torsal]
    _, su1, sv1 = surface.derivatives(u, np.full_like(u, 0.01), 1)
    _, su2, sv2 = surface.derivatives(u, np.full_like(u, 0.99), 1)
    n1, n2 = np.cross(su1, sv1), np.cross(su2, sv2)
    angle = np.arctan2(np.linalg.norm(np.cross(n1, n2), axis=1), np.einsum("ij,ij->i", n1, n2))
    assert len(u) >= 25 and np.all(np.linalg.norm(n1, axis=1) > 0)
    assert angle.max() < 1e-12  # measured 2e-13 (next to a tip), 3e-16 in the median
    assert np.isfinite(trimmed.warp[torsal]).all() and trimmed.warp[torsal].max() < 1e-12


def test_the_strip_is_within_the_tolerance_and_covers_the_designs_edge_between_its_boundaries():
    design, _, trimmed = strip()
    u, v = np.meshgrid(np.linspace(0, 1, 401), np.linspace(0, 1, 21), indexing="ij")
    points = trimmed.surface.point_at(u.ravel(), v.ravel())
    assert design.distance(points).max() <= TOL * 1.0001
    # the design's two ends between the boundaries' levels (a 30° saddle: the strip's cut ends)
    y = np.linspace(design.y[0] + LO * 8.0, design.y[0] + HI * 8.0, 41)
    for x in design.x:
        edge = design.points(np.full_like(y, x), y)
        assert distance_to_strip(trimmed.surface, edge).max() <= TOL


def test_the_strips_edges_run_on_both_boundaries_from_end_to_end():
    """Every point of each boundary lies on the strip's edge (to 1e-9 of the design's
    size): a neighbour on the same boundary meets this strip without a gap."""
    design, boundaries, trimmed = strip()
    for v, level in ((0.0, LO), (1.0, HI)):
        curve = boundaries.at(level).point_at(np.linspace(0, 1, 301))
        assert gaps_to_edge(trimmed.surface, v, curve).max() <= 1e-9 * design.size  # chords sag ~2e-10
