"""Whether two curves are one: the cheap rejection by their ends, one pair or many at once."""

from __future__ import annotations

from torsal.nodes.geometry.coincidence import coincident, ends_differ_each
from torsal.nodes.geometry.curves import Circle, Line


def test_pairs_whose_ends_differ_are_told_at_once_as_one_by_one():
    line = Line([0, 0, 0], [4, 0, 0])
    pairs = [
        (line, Line([0, 0, 0], [4, 0, 0])),  # the same ends
        (line, Line([4, 0, 0], [0, 0, 0])),  # the same ends, the other way round
        (line, Line([0, 1, 0], [4, 1, 0])),  # a parallel edge 1 away
        (line, Line([0, 0, 0], [4, 3e-6, 0])),  # one end 3e-6 away: 7.5e-7 of the spread of 4
        (line, Line([0, 0, 0], [4, 5e-6, 0])),  # 5e-6 away: 1.25e-6 of it
        (Circle(radius=1.0), Circle(radius=2.0)),  # two loops
    ]
    assert ends_differ_each(pairs) == [False, False, True, False, True, False]
    # a pair whose ends differ is never one curve
    assert not any(coincident(a, b) for (a, b), differ in zip(pairs, ends_differ_each(pairs), strict=True)
                   if differ)
    assert ends_differ_each([]) == []
