"""analysis.VectorAnalysis: numpy's cross, dot and angle, longest-list matching, zero vectors."""

from __future__ import annotations

import math

import numpy as np

from engine.values import Vector
from nodes.analysis.vectors import VectorAnalysis, as_vectors, vector_products
from tests.nodes.helpers import out, run, texts, tree

MILLION = 1_000_000


def vectors(*items: tuple[float, float, float]):
    return tree({(0,): [Vector(*v) for v in items]})


def solved(a, b):
    result = run(VectorAnalysis(), A=a, B=b)
    return result, [out(result, port)[(0,)] for port in ("Cross", "Dot", "Angle")]


def numpy_reference(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    dot = np.einsum("ij,ij->i", a, b)
    cosine = dot / (np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1))
    return np.cross(a, b), dot, np.arccos(np.clip(cosine, -1.0, 1.0))


def test_products_equal_numpy_on_a_million_random_pairs():
    """How fast, against numpy in the same run: bench_vectors.py."""
    rng = np.random.default_rng(2011)
    a, b = rng.normal(size=(MILLION, 3)), rng.normal(size=(MILLION, 3))
    result = vector_products(a, b)
    cross, dot, angle = numpy_reference(a, b)
    assert np.array_equal(result.cross, cross)
    assert np.array_equal(result.dot, dot)
    assert np.array_equal(result.angle, angle)
    # and the dot product is the textbook a_x b_x + a_y b_y + a_z b_z to rounding
    textbook = a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1] + a[:, 2] * b[:, 2]
    scale = np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1)
    assert np.max(np.abs(result.dot - textbook) / scale) < 1e-15


def test_node_on_a_million_engine_vectors_matches_numpy():
    """How fast, against plain numpy and Python in the same run: bench_vectors.py."""
    rng = np.random.default_rng(7)
    a, b = rng.normal(size=(MILLION, 3)), rng.normal(size=(MILLION, 3))
    va, vb = as_vectors(a), as_vectors(b)
    cross, dot, angle = VectorAnalysis().solve(va, vb)
    ref_cross, ref_dot, ref_angle = numpy_reference(a, b)
    assert type(cross[0]) is Vector and len(cross) == MILLION
    assert np.array_equal(np.asarray(cross), ref_cross)
    assert np.array_equal(np.asarray(dot), ref_dot)
    assert np.array_equal(np.asarray(angle), ref_angle)


def test_perpendicular_vectors_cross_to_the_third_axis_with_zero_dot_and_right_angle():
    result, (cross, dot, angle) = solved(vectors((2, 0, 0)), vectors((0, 3, 0)))
    assert result.state == "ok"
    assert cross == [Vector(0, 0, 6)] and dot == [0.0]
    assert angle == [math.pi / 2]


def test_opposite_vectors_make_an_angle_of_pi():
    _, (cross, dot, angle) = solved(vectors((1, 2, 3)), vectors((-2, -4, -6)))
    assert cross == [Vector(0, 0, 0)] and dot == [-28.0]
    assert angle == [math.pi]


def test_shorter_list_reuses_its_last_vector_and_says_so():
    result, (cross, dot, angle) = solved(vectors((1, 0, 0), (0, 1, 0), (1, 1, 0)), vectors((0, 1, 0)))
    assert dot == [0.0, 1.0, 1.0]
    assert np.allclose(angle, [math.pi / 2, 0.0, math.pi / 4], atol=1e-15)
    assert cross == [Vector(0, 0, 1), Vector(0, 0, 0), Vector(0, 0, 1)]
    assert texts(result) == ["A has 3 vectors, B has 1: B's last vector is reused for the rest"]


def test_zero_length_vector_gives_angle_zero_not_nan_and_warns():
    result, (cross, dot, angle) = solved(vectors((0, 0, 0), (1, 0, 0)), vectors((1, 1, 0), (0, 0, 0)))
    assert angle == [0.0, 0.0] and dot == [0.0, 0.0]
    assert cross == [Vector(0, 0, 0), Vector(0, 0, 0)]
    assert result.state == "warning"
    assert texts(result) == ["2 of 2 pairs have a zero-length vector (the first at index 0): it has no "
                             "direction, so their Angle is set to 0"]


def test_tiny_and_huge_vectors_still_get_their_angle():
    _, (_, _, angle) = solved(vectors((1e-200, 0, 0), (1e200, 1e200, 0)),
                              vectors((1e-200, 1e-200, 0), (0, 1e200, 0)))
    assert np.allclose(angle, [math.pi / 4, math.pi / 4], rtol=1e-15)


def test_torsal_ruling_has_parallel_normals_angle_zero():
    # a cylinder ruling R with equal edge tangents T: N1 = R × T and N2 = R × T are parallel
    ruling, t1, t2 = np.array([0, 0, 2.0]), np.array([0, 1.0, 0]), np.array([0, 3.0, 0])
    normals = vector_products([ruling, ruling], [t1, t2]).cross
    _, (_, _, angle) = solved(vectors(tuple(normals[0])), vectors(tuple(normals[1])))
    assert angle == [0.0]


def test_non_finite_coordinate_warns_with_its_index():
    result, _ = solved(vectors((1, 0, 0), (math.nan, 0, 0)), vectors((0, 1, 0)))
    assert result.state == "warning"
    assert texts(result) == ["A has 1 vectors with a coordinate that is not a finite number (NaN or "
                             "infinite), the first at index 1"]
