"""Which pieces of a strip crease (fans.creased_runs): runs of pieces beside fan rulings
with a fold among their rulings, on strips whose folds are known in closed form."""

from __future__ import annotations

import numpy as np

from tests.nodes.geometry.developable.test_kinds import cylinder_circle
from torsal.nodes.geometry.curve_rail import CurveRail
from torsal.nodes.geometry.developable.fans import creased_fans, creased_runs
from torsal.nodes.geometry.developable.kinds import sheet_folds


def test_a_run_creases_where_one_of_its_rulings_folds():
    #            pieces: 0  1  2  3  4  5  6  7   (rulings 0 … 8)
    in_fan = np.array([0, 1, 1, 0, 1, 1, 1, 0], dtype=bool)
    folded = np.zeros(9, dtype=bool)
    folded[5] = True  # inside the second run (between pieces 4 and 5)
    assert creased_runs(in_fan, folded).tolist() == [False, False, False, False, True, True, True, False]
    folded[:] = False
    folded[3] = True  # the first run's last ruling (its piece 2 ends there)
    assert creased_runs(in_fan, folded).tolist() == [False, True, True, False, False, False, False, False]
    assert not creased_runs(in_fan, np.zeros(9, dtype=bool)).any()


def test_a_fan_ruling_inside_a_smooth_sheet_creases_nothing():
    """A cut strip marks the line it keeps on a ramp of its pace a fan's (cut_pace): inside
    the smooth sheet, sharing no apex with its neighbours. On a cylinder strip (every ruling
    a generator, the sheet smooth) with one such ruling, no piece creases; by shared apexes
    alone (creased_fans) both pieces beside it did."""
    phi = np.array([0.0, 0.2, 0.4, 0.4 + 1e-5, 0.6, 0.8])
    u = np.linspace(0.0, 1.0, len(phi))
    a, b = cylinder_circle(0.0), cylinder_circle(1.0)
    starts, ends = a.point_at(phi), b.point_at(phi)
    fan = np.zeros(len(phi), dtype=bool)
    fan[3] = True
    folds = sheet_folds(CurveRail(a, u, phi), CurveRail(b, u, phi), u, starts, ends)
    folded = folds.creases(fan, 1e-7, starts, ends)
    assert not folded.any()
    assert not creased_runs(fan[:-1] | fan[1:], folded).any()
    assert creased_fans(starts, ends, fan).tolist() == [False, False, True, True, False]
