"""strip_crossings.crossings_all: the self-crossings of many strips found at once are each
strip's own, as crossings finds them alone (the same pairs in the same order, the same points)."""

from __future__ import annotations

import numpy as np

from torsal.nodes.geometry import strip_crossings
from torsal.nodes.geometry.strip_crossings import crossings, crossings_all


def looped_band(u0: float, u1: float, n: int, scale: float = 1.0, shift=(0.0, 0.0, 0.0)):
    """A band over the prolate cycloid (u − 2 sin u, 0, 1 − 2 cos u), rulings along y: it
    passes through itself where the centre line loops (|u| beyond 1.895)."""
    u = np.linspace(u0, u1, n)
    centre = np.column_stack([u - 2 * np.sin(u), np.zeros(n), 1 - 2 * np.cos(u)]) * scale + shift
    side = np.array([0.0, scale, 0.0])
    return centre - side, centre + side


def test_many_strips_cross_where_each_crosses_alone():
    strips = [
        looped_band(-2.5, 2.5, 201),
        looped_band(-1.0, 1.0, 30),  # no loop: no crossing
        looped_band(-3.0, 2.2, 77, scale=40.0, shift=(1e3, -2e3, 5.0)),  # another size, far away
        (np.zeros((1, 3)), np.ones((1, 3))),  # one ruling: no triangle
        looped_band(-2.2, 2.9, 300, scale=0.01),
    ]
    together = crossings_all(strips)
    assert [len(c) for c in together] == [len(crossings(*s)) for s in strips]
    assert len(together[0]) > 0 and len(together[2]) > 0 and len(together[4]) > 0 and len(together[1]) == 0
    for both, alone in zip(together, (crossings(*s) for s in strips), strict=True):
        np.testing.assert_array_equal(both.first, alone.first)
        np.testing.assert_array_equal(both.second, alone.second)
        np.testing.assert_array_equal(both.points, alone.points)


def test_no_strip_crosses_when_none_does():
    strips = [looped_band(-1.0, 1.0, 12), looped_band(-0.5, 1.5, 9, scale=3.0)]
    assert [len(c) for c in crossings_all(strips)] == [0, 0]


def test_candidate_pairs_searched_in_blocks_give_the_same_crossings(monkeypatch):
    rng = np.random.default_rng(3)
    tangled = [(rng.normal(size=(40, 3)), rng.normal(size=(40, 3))) for _ in range(3)]
    strips = [looped_band(-2.5, 2.5, 201), *tangled]
    at_once = crossings_all(strips)
    monkeypatch.setattr(strip_crossings, "_MOST_PAIRS", 0)
    in_blocks = crossings_all(strips)
    assert sum(len(c) for c in at_once) > 100
    for one, other in zip(at_once, in_blocks, strict=True):
        np.testing.assert_array_equal(one.first, other.first)
        np.testing.assert_array_equal(one.second, other.second)
        np.testing.assert_array_equal(one.points, other.points)
