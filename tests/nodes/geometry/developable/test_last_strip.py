"""A march's last strip narrower than MinWidth is merged into the one before or widened.

Strips here are closed forms of the square law: between levels lo and hi a strip is
10 (hi − lo) m wide and deviates 0.5 width² from the design (so 0.05 m at 0.316 m).
"""

from __future__ import annotations

from dataclasses import dataclass

from torsal.nodes.geometry.developable.last_strip import last_two


@dataclass
class Square:
    lo: float
    hi: float

    @property
    def width(self) -> float:
        return 10.0 * (self.hi - self.lo)

    @property
    def deviation(self) -> float:
        return 0.5 * self.width**2


def make(lo: float, hi: float) -> Square:
    return Square(lo, hi)


def test_a_remainder_that_fits_in_the_strip_before_is_merged_into_it():
    before, last = Square(0.5, 0.52), Square(0.52, 0.53)  # 0.2 m and 0.1 m wide
    (merged,) = last_two(make, before, last, 0.53, tolerance=0.05, min_width=0.2)
    assert (merged.lo, merged.hi) == (0.5, 0.53) and merged.deviation <= 0.05


def test_a_remainder_too_wide_to_merge_takes_minwidth_from_the_strip_before():
    before, last = Square(0.5, 0.53), Square(0.53, 0.542)  # 0.3 m and 0.12 m wide, as on the wave
    first, second = last_two(make, before, last, 0.542, tolerance=0.05, min_width=0.2)
    assert first.lo == 0.5 and second.hi == 0.542 and first.hi == second.lo
    assert abs(second.width - 0.202) <= 1e-12 and first.width >= 0.2  # aimed 1 % over MinWidth
    assert first.deviation <= 0.05 and second.deviation <= 0.05


def test_when_neither_is_possible_the_strips_stay_as_they_were():
    before, last = Square(0.5, 0.525), Square(0.525, 0.537)  # 0.25 m: no MinWidth to give
    out = last_two(make, before, last, 0.537, tolerance=0.05, min_width=0.2)
    assert out == [before, last]


def test_a_strip_that_cannot_be_made_leaves_them_as_they_were():
    before, last = Square(0.5, 0.53), Square(0.53, 0.542)
    out = last_two(lambda lo, hi: None, before, last, 0.542, tolerance=0.05, min_width=0.2)
    assert out == [before, last]
