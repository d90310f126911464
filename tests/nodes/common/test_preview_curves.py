"""A run of NURBS curves drawn at once: each curve's chain is the one it draws alone."""

from __future__ import annotations

import numpy as np

from torsal.nodes.common.preview import draws_many, preview_of, preview_of_many
from torsal.nodes.geometry.curves import Circle, InterpolatedCurve, NurbsCurve


def test_a_run_of_curves_draws_each_curves_own_points_bit_for_bit():
    rng = np.random.default_rng(3)
    edges = InterpolatedCurve.beziers(rng.normal(size=(6, 3, 3)) * 20.0 + 1e5)  # one knot vector
    splines = [NurbsCurve(rng.normal(size=(5, 3)), 3) for _ in range(3)]
    runs = [edges, splines, [NurbsCurve(rng.normal(size=(4, 3)), 2, weights=[1, 2, 1, 1]), splines[0]]]
    for run in runs:
        assert draws_many(type(run[0]))
        chains = preview_of_many(run).polylines
        assert np.shape(chains)[0] == len(run)
        for chain, curve in zip(chains, run, strict=True):
            alone = preview_of(curve).polylines[0]
            assert chain.tobytes() == alone.tobytes() and chain.shape == alone.shape
    assert not draws_many(Circle)  # (a conic draws itself alone)
