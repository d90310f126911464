"""When the strips ringing a design's bumps are tried and not kept, Rationalise says why and
where once: in its remark when the parameter lines it keeps are good, else inside its one
warning, the rings' point last among Where. The ring layout is stood in for (it refuses at
a point of the design chosen here); the parameter lines are solved on the dome.
(docs: the node's help, "Honest limits".)"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from tests.nodes.developable.test_rationalise import DOME, HALF
from tests.support.node_helpers import run, texts, tree
from tests.support.strip_grids import items
from torsal.engine.messages import Level
from torsal.nodes.developable.rationalise import RINGS_TRIED, Rationalise
from torsal.nodes.geometry.developable import freeform
from torsal.nodes.geometry.developable.rationalise import Rationalisation
from torsal.nodes.geometry.developable.ring_layout import RingsRefused

LOOSE = 0.3  # two strips on the dome, 8 segments each: ~2.6 CPU-s a solve
#: Where the stand-in's rings fall short: the middle of the dome's edge v = 0.
AT = (0.5, 0.0)


@pytest.fixture
def refused(monkeypatch):
    """Rings tried on the dome, and refused at :data:`AT` (given in the design the node
    hands over: its local frame)."""
    def ring_layout(design, tolerance, *args):
        point = np.atleast_2d(design.point_at(*AT))[0]
        raise RingsRefused("they leave the design's edge uncovered by 0.0567", point, 0.0567)

    monkeypatch.setattr(freeform, "_rings_worth_trying", lambda design, tolerance: True)
    monkeypatch.setattr(freeform, "ring_layout", ring_layout)


def _warnings(result):
    return [m.text for m in result.messages if m.level == Level.WARNING]


def test_good_parameter_lines_keep_the_reason_in_the_remark_and_where_empty(refused):
    result = run(Rationalise(), Surface=tree({(0,): [DOME.surface()]}), Tolerance=LOOSE, MaxStrips=40,
                 Segments=8)
    assert result.state == "ok", texts(result)
    (remark,) = [t for t in texts(result) if t.startswith(tuple("0123456789"))]
    assert f"{RINGS_TRIED}: they leave the design's edge uncovered by 0.0567" in remark
    assert items(result, "Where") == []


def test_parameter_lines_that_fall_short_too_give_one_warning_with_the_rings_point_last(refused):
    result = run(Rationalise(), Surface=tree({(0,): [DOME.surface()]}), Tolerance=LOOSE, MaxStrips=1,
                 Segments=8)
    assert result.state == "warning"
    (warning,) = _warnings(result)
    assert warning.startswith(f"Tolerance {LOOSE:g} is not met everywhere")
    said = f"{RINGS_TRIED}: they leave the design's edge uncovered by 0.0567 (the last Where point)"
    assert said in warning
    assert "a larger Tolerance, at which the strips round the bumps may meet it" in warning
    assert warning.count(RINGS_TRIED) == 1
    where = items(result, "Where")
    expected = [0.0, -HALF, DOME.f(0.0, -HALF)]  # (u, v) = (0.5, 0) of the closed form
    assert np.allclose([where[-1].x, where[-1].y, where[-1].z], expected, atol=1e-9 * HALF)
    assert len(where) >= 2  # the parameter lines' own point comes first


def _fake(deviation, gap):
    strip = SimpleNamespace(deviation=deviation, where=np.array([1.0, 2.0, 3.0]))
    return Rationalisation("rings", [strip], [], 0.05, [], np.array([[0.0, 0.0, 0.0], [4.0, 5.0, 6.0]]),
                           np.array([0.01, gap]))


@pytest.mark.parametrize(("deviation", "gap", "reason", "point"), [
    (0.0712, 0.01, "a strip between them is 0.0712 from the design", [1.0, 2.0, 3.0]),
    (0.04, 0.093, "they leave the design's edge uncovered by 0.093", [4.0, 5.0, 6.0]),
])
def test_rings_made_but_not_good_say_how_far_off_and_where(monkeypatch, deviation, gap, reason, point):
    monkeypatch.setattr(freeform, "ring_layout", lambda *args: _fake(deviation, gap))
    said, where = freeform._rings(DOME.surface(), 0.05, 64, 24, 1e-7, 0.2)
    assert said == reason
    assert np.array_equal(where, point)


def test_a_ring_layout_that_cannot_be_traced_says_so_with_no_point(monkeypatch):
    def fails(*args):
        raise ValueError("the ring of curvature round a bump crosses itself")

    monkeypatch.setattr(freeform, "ring_layout", fails)
    assert freeform._rings(DOME.surface(), 0.05, 64, 24, 1e-7, 0.2) == (
        "the ring of curvature round a bump crosses itself", None)
