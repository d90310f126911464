"""Kernel hot spots of issue 16 against independent baselines measured in the same run (``make bench``).

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_kernels.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

* The area of a bumpy 24 × 24 bicubic NURBS surface (adaptive, from the knot grid; it
  took 8–55 s on power-of-two cells) against scipy's ``NdBSpline`` derivatives summed by a
  fixed 16-point Gauss product on half knot spans (0.2 s, the reference of make test).
  Bar: under a second, i.e. within 5× that reference.
* Cancelling that area, and how often long kernels check for a cancel: bench_cancel.py.
* Nearest samples (4,000 on a helix, 10⁵ queries near it): a k-d tree, within 1.5× a
  bare ``cKDTree`` query (brute force took 2.9 s, 60× the tree).
* MeshSurface.closest_point (5,000 points on a thin strip with one big triangle: the
  search sized by the largest triangle took 60 s) against a k-d tree query of the same
  points among the triangles' centroids, the least any such search does.
* The one root solver on 2·10⁴ cubics x³ + x = c: within 3× ten plain Newton steps (the
  solver it replaced needed 59 calls, 1,800 problems still bisecting after 10).

What they compute is checked by ``make test`` (tests/nodes/geometry/test_area_knot_grid.py,
test_nearest_sample.py, test_triangle_search.py, test_roots.py).
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from tests.benchmarks.timing import ratio_to_baseline
from tests.nodes.geometry.test_area_knot_grid import bumpy_net, reference_area
from tests.nodes.geometry.test_nearest_sample import helix_samples
from tests.nodes.geometry.test_roots import cubic_problems
from tests.nodes.geometry.test_triangle_search import queries, thin_strip
from torsal.nodes.geometry.closest import nearest_sample
from torsal.nodes.geometry.mesh_surface import MeshSurface
from torsal.nodes.geometry.nurbs_surface import NurbsSurface
from torsal.nodes.geometry.roots import safeguarded_newton


def test_bumpy_nurbs_surface_area_within_5x_a_dense_scipy_gauss_product():
    net = bumpy_net(24)
    surface = NurbsSurface(net, 3, 3)
    ratio = ratio_to_baseline(
        "bumpy 24 × 24 bicubic NURBS surface, area",
        surface.area,
        "scipy NdBSpline + 16-point Gauss on half knot spans",
        lambda: reference_area(net),
        5,
    )
    assert ratio <= 5.0


def test_nearest_samples_within_1_5x_a_bare_kd_tree_query():
    rng = np.random.default_rng(0)
    samples = helix_samples(4000)
    points = samples[rng.integers(0, 4000, 100_000)] + rng.normal(0.0, 0.05, (100_000, 3))
    ratio = ratio_to_baseline(
        "nearest of 4,000 samples for 10⁵ points", lambda: nearest_sample(samples, points),
        "cKDTree(samples).query(points)", lambda: cKDTree(samples).query(points), 5,
    )
    assert ratio <= 1.5


def test_mesh_closest_point_on_a_thin_strip_within_100x_a_centroid_kd_tree_query():
    mesh = thin_strip(2000)
    surface = MeshSurface(mesh)
    points = queries(mesh, 5000, 0.05)
    centres = np.asarray(mesh.triangles).mean(axis=1)
    ratio = ratio_to_baseline(
        "MeshSurface.closest_point, 5,000 points on a 4,000-triangle thin strip",
        lambda: surface.closest_point(points),
        "cKDTree of the centroids, query", lambda: cKDTree(centres).query(points), 5,
    )
    assert ratio <= 100.0  # measured 10–55 on a busy machine; by the largest triangle ~10⁴


def test_root_solver_within_3x_ten_plain_newton_steps():
    c, low, high = cubic_problems()

    def newton() -> np.ndarray:
        x = 0.5 * (low + high)
        for _ in range(10):
            x = x - (x**3 + x - c) / (3 * x**2 + 1)
        return x

    ratio = ratio_to_baseline(
        "safeguarded Newton on 2·10⁴ cubics",
        lambda: safeguarded_newton(lambda x, i: (x**3 + x - c[i], 3 * x**2 + 1), low, high, (low + high) / 2),
        "10 unguarded Newton steps", newton, 7,
    )
    assert ratio <= 3.0
