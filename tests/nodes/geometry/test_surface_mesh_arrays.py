"""Surface.mesh_arrays: a surface's grid mesh as plain arrays (what the viewport draws)."""

from __future__ import annotations

import numpy as np
import pytest

from torsal.nodes.geometry.parametric_surface import cone, sphere
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.geometry.surface_base import grid_triangles, uv_grid


def fan_strip() -> RuledSurface:
    """A strip whose first ruling has zero length (as a developable strip starting in a
    fan): its normals there are degenerate and re-taken a step inwards."""
    u = np.linspace(0.0, 2.0, 7)
    starts = np.column_stack([u, 0.3 * np.sin(u), 0.0 * u])
    ends = starts + np.column_stack([0.2 * u, 0.5 * u, 0.1 * u * u])
    return RuledSurface.from_rulings(starts, ends)


def test_a_planar_ruled_rectangles_mesh_is_its_bilinear_grid_facing_up():
    surface = RuledSurface.from_rulings([[0, 0, 0], [2, 0, 0]], [[0, 1, 0], [2, 1, 0]])
    points, faces, normals = surface.mesh_arrays(5, 3)
    u, v = uv_grid(5, 3)
    np.testing.assert_allclose(points, np.column_stack([2 * u, v, 0 * u]), atol=1e-15)
    np.testing.assert_array_equal(faces, grid_triangles(5, 3))
    np.testing.assert_allclose(normals, np.tile([0.0, 0.0, 1.0], (15, 1)), atol=1e-15)


@pytest.mark.parametrize("surface", [sphere(2.0), cone(1.0, 3.0), fan_strip()], ids=["sphere", "cone", "fan"])
def test_mesh_normals_are_normal_at_on_the_grid_also_where_they_degenerate(surface):
    points, _faces, normals = surface.mesh_arrays(9, 7)
    u, v = uv_grid(9, 7)
    np.testing.assert_array_equal(normals, surface.normal_at(u, v))
    np.testing.assert_array_equal(points, surface.derivatives(u, v, 1)[0])


def test_every_surface_on_one_grid_shares_one_read_only_triangle_array():
    first, second = sphere(1.0).mesh_arrays(6, 4)[1], fan_strip().mesh_arrays(6, 4)[1]
    assert first is second
    assert not first.flags.writeable


def test_to_mesh_is_the_arrays_with_triangles_of_its_own():
    surface = fan_strip()
    points, faces, normals = surface.mesh_arrays(11, 2)
    mesh = surface.to_mesh(11, 2)
    np.testing.assert_array_equal(mesh.vertices, points)
    np.testing.assert_array_equal(mesh.faces, faces)
    np.testing.assert_array_equal(mesh.vertex_normals, normals)
    mesh.faces[0] = mesh.faces[0][::-1]  # a mesh's triangles are its own to change
    assert not np.array_equal(surface.mesh_arrays(11, 2)[1][0], mesh.faces[0])


def test_a_grid_below_two_by_two_is_refused():
    with pytest.raises(ValueError, match="2 × 2"):
        fan_strip().mesh_arrays(1, 5)
