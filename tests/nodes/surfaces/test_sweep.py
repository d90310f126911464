"""Sweep1: a circle swept along an arc is a piece of a torus, along a line a cylinder (closed forms)."""

from __future__ import annotations

import math

import numpy as np

from tests.support.node_helpers import out, run, texts, tree
from torsal.nodes.geometry.curves import Arc, Circle, Line, NurbsCurve, Polyline
from torsal.nodes.geometry.vectors import Plane
from torsal.nodes.surfaces.sweep import Sweep1

GRID = np.meshgrid(np.linspace(0, 1, 41), np.linspace(0, 1, 41))


def _sweep(rail, profile, **inputs):
    result = run(Sweep1(), Rail=tree({(0,): [rail]}), Profile=tree({(0,): [profile]}), **inputs)
    assert result.state == "ok", texts(result)
    return out(result)[(0,)][0].point_at(GRID[0].ravel(), GRID[1].ravel())


def test_a_circle_swept_along_a_quarter_arc_is_a_quarter_torus():
    big, small = 5.0, 1.0
    rail = Arc(Plane.from_normal([0, 0, 0], [0, 0, 1]), big, 0.0, math.pi / 2)
    profile = Circle(Plane.from_axes([big, 0, 0], [1, 0, 0], [0, 0, 1]), small)  # square to the rail
    p = _sweep(rail, profile)
    from_tube_centre = np.hypot(np.hypot(p[:, 0], p[:, 1]) - big, p[:, 2])
    assert np.abs(from_tube_centre - small).max() < 1e-6 * small  # 3.8e-7 measured at 33 sections
    angle = np.arctan2(p[:, 1], p[:, 0])
    assert angle.min() > -1e-12 and abs(angle.max() - math.pi / 2) < 1e-12


def test_a_profile_away_from_the_rail_keeps_its_place_a_square_along_a_line_is_a_tube():
    rail = Line([0, 0, 0], [0, 0, 7])
    square = Polyline([[2, -1, 0], [4, -1, 0], [4, 1, 0], [2, 1, 0]], closed=True)
    p = _sweep(rail, square, Sections=4)
    assert p[:, 2].min() > -1e-12 and p[:, 2].max() < 7 + 1e-12
    # every point keeps the square's x and y: the profile slides along z without turning
    on_sides = (np.isclose(p[:, 0], 2) | np.isclose(p[:, 0], 4)) & (np.abs(p[:, 1]) <= 1 + 1e-12)
    on_ends = (np.isclose(np.abs(p[:, 1]), 1)) & (p[:, 0] >= 2 - 1e-12) & (p[:, 0] <= 4 + 1e-12)
    assert np.all(on_sides | on_ends)


def test_sweep_refuses_three_sections_naming_sections():
    result = run(Sweep1(), Rail=tree({(0,): [Line([0, 0, 0], [0, 0, 1])]}),
                 Profile=tree({(0,): [Line([0, 0, 0], [1, 0, 0])]}), Sections=3)
    assert result.state == "warning"
    assert texts(result)[0].startswith("Sections must be at least 4")


def test_a_sweep_along_a_closed_knotted_rail_closes_its_last_section_onto_its_first():
    # a (2, 3) torus knot's curve: its torsion leaves plain rotation-minimising frames turned
    # after one round; the sweep shares that turn out along the rail
    t = np.linspace(0, 2 * np.pi, 13)[:-1]
    points = np.stack([(3 + np.cos(3 * t)) * np.cos(2 * t), (3 + np.cos(3 * t)) * np.sin(2 * t),
                       np.sin(3 * t)], axis=1)
    rail = NurbsCurve(points, degree=3, periodic=True)
    start, along = rail.point_at(0.0), rail.tangent_at(0.0)
    side = np.cross(along, [0.0, 0.0, 1.0])
    side /= np.linalg.norm(side)
    up = np.cross(along, side)
    corners = [start + 0.3 * side, start + 0.3 * up, start - 0.3 * side, start - 0.3 * up]
    square = Polyline(corners, closed=True)
    result = run(Sweep1(), Rail=tree({(0,): [rail]}), Profile=tree({(0,): [square]}), Sections=40)
    assert result.state == "ok", texts(result)
    surface = out(result)[(0,)][0]
    u = np.linspace(0, 1, 17)
    first, last = surface.point_at(u, np.zeros_like(u)), surface.point_at(u, np.ones_like(u))
    assert np.abs(first - last).max() < 1e-9 * 4  # the knot is about 4 across
