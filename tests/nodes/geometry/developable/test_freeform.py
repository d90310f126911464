"""Which layout Rationalise tries (torsal/nodes/geometry/developable/freeform.py): rings
round the bumps only on a design where both families of parameter lines cross its
asymptotic directions, never with guides or a direction, never on a closed design."""

from __future__ import annotations

import numpy as np
import pytest

from tests.support.freeform_designs import DESIGNS
from torsal.nodes.geometry.developable import freeform


def test_rings_are_tried_on_the_double_bump_alone_of_the_designs():
    tried = {name: freeform._rings_worth_trying(design.surface(), 0.05 * design.unit)
             for name, design in DESIGNS.items()}
    assert tried.pop("bumps")
    assert not any(tried.values()), [name for name, yes in tried.items() if yes]


@pytest.mark.parametrize("bad", [0.0, -1.0, float("nan"), float("inf")])
def test_a_tolerance_that_is_no_distance_goes_to_the_parameter_lines_checks(bad):
    assert not freeform._rings_worth_trying(DESIGNS["bumps"].surface(), bad)


def test_a_direction_or_guides_skip_the_rings(monkeypatch):
    asked = []
    monkeypatch.setattr(freeform, "_rings", lambda *args: asked.append(args))
    monkeypatch.setattr(freeform, "rationalise", lambda *args: "parameter lines")
    surface = DESIGNS["bumps"].surface()
    along_y = np.array([0.0, 1.0, 0.0])
    assert freeform.rationalise_freeform(surface, 0.05, direction=along_y) == "parameter lines"
    assert not asked
    assert freeform.rationalise_freeform(surface, 0.05) == "parameter lines"  # rings refused: None
    assert len(asked) == 1
