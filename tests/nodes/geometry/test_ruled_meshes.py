"""Ruled surfaces meshed together for drawing (issue "Fluid", item 3): each surface's
points and normals are its own public evaluations' (point_at, normal_at), bit for bit."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from torsal.app.headless import run_file
from torsal.nodes.geometry import ruled_meshes
from torsal.nodes.geometry.curve_rail import ruled_between
from torsal.nodes.geometry.curves import Line
from torsal.nodes.geometry.curves.conics import Circle
from torsal.nodes.geometry.curves.interpolated import InterpolatedCurve
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.geometry.ruled_meshes import ruled_mesh_arrays
from torsal.nodes.geometry.surface_base import DEGENERATE_RATIO, grid_triangles, uv_grid
from torsal.nodes.geometry.vectors import Plane

EXAMPLES = Path(__file__).resolve().parents[3] / "torsal" / "resources" / "examples"


@pytest.fixture(scope="module")
def strips() -> list[RuledSurface]:
    """The Kaohsiung roof's strip surfaces (between curve rails, fans among them)."""
    run = run_file(EXAMPLES / "kaohsiung-stadium.graph")
    return list(run.solver.results["strip"].outputs["Surface"].all_items())


def assert_drawn_as_evaluated(surfaces, meshes, nu, nv) -> None:
    u, v = uv_grid(nu, nv)
    assert len(meshes) == len(surfaces)
    for surface, (points, faces, normals) in zip(surfaces, meshes, strict=True):
        np.testing.assert_array_equal(points, surface.point_at(u, v))
        np.testing.assert_array_equal(normals, surface.normal_at(u, v))
        np.testing.assert_array_equal(faces, grid_triangles(nu, nv))


def degenerate(surface: RuledSurface, nu: int, nv: int) -> bool:
    """Whether a normal of the surface's grid degenerates (a fan's apex: re-taken inwards)."""
    _, su, sv = surface.derivatives(*uv_grid(nu, nv), 1)
    length = np.linalg.norm(np.cross(su, sv), axis=1)
    return bool((~(length > DEGENERATE_RATIO * ((su * su).sum(1) + (sv * sv).sum(1)))).any())


def test_the_kaohsiung_strips_are_drawn_as_each_evaluates_itself(strips):
    assert all(ruled_meshes._together(s) for s in strips)  # the joint pass, not one by one
    assert any(degenerate(s, 33, 2) for s in strips)  # and normals re-taken at fans' apexes
    assert_drawn_as_evaluated(strips, ruled_mesh_arrays(strips, 33, 2), 33, 2)


def test_other_surfaces_among_them_are_meshed_their_own_way_in_their_place(strips):
    a = InterpolatedCurve(np.array([[0.0, 0, 0], [1, 0.3, 0], [2, 0, 0.2], [3, 0.1, 0]]))
    lofted = RuledSurface(a, Line([0, 1, 0], [3, 1.5, 0.4]))
    from_rulings = RuledSurface.from_rulings([[0, 0, 0], [2, 0, 0]], [[0, 1, 0], [2, 1, 1]])
    mixed = [lofted, *strips[:5], from_rulings, *strips[5:9]]
    assert not ruled_meshes._together(lofted) and not ruled_meshes._together(from_rulings)
    assert_drawn_as_evaluated(mixed, ruled_mesh_arrays(mixed, 9, 3), 9, 3)


def test_a_single_surface_between_rails_is_meshed_alone(strips):
    assert_drawn_as_evaluated(strips[:1], ruled_mesh_arrays(strips[:1], 33, 2), 33, 2)


def test_strips_on_closed_curves_through_their_seams_are_drawn_as_each_evaluates_itself(strips):
    low = Circle(Plane.from_normal([0, 0, 0], [0, 0, 1]), 2.0)
    high = Circle(Plane.from_normal([0, 0, 1], [0, 0, 1]), 1.5)
    # B's parameters run on through its seam (0.95 → 0.1), A's do not
    rings = [ruled_between(low, [0.0, 0.2, 0.4, 0.6], high, [0.8, 0.95, 0.1, 0.3]),
             ruled_between(low, [0.5, 0.7, 0.9], high, [0.5, 0.6, 0.8])]
    assert all(ruled_meshes._together(s) for s in rings)
    mixed = [*rings, *strips[:3]]
    assert_drawn_as_evaluated(mixed, ruled_mesh_arrays(mixed, 33, 2), 33, 2)
