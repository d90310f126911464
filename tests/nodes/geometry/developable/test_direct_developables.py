"""Cylinders, cones and tangent developables: exact geometry and zero warp."""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsal.nodes.geometry.curves import InterpolatedCurve, Line, ParametricCurve
from torsal.nodes.geometry.developable import (
    cone_rulings,
    cylinder_rulings,
    tangent_developable_rulings,
    warp_angles,
)

# a non-planar, wavy space curve (a NURBS through points) and a helix with exact derivatives
WAVY = InterpolatedCurve(
    [[0, 0, 0], [1, 0.8, 0.3], [2, 0.2, -0.4], [3, 1.1, 0.5], [4, 0.4, 0.1], [5, 1.0, -0.3]]
)
R, H = 2.0, 0.8


def helix(u):
    return np.column_stack([R * np.cos(u), R * np.sin(u), H * u])


def helix_d1(u):
    return np.column_stack([-R * np.sin(u), R * np.cos(u), np.full_like(u, H)])


def helix_d2(u):
    return np.column_stack([-R * np.cos(u), -R * np.sin(u), np.zeros_like(u)])


def helix_d3(u):
    return np.column_stack([R * np.sin(u), -R * np.cos(u), np.zeros_like(u)])


HELIX = ParametricCurve(helix, (0.0, 2 * math.pi), derivatives=(helix_d1, helix_d2, helix_d3))


# -- cylinder ------------------------------------------------------------------------------------


def test_cylinder_rulings_are_parallel_to_the_direction_and_height_long():
    r = cylinder_rulings(WAVY, [1, 2, 3], 2.5, 30)
    assert len(r.starts) == 31
    direction = np.array([1, 2, 3]) / math.sqrt(14)
    np.testing.assert_allclose(r.ends - r.starts, np.broadcast_to(2.5 * direction, (31, 3)), atol=1e-14)
    np.testing.assert_allclose(r.starts, WAVY.point_at(r.parameters), atol=1e-14)


def test_cylinder_rulings_have_zero_warp():
    r = cylinder_rulings(WAVY, [0.3, -0.2, 1.0], 4.0, 50)
    assert r.warp.max() < 1e-10
    np.testing.assert_allclose(r.end_tangents, r.start_tangents, atol=1e-15)


def test_negative_height_extrudes_the_other_way():
    r = cylinder_rulings(WAVY, [0, 0, 1], -2.0, 4)
    np.testing.assert_allclose(r.ends[:, 2] - r.starts[:, 2], -2.0)


def test_cylinder_direction_must_not_be_zero():
    with pytest.raises(ValueError, match="zero length"):
        cylinder_rulings(WAVY, [0, 0, 0], 1.0, 4)


# -- cone ----------------------------------------------------------------------------------------


def test_cone_rulings_end_at_the_apex_when_the_height_reaches_it():
    apex = np.array([2.5, 0.5, 6.0])
    r = cone_rulings(WAVY, apex, 100.0, 20)
    np.testing.assert_allclose(r.ends, np.broadcast_to(apex, r.ends.shape), atol=1e-14)
    assert r.warp.max() < 1e-10


def test_cone_rulings_run_towards_the_apex_for_height_and_stop_there():
    apex = np.array([2.5, 0.5, 4.0])
    distance = np.linalg.norm(apex - WAVY.point_at(np.linspace(0, 1, 200)), axis=1)
    height = 0.5 * (distance.min() + distance.max())  # some rulings reach the apex, some do not
    r = cone_rulings(WAVY, apex, height, 40)
    to_apex = apex - r.starts
    rho = np.linalg.norm(to_apex, axis=1)
    ruling = r.ends - r.starts
    np.testing.assert_allclose(np.linalg.norm(ruling, axis=1), np.minimum(height, rho), atol=1e-13)
    # every ruling points at the apex
    np.testing.assert_allclose(np.linalg.norm(np.cross(ruling, to_apex), axis=1), 0, atol=1e-12)
    assert (height >= rho).any() and (height < rho).any()


