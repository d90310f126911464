"""Corners of a ruled surface's edges, and the samplings that hold a ruling on each of them
(torsal/nodes/geometry/edge_sampling.py).

Expected values are closed forms: a polyline's corners at its vertices' shares of its
length, a re-weighted rational arc's at the knots it was built with, the points there its
control points; lengths are sums of segment lengths.
"""

from __future__ import annotations

import math

import numpy as np

from tests.support import curve_pairs
from torsal.nodes.geometry.curve_rail import ruled_between
from torsal.nodes.geometry.curves.line import Polyline
from torsal.nodes.geometry.edge_sampling import KINK_SNAP, Samples, rulings_at
from torsal.nodes.geometry.nurbs_surface import NurbsSurface
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.geometry.unroll import unroll_surface

#: A zig-zag in the plane z = 0: a straight vertex (1), a right angle (2) and 45° (3).
ZIGZAG = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [2.0, 1.0, 0.0], [3.0, 2.0, 0.0]])
ZIGZAG_LENGTH = 3.0 + math.sqrt(2.0)


def test_a_polylines_kinks_are_the_vertices_where_it_turns():
    kinks = Polyline(ZIGZAG).kinks()
    np.testing.assert_allclose(kinks, [2.0 / ZIGZAG_LENGTH, 3.0 / ZIGZAG_LENGTH], rtol=0, atol=1e-15)
    assert not kinks.flags.writeable


def test_a_closed_polylines_seam_is_a_kink_and_a_smooth_curve_has_none():
    square = Polyline([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 0]])
    np.testing.assert_allclose(square.kinks(), [0.0, 0.25, 0.5, 0.75], atol=1e-15)
    circle = curve_pairs._arc_nurbs(1.0, 0.0, 2 * math.pi, 4, np.ones(9))  # double knots, tangent there
    assert circle.closed and len(circle.kinks()) == 0


def test_a_reweighted_rational_arc_turns_at_each_of_its_double_knots():
    """Changing the weights of a rational arc but keeping its weighted control points moves
    the points at its double knots along their rays: the tangent no longer runs on."""
    arc = curve_pairs._arc_nurbs(1.0, 0.5, 2.4, 4, 1.0 + 0.25 * np.sin(1.7 * np.arange(9)))
    np.testing.assert_allclose(arc.kinks(), [0.25, 0.5, 0.75], atol=1e-15)


def test_a_rail_on_a_kinked_curve_turns_where_its_pace_crosses_the_curves_corners():
    pair = curve_pairs.nurbs_cone_pair()
    s = np.linspace(0.0, 1.0, 13) ** 1.3  # a pace that meets no knot at a ruling
    t = np.linspace(0.0, 1.0, 13) ** 0.8
    surface = ruled_between(pair.a, s, pair.b, t)
    for rail, corners in ((surface.curve_a, pair.a.control_points[2:-2:2]),
                          (surface.curve_b, pair.b.control_points[2:-2:2])):
        kinks = rail.kinks()
        assert len(kinks) == len(corners)
        np.testing.assert_allclose(rail.point_at(kinks), corners, rtol=0, atol=1e-13 * pair.size)
    expected = np.sort(np.concatenate([surface.curve_a.kinks(), surface.curve_b.kinks()]))
    np.testing.assert_array_equal(surface.ruling_kinks(), expected)


def test_a_degree_1_nurbs_surfaces_kinks_are_its_inner_knots_across_the_rulings():
    corners = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [2, 1, 0]], dtype=float)  # a bent fence
    surface = NurbsSurface(np.stack([corners, corners + np.array([0.0, 0.0, 1.0])], axis=1), 1, 1)
    assert surface.ruling_direction == "v"
    np.testing.assert_allclose(surface.ruling_kinks(), [1 / 3, 2 / 3], atol=1e-15)


def test_every_sampling_holds_the_kinks_rulings_and_the_planned_ones_where_they_were():
    base = Polyline(ZIGZAG)
    surface = RuledSurface(base, Polyline(ZIGZAG + np.array([0.0, 0.0, 1.0])))
    samples = Samples(surface)
    sampling = samples.even(11)
    np.testing.assert_array_equal(sampling.u[sampling.grid], np.linspace(0.0, 1.0, 11))
    extra = np.setdiff1d(np.arange(len(sampling.u)), sampling.grid)
    np.testing.assert_allclose(sampling.u[extra], [2.0 / ZIGZAG_LENGTH, 3.0 / ZIGZAG_LENGTH], atol=1e-15)
    np.testing.assert_allclose(sampling.rulings[extra, 0], ZIGZAG[2:4], atol=1e-15)
    np.testing.assert_array_equal(sampling.rulings[sampling.grid], surface.rulings(11))
    # a kink as good as on a planned ruling is sampled by it
    near = np.array([0.0, 2.0 / ZIGZAG_LENGTH + 0.5 * KINK_SNAP, 3.0 / ZIGZAG_LENGTH, 1.0])
    merged = samples.at(near)
    assert len(merged.u) == 4 and merged.grid is None
    np.testing.assert_allclose(merged.rulings, rulings_at(surface, near))


def test_a_folded_plate_unrolls_with_edges_as_long_as_its_polylines():
    """The planar faces between a zig-zag and the same zig-zag halved towards an apex (a
    pyramid's sides): the flat edges are the polylines' lengths to rounding from 83
    rulings, where rulings that miss the corners cut them off (4.5e-7 of the size short
    with 32,783, the most the sampling takes: measured before the corners were sampled)."""
    apex = np.array([1.0, 3.0, 4.0])
    top = apex + 0.5 * (ZIGZAG - apex)
    surface = RuledSurface(Polyline(ZIGZAG), Polyline(top))
    development = unroll_surface(surface, 10, 8, edge_tolerance=1e-7)
    flat = [np.linalg.norm(np.diff(edge, axis=0), axis=1).sum()
            for edge in (development.starts2d, development.ends2d)]
    size = float(np.linalg.norm(np.ptp(np.vstack([ZIGZAG, top]), axis=0)))
    np.testing.assert_allclose(flat, [ZIGZAG_LENGTH, 0.5 * ZIGZAG_LENGTH], rtol=0, atol=1e-13 * size)
    assert len(development.rulings2d[0]) == 11  # the rulings asked for, the corners' among the others
    assert len(development.starts2d) == 10 * 8 + 1 + 2  # the first sampling was enough
    assert abs(development.area_error) < 1e-12
