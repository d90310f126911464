"""The development map: carrying points and polylines between the plane and the strip."""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsal.nodes.geometry.unroll import unroll_rulings

R, H, N = 1.0, 2.0, 40  # a full cylinder of N chords
CHORD = 2.0 * R * math.sin(math.pi / N)
RNG = np.random.default_rng(7)


def cylinder_rulings(n: int = N) -> tuple[np.ndarray, np.ndarray]:
    phi = np.linspace(0.0, 2.0 * np.pi, n + 1)
    base = np.column_stack([R * np.cos(phi), R * np.sin(phi), 0 * phi])
    return base, base + np.array([0.0, 0.0, H])


def cone_rulings(n: int = 30) -> tuple[np.ndarray, np.ndarray]:
    phi = np.linspace(0.0, 1.5 * np.pi, n + 1)
    base = np.column_stack([np.cos(phi), np.sin(phi), 0 * phi])
    return base, np.broadcast_to([0.1, 0.2, 1.5], base.shape)


def hypar_rulings(n: int = 12) -> tuple[np.ndarray, np.ndarray]:
    u = np.linspace(-1.0, 1.0, n)
    return np.column_stack([u, -1 + 0 * u, -u]), np.column_stack([u, 1 + 0 * u, u])


@pytest.mark.parametrize("rulings", [cylinder_rulings, cone_rulings, hypar_rulings])
def test_strip_coordinates_map_to_the_same_point_in_both_directions(rulings):
    dev = unroll_rulings(*rulings())
    m = dev.map
    i = RNG.integers(0, m.n - 1, 2000)
    a, b = RNG.random(2000), RNG.random(2000)
    flat, space = m.strip_to_2d(i, a, b), m.strip_to_3d(i, a, b)
    size = np.ptp(space, axis=0).max()
    assert np.abs(m.to_3d(flat) - space).max() < 1e-12 * size
    assert np.abs(m.to_2d(space) - flat).max() < 1e-12 * size


def test_strip_coordinates_at_the_corners_are_the_ruling_end_points():
    starts, ends = cone_rulings()
    m = unroll_rulings(starts, ends).map
    i = np.arange(m.n - 1)
    assert np.allclose(m.strip_to_3d(i, 0.0, 0.0), starts[:-1], atol=1e-15)
    assert np.allclose(m.strip_to_3d(i, 1.0, 0.0), starts[1:], atol=1e-15)
    assert np.allclose(m.strip_to_3d(i, 0.0, 1.0), ends[:-1], atol=1e-15)
    assert np.allclose(m.strip_to_3d(i, 1.0, 1.0), ends[1:], atol=1e-15)


def test_a_straight_line_on_a_developed_cylinder_is_split_at_every_ruling_and_diagonal():
    dev = unroll_rulings(*cylinder_rulings())
    # at y = h/4 the diagonal of quad i (A_{i+1} to B_i) is crossed at x = (i + 3/4)·chord
    line = np.array([[0.1 * CHORD, H / 4], [(N - 0.1) * CHORD, H / 4]])
    flat, space = dev.map.polyline_to_3d(line)
    assert len(flat) == 2 + (N - 1) + N  # ends, inner rulings, diagonals
    assert np.abs(space[:, 2] - H / 4).max() < 1e-14  # stays at its height on the surface
    assert np.abs(np.hypot(space[:, 0], space[:, 1]) - R).max() <= R * (1 - math.cos(math.pi / N))
    length3d = np.linalg.norm(np.diff(space, axis=0), axis=1).sum()
    assert length3d == pytest.approx(np.linalg.norm(line[1] - line[0]), rel=1e-13)  # isometry


def test_a_slanted_line_on_a_developed_cylinder_becomes_a_helix_of_the_same_length():
    dev = unroll_rulings(*cylinder_rulings())
    width = N * CHORD
    line = np.array([[0.0, 0.0], [width, H]])
    flat, space = dev.map.polyline_to_3d(line)
    assert np.linalg.norm(np.diff(space, axis=0), axis=1).sum() == pytest.approx(math.hypot(width, H),
                                                                                   rel=1e-13)
    # height grows with the developed x: z = H·x/width at every vertex
    assert np.abs(space[:, 2] - H * flat[:, 0] / width).max() < 1e-13


def test_max_length_splits_long_segments_evenly():
    m = unroll_rulings(*hypar_rulings()).map
    line = np.array([[0.01, 0.1], [1.5, 1.0], [0.2, 1.8]])
    fine = m.subdivide(line, max_length=0.05)
    assert np.linalg.norm(np.diff(fine, axis=0), axis=1).max() <= 0.05 + 1e-15
    assert np.array_equal(fine[[0, -1]], line[[0, -1]])


def test_many_polylines_subdivide_as_each_one_alone():
    m = unroll_rulings(*cone_rulings()).map
    lines = [RNG.random((5, 2)) for _ in range(6)]
    together = m.subdivide_many(lines, max_length=0.3)
    for line, fine in zip(lines, together, strict=True):
        assert np.array_equal(m.subdivide(line, max_length=0.3), fine)


def test_points_just_outside_the_development_extrapolate_the_nearest_triangle():
    m = unroll_rulings(*cylinder_rulings()).map
    p3 = m.to_3d(np.array([[2.5 * CHORD, -1e-3]]))  # 1 mm below the lower rail
    assert p3[0, 2] == pytest.approx(-1e-3, abs=1e-15)


def test_a_turned_development_carries_turned_points_to_the_same_surface_points():
    dev = unroll_rulings(*cone_rulings())
    turned = dev.rotated(37.0)
    pts = dev.map.strip_to_2d(RNG.integers(0, dev.map.n - 1, 200), RNG.random(200), RNG.random(200))
    angle, centre = math.radians(37.0), dev.centroid
    c, s = math.cos(angle), math.sin(angle)
    moved = centre + (pts - centre) @ np.array([[c, s], [-s, c]])
    assert np.abs(turned.map.to_3d(moved) - dev.map.to_3d(pts)).max() < 1e-13
    assert turned.area_2d == dev.area_2d and np.allclose(turned.centroid, centre, atol=1e-14)


def test_a_seam_point_goes_to_the_side_its_hint_is_on():
    dev = unroll_rulings(*cylinder_rulings())
    seam = np.array([[R, 0.0, 0.5]])  # on the first ruling = the last ruling
    width = N * CHORD
    left = dev.map.to_2d(seam, hints2d=[[0.1, 0.5]])
    right = dev.map.to_2d(seam, hints2d=[[width - 0.1, 0.5]])
    assert np.allclose(left, [[0.0, 0.5]], atol=1e-13)
    assert np.allclose(right, [[width, 0.5]], atol=1e-12)


def test_a_panel_on_the_seam_comes_back_to_its_own_side():
    dev = unroll_rulings(*cylinder_rulings())
    width = N * CHORD
    for x0 in (0.0, width - 0.3):  # a panel touching the first, then the last ruling
        ring = np.array([[x0, 0.2], [x0 + 0.3, 0.2], [x0 + 0.3, 0.9], [x0, 0.9], [x0, 0.2]])
        flat, space = dev.map.polyline_to_3d(ring)
        assert np.abs(dev.map.polyline_to_2d(space) - flat).max() < 1e-12
