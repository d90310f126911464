"""analysis.VectorAnalysis: cross, dot and angle against the textbook formulas, longest-list
matching, zero vectors."""

from __future__ import annotations

import math

import numpy as np

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.values import Vector
from torsal.nodes.analysis.vectors import VectorAnalysis, as_vectors, vector_products

MILLION = 1_000_000


def vectors(*items: tuple[float, float, float]):
    return tree({(0,): [Vector(*v) for v in items]})


def solved(a, b):
    result = run(VectorAnalysis(), A=a, B=b)
    return result, [out(result, port)[(0,)] for port in ("Cross", "Dot", "Angle")]


def textbook(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Cross and dot product written out component by component, the angle by the other
    formula, atan2(|a × b|, a · b), and sin θ = |a × b| / (|a| |b|)."""
    ax, ay, az = a.T
    bx, by, bz = b.T
    cross = np.column_stack([ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx])
    dot = ax * bx + ay * by + az * bz
    sine = np.sqrt((cross**2).sum(axis=1)) / np.sqrt((a**2).sum(axis=1) * (b**2).sum(axis=1))
    return cross, dot, np.arctan2(np.sqrt((cross**2).sum(axis=1)), dot), sine


def assert_textbook_products(a: np.ndarray, b: np.ndarray, cross, dot, angle) -> None:
    """The products against :func:`textbook`, to rounding measured on 10⁶ random pairs.

    Cross: each component is one difference of two rounded products (measured: equal).
    Dot: a sum of three products, 3.4e-16 of |a| |b| at most. Angle: arccos amplifies
    the cosine's rounding by 1 / sin θ, so the difference times sin θ is bounded
    (measured 7.7e-16; near θ = 0 or π the raw difference reaches 1.5e-13).
    """
    ref_cross, ref_dot, ref_angle, sine = textbook(a, b)
    scale = np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1)
    assert np.max(np.abs(np.asarray(cross) - ref_cross).max(axis=1) / scale) <= 2.0**-52
    assert np.max(np.abs(np.asarray(dot) - ref_dot) / scale) < 5e-16
    assert np.max(np.abs(np.asarray(angle) - ref_angle) * sine) < 1.5e-15


def test_products_match_the_textbook_formulas_on_a_million_random_pairs():
    """How fast, against numpy in the same run: bench_vectors.py."""
    rng = np.random.default_rng(2011)
    a, b = rng.normal(size=(MILLION, 3)), rng.normal(size=(MILLION, 3))
    result = vector_products(a, b)
    assert_textbook_products(a, b, result.cross, result.dot, result.angle)


def test_dot_product_is_within_rounding_of_the_correctly_rounded_sum():
    """math.fsum sums the three (rounded) products exactly: measured 2.1e-16 of |a| |b|."""
    rng = np.random.default_rng(5)
    a, b = rng.normal(size=(2000, 3)), rng.normal(size=(2000, 3))
    exact = np.array([math.fsum(row) for row in (a * b).tolist()])
    scale = np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1)
    assert np.max(np.abs(vector_products(a, b).dot - exact) / scale) < 3e-16


def test_node_on_a_million_engine_vectors_matches_the_textbook_formulas():
    """How fast, against plain numpy and Python in the same run: bench_vectors.py."""
    rng = np.random.default_rng(7)
    a, b = rng.normal(size=(MILLION, 3)), rng.normal(size=(MILLION, 3))
    cross, dot, angle = VectorAnalysis().solve(as_vectors(a), as_vectors(b))
    assert type(cross[0]) is Vector and len(cross) == len(dot) == len(angle) == MILLION
    assert_textbook_products(a, b, cross, dot, angle)


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
    # a cylinder ruling R = (0, 0, 2) with parallel edge tangents T1 = (0, 1, 0), T2 = (0, 3, 0):
    # the normals R × T1 = (−2, 0, 0) and R × T2 = (−6, 0, 0) are parallel
    _, (normals, _, _) = solved(vectors((0, 0, 2), (0, 0, 2)), vectors((0, 1, 0), (0, 3, 0)))
    assert normals == [Vector(-2, 0, 0), Vector(-6, 0, 0)]
    _, (_, _, angle) = solved(vectors(normals[0]), vectors(normals[1]))
    assert angle == [0.0]


def test_non_finite_coordinate_warns_with_its_index():
    result, _ = solved(vectors((1, 0, 0), (math.nan, 0, 0)), vectors((0, 1, 0)))
    assert result.state == "warning"
    assert texts(result) == ["A has 1 vectors with a coordinate that is not a finite number (NaN or "
                             "infinite), the first at index 1"]
