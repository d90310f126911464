"""vec_ops' row-wise helpers give numpy's own values, bit for bit."""

import numpy as np
import pytest

from torsal.nodes.geometry.vec_ops import cross, linalg_norm

SHAPES = [
    ((1, 3), (1, 3)), ((2000, 3), (2000, 3)), ((5, 3), (3,)), ((3,), (4, 3)), ((2, 7, 3), (7, 3)),
    ((0, 3), (0, 3)),
]


@pytest.mark.parametrize(("shape_a", "shape_b"), SHAPES)
def test_cross_is_numpys_cross_bit_for_bit_whatever_the_shapes(shape_a, shape_b):
    rng = np.random.default_rng(len(shape_a) + shape_a[0])
    a, b = rng.standard_normal(shape_a), rng.standard_normal(shape_b)
    a.reshape(-1)[:3] = -0.0  # (signs of zero carried as np.cross carries them)
    got, want = cross(a, b), np.cross(a, b)
    assert got.shape == want.shape
    np.testing.assert_array_equal(got, want)
    np.testing.assert_array_equal(np.signbit(got), np.signbit(want))


def test_cross_carries_nan_and_infinity_as_numpy_does():
    a, b = np.array([[np.nan, 1.0, np.inf]]), np.array([[1.0, np.inf, 2.0]])
    np.testing.assert_array_equal(cross(a, b), np.cross(a, b))


@pytest.mark.parametrize("coordinates", [1, 2, 3, 7, 9])
def test_linalg_norm_is_numpys_norm_bit_for_bit(coordinates):
    rng = np.random.default_rng(coordinates)
    a = rng.standard_normal((4000, coordinates)) * 10.0 ** rng.uniform(-8, 8, (4000, coordinates))
    a[0] = -0.0
    np.testing.assert_array_equal(linalg_norm(a), np.linalg.norm(a, axis=-1))
    triangles = rng.standard_normal((50, 3, coordinates))
    np.testing.assert_array_equal(linalg_norm(triangles), np.linalg.norm(triangles, axis=2))
