"""What every surface-making toolbox node hands on: the loft of its rulings, the
rulings as lines, and their warp angles.

The thesis convention, kept here: a developable is *built on* its rulings, so the
output surface is the ruled surface whose rulings are exactly the output lines, and
the warp angles are reported with it so developability is visible, not assumed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from engine.node import NodeError
from nodes.geometry.curves.line import Line
from nodes.geometry.developable.warp import warp_angles, warp_of_rulings
from nodes.geometry.ruled import RuledSurface


@dataclass(frozen=True)
class StripOutputs:
    """``Surface``, ``Rulings`` and ``WarpAngles`` of one ruled strip, ready for a node."""

    surface: RuledSurface
    rulings: list[Line]
    warp: list[float]

    def as_tuple(self) -> tuple[RuledSurface, list[Line], list[float]]:
        return self.surface, self.rulings, self.warp


def strip_outputs(
    starts: ArrayLike,
    ends: ArrayLike,
    tangents_a: ArrayLike | None = None,
    tangents_b: ArrayLike | None = None,
    *,
    warp: ArrayLike | None = None,
) -> StripOutputs:
    """Loft ``(n, 3)`` ruling ends into a ruled surface, with lines and warp angles.

    When the exact edge tangents are known (a cylinder's section curve, a tangent
    developable's edge) the warp uses them; otherwise it uses the edge polylines'
    tangents (second-order accurate in the ruling spacing). A caller that has the
    warp angles already (RulingDevelopable's kernel reports them) passes ``warp``.
    """
    a = np.asarray(starts, dtype=float)
    b = np.asarray(ends, dtype=float)
    if len(a) < 2:
        raise NodeError("A strip needs at least two rulings: set Segments to 1 or more.")
    if not (np.isfinite(a).all() and np.isfinite(b).all()):
        raise NodeError("Some rulings have points that are not finite numbers: check the inputs for NaN.")
    if warp is not None:
        warp = np.asarray(warp, dtype=float)
    elif tangents_a is not None and tangents_b is not None:
        warp = warp_angles(a, b, tangents_a, tangents_b)
    else:
        warp = warp_of_rulings(a, b)
    try:
        surface = RuledSurface.from_rulings(a, b)
    except ValueError as exc:
        raise NodeError(f"The rulings do not make a surface: {exc}") from None
    lines = Line.many(a, b)
    return StripOutputs(surface, lines, (np.nan_to_num(warp) if np.isnan(warp).any() else warp).tolist())


def warp_summary(warp: ArrayLike, tolerance: float | None = None) -> str:
    """One line for a node's remark: the largest warp and, given a tolerance, how many exceed it."""
    w = np.asarray(warp, dtype=float)
    if w.size == 0:
        return "no rulings"
    text = f"largest warp {np.max(w):.3g} rad over {w.size} rulings"
    if tolerance is not None:
        over = int(np.count_nonzero(w > tolerance))
        text += f"; {over} above {tolerance:g} rad" if over else f"; all within {tolerance:g} rad"
    return text
