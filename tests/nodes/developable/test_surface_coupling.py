"""developable.SurfaceCoupling through real graphs (patches handed in by a source node).

Test patches that admit an exact developable connection (see nodes/geometry/coupling.py):

* two cones with one common apex (the origin), an oblique circular one and an elliptical
  one, each cut by the planes z = 1 and z = 2. Their straight edges are generators
  through the apex, the z = 2 section is the z = 1 section scaled by 2 about the apex,
  and the construction commutes with that scaling: the connector's upper curve is its
  lower curve scaled by 2, so the connector is a cone through the same apex — exactly
  developable, with partners at equal parameters.
* two flat vertical strips whose tangent planes y = x and y = −x meet in the z axis: the
  connector's curves lie in horizontal planes and are hand-computable.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from tests.support.node_helpers import out, run, texts, tree
from torsal.nodes.developable.surface_coupling import SurfaceCoupling
from torsal.nodes.geometry.curves import Line, ParametricCurve
from torsal.nodes.geometry.ruled import RuledSurface


def ellipse_arc(
    cx: float, cy: float, rx: float, ry: float, start: float, end: float, z: float
) -> ParametricCurve:
    """z·(cx + rx cos φ, cy + ry sin φ, 1) for φ from start to end: on the cone over the
    ellipse at height 1 with its apex at the origin."""
    k = end - start

    def point(t):
        p = start + k * np.asarray(t, dtype=float)
        return np.column_stack([z * (cx + rx * np.cos(p)), z * (cy + ry * np.sin(p)), np.full_like(p, z)])

    def first(t):
        p = start + k * np.asarray(t, dtype=float)
        return np.column_stack([-z * rx * k * np.sin(p), z * ry * k * np.cos(p), 0 * p])

    def second(t):
        p = start + k * np.asarray(t, dtype=float)
        return np.column_stack([-z * rx * k * k * np.cos(p), -z * ry * k * k * np.sin(p), 0 * p])

    return ParametricCurve(point, (0.0, 1.0), derivatives=(first, second))


def cone_patch(cx, cy, rx, ry, start, end) -> RuledSurface:
    """The cone strip between heights 1 and 2 (apex at the origin); rulings at edges 1, 3."""
    low = ellipse_arc(cx, cy, rx, ry, start, end, 1.0)
    return RuledSurface(low, ellipse_arc(cx, cy, rx, ry, start, end, 2.0))


CONE_A = cone_patch(3.0, 0.0, 1.0, 1.0, -1.0, 1.0)  # oblique circular cone, right of the axis
CONE_B = cone_patch(-3.0, 0.5, 1.2, 0.7, 2.2, 4.1)  # elliptical cone, left of it


def couple(a=CONE_A, b=CONE_B, edge_a=1, edge_b=3, segments=40):
    return run(SurfaceCoupling(), SurfaceA=tree({(0,): [a]}), SurfaceB=tree({(0,): [b]}),
               EdgeA=edge_a, EdgeB=edge_b, Segments=segments)


def only(result, port):
    (value,) = out(result, port)[(0,)]
    return value


def angle(a, b) -> float:
    return math.atan2(float(np.linalg.norm(np.cross(a, b))), float(np.dot(a, b)))


def into_patch(surface, u, v, along: str, sign: float) -> np.ndarray:
    """The patch's boundary tangent at corner (u, v), pointing into the patch."""
    _, su, sv = surface.derivatives(np.array([u]), np.array([v]), 1)
    return sign * (su if along == "u" else sv)[0]


# -- the bars -------------------------------------------------------------------------------


def test_connecting_curves_continue_both_patches_boundaries_at_angle_pi_to_rounding():
    result = couple()
    assert result.state == "ok"
    curve_a, curve_b = only(result, "CurveA"), only(result, "CurveB")
    # edge 1 of A is u = 1 (corners v = 0 then v = 1); edge 3 of B is u = 0, and its v = 0
    # corner (z = 1) pairs with A's z = 1 corner
    pairs = [
        (curve_a.tangent_at(0.0), into_patch(CONE_A, 1.0, 0.0, "u", -1.0)),
        (curve_b.tangent_at(0.0), into_patch(CONE_A, 1.0, 1.0, "u", -1.0)),
        (-curve_a.tangent_at(1.0), into_patch(CONE_B, 0.0, 0.0, "u", 1.0)),
        (-curve_b.tangent_at(1.0), into_patch(CONE_B, 0.0, 1.0, "u", 1.0)),
    ]
    for connector, patch in pairs:
        assert abs(angle(connector, patch) - math.pi) < 1e-14  # measured 0


def test_connecting_surface_between_two_cones_is_developable_to_rounding():
    warp = out(couple(), "WarpAngles")[(0,)]
    assert len(warp) == 41
    assert max(warp) < 1e-14  # measured 8.6e-17


def test_connecting_surface_starts_and_ends_on_the_patches_edge_rulings():
    rulings = out(couple(), "Rulings")[(0,)]
    first, last = rulings[0], rulings[-1]
    assert np.allclose([first.start, first.end], CONE_A.point_at([1.0, 1.0], [0.0, 1.0]), atol=1e-12)
    assert np.allclose([last.start, last.end], CONE_B.point_at([0.0, 0.0], [0.0, 1.0]), atol=1e-12)