def test_cone_rulings_have_zero_warp_with_exact_tangents():
    apex = np.array([2.0, 3.0, 5.0])
    r = cone_rulings(WAVY, apex, 2.0, 60)
    assert r.warp.max() < 1e-10

    def far_edge(x):  # E(u) = C(u) + h·unit(P − C(u))
        c = WAVY.point_at(x)
        return c + 2.0 * (apex - c) / np.linalg.norm(apex - c, axis=1)[:, None]

    u, step = r.parameters[10:13], 1e-6
    numeric = (far_edge(u + step) - far_edge(u - step)) / (2 * step)
    np.testing.assert_allclose(
        r.end_tangents[10:13], numeric / np.linalg.norm(numeric, axis=1)[:, None], atol=1e-8
    )


def test_negative_cone_height_flares_away_from_the_apex():
    apex = np.array([2.5, 0.5, 3.0])
    r = cone_rulings(WAVY, apex, -1.5, 10)
    away = r.starts - apex
    np.testing.assert_allclose(
        r.ends - r.starts, 1.5 * away / np.linalg.norm(away, axis=1)[:, None], atol=1e-14
    )
    assert r.warp.max() < 1e-10


# -- tangent developable ---------------------------------------------------------------------------


def test_tangent_developable_rulings_run_along_the_exact_tangents():
    r = tangent_developable_rulings(HELIX, 36, length=3.0, cutting_length=0.5)
    u = 2 * math.pi * r.parameters
    tangent = helix_d1(u) / math.hypot(R, H)
    point = helix(u)
    np.testing.assert_allclose(r.starts, point + 0.5 * tangent, atol=1e-13)
    np.testing.assert_allclose(r.ends, point + 3.0 * tangent, atol=1e-13)


def test_tangent_developable_has_zero_warp():
    r = tangent_developable_rulings(HELIX, 80, length=4.0, cutting_length=0.3)
    assert r.warp.max() < 1e-10
    r = tangent_developable_rulings(WAVY, 80, length=1.0, cutting_length=0.1)
    assert r.warp.max() < 1e-10


def test_tangent_developable_edge_tangents_are_exact():
    """The edge v = const of the helix's tangent developable, C + vT, has tangent
    C' + vT' = C' + v·C''/|C'| (T' = C''/|C'| since |C'| is constant)."""
    v = 2.0
    r = tangent_developable_rulings(HELIX, 12, length=v, cutting_length=0.5)
    u = 2 * math.pi * r.parameters
    edge = helix_d1(u) + v * helix_d2(u) / math.hypot(R, H)
    np.testing.assert_allclose(r.end_tangents, edge / np.linalg.norm(edge, axis=1)[:, None], atol=1e-13)


def test_two_sided_tangent_developable_adds_the_backward_sheet():
    r = tangent_developable_rulings(HELIX, 10, length=2.0, cutting_length=0.25, two_sided=True)
    assert len(r.starts) == 22
    forward, backward = np.split(r.ends - r.starts, 2)
    np.testing.assert_allclose(backward, -forward, atol=1e-13)
    np.testing.assert_allclose(np.linalg.norm(forward, axis=1), 1.75)
    assert r.warp.max() < 1e-10


@pytest.mark.parametrize(
    ("length", "cutting", "two_sided"), [(1.0, 1.0, False), (0.5, 1.0, False), (1.0, -0.5, True)]
)
def test_tangent_developable_lengths_must_make_a_ruling(length, cutting, two_sided):
    with pytest.raises(ValueError):
        tangent_developable_rulings(HELIX, 4, length, cutting, two_sided)


@pytest.mark.parametrize("segments", [0, 1.5])
def test_direct_developables_need_at_least_one_segment(segments):
    with pytest.raises(ValueError, match="Segments"):
        cylinder_rulings(WAVY, [0, 0, 1], 1.0, segments)


def test_rulings_start_at_stations_evenly_spaced_along_the_curve():
    r = cone_rulings(WAVY, [0, 0, 5], 1.0, 25)
    np.testing.assert_allclose(
        np.diff(WAVY.length_at(r.parameters)), WAVY.length / 25, atol=1e-6 * WAVY.length
    )
    straight = cylinder_rulings(Line([0, 0, 0], [3, 0, 0]), [0, 1, 0], 1.0, 3)
    np.testing.assert_allclose(straight.starts[:, 0], [0, 1, 2, 3])


def test_reported_warp_is_warp_angles_of_the_returned_tangents():
    r = cone_rulings(WAVY, [1, 1, 3], 1.5, 20)
    np.testing.assert_array_equal(r.warp, warp_angles(r.starts, r.ends, r.start_tangents, r.end_tangents))
