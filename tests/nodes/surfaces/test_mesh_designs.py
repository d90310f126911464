"""A mesh design (OBJ through trimesh) becomes a surface Rationalise can cover within tolerance.

The mesh is a canopy sampled on a 61 × 41 grid and written as OBJ; distances are checked
independently: surface samples against the mesh's own triangles (matplotlib's linear
interpolation on them, vertical distance, an upper bound), mesh vertices against the
surface (its closest points).
"""

from __future__ import annotations

import matplotlib.tri as mtri
import numpy as np
import pytest
import trimesh

from tests.support.node_helpers import run, texts, tree
from tests.support.strip_grids import distance_to_strip
from torsal.engine.solver import OK, WARNING
from torsal.nodes.io.meshes import ImportMesh
from torsal.nodes.surfaces.mesh import SurfaceFromMesh


def canopy_mesh(wall: bool = False) -> trimesh.Trimesh:
    x, y = np.linspace(0, 12, 61), np.linspace(0, 8, 41)
    gx, gy = np.meshgrid(x, y, indexing="ij")
    across = 1 - ((gy - 4) / 4) ** 2
    gz = 3 + 1.2 * across - 0.3 * (1 - ((gx - 6) / 6) ** 2) * across + 0.2 * np.sin(gx / 2)
    if wall:  # fold the last columns down into a wall
        gz[-6:] -= np.linspace(0, 40, 6)[:, None]
        gx[-6:] = gx[-6]
    vertices = np.stack([gx, gy, gz], -1).reshape(-1, 3)
    index = np.arange(gx.size).reshape(gx.shape)
    a, b, c, d = (index[:-1, :-1].ravel(), index[1:, :-1].ravel(), index[1:, 1:].ravel(),
                  index[:-1, 1:].ravel())
    faces = np.vstack([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    return trimesh.Trimesh(vertices, faces, process=False)


def test_a_mesh_design_from_an_obj_file_is_fitted_within_its_tolerance(tmp_path):
    source = canopy_mesh()
    source.export(str(tmp_path / "canopy.obj"), digits=15)
    mesh = run(ImportMesh(), Path=str(tmp_path / "canopy.obj")).outputs["Mesh"].all_items()[0]
    result = run(SurfaceFromMesh(), Mesh=tree({(0,): [mesh]}), Tolerance=0.002)
    assert result.state == OK, texts(result)
    (surface,) = result.outputs["Surface"].all_items()
    (deviation,) = result.outputs["Deviation"].all_items()
    assert deviation <= 0.002
    vertices, faces = np.asarray(source.vertices), np.asarray(source.faces)
    on_mesh = mtri.LinearTriInterpolator(mtri.Triangulation(vertices[:, 0], vertices[:, 1], faces),
                                         vertices[:, 2])
    uv = np.random.default_rng(4).random((3000, 2))
    points = surface.point_at(uv[:, 0], uv[:, 1])
    heights = np.ma.filled(on_mesh(points[:, 0], points[:, 1]), np.nan)
    inside = np.isfinite(heights)
    assert inside.mean() > 0.98
    assert np.abs(heights[inside] - points[inside, 2]).max() <= 0.002
    assert surface.closest_point(vertices).distances.max() <= 0.002


def test_a_mesh_that_folds_over_its_plane_is_refused_with_the_reason():
    result = run(SurfaceFromMesh(), Mesh=tree({(0,): [canopy_mesh(wall=True)]}), Tolerance=0.002)
    assert result.state == WARNING
    assert "folds over itself" in texts(result)[0]


@pytest.mark.parametrize("tolerance", [0.0, -1.0, float("nan"), 1e9])
def test_a_tolerance_that_is_no_distance_or_larger_than_the_mesh_is_a_warning_naming_it(tolerance):
    result = run(SurfaceFromMesh(), Mesh=tree({(0,): [canopy_mesh()]}), Tolerance=tolerance)
    assert result.state == WARNING and texts(result)[0].startswith("Tolerance must be")


def test_rationalise_on_the_fitted_surface_keeps_its_strips_within_tolerance_of_the_mesh():
    from torsal.nodes.developable.rationalise import Rationalise

    source = canopy_mesh()
    fit = run(SurfaceFromMesh(), Mesh=tree({(0,): [source]}), Tolerance=0.002)
    (surface,) = fit.outputs["Surface"].all_items()
    (deviation,) = fit.outputs["Deviation"].all_items()
    result = run(Rationalise(), Surface=tree({(0,): [surface]}), Tolerance=0.03 - deviation)
    strips = result.outputs["Strips"].all_items()
    assert strips
    vertices, faces = np.asarray(source.vertices), np.asarray(source.faces)
    on_mesh = mtri.LinearTriInterpolator(mtri.Triangulation(vertices[:, 0], vertices[:, 1], faces),
                                         vertices[:, 2])
    u, v = np.meshgrid(np.linspace(0, 1, 41), np.linspace(0, 1, 9))
    for strip in strips:
        points = strip.point_at(u.ravel(), v.ravel())
        heights = np.ma.filled(on_mesh(points[:, 0], points[:, 1]), np.nan)
        inside = np.isfinite(heights)
        assert np.abs(heights[inside] - points[inside, 2]).max() <= 0.03


def distance_to_triangles(mesh: trimesh.Trimesh, points: np.ndarray, nearest: int = 24) -> np.ndarray:
    """Each point's exact distance to the mesh: trimesh's closest point on the triangles whose
    centres are nearest it (a KD tree on the centres; the mesh's cells are 20 cm, the points
    within centimetres of it)."""
    from scipy.spatial import cKDTree

    _, index = cKDTree(mesh.triangles_center).query(points, k=nearest)
    query = np.repeat(points, nearest, axis=0)
    found = trimesh.triangles.closest_point(mesh.triangles[np.asarray(index).ravel()], query)
    return np.linalg.norm(found - query, axis=1).reshape(len(points), nearest).min(axis=1)


def test_rationalised_strips_of_a_mesh_file_lie_within_the_tolerance_of_the_mesh_itself(tmp_path):
    from torsal.nodes.developable.rationalise import Rationalise

    source = canopy_mesh()
    source.export(str(tmp_path / "canopy.ply"))
    mesh = run(ImportMesh(), Path=str(tmp_path / "canopy.ply")).outputs["Mesh"].all_items()[0]
    fit = run(SurfaceFromMesh(), Mesh=tree({(0,): [mesh]}), Tolerance=0.002)
    assert fit.state == OK, texts(fit)
    (surface,) = fit.outputs["Surface"].all_items()
    (deviation,) = fit.outputs["Deviation"].all_items()
    result = run(Rationalise(), Surface=tree({(0,): [surface]}), Tolerance=0.03 - deviation)
    assert result.state == OK, texts(result)
    u, v = np.meshgrid(np.linspace(0, 1, 121), np.linspace(0, 1, 17))
    points = np.concatenate([s.point_at(u.ravel(), v.ravel()) for s in result.outputs["Strips"].all_items()])
    # measured 2.82 cm (4.6 cm at the curved ends before the fit was trimmed by the outline)
    assert distance_to_triangles(source, points).max() <= 0.03
    # and the strips reach the mesh's edges: its boundary vertices within the tolerance of them
    edges = np.sort(np.asarray(source.faces)[:, [0, 1, 1, 2, 2, 0]].reshape(-1, 2), axis=1)
    unique, count = np.unique(edges, axis=0, return_counts=True)
    boundary = np.asarray(source.vertices)[np.unique(unique[count == 1])]
    strips = result.outputs["Strips"].all_items()
    assert np.min([distance_to_strip(s, boundary) for s in strips], axis=0).max() <= 0.03  # measured 2.29 cm


def test_a_mesh_over_a_tilted_rectangle_is_fitted_over_that_rectangle_untrimmed():
    # a cushion that is 0 on the edges of a 10 × 6 rectangle, turned about an arbitrary axis:
    # its outline is that rectangle, in a plane neither the world's nor its vertices' mean plane
    x, y = np.linspace(-5, 5, 51), np.linspace(-3, 3, 31)
    gx, gy = np.meshgrid(x, y, indexing="ij")
    gz = 1.5 * (1 - (gx / 5) ** 2) * (1 - (gy / 3) ** 2) + 0.4 * np.sin(np.pi * gx / 5) * (1 - (gy / 3) ** 2)
    from scipy.spatial.transform import Rotation

    turn, shift = Rotation.from_rotvec([0.3, -0.5, 0.7]), np.array([100.0, -40.0, 7.0])
    vertices = turn.apply(np.stack([gx, gy, gz], -1).reshape(-1, 3)) + shift
    index = np.arange(gx.size).reshape(gx.shape)
    a, b, c, d = (index[:-1, :-1].ravel(), index[1:, :-1].ravel(), index[1:, 1:].ravel(),
                  index[:-1, 1:].ravel())
    mesh = trimesh.Trimesh(vertices, np.vstack([np.column_stack([a, b, c]), np.column_stack([a, c, d])]),
                           process=False)
    # (the mesh's chords are 5 mm off the cushion: a tolerance it can be fitted to)
    result = run(SurfaceFromMesh(), Mesh=tree({(0,): [mesh]}), Tolerance=0.01)
    assert result.state == OK, texts(result)
    (surface,) = result.outputs["Surface"].all_items()
    assert type(surface).__name__ == "NurbsSurface"  # not trimmed: the outline is its rectangle
    corners = surface.point_at(np.array([0.0, 1.0, 0.0, 1.0]), np.array([0.0, 0.0, 1.0, 1.0]))
    expected = turn.apply([[sx * 5, sy * 3, 0.0] for sx in (-1, 1) for sy in (-1, 1)]) + shift
    gaps = np.linalg.norm(corners[:, None] - expected[None], axis=2).min(axis=1)
    assert gaps.max() <= 0.01  # measured 8e-15: the rectangle is the outline