def test_connecting_surface_has_each_patchs_tangent_plane_along_the_shared_ruling():
    result = couple()
    curve_a, curve_b = only(result, "CurveA"), only(result, "CurveB")
    rulings = out(result, "Rulings")[(0,)]
    for end, surface, u in ((0.0, CONE_A, 1.0), (1.0, CONE_B, 0.0)):
        ruling = rulings[0] if end == 0.0 else rulings[-1]
        r = ruling.end - ruling.start
        connector = [np.cross(r, curve.tangent_at(end)) for curve in (curve_a, curve_b)]
        patch = surface.normal_at(np.array([u, u]), np.array([0.0, 1.0]))
        for n1, n2 in zip(connector, patch, strict=True):
            assert min(angle(n1, n2), math.pi - angle(n1, n2)) < 1e-14  # measured 0


def test_connector_between_cones_with_a_common_apex_is_a_cone_through_that_apex():
    rulings = out(couple(), "Rulings")[(0,)]
    starts = np.array([r.start for r in rulings])
    ends = np.array([r.end for r in rulings])
    apex_distance = np.linalg.norm(np.cross(starts, ends), axis=1) / np.linalg.norm(ends - starts, axis=1)
    assert apex_distance.max() < 1e-14  # measured 2.3e-15


def test_connecting_curves_are_cubic_with_four_control_points():
    result = couple()
    for port in ("CurveA", "CurveB"):
        curve = only(result, port)
        assert curve.degree == 3
        assert len(curve.control_points) == 4


# -- the construction, by hand ----------------------------------------------------------------


def flat_strip(foot: list[float], corner: list[float]) -> RuledSurface:
    """A vertical flat strip 1 high from ``foot`` to ``corner`` (its edge 1 stands at the corner)."""
    up = np.array([0.0, 0.0, 1.0])
    return RuledSurface(Line(foot, corner), Line(np.add(foot, up), np.add(corner, up)))


def test_inner_control_points_sit_two_thirds_of_the_way_to_where_the_tangent_planes_meet():
    """Strips in the planes y = x (ending at (−1, −1)) and y = −x (starting at (1, −1)): their
    boundary tangent lines meet on the z axis, at the origin for z = 0."""
    a = flat_strip([-2.0, -2.0, 0.0], [-1.0, -1.0, 0.0])
    b = RuledSurface(Line([1, -1, 0], [2, -2, 0]), Line([1, -1, 1], [2, -2, 1]))
    result = couple(a, b, 1, 3, segments=8)
    assert result.state == "ok"
    third = 1.0 / 3.0
    expected = [[-1, -1, 0], [-third, -third, 0], [third, -third, 0], [1, -1, 0]]
    assert np.allclose(only(result, "CurveA").control_points, expected, atol=1e-14)
    assert np.allclose(only(result, "CurveB").control_points, np.add(expected, [0, 0, 1]), atol=1e-14)
    rulings = out(result, "Rulings")[(0,)]
    assert all(np.allclose(r.end - r.start, [0, 0, 1], atol=1e-12) for r in rulings)  # a cylinder


@pytest.mark.parametrize("strip_b, edge_b", [
    (RuledSurface(Line([1, -1, 0], [2, -2, 0]), Line([1, -1, 1], [2, -2, 1])), 3),  # runs down
    (flat_strip([2.0, -2.0, 0.0], [1.0, -1.0, 0.0]), 1),  # runs up
])
def test_edges_are_paired_bottom_to_bottom_whichever_way_edge_b_runs(strip_b, edge_b):
    a = flat_strip([-2.0, -2.0, 0.0], [-1.0, -1.0, 0.0])
    result = couple(a, strip_b, 1, edge_b, segments=8)
    assert np.allclose(only(result, "CurveA").end, [1, -1, 0], atol=1e-14)
    assert np.allclose(only(result, "CurveB").end, [1, -1, 1], atol=1e-14)


# -- inputs that cannot work ---------------------------------------------------------------


def test_a_curved_edge_is_a_warning_asking_for_a_straight_one():
    result = couple(edge_a=0)
    assert result.state == "warning"
    (message,) = texts(result)
    assert message.startswith("Edge 0 of SurfaceA is not straight (it bows ")
    assert message.endswith("couple along a straight edge, a ruling of the patch")


def test_an_edge_number_out_of_range_is_a_warning_listing_the_numbers():
    result = couple(edge_b=4)
    assert result.state == "warning"
    assert texts(result) == ["EdgeB is 4: edges are numbered 0 (v = 0), 1 (u = 1), 2 (v = 1) and 3 (u = 0)"]


def test_patches_that_already_touch_are_a_warning():
    a = flat_strip([-2.0, -2.0, 0.0], [-1.0, -1.0, 0.0])
    b = RuledSurface(Line([-1, -1, 0], [0, -2, 0]), Line([-1, -1, 1], [0, -2, 1]))
    result = couple(a, b, 1, 3)
    assert result.state == "warning"
    assert texts(result) == ["The two edges share a corner: there is no gap for a connecting surface"]


def test_a_double_curved_patch_is_warned_about():
    """A hyperbolic paraboloid's straight edge is not torsal: along the ruling (0, 1, 1) its
    tangent plane turns from normal (0, 1, −1) to (−1, 2, −2), by acos(4 / (3√2)) = 0.34 rad."""
    hypar = RuledSurface(Line([-3, -1, 0], [-1, -1, 0]), Line([-3, -1, 1], [-1, 0, 1]))
    result = couple(hypar, CONE_B, 1, 3)
    assert result.state == "warning"
    assert texts(result)[0] == (
        "Edge 1 of SurfaceA is not a torsal ruling (its tangent planes at the two corners differ by "
        f"{math.acos(4 / (3 * math.sqrt(2))):.3g} rad): the join is smooth only at its corners"
    )
