"""Bounds declared on an input port: the solver refuses a value outside them, naming the input."""

from __future__ import annotations

from tests.support.node_helpers import out, run, texts, tree
from torsal.engine.bounds import bounds_text
from torsal.engine.node import In, Node, Out
from torsal.engine.types import INTEGER, NUMBER


class Strips(Node):
    """Test-only node: doubles a bounded count."""

    type_id = "test.Strips"
    inputs = (In("Segments", INTEGER, "S", "Strips.", default=4, min=1, max=1000),)
    outputs = (Out("Twice", INTEGER, "T", "2 × Segments."),)

    def solve(self, segments: int) -> int:
        return 2 * segments


class Angle(Node):
    """Test-only node: a bounded number passed on."""

    type_id = "test.Angle"
    inputs = (In("Angle", NUMBER, "A", "An angle.", default=0.5, max=1.5),)
    outputs = (Out("Same", NUMBER, "S", "The angle."),)

    def solve(self, angle: float) -> float:
        return angle


def test_a_value_within_the_bounds_reaches_solve():
    result = run(Strips(), Segments=1000)
    assert result.state == "ok" and out(result, "Twice") == {(0,): [2000]}


def test_a_value_below_the_least_is_a_warning_naming_the_input_and_solve_is_not_called():
    result = run(Strips(), Segments=0)
    assert result.state == "warning"
    assert texts(result) == ["Segments must be at least 1, not 0"]
    assert out(result, "Twice") == {}


def test_a_count_past_the_greatest_says_how_many_can_be_made():
    result = run(Strips(), Segments=10**12)
    assert texts(result) == ["Segments is 1,000,000,000,000; at most 1,000 can be made at once"]


def test_a_wired_list_is_refused_for_its_one_value_outside_the_bounds():
    result = run(Strips(), Segments=tree({(0,): [3, 5, 2000]}))
    assert result.state == "warning"
    assert texts(result) == ["Segments is 2,000; at most 1,000 can be made at once"]


def test_a_number_past_its_greatest_is_refused_with_both_values():
    result = run(Angle(), Angle=3.0)
    assert texts(result) == ["Angle must be at most 1.5, not 3"]


def test_bounds_read_as_the_inspector_shows_them():
    assert bounds_text(Strips.inputs[0]) == "1 to 1,000"
    assert bounds_text(Angle.inputs[0]) == "at most 1.5"
    assert bounds_text(In("Count", INTEGER, min=0)) == "0 or more"
    assert bounds_text(In("X", NUMBER)) == ""


def test_a_developable_refuses_segments_outside_its_port_bounds_before_any_ruling_is_made():
    from torsal.engine.values import Vector
    from torsal.nodes.developable.cylindrical import CylindricalSurface
    from torsal.nodes.geometry.curves import Line
    from torsal.nodes.limits import MAX_SEGMENTS

    port = next(p for p in CylindricalSurface.inputs if p.name == "Segments")
    assert (port.min, port.max) == (1, MAX_SEGMENTS)
    curve = Line([0, 0, 0], [1, 0, 0])
    for segments, message in ((0, "Segments must be at least 1, not 0"),
                              (MAX_SEGMENTS + 1, f"Segments is {MAX_SEGMENTS + 1:,}; at most "
                                                 f"{MAX_SEGMENTS:,} can be made at once")):
        result = run(CylindricalSurface(), Curve=tree({(0,): [curve]}), Direction=Vector(0, 0, 1),
                     Segments=segments)
        assert result.state == "warning" and texts(result) == [message]
        assert out(result, "Surface") == {}
