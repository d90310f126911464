"""The kernel's one count check (:func:`torsal.nodes.geometry.counts.segment_count`), and the
kernel functions that take a count through it (unrolling, the paper strip)."""

from __future__ import annotations

import numpy as np
import pytest

from torsal.nodes.geometry.counts import segment_count
from torsal.nodes.geometry.paper_strip import paper_strip
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.geometry.unroll import unroll_surface


@pytest.mark.parametrize("given", [1, 7.0, np.int64(3)])
def test_whole_numbers_from_one_up_pass_as_ints(given):
    assert segment_count(given) == int(given) and type(segment_count(given)) is int


@pytest.mark.parametrize("given", [0, -2, 2.5, float("nan")])
def test_anything_else_is_refused(given):
    with pytest.raises(ValueError):
        segment_count(given)


def test_the_refusal_names_the_count():
    with pytest.raises(ValueError, match="Subdivisions must be a whole number >= 1; got 0"):
        segment_count(0, "Subdivisions")


def test_unrolling_and_the_paper_strip_take_their_counts_through_it():
    with pytest.raises(ValueError, match="Segments must be a whole number >= 1; got 0"):
        paper_strip(1.0, 0.1, [], [], 0)
    square = RuledSurface.from_rulings(np.array([[0.0, 0, 0], [1, 0, 0]]), np.array([[0.0, 1, 0], [1, 1, 0]]))
    with pytest.raises(ValueError, match="Subdivisions must be a whole number >= 1; got 0"):
        unroll_surface(square, 4, 0)
