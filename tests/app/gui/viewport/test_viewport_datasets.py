"""The viewport's datasets: arrows for vectors, and moving points in place during a drag."""

from __future__ import annotations

import numpy as np

from torsal.app.gui.viewport.datasets import (
    ARROW_HEAD,
    ARROW_RADIUS,
    ARROW_SIDES,
    Piece,
    arrows,
    collect,
    dataset,
    move_points,
    pieces,
    same_topology,
)
from torsal.engine.values import Vector
from torsal.nodes.geometry.curves import Line


def test_an_arrow_runs_from_the_origin_to_its_vector_with_a_cone_head():
    vectors = np.array([[3.0, 0.0, 0.0], [0.0, 0.0, 2.0], [1.0, 2.0, 2.0]])
    points, faces, lines = arrows(vectors)
    stride = 3 + ARROW_SIDES
    assert points.shape == (3 * stride, 3) and faces.shape == (3 * 2 * ARROW_SIDES, 3)
    for k, vector in enumerate(vectors):
        length = np.linalg.norm(vector)
        origin, base, tip, rim = points[k * stride], points[k * stride + 1], points[k * stride + 2], points[
            k * stride + 3 : (k + 1) * stride
        ]
        np.testing.assert_allclose(origin, 0.0, atol=1e-15)
        np.testing.assert_allclose(tip, vector, atol=1e-15)
        np.testing.assert_allclose(base, (1 - ARROW_HEAD) * vector, atol=1e-14)
        np.testing.assert_allclose(np.linalg.norm(rim - base, axis=1), ARROW_RADIUS * length, rtol=1e-12)
        np.testing.assert_allclose((rim - base) @ vector, 0.0, atol=1e-12)  # the rim is square to the axis
    # each shaft is one line from the origin to the head's base
    assert lines.tolist()[:3] == [2, 0, 1] and len(lines) == 3 * 3
    # cone faces point outwards: their normals have a positive component away from the axis
    a, b, c = points[faces[:ARROW_SIDES]].transpose(1, 0, 2)
    normals = np.cross(b - a, c - a)
    outward = (a + b) / 2 - points[1]
    assert np.all(np.einsum("ij,ij->i", normals, outward) > 0)


def test_vectors_and_geometry_collect_into_one_piece_per_kind():
    found = collect([Vector(0, 0, 1), Vector(1, 0, 0), Line((0, 0, 0), (1, 1, 0)), 4.0, "text"])
    kinds = {p.kind: p for p in pieces(found)}
    assert set(kinds) == {"vectors", "curves"}
    assert len(kinds["vectors"].points) == 2 * (3 + ARROW_SIDES)


def test_moving_points_keeps_the_dataset_and_its_normals():
    faces = np.array([[0, 1, 2]])
    normals = np.array([[0.0, 0.0, 1.0]] * 3)
    first = Piece("surfaces", np.eye(3), faces=faces, normals=normals)
    moved = Piece("surfaces", 2 * np.eye(3), faces=faces.copy(), normals=normals)
    poly = dataset(first)
    assert same_topology(first, moved)
    move_points(poly, moved)
    np.testing.assert_allclose(poly.points, 2 * np.eye(3))
    np.testing.assert_allclose(poly.point_data.active_normals, normals)
    assert poly.bounds[1] == 2.0
    other_faces = Piece("surfaces", 2 * np.eye(3), faces=np.array([[0, 2, 1]]), normals=normals)
    assert not same_topology(first, other_faces)
