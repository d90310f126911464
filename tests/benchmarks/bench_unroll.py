"""Unrolling, paper strips and the development map against plain numpy and scipy (``make bench``).

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_unroll.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

Each kernel is timed against a baseline measured in the same run:

* ``unroll_rulings`` of 10⁴ rulings (bar: well under a second) against the least any
  unrolling must do, the edge lengths and normals of the strip's 2·10⁴ triangles in numpy;
* ``paper_strip`` of 1000 segments (bar: milliseconds) against the plain way of building
  it, composing the 2 × 1000 fold rotations one after the other;
* ``DevelopmentMap.locate`` of 2·10⁴ points (bar: a few tens of milliseconds) against a
  scipy k-d tree query of the same points among the triangles' centroids, a point
  location that is not exact.

What they compute is checked by ``make test`` (``tests/nodes/geometry``, ``tests/nodes/analysis``).
"""

from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

from tests.benchmarks.timing import ratio_to_baseline
from tests.nodes.geometry.test_development_locate import helix_tangent, inside_points
from tests.nodes.geometry.test_unroll_rulings import helix_tangent_rulings
from torsal.nodes.geometry.paper_strip import paper_strip
from torsal.nodes.geometry.unroll import unroll_rulings


def test_ten_thousand_rulings_unroll_within_25x_numpy_measuring_their_triangles():
    starts, ends = helix_tangent_rulings(9999, turns=10)

    def triangle_edges_and_normals() -> tuple[np.ndarray, np.ndarray]:
        a0, a1, b0, b1 = starts[:-1], starts[1:], ends[:-1], ends[1:]
        triangles = np.stack([np.stack([a0, a1, b0], axis=1), np.stack([a1, b1, b0], axis=1)])
        edges = np.linalg.norm(triangles - np.roll(triangles, -1, axis=2), axis=3)
        corner = triangles[..., 0, :]
        normals = np.cross(triangles[..., 1, :] - corner, triangles[..., 2, :] - corner)
        return edges, normals

    ratio = ratio_to_baseline(
        "unroll_rulings, 10^4 rulings",
        lambda: unroll_rulings(starts, ends),
        "numpy: edge lengths and normals of its 2·10^4 triangles",
        triangle_edges_and_normals,
        9,
    )
    assert ratio <= 25.0


def test_a_thousand_segment_paper_strip_builds_faster_than_folding_one_segment_at_a_time():
    rng = np.random.default_rng(11)
    iso, curvature = rng.uniform(1.5, 1.64, 1000), rng.uniform(-0.1, 0.1, 1000)

    def fold_one_by_one() -> list[np.ndarray]:
        """The frames of the bent strip and of the flat one, a 3 × 3 product per segment."""
        theta = 0.5 * np.pi - iso
        ct, st = np.cos(theta), np.sin(theta)
        frames = []
        for kappa in (curvature, np.zeros_like(curvature)):
            ck, sk = np.cos(kappa), np.sin(kappa)
            frame = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
            for i in range(len(iso)):
                fold = np.array([
                    [ct[i], -st[i], 0.0],
                    [st[i] * ck[i], ct[i] * ck[i], -sk[i]],
                    [st[i] * sk[i], ct[i] * sk[i], ck[i]],
                ])
                frame = frame @ fold
                frames.append(frame)
        return frames

    ratio = ratio_to_baseline(
        "paper_strip, 1000 segments",
        lambda: paper_strip(100.0, 0.5, iso, curvature, 1000),
        "the 2 × 1000 fold rotations composed one by one",
        fold_one_by_one,
        15,
    )
    assert ratio <= 1.0


def test_twenty_thousand_points_are_located_within_8x_a_kd_tree_query():
    development = unroll_rulings(*helix_tangent(400, 0.9))
    points = inside_points(development, 20_000, seed=1)
    development.map.locate(points[:10])  # the walk's k-d tree is built once
    m = development.map
    centroids = m.vertices2d[m.triangles[m.proper]].mean(axis=1)
    tree = cKDTree(centroids)
    ratio = ratio_to_baseline(
        "DevelopmentMap.locate, 2·10^4 points",
        lambda: m.locate(points),
        f"scipy cKDTree query among {len(centroids)} triangle centroids",
        lambda: tree.query(points),
        15,
    )
    assert ratio <= 8.0
