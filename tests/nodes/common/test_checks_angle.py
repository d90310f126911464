"""torsal.nodes.common.checks.angle: the one check of a tolerance angle, positive or (exact) 0 and up."""

from __future__ import annotations

import math

import pytest

from torsal.engine.node import NodeWarning
from torsal.nodes.common.checks import angle, tolerance


def test_a_positive_angle_up_to_a_quarter_turn_passes():
    assert angle("Deviation", 0.01) == 0.01
    assert angle("Deviation", math.pi / 2) == math.pi / 2


@pytest.mark.parametrize("value", [0.0, -0.1, math.nan])
def test_an_angle_that_is_not_positive_is_refused_naming_the_input(value):
    with pytest.raises(NodeWarning, match=r"^Deviation must be a positive angle in radians, such as 0\.01"):
        angle("Deviation", value)


def test_an_angle_past_a_quarter_turn_is_refused():
    with pytest.raises(NodeWarning, match=r"^Tolerance is 2 rad; .* at most 1\.571 \(π/2\)$"):
        angle("Tolerance", 2.0)


def test_exact_lets_0_through_and_no_greatest_lets_any_size():
    assert angle("WarpTolerance", 0.0, exact=True, largest=None) == 0.0
    assert tolerance("WarpTolerance", 3.0) == 3.0


def test_exact_still_refuses_a_negative_angle_and_nan():
    for value in (-1.0, math.nan):
        with pytest.raises(NodeWarning, match=r"^WarpTolerance must be an angle of 0 rad or more"):
            tolerance("WarpTolerance", value)


def test_an_empty_angle_asks_for_one():
    with pytest.raises(NodeWarning, match=r"^Deviation is empty: give an angle in rad, such as 0\.01$"):
        angle("Deviation", None)
