"""Ring patches and regions (torsal/nodes/geometry/developable/rings.py): a ring patch lies
on its design with the derivatives its differences show, its parameter lines round a
Gaussian bump are circles (the bump's parallels, its lines of curvature), and a region's
signed distance is the plan distance to it, none past the design's own edge."""

from __future__ import annotations

import numpy as np
import pytest
import shapely

from tests.support.freeform_designs import Design
from torsal.nodes.geometry.curve_rail import ruled_between
from torsal.nodes.geometry.curves import Line
from torsal.nodes.geometry.developable.rationalise import AIM, Strip
from torsal.nodes.geometry.developable.rings import (
    ESTIMATE,
    INSIDE,
    SETTLE,
    RingPatch,
    _estimate,
    _next_width,
    region_inside,
)


def _bump(x, y):
    e = 2 * np.exp(-(x * x + y * y) / 18)
    gx, gy = -x / 9, -y / 9
    return e, e * gx, e * gy, e * (gx * gx - 1 / 9), e * gx * gy, e * (gy * gy - 1 / 9)


def _flat(x, y):
    zero = 0 * x
    return zero, zero, zero, zero, zero, zero


DESIGN = Design("bump", _bump, (-6.0, 6.0), (-6.0, 6.0))
SCALE = np.array([12.0, 12.0])  # the plan is (x + 6, y + 6)
CENTRE = np.array([6.0, 6.0])


def _patch():
    return RingPatch(DESIGN.surface(), CENTRE, SCALE, np.linspace(1.0, 5.0, 9), (-0.2, np.pi + 0.2), 1,
                     0.5 * np.pi)


def test_a_ring_patch_lies_on_the_design_and_its_rings_are_the_bumps_parallels():
    patch = _patch()
    s, t = np.meshgrid(np.linspace(0, 1, 13), np.linspace(0, 1, 7), indexing="ij")
    points = patch.point_at(s.ravel(), t.ravel())
    assert np.allclose(points[:, 2], DESIGN.height(points[:, 0], points[:, 1]), atol=1e-12)
    radius = np.hypot(points[:, 0], points[:, 1]).reshape(s.shape)
    assert np.allclose(radius, 1.0 + 4.0 * t, atol=1e-7)  # circles, the seeds' radii
    theta = np.unwrap(np.arctan2(points[:, 1], points[:, 0]).reshape(s.shape), axis=0)
    assert np.allclose(theta, -0.2 + s * (np.pi + 0.4), atol=1e-12)


def test_a_ring_patch_derivatives_match_differences():
    patch = _patch()
    rng = np.random.default_rng(2)
    s, t = rng.uniform(0.1, 0.9, 20), rng.uniform(0.1, 0.9, 20)
    _, ps, pt, pss, pst, ptt = patch.derivatives(s, t, 2)
    h = 1e-5

    def at(a, b, k=0):
        return patch.derivatives(a, b, 1)[k]

    assert np.allclose(ps, (at(s + h, t) - at(s - h, t)) / (2 * h), atol=1e-7)
    assert np.allclose(pt, (at(s, t + h) - at(s, t - h)) / (2 * h), atol=1e-7)
    assert np.allclose(pss, (at(s + h, t, 1) - at(s - h, t, 1)) / (2 * h), atol=1e-5)
    assert np.allclose(pst, (at(s, t + h, 1) - at(s, t - h, 1)) / (2 * h), atol=1e-5)
    assert np.allclose(ptt, (at(s, t + h, 2) - at(s, t - h, 2)) / (2 * h), atol=1e-5)


def test_region_signed_distance_is_the_plan_distance_with_a_margin_inside_the_design_only():
    flat = Design("flat", _flat, (0.0, 10.0), (0.0, 4.0)).surface()
    region = shapely.box(0.0, 0.0, 5.0, 4.0)  # the left half: its edge x = 5 lies inside the design
    inside = region_inside(flat, region, [10.0, 4.0], margin=0.1)
    points = np.array([[2.0, 2.0, 0.3], [5.05, 2.0, 0.0], [5.3, 2.0, 0.0], [-0.02, 2.0, 0.0],
                       [2.0, 4.5, 0.0], [-0.3, -0.4, 0.0]])
    found = inside(points)
    # (2, 2): 2 from the design's edge (no margin there), 2.1 from the region's with it; x = 5.05 and
    # 5.3: past the region's edge inside the design (margin 0.1); x = -0.02, y = 4.5: past the design's;
    # (-0.3, -0.4): past its corner, 0.5 from it
    assert np.allclose(found, [2.0, 0.05, -0.2, -0.02, -0.5, -0.5], atol=1e-9)


def test_a_region_measures_points_distance_from_the_design_from_the_same_projection():
    flat = Design("flat", _flat, (0.0, 10.0), (0.0, 4.0)).surface()
    inside = region_inside(flat, shapely.box(0.0, 0.0, 5.0, 4.0), [10.0, 4.0], margin=0.1)
    points = np.array([[2.0, 2.0, 0.3], [4.0, 1.0, -0.25], [5.3, 2.0, 0.04]])
    signed, distance = inside.measured(points)
    assert np.allclose(signed, inside(points), atol=0.0)
    assert np.allclose(distance, [0.3, 0.25, 0.04], atol=1e-12)  # straight above or below the plane


