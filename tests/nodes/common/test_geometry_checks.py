"""The input checks of curves: which curves have a length, told one by one or many at once."""

from __future__ import annotations

from torsal.nodes.common.geometry_checks import curves_with_length, has_no_length
from torsal.nodes.geometry.curves import Circle, Line


def test_curves_whose_ends_lie_apart_have_a_length_found_at_once():
    line = Line([1e6, 0, 0], [1e6, 2, 0])  # 2 m long, a million metres out
    point = Line([1e6, 0, 0], [1e6, 0, 0])
    loop = Circle(radius=1.0)  # its ends meet: left to has_no_length
    found = curves_with_length([line, point, loop, None, 3.0, line])
    assert found == {id(line)}
    assert not has_no_length(line) and has_no_length(point) and not has_no_length(loop)
    assert curves_with_length([]) == set()
