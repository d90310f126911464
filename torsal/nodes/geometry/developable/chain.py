"""A chain of curves end to end: a cut strip's edge, stretches of its rails and of the trim.

Made by the cut (:func:`~.trimmed.cut_strip`, step 4 of :mod:`.trimmed`) and by the ring
layout's boundaries (:mod:`.ring_boundaries`); smooth on each piece, its joins are its
breakpoints.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from ..array_types import FloatArray
from ..curve_base import Curve


class Chain(Curve):
    """Pieces of curves end to end: piece k is ``curve`` over its own parameters ``p0 → p1``,
    run on t in ``[knots[k], knots[k + 1]]`` (the pieces' shares by their parameter spans:
    pieces that follow on in one parameter make a chain linear in it).
    Smooth on each piece; the joins are its breakpoints (corners, in general)."""

    def __init__(self, pieces: list[tuple[Curve, float, float]]) -> None:
        self.pieces = pieces
        lengths = np.array([p1 - p0 for _, p0, p1 in pieces])
        self.knots = np.concatenate([[0.0], np.cumsum(lengths) / lengths.sum()])
        self.knots[-1] = 1.0

    def at(self, piece: int, p: FloatArray) -> FloatArray:
        """The chain's t where piece ``piece`` is at its own parameters ``p``."""
        _, p0, p1 = self.pieces[piece]
        share = (np.asarray(p, dtype=float) - p0) / (p1 - p0) if p1 != p0 else np.zeros(np.shape(p))
        return self.knots[piece] + share * (self.knots[piece + 1] - self.knots[piece])

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        t = np.clip(np.atleast_1d(np.asarray(t, dtype=float)), 0.0, 1.0)
        which = np.clip(np.searchsorted(self.knots, t, side="right") - 1, 0, len(self.pieces) - 1)
        out = [np.empty((len(t), 3)) for _ in range(order + 1)]
        for k in np.unique(which):
            curve, p0, p1 = self.pieces[k]
            mine = which == k
            rate = (p1 - p0) / (self.knots[k + 1] - self.knots[k])
            p = p0 + (t[mine] - self.knots[k]) * rate
            for d, value in enumerate(curve.derivatives(p, order)):
                out[d][mine] = value * rate**d
        return out

    def _breakpoints(self) -> FloatArray:
        """The joins, and each piece's own breakpoints strictly inside its ``p0 → p1``."""
        inner = []
        for k, (curve, p0, p1) in enumerate(self.pieces):
            own = curve._breakpoints()
            inner.append(self.at(k, own[(own > min(p0, p1)) & (own < max(p0, p1))]))
        return np.unique(np.clip(np.concatenate([self.knots, *inner]), 0.0, 1.0))
