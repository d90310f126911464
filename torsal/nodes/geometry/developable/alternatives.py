"""Hints that work: solve the other pairings of two curves and say what they gain.

When a strip needs many flat triangles (no torsal ruling over part of it), two changes
a designer can make in a second are swapping the curves (stations then lie on the
other one) and reversing B (when the two were drawn in opposite directions). Rather
than guess, :func:`better_pairing` solves both and names the one that lowers the fan
share, with the share it reaches — or returns None, and nothing is suggested.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from ..curve_base import Curve
from .ruling import RulingResult, ruling_developable, ruling_developables

#: An alternative is worth naming when it lowers the fan share by at least this much.
GAIN = 0.01
#: B is reversed when that lowers the fan share by more than this (rounding): the strip
#: then does not depend on which way B was drawn.
ALIGN = 1e-9


@dataclass(frozen=True)
class Alternative:
    """Another way to pair the curves, and the fan share it gives."""

    change: str  #: what the designer does, e.g. "swap CurveA and CurveB"
    fan_share: float  #: share of the area in creased fans (the ones that need the designer)


def alternatives(
    curve_a: Curve, curve_b: Curve, segments: int, tolerance: float
) -> list[Alternative]:
    """The fan shares of the strip with the curves swapped and with B reversed."""
    tries: list[tuple[str, Callable[[], RulingResult]]] = [
        ("swap CurveA and CurveB", lambda: ruling_developable(curve_b, curve_a, segments, tolerance)),
        ("reverse CurveB", lambda: ruling_developable(curve_a, curve_b.reversed(), segments, tolerance)),
    ]
    return [Alternative(change, solve().creased_share) for change, solve in tries]


def better_pairing(
    curve_a: Curve, curve_b: Curve, segments: int, tolerance: float, result: RulingResult
) -> str | None:
    """A sentence naming the alternative that lowers the fan share of ``result`` most
    (by at least :data:`GAIN`), e.g. "swap CurveA and CurveB: creased fans fall to 0 %
    of the area"; None when neither helps."""
    best = min(alternatives(curve_a, curve_b, segments, tolerance), key=lambda a: a.fan_share)
    if best.fan_share > result.creased_share - GAIN:
        return None
    return f"{best.change}: creased fans fall to {100 * best.fan_share:.3g} % of the area"


def align_b(
    jobs: Sequence[tuple[Curve, Curve, int, float]], results: list[RulingResult | ValueError]
) -> list[tuple[Curve, str] | None]:
    """Where a strip closed partly by fans has torsal rulings that run backwards along B
    (partners whose normals flip: B was drawn against A there) or B runs against A by
    their ends (:func:`drawn_against`), the strip solved with B reversed, taken when that
    closes less of its area with fans (by more than :data:`ALIGN`) or, when it closes as
    much (a tie: nothing in the fans tells the two ways apart), when B runs against A by
    their ends. So B drawn either way gives one strip, not the one it was drawn as.
    ``results`` are replaced in place and, at each such place, the reversed curve and why
    it was reversed are returned (None elsewhere). A designer expects the strip between
    the curves whichever way each was drawn, as Rhino's Loft aligns its curves; every
    strip is solved side by side (:func:`.ruling.ruling_developables`)."""
    against = [drawn_against(job[0], job[1]) for job in jobs]
    redo = [
        i for i, result in enumerate(results)
        if not isinstance(result, ValueError) and result.fan.any()
        and (result.backward or result.any_backward or against[i])
    ]
    reversed_b: list[tuple[Curve, str] | None] = [None] * len(results)
    if not redo:
        return reversed_b
    flipped = {i: jobs[i][1].reversed() for i in redo}
    again = ruling_developables([(jobs[i][0], flipped[i], *jobs[i][2:]) for i in redo])
    for i, other in zip(redo, again, strict=True):
        before = results[i]
        if isinstance(other, ValueError) or isinstance(before, ValueError):  # (only solved ones are redone)
            continue
        gain = before.fan_share - other.fan_share
        if gain > ALIGN:
            why = (FEWER_FANS.format(before=100 * before.fan_share, after=100 * other.fan_share)
                   if not (before.backward or before.any_backward) else BACKWARDS)
            results[i], reversed_b[i] = other, (flipped[i], why)
        elif gain >= -ALIGN and against[i]:  # a tie: B as Loft would align it
            results[i], reversed_b[i] = other, (flipped[i], BY_ENDS)
    return reversed_b


#: Why :func:`align_b` reversed B, as the node's remark completes "CurveB runs against CurveA…".
BACKWARDS = " (its torsal rulings ran backwards along it)"
FEWER_FANS = (
    " (reversed, flat triangles close less of the strip: {after:.3g} % of its area, not {before:.3g} %)"
)
BY_ENDS = " by their ends (flat triangles close as much of the strip whichever way it runs)"


def drawn_against(curve_a: Curve, curve_b: Curve) -> bool:
    """Whether B runs against A by their ends, as Rhino's Loft reads two curves: A's ends
    are nearer B's ends crossed than in order. It settles a strip that fans cover as much
    whichever way B runs, so that B drawn either way still gives one strip."""
    (a0, a1), (b0, b1) = curve_a.end_points, curve_b.end_points
    in_order = np.linalg.norm(a0 - b0) + np.linalg.norm(a1 - b1)
    crossed = np.linalg.norm(a0 - b1) + np.linalg.norm(a1 - b0)
    return bool(crossed < in_order)
