"""The lean evaluation paths give numpy's and the general path's values, bit for bit.

NURBS curves evaluate through several entry points (``derivatives``, ``local_derivatives``,
``derivative_at``, ``point_at``) that share the parameter conversion and the anchor; vec_ops
writes out numpy routines for small arrays. Each must agree with the plain computation to
the last bit, whatever the parameters' layout (scalar, one point, strided, 2-D).
"""

from __future__ import annotations

import numpy as np
import pytest

from torsal.nodes.geometry.curves import InterpolatedCurve, NurbsCurve
from torsal.nodes.geometry.spline_eval import evaluation_parameters
from torsal.nodes.geometry.vec_ops import anchor, bounds, cross, cross2, extent


def same(a: np.ndarray, b: np.ndarray) -> bool:
    """Equal shapes and equal bits (signed zeros included)."""
    a, b = np.asarray(a), np.asarray(b)
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


def far_curves() -> list[NurbsCurve]:
    """Polynomial and rational curves away from the origin, on unit and other domains."""
    rng = np.random.default_rng(7)
    site = np.array([2.5e5, -1.2e5, 40.0])
    edge = InterpolatedCurve(site + rng.normal(size=(3, 3)) * 10, degree=2)
    base = InterpolatedCurve(site + np.cumsum(rng.normal(size=(9, 3)) * 10, axis=0), degree=3)
    knots = np.array([2.0, 2.0, 2.0, 2.0, 2.7, 3.1, 5.0, 5.0, 5.0, 5.0])
    stretched = NurbsCurve(site + rng.normal(size=(6, 3)), degree=3, knots=knots)
    rational = NurbsCurve(site + rng.normal(size=(5, 3)), degree=2, weights=rng.uniform(0.5, 2, 5))
    return [edge, base, stretched, rational]


PARAMETERS = {
    "one": np.array([0.37]),
    "several": np.linspace(0.0, 1.0, 13),
    "strided": np.linspace(0.0, 1.0, 26)[::2],
    "column": np.linspace(0.0, 1.0, 5)[:, None],
}


@pytest.mark.parametrize("name", sorted(PARAMETERS))
def test_every_entry_point_gives_the_general_paths_bits(name):
    t = PARAMETERS[name]
    flat = np.ascontiguousarray(t).reshape(-1)
    for curve in far_curves():
        for order in range(5):
            full = curve.derivatives(t, order)
            local = curve.local_derivatives(flat, order)
            assert len(full) == len(local) == order + 1
            assert same(full[0], local[0] + curve.anchor)
            for k in range(1, order + 1):
                assert same(full[k], local[k])
                assert same(curve.derivative_at(t, k), full[k])
        assert same(curve.point_at(t), curve.derivatives(flat, 0)[0])
        assert same(curve.derivative_at(t, 0), curve.point_at(flat))


def test_a_scalar_parameter_gives_one_vector_with_the_arrays_bits():
    for curve in far_curves():
        row = curve.derivatives(np.array([0.61]), 2)
        assert same(curve.point_at(0.61), row[0][0])
        assert same(curve.derivative_at(0.61, 2), row[2][0])
        assert same(curve.tangent_at(0.61), curve.tangent_at(np.array([0.61]))[0])


def test_evaluation_parameters_pass_a_ready_array_through_and_convert_the_rest():
    t = np.linspace(0.0, 1.0, 4)
    assert evaluation_parameters(t) is t
    for value in (0.5, [0.1, 0.2], t[::2], t[:, None], t.astype(np.float32)):
        x = evaluation_parameters(value)
        assert x.ndim == 1 and x.dtype == np.float64 and x.flags.c_contiguous
        assert same(x, np.asarray(value, dtype=float).reshape(-1))


def awkward_vectors(rng: np.random.Generator, shape: tuple[int, ...]) -> np.ndarray:
    """Vectors over many magnitudes, with zeros of both signs."""
    v = rng.normal(size=shape) * 10.0 ** rng.integers(-8, 8, size=shape)
    v[rng.random(shape) < 0.1] = 0.0
    v[rng.random(shape) < 0.1] = -0.0
    return v


@pytest.mark.parametrize(
    ("shape_a", "shape_b"),
    [((3,), (3,)), ((1, 3), (1, 3)), ((15, 3), (15, 3)), ((15, 3), (2, 15, 3)), ((10, 3), (3,))],
)
def test_cross_is_numpys_cross_bit_for_bit(shape_a, shape_b):
    rng = np.random.default_rng(len(shape_a) + 10 * len(shape_b))
    for _ in range(20):
        a, b = awkward_vectors(rng, shape_a), awkward_vectors(rng, shape_b)
        assert same(cross(a, b), np.cross(a, b))
        assert cross(a, b).flags.c_contiguous
    strided = awkward_vectors(rng, (8, 6))[:, ::2]
    assert same(cross(strided, strided[::-1]), np.cross(strided, strided[::-1]))


def test_bounds_make_the_anchor_and_the_extent():
    rng = np.random.default_rng(3)
    for count in (1, 2, 9, 40):
        points = awkward_vectors(rng, (count, 3)) + 1e6
        low, high = bounds(points)
        assert same(low, points.min(axis=0)) and same(high, points.max(axis=0))
        assert same(0.5 * (high + low), anchor(points))
        assert same(high - low, extent(points))


def test_cross2_is_the_z_of_numpys_cross_of_the_plane_vectors():
    rng = np.random.default_rng(11)
    a, b = rng.normal(size=(2, 50, 2)) * 10.0 ** rng.integers(-5, 5, size=(2, 50, 1))
    padded = [np.column_stack([v, np.zeros(len(v))]) for v in (a, b)]
    assert same(cross2(a, b), np.cross(*padded)[:, 2])
