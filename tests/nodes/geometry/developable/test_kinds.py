"""Fans and creases of a strip's sheet (kinds.sheet_folds, kinds.fan_kinds), against angles
worked out by hand from the triangles' vertices and the curves' closed forms."""

from __future__ import annotations

import numpy as np
import pytest

from torsal.nodes.geometry.curve_rail import CurveRail
from torsal.nodes.geometry.curves import Line, ParametricCurve
from torsal.nodes.geometry.developable.kinds import fan_kinds, sheet_folds

WARP = 1e-7


def _strip(curve_a, curve_b, s, t):
    """Rails run at one parameter u (evenly spaced rulings) through A(s) and B(t)."""
    u = np.linspace(0.0, 1.0, len(s))
    rail_a, rail_b = CurveRail(curve_a, u, s), CurveRail(curve_b, u, t)
    return rail_a, rail_b, u, curve_a.point_at(np.asarray(s)), curve_b.point_at(np.asarray(t))


def _plane_angle(p, q, r, x, y, z):
    """The angle between the planes of triangles pqr and xyz, rad, in [0, π/2]."""
    n1, n2 = np.cross(q - p, r - p), np.cross(y - x, z - x)
    return float(np.arctan2(np.linalg.norm(np.cross(n1, n2)), abs(n1 @ n2)))


def test_two_triangles_in_one_plane_are_a_fan_and_valid():
    """Two coplanar segments bound a planar quad, closed by a fan through B(0) from three
    points of A and one through A(1) to three points of B: every ruling in the plane z = 0."""
    a, b = Line([0, 0, 0], [2, 0, 0]), Line([0, 1, 0], [3, 2, 0])
    s, t = [0.0, 0.5, 1.0, 1.0, 1.0, 1.0], [0.0, 0.0, 0.0, 1 / 3, 2 / 3, 1.0]
    rail_a, rail_b, u, starts, ends = _strip(a, b, s, t)
    judged = fan_kinds(rail_a, rail_b, u, starts, ends, np.ones(6, dtype=bool), WARP)
    assert judged.kind == ["fan"] * 6
    assert judged.flat.all()
    assert np.abs(judged.fold).max() <= 1e-12


@pytest.mark.parametrize("h", [0.1, 1e-3, 1e-6])
def test_two_triangles_at_a_known_dihedral_angle_are_a_crease_of_that_angle(h):
    """Triangles A0 A1 B0 and A1 B0 B1 between A from (0, 0, 0) to (1, 0, 0) and B from
    (0, 1, 0) to (1, 1, h): their planes z = 0 and h·x + h·y − z = h meet along A1 B0 at
    atan(√2·h) (normals (0, 0, 1) and (h, h, −1))."""
    a, b = Line([0, 0, 0], [1, 0, 0]), Line([0, 1, 0], [1, 1, h])
    rail_a, rail_b, u, starts, ends = _strip(a, b, [0.0, 1.0, 1.0], [0.0, 0.0, 1.0])
    judged = fan_kinds(rail_a, rail_b, u, starts, ends, np.ones(3, dtype=bool), WARP)
    expected = np.arctan(np.sqrt(2.0) * h)
    by_vertices = _plane_angle(starts[0], starts[1], ends[0], starts[1], ends[0], ends[2])
    assert by_vertices == pytest.approx(expected, rel=1e-9)
    assert judged.kind == ["fan", "crease", "fan"]  # (a strip's end rulings have one side)
    assert judged.fold[1] == pytest.approx(expected, rel=1e-7)
    assert not judged.flat[1]


def test_a_fold_below_the_tolerance_is_a_fan():
    h = 1e-9  # the planes meet at √2·1e-9 rad
    a, b = Line([0, 0, 0], [1, 0, 0]), Line([0, 1, 0], [1, 1, h])
    rail_a, rail_b, u, starts, ends = _strip(a, b, [0.0, 1.0, 1.0], [0.0, 0.0, 1.0])
    judged = fan_kinds(rail_a, rail_b, u, starts, ends, np.ones(3, dtype=bool), WARP)
    assert judged.kind == ["fan"] * 3 and judged.flat.all()


