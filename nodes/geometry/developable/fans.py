"""Closing a strip where its curves admit no torsal ruling: flat triangles, and their share.

Over a run of stations on A without a torsal partner on B, the strip is bounded by the
torsal rulings on either side (or by the curves' ends) and by the two stretches of A
and B in between. That piece is closed by a strip of triangles, each with two corners
on one curve and one on the other — a sequence of fans through single points, as the
planar middle of the ZVE roof edge is made. Three points are always coplanar, so every
triangle is flat and the strip stays developable (it unrolls exactly); what it gives up
is tangency to the curves, so its rulings are flagged, not counted as torsal.

The triangles follow the two stretches in step: the next ruling advances along the
curve whose next vertex is nearer in *fraction of its stretch's length*, so the
triangles are about as wide on both curves and no ruling crosses another.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..curve_base import FloatArray
from ..vec_ops import cross, norm

IntArray = NDArray[np.int64]


def zigzag(length_a: FloatArray, length_b: FloatArray) -> tuple[IntArray, IntArray]:
    """Vertex indices ``(i, j)`` of the rulings of the triangle strip between a chain of
    points on A at arc lengths ``length_a`` (non-decreasing) and one on B at
    ``length_b``: from (0, 0) to (last, last), each step advancing along one chain.

    >>> i, j = zigzag(np.array([0.0, 1.0, 2.0]), np.array([0.0, 3.0, 4.0]))
    >>> i.tolist(), j.tolist()
    ([0, 1, 1, 2, 2], [0, 0, 1, 1, 2])
    """
    fa, fb = _fractions(length_a), _fractions(length_b)
    keys = np.concatenate([fa[1:], fb[1:]])
    along_b = np.concatenate([np.zeros(len(fa) - 1, dtype=bool), np.ones(len(fb) - 1, dtype=bool)])
    # step to whichever next vertex comes first, A's before B's at a tie
    steps = along_b[np.lexsort((along_b, keys))]
    i = np.concatenate([[0], np.cumsum(~steps)])
    j = np.concatenate([[0], np.cumsum(steps)])
    return i.astype(np.int64), j.astype(np.int64)


def _fractions(length: FloatArray) -> FloatArray:
    """Arc lengths as fractions of the chain's length (even steps if it has none)."""
    span = float(length[-1] - length[0])
    if len(length) < 2 or not span > 0:
        return np.linspace(0.0, 1.0, len(length))
    return (length - length[0]) / span


def patch_areas(starts: FloatArray, ends: FloatArray) -> FloatArray:
    """Area of each piece of strip between consecutive rulings ``(starts[k], ends[k])`` and
    ``(starts[k+1], ends[k+1])``: half the cross product of the quad's diagonals, exact
    for a flat quad and for a triangle (two rulings sharing an end)."""
    diagonal = ends[1:] - starts[:-1]
    other = ends[:-1] - starts[1:]
    return 0.5 * norm(cross(diagonal, other))


def creased_fans(starts: FloatArray, ends: FloatArray, fan: NDArray[np.bool_]) -> NDArray[np.bool_]:
    """Which pieces between consecutive rulings belong to a fan that creases the sheet.

    A run of fan pieces whose rulings all pass through one point (a cone through a single
    point of A or of B, like the triangle that closes a strip's end where the curves' ends
    admit no torsal ruling) meets the torsal rulings on either side in their own tangent
    planes — both contain the ruling and the moving curve's tangent — so the sheet stays
    smooth (G1) and exactly developable. A run that needs apexes on both curves (a zigzag
    of triangles over a stretch with no torsal ruling) folds at every change of apex:
    those are the pieces that need the designer. Returns one flag per piece.
    """
    in_fan = fan[:-1] | fan[1:]
    creased = np.zeros(len(in_fan), dtype=bool)
    if not in_fan.any():
        return creased
    size = float(np.ptp(np.concatenate([starts, ends]), axis=0).max()) or 1.0
    same_start = norm(starts[1:] - starts[:-1]) <= 1e-12 * size
    same_end = norm(ends[1:] - ends[:-1]) <= 1e-12 * size
    edges = np.flatnonzero(np.diff(np.concatenate([[0], in_fan.astype(np.int8), [0]])))
    for first, stop in zip(edges[::2], edges[1::2], strict=True):  # runs of fan pieces
        one_apex = same_start[first:stop].all() or same_end[first:stop].all()
        creased[first:stop] = not one_apex
    return creased


def area_share(starts: FloatArray, ends: FloatArray, pieces: NDArray[np.bool_]) -> float:
    """The share of the strip's area in the flagged ``pieces`` (0 to 1)."""
    areas = patch_areas(starts, ends)
    total = float(areas.sum())
    if not total > 0:
        return 0.0 if not pieces.any() else 1.0
    return float(areas[pieces].sum() / total)


def fan_share(starts: FloatArray, ends: FloatArray, fan: NDArray[np.bool_]) -> float:
    """The share of the strip's area in pieces next to a fan ruling (0 to 1)."""
    areas = patch_areas(starts, ends)
    total = float(areas.sum())
    if not total > 0:
        return 0.0 if not fan.any() else 1.0
    in_fan = fan[:-1] | fan[1:]
    return float(areas[in_fan].sum() / total)
