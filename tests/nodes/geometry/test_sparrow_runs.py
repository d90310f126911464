"""The budget shared by one nesting's sparrow packings: its progress fraction."""

from __future__ import annotations

import pytest

from torsal.nodes.geometry.sparrow_runs import STEPS_PER_SECOND, Budget


def budget_of(seconds: float) -> tuple[Budget, list[float]]:
    heard: list[float] = []
    return Budget(seconds, None, heard.append), heard


def test_packings_side_by_side_count_together():
    run, heard = budget_of(10.0)  # 400 steps
    run.tick(1, 50, 400)
    run.tick(2, 30, 100)
    assert run.steps == 10 * STEPS_PER_SECOND
    assert heard[-1] == pytest.approx((50 + 30) / 400)


def test_in_the_last_round_a_packing_that_ends_early_leaves_the_rest_to_the_one_still_running():
    run, heard = budget_of(10.0)
    run.last_round = True  # the packings under way place every part left
    run.tick(1, 50, 300)  # a sheet's set, expected to take 300 steps to fit
    run.tick(2, 50, 100)  # the last sheet beside it
    assert heard[-1] == pytest.approx(100 / 400)
    run.spend(60, 1)  # the set fitted after 60 steps: its other 240 are not coming
    run.tick(2, 80, 100)
    assert heard[-1] == pytest.approx((60 + 80) / (60 + 100))


def test_before_the_last_round_the_whole_budget_is_expected():
    run, heard = budget_of(10.0)
    run.tick(1, 40, 100)
    run.spend(40, 1)
    run.tick(2, 40, 100)
    assert heard[-1] == pytest.approx(80 / 400)


def test_the_fraction_stays_below_one_and_never_goes_back():
    run, heard = budget_of(1.0)
    run.last_round = True
    run.tick(1, 500, 10)  # more steps than expected (a failed attempt counts 20)
    run.tick(1, 5, 10)
    assert heard == [0.99]


def test_parts_handed_to_sparrow_turned_come_back_with_the_angles_of_the_parts_as_given():
    """A bar 100 mm wide and 300 tall, handed to sparrow turned 90° (lying) for a strip 130 mm
    tall, 10 mm from its edges: it can only lie in it. The angle returned, applied to the bar
    as given (standing), lays it down inside the strip."""
    import numpy as np
    import shapely

    from torsal.nodes.geometry.nesting import place
    from torsal.nodes.geometry.sparrow_runs import FEWEST, strip

    bar = np.array([[-50.0, -150.0], [50.0, -150.0], [50.0, 150.0], [-50.0, 150.0]])
    packing = strip([bar], [0], 130.0, 10.0, None, FEWEST, 0, Budget(1.0, None, None), turn=90.0)
    assert packing is not None
    angle, shift = packing[0]
    placed = shapely.Polygon(place(bar, angle, shift))
    assert abs(angle % 180.0 - 90.0) < 1e-3  # turned a quarter from the bar as given
    assert placed.bounds[1] >= 10.0 - 0.05 and placed.bounds[3] <= 120.0 + 0.05
