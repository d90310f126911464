"""closest.nearest_sample: a k-d tree of the samples, equal to brute force (scipy's cdist).

How fast, against brute force and a bare cKDTree: tests/benchmarks/bench_kernels.py.
"""

from __future__ import annotations

import numpy as np
from scipy.spatial.distance import cdist

from torsal.nodes.geometry.closest import nearest_sample


def helix_samples(count: int, offset: float = 0.0) -> np.ndarray:
    t = np.linspace(0.0, 20 * np.pi, count)
    return np.column_stack([np.cos(t), np.sin(t), t / 10]) + offset


def test_nearest_sample_distances_equal_brute_force_at_site_coordinates():
    rng = np.random.default_rng(3)
    samples = helix_samples(500, offset=1e6)
    queries = samples[rng.integers(0, 500, 2000)] + rng.normal(0.0, 0.05, (2000, 3))
    found = nearest_sample(samples, queries)
    expected = cdist(queries - 1e6, samples - 1e6).min(axis=1)
    # measured 0; the distances themselves round to ~1e-10 at 1e6 m
    np.testing.assert_allclose(np.linalg.norm(samples[found] - queries, axis=1), expected, atol=1e-9)


def test_a_non_finite_query_gets_a_valid_index():
    samples = helix_samples(50)
    found = nearest_sample(samples, np.array([[np.nan, 0.0, 0.0], [1.0, 0.0, 0.0]]))
    assert found.tolist() == [0, 0]
