"""Several strips' rows in one array: what lets a step of the solve run once for many strips.

The strips of one node solve are solved side by side (:func:`.ruling.ruling_developables`):
a step stacks every strip's rows (stations, candidates, rulings) one strip after another
in the same arrays, as :func:`numpy.add.reduceat` takes ragged groups, and keeps beside
them where each strip's rows start (:class:`Stack`). Row-wise arithmetic then runs once
for all strips, with the same values a strip's rows get alone; a per-strip scalar (a size,
a tolerance) is repeated onto its rows; a per-strip reduction is a ``reduceat``. The curves
are evaluated together where they share their knots (:func:`evaluate_each`).
"""

from __future__ import annotations

from collections.abc import Sequence
from itertools import pairwise

import numpy as np

from ..array_types import FloatArray, IntArray
from ..curve_base import Curve
from ..curves.shared_knots import derivatives_together


class Stack:
    """Where each strip's rows lie in a stacked array: strip ``i`` has rows
    ``offsets[i]:offsets[i + 1]``."""

    __slots__ = ("counts", "offsets", "starts")

    def __init__(self, counts: Sequence[int] | IntArray) -> None:
        self.counts = np.asarray(counts, dtype=np.int64)
        self.offsets = np.zeros(len(self.counts) + 1, dtype=np.int64)
        np.cumsum(self.counts, out=self.offsets[1:])
        self.starts = self.offsets[:-1]  #: each strip's first row (``reduceat``'s indices)

    @classmethod
    def of(cls, arrays: Sequence[np.ndarray]) -> Stack:
        """The stack of ``arrays`` (one per strip) joined along their first axis."""
        return cls([len(a) for a in arrays])

    def __len__(self) -> int:
        return len(self.counts)

    @property
    def rows(self) -> int:
        """How many rows all strips have together."""
        return int(self.offsets[-1])

    def owner(self) -> IntArray:
        """The strip of every row."""
        return np.repeat(np.arange(len(self.counts)), self.counts)

    def repeat(self, values: np.ndarray) -> np.ndarray:
        """A value per strip, as a value per row."""
        return np.repeat(values, self.counts, axis=0)

    def split(self, array: np.ndarray) -> list[np.ndarray]:
        """A stacked array as one array per strip (views)."""
        bounds = self.offsets.tolist()
        return [array[low:high] for low, high in pairwise(bounds)]

    def groups(self, rows: IntArray) -> IntArray:
        """For increasing row indices ``rows``, where each strip's ones start and end among
        them: strip ``i``'s are ``rows[bounds[i]:bounds[i + 1]]``."""
        return np.searchsorted(rows, self.offsets)

    def reduce_max(self, array: np.ndarray) -> np.ndarray:
        """Each strip's largest value of every column (its rows must not be empty)."""
        return np.maximum.reduceat(array, self.starts, axis=0)

    def reduce_min(self, array: np.ndarray) -> np.ndarray:
        """Each strip's smallest value of every column (its rows must not be empty)."""
        return np.minimum.reduceat(array, self.starts, axis=0)


def evaluate_each(
    curves: Sequence[Curve], x: FloatArray, bounds: IntArray, order: int, local: bool = False
) -> list[FloatArray]:
    """Points and derivatives up to ``order`` of curve ``i`` at its parameters
    ``x[bounds[i]:bounds[i + 1]]`` (relative to the curve's anchor where ``local``: its
    ``local_derivatives``), the values each curve gives them alone, stacked as ``x`` is:
    curves that share their knots are evaluated together (:mod:`..curves.shared_knots`)."""
    return list(derivatives_together(curves, x, bounds, order, local))


def evaluate_rows(curves: Sequence[Curve], x: FloatArray, strip_of: IntArray, order: int) -> list[FloatArray]:
    """Curve ``strip_of[i]``'s points and derivatives up to ``order`` at ``x[i]``, the rows
    in any order: each curve evaluated once at its own parameters (:func:`evaluate_each`)."""
    if len(curves) == 1:
        return curves[0].derivatives(x, order)
    by_strip = np.argsort(strip_of, kind="stable")
    bounds = np.searchsorted(strip_of[by_strip], np.arange(len(curves) + 1))
    grouped = evaluate_each(curves, x[by_strip], bounds, order)
    out = np.empty((order + 1, len(x), 3))
    out[:, by_strip] = grouped
    return list(out)
