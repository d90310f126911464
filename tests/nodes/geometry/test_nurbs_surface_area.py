"""NURBS surface areas, integrated knot span by knot span."""

from __future__ import annotations

import numpy as np

from torsal.nodes.geometry.curves import Circle
from torsal.nodes.geometry.nurbs_surface import Loft, NurbsSurface
from torsal.nodes.geometry.vectors import Plane


def test_bilinear_patch_area_matches_the_closed_form_of_a_flat_rectangle():
    grid = np.array([[[0, 0, 0], [0, 3, 0]], [[2, 0, 0], [2, 3, 0]]], dtype=float)
    surface = NurbsSurface(grid, 1, 1)
    area, centroid = surface.area_and_centroid()
    assert abs(area - 6.0) < 1e-12
    np.testing.assert_allclose(centroid, [1.0, 1.5, 0.0], atol=1e-12)


def test_loft_of_two_equal_circles_has_the_area_of_a_cylinder():
    """How fast, against scipy's Simpson rule in the same run: bench_areas.py."""
    radius, height = 1.5, 2.0
    circles = [Circle(Plane.from_normal([0, 0, z], [0, 0, 1]), radius) for z in (0.0, height)]
    area = Loft(circles).area()
    assert abs(area - 2 * np.pi * radius * height) < 1e-6 * area