def _arc():
    """B(t) = (cos θ, sin θ, 1), θ = t·π/2: a quarter circle over the apex (0, 0, 0)."""

    def point(t):
        q = 0.5 * np.pi * np.asarray(t, dtype=float)
        return np.column_stack([np.cos(q), np.sin(q), np.ones_like(q)])

    def tangent(t):
        q = 0.5 * np.pi * np.asarray(t, dtype=float)
        return 0.5 * np.pi * np.column_stack([-np.sin(q), np.cos(q), np.zeros_like(q)])

    return ParametricCurve(point, (0.0, 1.0), derivatives=(tangent,))


def test_a_cone_through_one_point_of_a_is_smooth_not_a_crease():
    """Five rulings from A(0.5) = (0, 0, 0) to a quarter circle of radius 1 at height 1: a
    piece of the cone x² + y² = z², smooth (its tangent plane along a generator contains
    the circle's tangent), though the flat triangles through its chords fold by more than 0.1 rad
    at each inner ruling."""
    a = Line([-1, 0, 0], [1, 0, 0])
    t = np.linspace(0.0, 1.0, 5)
    rail_a, rail_b, u, starts, ends = _strip(a, _arc(), np.full(5, 0.5), t)
    judged = fan_kinds(rail_a, rail_b, u, starts, ends, np.ones(5, dtype=bool), WARP)
    assert judged.kind == ["fan"] * 5 and judged.flat.all()
    assert np.abs(judged.fold).max() <= 1e-9
    # the chords' triangles do fold: a cone is not a run of coplanar triangles
    apex = starts[0]
    chords = [_plane_angle(apex, ends[i - 1], ends[i], apex, ends[i], ends[i + 1]) for i in range(1, 4)]
    assert min(chords) > 0.1


def cylinder_circle(y):
    """A(φ) = (sin φ, y, cos φ), φ = the parameter: a circle of the cylinder x² + z² = 1."""

    def point(p):
        p = np.asarray(p, dtype=float)
        return np.column_stack([np.sin(p), np.full_like(p, y), np.cos(p)])

    def tangent(p):
        p = np.asarray(p, dtype=float)
        return np.column_stack([np.cos(p), np.zeros_like(p), -np.sin(p)])

    return ParametricCurve(point, (0.0, 1.0), derivatives=(tangent,))


def test_a_cone_joins_the_generators_smoothly_and_folds_against_a_warped_piece():
    """Between the cylinder's circles at y = 0 and y = 1: generators at φ = 0, 0.25, 0.5, then
    a cone through A(0.5) sweeping B to φ = 0.7, then a warped quad to A(0.75) → B(0.95). The
    cone's plane along the generator A(0.5) → B(0.5) is the cylinder's (B's tangent there is
    A's): no fold. Along its last ruling R = B(0.7) − A(0.5) the cone's plane is R × B'(0.7)
    and the quad's, at A, R × A'(0.5): the sheet folds by their angle there."""
    s = [0.0, 0.25, 0.5, 0.5, 0.5, 0.75, 1.0]
    t = [0.0, 0.25, 0.5, 0.6, 0.7, 0.95, 1.0]
    rail_a, rail_b, u, starts, ends = _strip(cylinder_circle(0.0), cylinder_circle(1.0), s, t)
    r = ends[4] - starts[4]
    n1, n2 = np.cross(r, [np.cos(0.5), 0, -np.sin(0.5)]), np.cross(r, [np.cos(0.7), 0, -np.sin(0.7)])
    expected = np.arccos(n1 @ n2 / np.linalg.norm(n1) / np.linalg.norm(n2))
    folds = sheet_folds(rail_a, rail_b, u, starts, ends)
    assert folds.across[2] <= 1e-9 and folds.across[3] <= 1e-9
    assert folds.across[4] == pytest.approx(expected, rel=1e-6)
    fan = np.array([False, False, True, True, True, False, False])  # (the cone's rulings)
    judged = fan_kinds(rail_a, rail_b, u, starts, ends, fan, WARP)
    assert judged.kind == ["torsal", "torsal", "fan", "fan", "crease", "torsal", "torsal"]
    assert judged.flat[:4].all() and not judged.flat[4:6].any()
