"""Where a strip's sheet folds: its sharp creases and the places it passes through itself,
as a node's warning and its Folds points (see :mod:`torsal.nodes.geometry.strip_crossings`
and :mod:`torsal.nodes.geometry.developable.kinds`)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from torsal.engine.values import Point
from torsal.nodes.common.convert import points as as_points
from torsal.nodes.geometry.strip_crossings import Crossings, crossings, crossings_all


@dataclass(frozen=True)
class FoldReport:
    """The warning (None when the sheet neither creases sharply nor crosses itself) and the
    points: the middle of each sharp crease, then a point of each crossing pair."""

    message: str | None
    points: list[Point]
    creases: int
    crossing_pairs: int


def _at(point: np.ndarray) -> str:
    return "(" + ", ".join(f"{x:.6g}" for x in point) + ")"


def fold_report(
    starts: ArrayLike,
    ends: ArrayLike,
    crease_angle: ArrayLike,
    sharp: float,
    origin: ArrayLike | None = None,
    crossed: Crossings | None = None,
) -> FoldReport:
    """Creases of the strip whose angle (rad, NaN never) exceeds ``sharp``, and the pairs of its
    triangles that cross, with the message naming how many and the first of each. The rulings
    may be given in a frame anchored at the model whose ``origin`` is this (the points and the
    message are then in world coordinates). ``crossed`` is the strip's :func:`crossings` where
    the caller has it (:func:`crossings_all` of several strips at once)."""
    a = np.asarray(starts, dtype=float).reshape(-1, 3)
    b = np.asarray(ends, dtype=float).reshape(-1, 3)
    angle = np.asarray(crease_angle, dtype=float)
    sharp_rows = np.flatnonzero(angle > sharp)
    shift = np.zeros(3) if origin is None else np.asarray(origin, dtype=float)
    middles = 0.5 * (a[sharp_rows] + b[sharp_rows]) + shift
    crossed = crossings(a, b) if crossed is None else crossed
    crossed_at = crossed.points + shift
    parts = []
    if len(sharp_rows):
        parts.append(
            f"{len(sharp_rows)} creases sharper than {sharp:g} rad (up to {float(angle.max()):.3g} rad; "
            f"first: ruling {int(sharp_rows[0])}, its middle at {_at(middles[0])})"
        )
    if len(crossed):
        parts.append(
            f"{len(crossed)} pairs of its triangles cross each other (first: between rulings "
            f"{int(crossed.first[0])} and {int(crossed.second[0]) + 1}, at {_at(crossed_at[0])})"
        )
    message = None
    if parts:
        message = "the sheet folds: " + "; ".join(parts) + ". Folds gives where"
    points = as_points(np.concatenate([middles, crossed_at])) if parts else []
    return FoldReport(message, points, len(sharp_rows), len(crossed))


def fold_reports(
    strips: list[tuple[np.ndarray, np.ndarray, np.ndarray, float, np.ndarray | None, Crossings]],
) -> list[FoldReport]:
    """:func:`fold_report` of every strip ``(starts, ends, crease_angle, sharp, origin,
    crossed)``: the strips that neither crease by more than their ``sharp`` nor cross
    themselves told at once (their report says nothing), the others reported one by one."""
    if not strips:
        return []
    counts = [len(strip[2]) for strip in strips]
    angle = np.concatenate([np.asarray(strip[2], dtype=float).reshape(-1) for strip in strips])
    sharp = np.repeat([strip[3] for strip in strips], counts)
    creased = (angle > sharp).tolist()
    bounds = np.cumsum([0, *counts]).tolist()
    return [
        fold_report(*strip) if len(strip[5]) or any(creased[low:high]) else FoldReport(None, [], 0, 0)
        for strip, low, high in zip(strips, bounds[:-1], bounds[1:], strict=True)
    ]


def strips_crossings(strips: list[tuple[np.ndarray, np.ndarray]]) -> list[Crossings | None]:
    """The :func:`crossings` of every strip ``(starts, ends)`` whose ends are all finite (at
    once, :func:`crossings_all`); None for the others (they make no strip)."""
    finite = [len(a) >= 2 and bool(np.isfinite(a).all() and np.isfinite(b).all()) for a, b in strips]
    found = iter(crossings_all([strip for strip, ok in zip(strips, finite, strict=True) if ok]))
    return [next(found) if ok else None for ok in finite]
