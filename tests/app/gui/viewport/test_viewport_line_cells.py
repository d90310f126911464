"""Polylines merge into one VTK line-cell array: each chain's count, then its point indices."""

from __future__ import annotations

import numpy as np

from torsal.app.gui.viewport.datasets import _line_cells


def test_chains_of_3_2_and_4_points_give_their_counts_then_consecutive_indices():
    chains = [np.full((n, 3), float(n)) for n in (3, 2, 4)]
    points, cells = _line_cells(chains)
    assert cells.dtype == np.int64
    assert cells.tolist() == [3, 0, 1, 2, 2, 3, 4, 4, 5, 6, 7, 8]
    assert points.shape == (9, 3)
    assert points[:, 0].tolist() == [3, 3, 3, 2, 2, 4, 4, 4, 4]


def test_a_block_of_four_chains_of_3_points_counts_as_those_four_chains():
    block = np.arange(36, dtype=float).reshape(4, 3, 3)
    points, cells = _line_cells([np.zeros((2, 3)), block, np.ones((5, 3))])
    blocked = [v for k in range(4) for v in (3, 2 + 3 * k, 3 + 3 * k, 4 + 3 * k)]
    assert cells.tolist() == [2, 0, 1, *blocked, 5, 14, 15, 16, 17, 18]
    assert points.shape == (19, 3)
    np.testing.assert_array_equal(points[2:14], block.reshape(-1, 3))


def test_chains_of_one_length_get_the_same_cells_however_they_are_grouped():
    chains = [np.zeros((2, 3))] * 6
    one = _line_cells([np.zeros((4, 2, 3)), np.zeros((2, 2, 3))])[1]
    assert one is _line_cells(chains)[1]
    assert not one.flags.writeable
