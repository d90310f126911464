"""Polylines merge into one VTK line-cell array: each chain's count, then its point indices."""

from __future__ import annotations

import numpy as np

from app.gui.viewport.datasets import _line_cells


def test_chains_of_3_2_and_4_points_give_their_counts_then_consecutive_indices():
    chains = [np.full((n, 3), float(n)) for n in (3, 2, 4)]
    points, cells = _line_cells(chains)
    assert cells.dtype == np.int64
    assert cells.tolist() == [3, 0, 1, 2, 2, 3, 4, 4, 5, 6, 7, 8]
    assert points.shape == (9, 3)
    assert points[:, 0].tolist() == [3, 3, 3, 2, 2, 4, 4, 4, 4]
