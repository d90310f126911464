"""Rationalise and SplineApproximation refuse one bad item with a warning naming the
input; that item's outputs are null and the node's other items still solve (the rule in
nodes/common/checks.py). An error is left for what no item gets past (too many rulings
at once)."""

from __future__ import annotations

import pytest

from tests.nodes.developable.test_rationalise import DOME
from tests.nodes.developable.test_spline_approximation import twisted_strip
from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.node import NodeWarning
from torsal.engine.values import Vector
from torsal.nodes.developable.rationalise import Rationalise
from torsal.nodes.developable.spline_approximation import SplineApproximation

#: Loose enough for three strips on the dome: each good item solves in a fraction of a second.
LOOSE = 0.3


def _strip_counts(result) -> list[int]:
    return [len(strips) for _, strips in sorted(out(result, "Strips").items())]


@pytest.mark.parametrize(("inputs", "named"), [
    ({"Tolerance": tree({(0,): [LOOSE, -1.0]})}, "Tolerance must be a positive distance"),
    ({"Tolerance": tree({(0,): [LOOSE, float("nan")]})}, "Tolerance must be a positive distance"),
    ({"Tolerance": LOOSE, "Direction": tree({(0,): [Vector(0.0, 1.0, 0.0), Vector(0.0, 0.0, 0.0)]})},
     "Direction must be a non-zero vector"),
], ids=["negative-tolerance", "nan-tolerance", "zero-direction"])
def test_one_refused_item_warns_naming_its_input_and_the_other_item_still_solves(inputs, named):
    result = run(Rationalise(), Surface=tree({(0,): [DOME.surface()]}), MaxStrips=40, **inputs)
    assert result.state == "warning"
    assert any(t.startswith(named) for t in texts(result)), texts(result)
    first, second = _strip_counts(result)
    assert first > 0 and second == 0


def test_a_guides_item_that_is_not_a_curve_is_a_warning_naming_the_item():
    # (in a graph the Guides port refuses it first; the node's own check names the item)
    with pytest.raises(NodeWarning, match="Guides item 2 is a Vector, not a curve"):
        Rationalise().solve(DOME.surface(), LOOSE, 40, None, [None, Vector(1.0, 0.0, 0.0)], 24, 1e-7)


def test_too_many_rulings_at_once_stay_an_error():
    result = run(Rationalise(), Surface=tree({(0,): [DOME.surface()]}), Tolerance=LOOSE, MaxStrips=200,
                 Segments=200)
    assert result.state == "error"


def test_a_wrong_angles_list_warns_and_the_other_branch_still_solves():
    surface, edge = twisted_strip()
    result = run(SplineApproximation(), Surface=tree({(0,): [surface]}), Curve=tree({(0,): [edge]}),
                 Segments=4, Angles=tree({(0,): [0.1], (1,): [0.1, 0.2, 0.3]}))
    assert result.state == "warning"
    assert any(t.startswith("Angles has 3 values") for t in texts(result))
    best = dict(out(result, "BestAngles"))
    assert best[(0,)] == [0.1] * 5
    assert best[(1,)] == []


def test_an_angle_that_is_not_a_number_is_a_warning_naming_angles():
    surface, edge = twisted_strip()
    result = run(SplineApproximation(), Surface=tree({(0,): [surface]}), Curve=tree({(0,): [edge]}),
                 Segments=4, Angles=[0.1, float("inf")])
    assert result.state == "warning"
    assert "Angles contains a value that is not a finite number" in texts(result)
