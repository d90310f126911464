"""Where strips fold, several reported together (torsal.nodes.common.strip_folds)."""

from __future__ import annotations

import numpy as np

from torsal.nodes.common.strip_folds import fold_report, fold_reports, strips_crossings


def test_strips_reported_together_get_what_each_gets_alone():
    x = np.linspace(0.0, 3.0, 4)
    flat = (np.c_[x, 0 * x, 0 * x], np.c_[x, 0 * x + 1, 0 * x])  # a plane strip: no fold
    # the flat strip, then back through it: an upright quad at y = 0.5 from x = 1.5 to 0.5
    crossing = (np.r_[flat[0], [[1.5, 0.5, -1.0], [0.5, 0.5, -1.0]]],
                np.r_[flat[1], [[1.5, 0.5, 1.0], [0.5, 0.5, 1.0]]])
    creased = np.array([0.0, 0.7, 0.2, 0.0])  # one crease of 0.7 rad, sharper than 0.5
    strips = [flat, flat, crossing]
    crossed = strips_crossings(strips)
    assert len(crossed[2]) > 0 and len(crossed[0]) == 0
    jobs = [
        (*flat, np.zeros(4), 0.5, None, crossed[0]),
        (*flat, creased, 0.5, np.array([8.0, 0.0, 0.0]), crossed[1]),
        (*crossing, np.zeros(6), 0.5, None, crossed[2]),
    ]
    together = fold_reports(jobs)
    for job, made in zip(jobs, together, strict=True):
        alone = fold_report(*job)
        assert (made.message, made.creases, made.crossing_pairs) == (alone.message, alone.creases,
                                                                    alone.crossing_pairs)
        assert [p.tolist() if hasattr(p, "tolist") else p for p in made.points] == [
            p.tolist() if hasattr(p, "tolist") else p for p in alone.points]
    assert together[0].message is None and together[1].creases == 1 and together[2].crossing_pairs > 0
