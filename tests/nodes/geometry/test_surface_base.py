"""The generic Surface contract: evaluation shapes, isocurves, edges, meshing, boxes."""

from __future__ import annotations

import numpy as np
import pytest

from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.nurbs_surface import NurbsSurface
from torsal.nodes.geometry.parametric_surface import ParametricSurface, cylinder, sphere, torus
from torsal.nodes.geometry.surface_base import IsoCurve, TransformedSurface, uv_grid


def saddle():
    return ParametricSurface(lambda x, y: (x, y, x * y), (-1.0, 2.0), (-1.0, 1.0))


def test_point_at_returns_a_point_for_scalars_and_rows_for_arrays():
    surface = saddle()
    assert surface.point_at(0.5, 0.5).shape == (3,)
    assert surface.point_at([0.1, 0.2, 0.3], 0.5).shape == (3, 3)
    assert surface.point_at(np.zeros((2, 4)), np.ones((2, 4))).shape == (8, 3)
    np.testing.assert_allclose(surface.point_at(0.0, 1.0), [-1.0, 1.0, -1.0])


def test_derivatives_come_in_the_documented_order():
    surface = saddle()
    assert len(surface.derivatives(0.2, 0.3, 0)) == 1
    assert len(surface.derivatives(0.2, 0.3, 1)) == 3
    _, su, sv, suu, suv, svv = surface.derivatives(0.2, 0.3, 2)
    # x = −1 + 3s, y = −1 + 2t: Su = 3·(1, 0, y), Sv = 2·(0, 1, x), Suv = 6·(0, 0, 1)
    x, y = -1 + 3 * 0.2, -1 + 2 * 0.3
    np.testing.assert_allclose(su[0], [3, 0, 3 * y], atol=1e-11)
    np.testing.assert_allclose(sv[0], [0, 2, 2 * x], atol=1e-11)
    np.testing.assert_allclose(suv[0], [0, 0, 6], atol=1e-9)
    np.testing.assert_allclose(suu[0], 0, atol=1e-9)
    np.testing.assert_allclose(svv[0], 0, atol=1e-9)
    with pytest.raises(ValueError, match="order 2"):
        surface.derivatives(0.2, 0.3, 3)


def test_edges_run_counter_clockwise_and_join_end_to_start():
    surface = saddle()
    edges = surface.edges()
    corners = [surface.point_at(*c) for c in [(0, 0), (1, 0), (1, 1), (0, 1)]]
    for k, edge in enumerate(edges):
        assert isinstance(edge, Curve)
        np.testing.assert_allclose(edge.point_at(0.0), corners[k], atol=1e-15)
        np.testing.assert_allclose(edge.point_at(1.0), corners[(k + 1) % 4], atol=1e-15)
        np.testing.assert_allclose(edges[k].point_at(1.0), edges[(k + 1) % 4].point_at(0.0))
    # Edge 0 is v = 0, edge 1 is u = 1, edge 2 is v = 1, edge 3 is u = 0.
    t = np.linspace(0, 1, 5)
    np.testing.assert_allclose(edges[0].point_at(t), surface.point_at(t, 0.0))
    np.testing.assert_allclose(edges[1].point_at(t), surface.point_at(1.0, t))
    np.testing.assert_allclose(edges[2].point_at(t), surface.point_at(1 - t, 1.0))
    np.testing.assert_allclose(edges[3].point_at(t), surface.point_at(0.0, 1 - t))


def test_isocurve_derivatives_are_the_surface_partials():
    surface = torus(2.0, 0.5)
    t = np.linspace(0, 1, 7)
    _, c1, c2 = surface.isocurve("v", 0.3).derivatives(t, 2)
    *_, sv, _, _, svv = surface.derivatives(0.3, t, 2)
    np.testing.assert_allclose(c1, sv)
    np.testing.assert_allclose(c2, svv)
    _, r1, r2 = IsoCurve(surface, "u", 0.6, reverse=True).derivatives(t, 2)
    _, su, _, suu, _, _ = surface.derivatives(1 - t, 0.6, 2)
    np.testing.assert_allclose(r1, -su)
    np.testing.assert_allclose(r2, suu)


def test_isocurve_third_derivative_of_a_circle_by_differences():
    # The u-isocurve of the torus at v = 0 is the circle of radius R + r, t ↦ 2πt.
    big, small = 2.0, 0.5
    circle = torus(big, small).isocurve("u", 0.0)
    t = np.linspace(0, 1, 9)
    third = circle.derivatives(t, 3)[3]
    w = 2 * np.pi
    exact = (big + small) * w**3 * np.column_stack([np.sin(w * t), -np.cos(w * t), 0 * t])
    np.testing.assert_allclose(third, exact, atol=1e-8 * np.abs(exact).max())
    assert circle.closed


