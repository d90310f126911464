"""Rationalise's strips marched cut at the design's edge where cones would stand at their ends.

The design is half a monkey saddle, z = (x³ − 3xy²)/400 on 1 ≤ x ≤ 7, |y| ≤ 7: the
boundaries are the lines x = const, and the rulings of a strip along them run in the
conjugate direction, which for the Hessian (6/400)·[[x, −y], [−y, −x]] and a boundary
along y is (x, −y) up to scale — at 45° to the boundary where |y| = x, and within 10° of it
near the corners (1, ±7). So near the top and bottom edges a strip's two boundaries reach
the edge far apart along the rulings: strips as wide as the tolerance allows end in cones
over much of their area, and cut at the edge those widths are beyond the tolerance.
Rationalise then marches the strips again, each trial cut at the edge.

Every check is independent of the kernel: distances by the Newton iteration of
:mod:`tests.support.freeform_designs` on the closed form; the area in fans from the
rulings alone (a piece between two consecutive rulings that share an end point is a
triangle of a fan, whatever the kernel flags it as).
"""

from __future__ import annotations

from functools import cache

import numpy as np

import torsal.nodes.geometry.developable.rationalise as kernel
from tests.support.freeform_designs import Design, _monkey
from tests.support.strip_grids import distance_to_strip
from torsal.nodes.geometry.developable.fans import patch_areas

HALF = Design("half monkey saddle", _monkey, (1.0, 7.0), (-7.0, 7.0))
TOL = 0.1


def _triangle_share(strips) -> float:
    """The share of the strips' area in pieces whose two rulings share an end point."""
    fan = total = 0.0
    for strip in strips:
        starts, ends = strip.result.starts, strip.result.ends
        areas = patch_areas(starts, ends)
        size = float(np.linalg.norm(np.ptp(np.vstack([starts, ends]), axis=0)))
        shared = (np.linalg.norm(np.diff(starts, axis=0), axis=1) <= 1e-12 * size) | \
                 (np.linalg.norm(np.diff(ends, axis=0), axis=1) <= 1e-12 * size)
        fan += float(areas[shared].sum())
        total += float(areas.sum())
    return fan / total


@cache
def solved(recut: float = kernel.RECUT):
    saved = kernel.RECUT
    kernel.RECUT = recut
    try:
        return kernel.rationalise(HALF.surface(), TOL, 64, min_width=0.2)
    finally:
        kernel.RECUT = saved


def test_strips_as_wide_as_their_cones_allow_end_in_cones_over_a_fifth_of_their_area():
    plain = solved(2.0)  # (no second march: the cones that cutting after the march leaves)
    assert _triangle_share(plain.strips) > 0.2


def test_marched_cut_the_strips_have_no_cones_and_are_no_more():
    result = solved()
    assert _triangle_share(result.strips) < 0.01
    assert len(result.strips) <= len(solved(2.0).strips)


def test_marched_cut_the_strips_are_within_the_tolerance_by_an_independent_newton():
    u, v = (a.ravel() for a in np.meshgrid(np.linspace(0, 1, 161), np.linspace(0, 1, 17)))
    result = solved()
    worst = max(float(HALF.distance(strip.surface.point_at(u, v)).max()) for strip in result.strips)
    assert worst <= TOL
    assert worst <= result.deviation * (1 + 1e-9)  # the node's certified bound is not below it


def test_marched_cut_the_strips_cover_the_designs_edge_within_the_tolerance():
    edge = HALF.edge(60)
    gaps = np.min([distance_to_strip(strip.surface, edge) for strip in solved().strips], axis=0)
    assert gaps.max() <= TOL
