"""Several strips' rows in one array: what lets a step of the solve run once for many strips.

The strips of one node solve are solved side by side (:func:`.ruling.ruling_developables`):
a step stacks every strip's rows (stations, candidates, rulings) one strip after another
in the same arrays, as :func:`numpy.add.reduceat` takes ragged groups, and keeps beside
them where each strip's rows start (:class:`Stack`). Row-wise arithmetic then runs once
for all strips, with the same values a strip's rows get alone; a per-strip scalar (a size,
a tolerance) is repeated onto its rows; a per-strip reduction is a ``reduceat``. Only the
curves are evaluated strip by strip (each strip has its own two curves):
:func:`evaluate_each`.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..array_types import FloatArray, IntArray
from ..curve_base import Curve
from ..vec_ops import flatnonzero, norm
from .warp import _size


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
        return np.split(array, self.offsets[1:-1])

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
    ``local_derivatives``): each curve is evaluated once, at its own parameters (the
    values it gives them alone), and the results are stacked as ``x`` is."""
    out = np.empty((order + 1, len(x), 3))
    for curve, low, high in zip(curves, bounds[:-1].tolist(), bounds[1:].tolist(), strict=True):
        if high > low:
            evaluate = curve.local_derivatives if local else curve.derivatives
            out[:, low:high] = evaluate(x[low:high], order)
    return list(out)


def sizes(stack: Stack, starts: FloatArray, ends: FloatArray) -> FloatArray:
    """:func:`.warp._size` of each strip's rows of ``starts`` and ``ends``: the diagonal of
    the bounding box of their finite points (0 for a strip without rows)."""
    size = np.zeros(len(stack))
    rows = flatnonzero(stack.counts > 0)
    if len(rows) == 0:
        return size
    first = stack.starts[rows]  # (reduceat over the strips that have rows)
    high = np.maximum(np.maximum.reduceat(starts, first, axis=0), np.maximum.reduceat(ends, first, axis=0))
    low = np.minimum(np.minimum.reduceat(starts, first, axis=0), np.minimum.reduceat(ends, first, axis=0))
    size[rows] = norm(high - low)
    for i in flatnonzero(~np.isfinite(size)):  # a NaN or infinite coordinate: the finite ones'
        low_row, high_row = stack.offsets[i], stack.offsets[i + 1]
        size[i] = _size(starts[low_row:high_row], ends[low_row:high_row])
    return size
