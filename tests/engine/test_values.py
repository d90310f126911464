"""The engine's points and vectors: :meth:`Triple.many`, the bulk constructor, gives what the
constructor gives, value and type, for rows of Python floats of every kind (signed zeros,
denormals, infinities, NaN)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from torsal.engine.values import Point, Vector


@pytest.mark.parametrize("cls", [Point, Vector])
def test_many_is_the_constructor_row_by_row(cls):
    rng = np.random.default_rng(5)
    rows = np.concatenate([
        rng.normal(size=(50, 3)) * 10.0 ** rng.integers(-300, 300, size=(50, 1)),
        [[-0.0, 0.0, 5e-324], [math.inf, -math.inf, math.nan], [1e308, -1e-308, 1.0]],
    ]).tolist()
    made, plain = cls.many(rows), [cls(*row) for row in rows]
    assert all(type(item) is cls for item in made)
    assert [tuple(map(float.hex, item)) for item in made] == [tuple(map(float.hex, item)) for item in plain]
    assert made[0].x == rows[0][0] and made[0].z == rows[0][2]
