"""Divide Surface, Contour and Section: grids from a bilinear patch's closed form; sections
of spheres against their circles and of meshes against trimesh's own plane cuts."""

from __future__ import annotations

import math

import numpy as np
import pytest
import trimesh

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.values import Plane, Point, Vector
from torsal.nodes.geometry.curves import Polyline
from torsal.nodes.geometry.nurbs_surface import NurbsSurface
from torsal.nodes.geometry.trimmed_surface import TrimmedSurface
from torsal.nodes.surfaces.division import DivideSurface
from torsal.nodes.surfaces.primitives import Sphere
from torsal.nodes.surfaces.sections import Contour, Section

CORNERS = np.array([[[0, 0, 0], [0, 4, 1]], [[6, 0, 2], [6, 4, 0]]], dtype=float)  # a twisted patch


def _items(result, port=None):
    return [item for branch in out(result, port).values() for item in branch]


def _sphere(radius: float):
    return _items(run(Sphere(), Radius=radius))[0]


def test_divide_surface_gives_rows_of_the_bilinear_patchs_points():
    patch = NurbsSurface(CORNERS, degree_u=1, degree_v=1)
    result = run(DivideSurface(), Surface=tree({(0,): [patch]}), U=3, V=2)
    rows = out(result, "Points")
    assert list(rows) == [(0, 0), (0, 1), (0, 2), (0, 3)]
    for i, row in enumerate(rows.values()):
        u = i / 3
        for j, p in enumerate(row):
            v = j / 2  # the bilinear form (1-u)(1-v)P00 + u(1-v)P10 + (1-u)v P01 + uv P11
            expected = ((1 - u) * (1 - v) * CORNERS[0, 0] + u * (1 - v) * CORNERS[1, 0]
                        + (1 - u) * v * CORNERS[0, 1] + u * v * CORNERS[1, 1])
            assert list(p) == pytest.approx(expected.tolist(), abs=1e-14)
    uv = _items(result, "Parameters")
    assert [(p[0], p[1]) for p in uv[:3]] == [(0.0, 0.0), (0.0, 0.5), (0.0, 1.0)]


def test_divide_surface_refuses_a_count_of_zero_naming_u():
    result = run(DivideSurface(), Surface=tree({(0,): [_sphere(1.0)]}), U=0)
    assert result.state == "warning"
    assert texts(result)[0].startswith("U must be at least 1")


def test_contours_of_a_sphere_are_closed_circles_on_the_sphere_and_their_planes():
    r = 2.0
    result = run(Contour(), Shape=tree({(0,): [_sphere(r)]}), Distance=0.5, Density=97)
    curves, levels = _items(result, "Curves"), _items(result, "Levels")
    inside = [k * 0.5 for k in range(-3, 4)]  # the planes strictly between the poles
    assert [lv for lv in levels if abs(lv) < r] == inside
    for curve, level in zip(curves, levels, strict=True):
        if abs(level) >= r:
            continue
        assert isinstance(curve, Polyline) and curve.closed
        points = curve.points
        assert np.abs(np.linalg.norm(points, axis=1) - r).max() < 1e-12 * r  # corners on the sphere
        assert np.abs(points[:, 2] - level).max() < 1e-12 * r  # and on the plane
        circle = 2 * math.pi * math.sqrt(r * r - level * level)
        assert curve.length == pytest.approx(circle, rel=2e-4)  # the chords of a 97-point grid


def test_contours_of_a_mesh_match_trimeshs_plane_cuts():
    mesh = trimesh.creation.icosphere(subdivisions=3, radius=3.0)
    result = run(Contour(), Shape=tree({(0,): [mesh]}), Point=Point(0.1, 0.0, 0.0),
                 Direction=Vector(1.0, 1.0, 0.0), Distance=0.7)
    curves, levels = _items(result, "Curves"), _items(result, "Levels")
    normal = np.array([1.0, 1.0, 0.0]) / math.sqrt(2)
    for level in sorted(set(levels)):
        origin = np.array([0.1, 0.0, 0.0]) + level * normal
        lines = trimesh.intersections.mesh_plane(mesh, normal, origin)
        expected = float(np.linalg.norm(lines[:, 0] - lines[:, 1], axis=1).sum())
        ours = sum(c.length for c, lv in zip(curves, levels, strict=True) if lv == level)
        assert ours == pytest.approx(expected, rel=1e-12)


def test_section_by_a_plane_that_misses_gives_nothing_and_a_cutting_one_a_closed_curve():
    sphere = _sphere(1.0)
    missing = run(Section(), Shape=tree({(0,): [sphere]}), Plane=Plane(Point(0, 0, 5), Vector(1, 0, 0),
                                                                       Vector(0, 1, 0)))
    assert missing.state == "ok" and _items(missing) == []
    tilted = Plane(Point(0, 0, 0.3), Vector(1, 0, 0.5), Vector(0, 1, 0))
    (curve,) = _items(run(Section(), Shape=tree({(0,): [sphere]}), Plane=tilted, Density=129))
    normal = np.cross([1, 0, 0.5], [0, 1, 0])
    normal /= np.linalg.norm(normal)
    distance = 0.3 * normal[2]  # from the centre to the plane
    assert curve.closed
    assert curve.length == pytest.approx(2 * math.pi * math.sqrt(1 - distance**2), rel=1e-4)


def test_contour_refuses_a_zero_distance_naming_it():
    result = run(Contour(), Shape=tree({(0,): [_sphere(1.0)]}), Distance=0.0)
    assert result.state == "warning"
    assert texts(result)[0].startswith("Distance must be a positive length")


def test_a_section_of_a_trimmed_surface_keeps_only_the_part_inside_the_trim():
    corners = np.array([[[0, 0, 0], [0, 4, 0]], [[4, 0, 0], [4, 4, 0]]], float)
    square = NurbsSurface(corners, degree_u=1, degree_v=1)
    around = np.linspace(0, 2 * np.pi, 401)
    loop = np.stack([0.5 + 0.4 * np.cos(around), 0.5 + 0.4 * np.sin(around)], axis=1)
    disc = TrimmedSurface(square, loop)
    plane = Plane(Point(2.5, 0, 0), Vector(0, 1, 0), Vector(0, 0, 1))  # x = 2.5, 0.5 from the disc's centre
    (chord,) = _items(run(Section(), Shape=tree({(0,): [disc]}), Plane=plane))
    # the disc of radius 1.6 round (2, 2), cut 0.5 from its centre (its trim a 400-gon: 5e-5 off the circle)
    assert chord.length == pytest.approx(2 * math.sqrt(1.6**2 - 0.5**2), abs=2e-4)
    ends = chord.points[[0, -1]]
    assert np.allclose(ends[:, 0], 2.5, atol=1e-12)
    assert np.abs(np.hypot(ends[:, 0] - 2, ends[:, 1] - 2) - 1.6).max() < 1e-4
