"""Mesh Union, Difference and Intersection against closed-form volumes of overlapping cubes."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from tests.support.node_helpers import run, texts, tree
from torsal.nodes.geometry import mesh_booleans
from torsal.nodes.surfaces.mesh_booleans import MeshDifference, MeshIntersection, MeshUnion

needs_engine = pytest.mark.skipif(mesh_booleans.engine_missing() is not None,
                                  reason="manifold3d not installed")


def cube(x: float = 0.0, y: float = 0.0, z: float = 0.0, side: float = 1.0) -> trimesh.Trimesh:
    """An axis-aligned cube of ``side`` centred on (x, y, z)."""
    box = trimesh.creation.box(extents=(side, side, side))
    box.apply_translation((x, y, z))
    return trimesh.Trimesh(box.vertices, box.faces)


def meshes(*items: trimesh.Trimesh):
    """A list of meshes wired in (a mesh cannot be typed into an input)."""
    return tree({(0,): list(items)})


def result_mesh(result) -> trimesh.Trimesh:
    (mesh,) = result.output("Result").all_items()
    assert mesh_booleans.why_not_closed(mesh) is None
    return mesh


@needs_engine
@pytest.mark.parametrize("origin", [(0.0, 0.0, 0.0), (1e6, 2e6, 30.0)])
def test_two_unit_cubes_half_overlapping_give_the_volumes_of_their_union_difference_and_intersection(origin):
    x, y, z = origin
    a, b = cube(x, y, z), cube(x + 0.5, y, z)  # they share a 0.5 × 1 × 1 box
    union = result_mesh(run(MeshUnion(), Meshes=meshes(a, b)))
    difference = result_mesh(run(MeshDifference(), A=meshes(a), B=meshes(b)))
    intersection = result_mesh(run(MeshIntersection(), A=meshes(a), B=meshes(b)))
    assert union.volume == pytest.approx(1.5, rel=1e-9)
    assert difference.volume == pytest.approx(0.5, rel=1e-9)
    assert intersection.volume == pytest.approx(0.5, rel=1e-9)
    assert np.allclose(intersection.bounds, [[x, y - 0.5, z - 0.5], [x + 0.5, y + 0.5, z + 0.5]], atol=1e-9)
    assert np.allclose(difference.bounds, [[x - 0.5, y - 0.5, z - 0.5], [x, y + 0.5, z + 0.5]], atol=1e-9)


@needs_engine
def test_several_meshes_on_each_side_are_joined_first():
    a = [cube(0, 0, 0, 2.0), cube(1.5, 0, 0, 2.0)]  # together a 3.5 × 2 × 2 box from x = -1 to 2.5
    b = [cube(-1.0, 0, 0, 1.0), cube(2.5, 0, 0, 1.0)]  # two unit cubes centred on its ends
    difference = result_mesh(run(MeshDifference(), A=meshes(*a), B=meshes(*b)))
    intersection = result_mesh(run(MeshIntersection(), A=meshes(*a), B=meshes(*b)))
    assert difference.volume == pytest.approx(3.5 * 4 - 2 * 0.5, rel=1e-9)
    assert intersection.volume == pytest.approx(2 * 0.5, rel=1e-9)


@needs_engine
def test_cubes_apart_have_no_intersection_and_the_node_says_so():
    result = run(MeshIntersection(), A=meshes(cube()), B=meshes(cube(3.0)))
    assert result.state == "warning"
    assert texts(result) == ["A and B do not overlap: their intersection is empty"]
    assert result.output("Result").all_items() == [None]


def test_an_open_mesh_is_refused_naming_its_input_and_item():
    box = cube()
    open_box = trimesh.Trimesh(box.vertices, box.faces[:-1])
    result = run(MeshUnion(), Meshes=meshes(box, open_box))
    if mesh_booleans.engine_missing():
        pytest.skip("manifold3d not installed")
    assert result.state == "warning"
    assert texts(result) == [
        "Meshes item 1 cannot take part in a boolean: it is not closed: "
        "3 of its edges belong to one triangle only"
    ]


def test_without_the_engine_the_node_says_what_to_install(monkeypatch):
    monkeypatch.setattr(mesh_booleans.importlib.util, "find_spec", lambda name: None)
    result = run(MeshDifference(), A=meshes(cube()), B=meshes(cube(0.5)))
    assert result.state == "error"
    assert texts(result) == [
        "Mesh booleans need the manifold3d library, which is not installed (pip install 'torsal[booleans]')"
    ]
