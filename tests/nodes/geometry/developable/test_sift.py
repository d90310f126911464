"""developable.sift: the first pass of the partner search over every strip at once finds,
for each strip, the intervals of B where f = det[B − A, Â', B'] changes sign (and the
samples where it is zero) that the strip has alone."""

from __future__ import annotations

import numpy as np
import pytest

from torsal.nodes.geometry.curves import Line, NurbsCurve
from torsal.nodes.geometry.developable import sift
from torsal.nodes.geometry.developable.sift import sift_all
from torsal.nodes.geometry.developable.strip import Strip, set_up


def _strip(a, b, segments: int = 6, samples: int = 16) -> Strip:
    return set_up([(a, b, segments, 0.01)], "length", samples)[0]


def _wavy(z: float, phase: float, points: int = 9) -> NurbsCurve:
    u = np.linspace(0.0, 1.0, points)
    return NurbsCurve(np.column_stack([4 * u, np.sin(3 * u + phase), z + 0.2 * np.cos(5 * u)]), degree=3)


#: B(t) = (2t, (t − 0.4)², 1) as a quadratic Bézier curve: B'_y = 2(t − 0.4).
_DIP = NurbsCurve([[0.0, 0.16, 1.0], [1.0, -0.24, 1.0], [2.0, 0.36, 1.0]], degree=2)


def test_a_partner_where_b_turns_parallel_to_a_is_bracketed_at_every_station():
    # A along x at z = 0: f = (B − A)·(Â' × B') = (B_z − A_z)·B'_y = 2(t − 0.4), one simple
    # root at t = 0.4 whatever the station
    strip = _strip(Line([0, 0, 0], [1, 0, 0]), _DIP)
    first = sift_all([strip]).first
    change = np.signbit(first.f0) != np.signbit(first.f1)
    rows = first.row[change]
    assert rows.tolist() == list(range(len(strip.s)))
    assert np.all((first.x0[change] < 0.4) & (first.x1[change] > 0.4))
    assert np.all((first.f0[change] < 0) & (first.f1[change] > 0))


def test_two_coplanar_lines_give_each_station_one_flat_run_over_all_of_b():
    strip = _strip(Line([0, 0, 0], [2, 0, 0]), Line([0, 1, 0], [3, 2, 0]), segments=3)
    sifted = sift_all([strip])
    rows, first, last, flat = sifted.runs[0]
    m = len(strip.grid.t)
    assert rows.tolist() == [0, 1, 2, 3]
    assert first.tolist() == [0] * 4 and last.tolist() == [m - 1] * 4 and flat.all()
    assert len(sifted.first.row) == 0


@pytest.mark.parametrize("cells", [sift.CELLS, 64])
def test_every_strip_among_others_gets_what_it_gets_alone(monkeypatch, cells):
    # strips of different sample counts side by side (the narrower padded), and in small
    # batches when the cells allow few rows
    monkeypatch.setattr(sift, "CELLS", cells)
    strips = [
        _strip(_wavy(0.0, 0.0), _wavy(1.0, 0.2, 14), segments=9, samples=40),
        _strip(Line([0, 0, 0], [2, 0, 0]), Line([0, 1, 0], [3, 2, 0]), segments=3),
        _strip(Line([0, 0, 0], [1, 0, 0]), _DIP, segments=5, samples=24),
        _strip(_wavy(0.0, 0.3), _wavy(1.2, 1.5), segments=4),
    ]
    together = sift_all(strips)
    row_shift = np.cumsum([0] + [len(strip.s) for strip in strips])
    col_shift = np.cumsum([0] + [len(strip.grid.t) for strip in strips])
    owner = np.searchsorted(row_shift, together.first.row, side="right") - 1
    for i, strip in enumerate(strips):
        alone = sift_all([strip])
        mine = owner == i
        for name in ("x0", "x1", "f0", "f1", "d0", "d1"):
            np.testing.assert_array_equal(getattr(together.first, name)[mine], getattr(alone.first, name))
        np.testing.assert_array_equal(together.first.row[mine] - row_shift[i], alone.first.row)
        np.testing.assert_array_equal(together.cols[mine] - col_shift[i], alone.cols)
        np.testing.assert_array_equal(together.curvature[mine], alone.curvature)
        np.testing.assert_array_equal(together.lengths[:, mine], alone.lengths)
        ends_together = together.piece_ends(np.flatnonzero(mine))
        ends_alone = alone.piece_ends(np.arange(len(alone.first.row)))
        for name, values in ends_alone.items():
            np.testing.assert_array_equal(ends_together[name], values)
        for part, part_alone in zip(together.runs[i] + together.corners[i], alone.runs[0] + alone.corners[0],
                                    strict=True):
            np.testing.assert_array_equal(part, part_alone)
    assert any(len(runs[0]) for runs in together.runs) and len(together.first.row) > 20
