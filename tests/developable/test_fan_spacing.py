"""A fan's rulings are spaced by numpy's own linspace, written out (bit for bit)."""

from __future__ import annotations

import numpy as np

from nodes.geometry.developable.strip import _linspace


def test_fan_spacing_is_numpy_linspace_bit_for_bit():
    rng = np.random.default_rng(7)
    for _ in range(2000):
        start = float(rng.normal() * 10.0 ** rng.integers(-5, 5))
        stop = start + float(abs(rng.normal()) * 10.0 ** rng.integers(-320, 5)) * (rng.random() > 0.05)
        count = int(rng.integers(2, 40))
        ours = _linspace(np.float64(start), np.float64(stop), count)
        assert ours.tobytes() == np.linspace(np.float64(start), np.float64(stop), count).tobytes()
