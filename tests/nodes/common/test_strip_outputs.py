"""Outputs of several strips between curves made together (torsal.nodes.common.strip_outputs)."""

from __future__ import annotations

import numpy as np

from torsal.nodes.common.strip_outputs import curve_strip_outputs, curve_strips_outputs
from torsal.nodes.geometry.curves.line import Line
from torsal.nodes.geometry.developable.measure import within_tolerance


def test_strips_made_together_get_what_each_gets_alone():
    a, b = Line([0, 0, 0], [2, 0, 0]), Line([0, 1, 0], [3, 2, 1])
    s = np.array([0.0, 0.25, 0.5, 1.0])
    t = np.array([0.0, 0.3, 0.6, 1.0])
    back = np.array([0.0, 0.6, 0.5, 1.0])  # runs back on A: no rails, the loft through the rulings
    strips = []
    for ss, warp, claimed in [
        (s, np.zeros(4), None),
        (s, np.array([0.0, np.nan, 0.2, 0.001]), np.ones(4, dtype=bool)),  # a NaN warp, one refused
        (back, np.full(4, 0.003), np.ones(4, dtype=bool)),
    ]:
        starts, ends = a.point_at(ss), b.point_at(t)
        valid = within_tolerance(warp, 0.01, starts, ends)
        strips.append((a, b, ss, t, starts, ends, 0.01, claimed, warp, valid))
    together = curve_strips_outputs(strips)
    u = np.linspace(0.0, 1.0, 9)
    for strip, made in zip(strips, together, strict=True):
        *job, claimed, warp, valid = strip
        alone = curve_strip_outputs(*job, claimed, warp=warp, valid=valid)
        assert made.warp == alone.warp or np.array_equal(made.warp, alone.warp, equal_nan=True)
        assert made.valid == alone.valid
        assert made.messages == alone.messages
        assert np.array_equal(made.undefined, alone.undefined)
        assert [(line.start.tolist(), line.end.tolist()) for line in made.rulings] == [
            (line.start.tolist(), line.end.tolist()) for line in alone.rulings]
        assert made.surface.point_at(u, u).tobytes() == alone.surface.point_at(u, u).tobytes()
    assert len(together[1].messages) == 2  # the NaN warp, and the ruling whose warp is above 0.01