def test_a_trial_strip_is_estimated_by_its_farthest_sample_that_the_region_keeps():
    # over the plane z = 0, a strip from the line z = x/10 (y = 1) to z = 0 (y = 3), rulings at
    # x = 0, 2.5, ..., 10: its samples lie ESTIMATE[0] per ruling interval along, so the farthest
    # one the region x <= 5 (+ 0.3) keeps is x = 5 on rail A, 0.5 above the plane
    flat = Design("flat", _flat, (0.0, 10.0), (0.0, 4.0)).surface()
    a, b = Line([0.0, 1.0, 0.0], [10.0, 1.0, 1.0]), Line([0.0, 3.0, 0.0], [10.0, 3.0, 0.0])
    at = np.linspace(0.0, 1.0, 5)
    surface = ruled_between(a, at, b, at)
    strip = Strip(0.0, 1.0, None, surface, np.zeros(5), 0.0, np.zeros(3))
    inside = region_inside(flat, shapely.box(0.0, 0.0, 5.0, 4.0), [10.0, 4.0], margin=0.3)
    assert 2.5 / ESTIMATE[0] > 0.3  # no sample past x = 5 within the margin
    assert _estimate(strip, inside) == pytest.approx(0.5, abs=1e-12)
    outside = region_inside(flat, shapely.box(0.0, 3.5, 10.0, 4.0), [10.0, 4.0])
    assert _estimate(strip, outside) == 0.0  # the region keeps none of it


def test_the_march_closes_in_on_the_square_law_width_from_both_sides_of_the_bracket():
    # deviation k·w² (the square law): the secant of √deviation through a width within and
    # one too wide lands on the width at AIM of the tolerance exactly
    k, tol = 2.0, 0.02
    w_in, w_out = 0.08, 0.11
    best = np.sqrt(AIM * tol / k)
    found = _next_width(w_out, k * w_out**2, tol, w_in, k * w_in**2, w_out, k * w_out**2, 1.0)
    assert found == pytest.approx(best, rel=1e-12)


def test_the_march_stops_where_the_deviation_jumps_rather_than_creep_up_to_it():
    # within at 0.25 (half the tolerance), beyond a hair wider: the deviation jumps between
    # them (a cut that gains a piece); no width between is worth a trial once the gap is SETTLE
    tol = 0.02
    assert _next_width(0.25, 0.01, tol, 0.25, 0.01, 0.25 * (1 + 0.5 * SETTLE), 0.03, 1.0) is None
    # a wider gap: the next trial keeps INSIDE of it from either end
    found = _next_width(0.30, 0.03, tol, 0.25, 0.0199, 0.30, 0.03, 1.0)
    assert 0.25 + INSIDE * 0.05 - 1e-12 <= found <= 0.30 - INSIDE * 0.05 + 1e-12


def test_a_deviation_growing_slower_than_the_square_law_is_followed_by_its_secant():
    # √deviation linear in w with an offset (a cut edge's share): from 0.09 and 0.1 the
    # secant reaches √(AIM·tol) where the line does, farther than the square law from 0.1
    tol = 0.02

    def root(w):
        return 0.1 + 0.25 * w

    before = (0.09, root(0.09) ** 2)
    found = _next_width(0.1, root(0.1) ** 2, tol, 0.1, root(0.1) ** 2, 2.0, np.nan, 1.0, before)
    assert found == pytest.approx((np.sqrt(AIM * tol) - 0.1) / 0.25, rel=1e-12)
    assert found > 0.1 * np.sqrt(AIM * tol) / root(0.1)


def test_a_ring_is_the_patchs_parameter_line_as_one_smooth_curve_made_once_per_level():
    patch = _patch()
    ring = patch.ring(0.5)
    assert patch.ring(0.5) is ring  # strips on both sides share the one curve
    s = np.linspace(0.0, 1.0, 997)  # between the ring's samples
    theta = -0.2 + s * (np.pi + 0.4)
    circle = 3.0 * np.column_stack([np.cos(theta), np.sin(theta)])  # the bump's parallel, radius 3
    points, tangent = ring.derivatives(s, 1)
    assert np.abs(points[:, :2] - circle).max() <= 1e-7  # (the traced rings' own accuracy)
    assert np.abs(points[:, 2] - DESIGN.height(points[:, 0], points[:, 1])).max() <= 1e-9
    along = (np.pi + 0.4) * np.column_stack([-circle[:, 1], circle[:, 0]])
    assert np.abs(tangent[:, :2] - along).max() <= 1e-6 * 3.0 * (np.pi + 0.4)
    assert np.abs(points - patch.point_at(s, np.full(len(s), 0.5))).max() <= 1e-9 * 12.0
    assert ring._breakpoints().tolist() == [0.0, 1.0]