def test_isocurve_rejects_unknown_direction():
    with pytest.raises(ValueError, match="'u' or 'v'"):
        saddle().isocurve("w", 0.5)


def test_to_mesh_vertices_follow_the_grid_and_faces_the_normal():
    surface = saddle()
    mesh = surface.to_mesh(7, 5)
    gu, gv = uv_grid(7, 5)
    np.testing.assert_allclose(mesh.vertices, surface.point_at(gu, gv))
    assert len(mesh.faces) == 2 * 6 * 4
    face_normal_at_centroid = surface.normal_at(gu[mesh.faces].mean(axis=1), gv[mesh.faces].mean(axis=1))
    assert np.all(np.einsum("ij,ij->i", mesh.face_normals, face_normal_at_centroid) > 0.9)
    with pytest.raises(ValueError):
        surface.to_mesh(1, 5)


def test_bounding_box_is_tight_beyond_the_sampling():
    surface = torus(2.0, 0.7)
    np.testing.assert_allclose(
        surface.bounding_box(samples=5), [[-2.7, -2.7, -0.7], [2.7, 2.7, 0.7]], atol=1e-9
    )
    box = sphere(1.0, center=(1, 2, 3)).bounding_box(samples=3)
    np.testing.assert_allclose(box, [[0, 1, 2], [2, 3, 4]], atol=1e-9)


def test_transformed_surface_moves_points_and_keeps_curvature():
    angle = 0.7
    rotation = np.array([[np.cos(angle), -np.sin(angle), 0], [np.sin(angle), np.cos(angle), 0], [0, 0, 1]])
    matrix = np.eye(4)
    matrix[:3, :3], matrix[:3, 3] = rotation, [1.0, -2.0, 0.5]
    original = torus(2.0, 0.7)
    moved = original.transformed(matrix)
    assert isinstance(moved, TransformedSurface) and moved.closed_u and moved.closed_v
    u, v = np.linspace(0, 1, 9), np.linspace(0.1, 0.9, 9)
    np.testing.assert_allclose(moved.point_at(u, v), original.point_at(u, v) @ rotation.T + [1.0, -2.0, 0.5])
    np.testing.assert_allclose(moved.gaussian_curvature(u, v), original.gaussian_curvature(u, v), rtol=1e-12)
    with pytest.raises(ValueError):
        original.transformed(np.ones((4, 4)))


def test_closedness_is_detected_from_the_edges():
    assert torus().closed_u and torus().closed_v
    wrapped = ParametricSurface(lambda u, v: (np.cos(u), np.sin(u), v), (-3.7, -3.7 + 2 * np.pi), (0, 1))
    assert wrapped.closed_u and not wrapped.closed_v
    assert not saddle().closed_u
    rng = np.random.default_rng(0)
    assert not NurbsSurface(rng.random((4, 4, 3)), 3, 3).closed_u
    assert cylinder().isocurve("u", 0.5).closed


def test_frame_is_orthonormal_with_x_along_su():
    surface = saddle()
    _, x, y, z = surface.frame_at([0.2, 0.7], [0.4, 0.9])
    _, su, _ = surface.derivatives([0.2, 0.7], [0.4, 0.9], 1)
    np.testing.assert_allclose(x, su / np.linalg.norm(su, axis=1, keepdims=True))
    np.testing.assert_allclose(np.cross(x, y), z, atol=1e-15)
    np.testing.assert_allclose(np.einsum("ij,ij->i", x, y), 0.0, atol=1e-15)


def test_parametric_surface_accepts_stacked_transposed_and_constant_results():
    flat = ParametricSurface(lambda u, v: (u, v, 0.0))
    np.testing.assert_allclose(flat.point_at([0.5], [0.25]), [[0.5, 0.25, 0.0]])
    transposed = ParametricSurface(lambda u, v: np.vstack([u, v, u + v]))
    np.testing.assert_allclose(transposed.point_at([0.5, 0.1], [0.25, 0.2])[:, 2], [0.75, 0.3])
    with pytest.raises(ValueError, match="empty"):
        ParametricSurface(lambda u, v: (u, v, 0.0), (1.0, 1.0))
    with pytest.raises(ValueError, match="shape"):
        ParametricSurface(lambda u, v: np.zeros((len(u), 2)))


def test_isocurve_of_nurbs_surface_breaks_at_its_knots():
    grid = np.random.default_rng(0).random((6, 5, 3))
    surface = NurbsSurface(grid, 3, 2)
    iso = surface.isocurve("u", 0.5)
    np.testing.assert_allclose(iso._breakpoints(), np.unique(surface.knots_u))
    assert iso.length == pytest.approx(
        np.sum(np.linalg.norm(np.diff(iso.point_at(np.linspace(0, 1, 20001)), axis=0), axis=1)),
        rel=1e-8,
    )
