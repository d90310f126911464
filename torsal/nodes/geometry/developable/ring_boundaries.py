"""The boundaries of a ring layout's half and the creases along them (Rationalise's outputs).

A half of the ring layout (:mod:`.ring_layout`) is marched with rings of curvature as
boundaries (:func:`~.rings.march_rings`): the strip between the rings at levels ``lo`` and
``hi`` of its :class:`~.rings.RingPatch` is cut to the half (:func:`~.trimmed.cut_strip`),
so it may keep one piece, several or none, each between the same two rings. Neighbouring
pieces share the stretch of ring they both keep exactly (their edges run on the ring
there), and there they meet at an angle: the crease a designer sees.

:func:`half_boundaries` gives, for one half, the rings its strips lie between, in order
(each cut to the stretch of it inside the half, :func:`ring_inside`), and the crease along
each inner one (:func:`fold_along`): the largest angle between the two pieces' normals at
points of the ring that lie on both their edges — the fold angle the parameter-line layout
reports per inner boundary (:func:`~.certify.crease_angle`). A cap of the layout is a
trimmed face (:mod:`.trimmed`): its boundaries are those of its strips before the cut, and
:func:`cut_creases` measures the creases along them on the cut strips the same way.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from ..array_types import FloatArray
from ..curve_base import Curve
from ..vectors import angle_between
from .chain import Chain
from .rationalise import Strip
from .rings import RingPatch

#: Samples along a ring where it is judged inside the half, and where the fold is measured.
SAMPLES = 241
#: Points of a ring count as on a piece's edge within this share of the design's size
#: (the edges run on the ring itself: they differ by rounding).
ON_EDGE = 1e-9


def _runs(keep: FloatArray) -> list[tuple[int, int]]:
    """The runs of True in ``keep``, as (first, last) indices."""
    edges = np.flatnonzero(np.diff(np.concatenate([[0], keep.astype(int), [0]])))
    return [(int(a), int(b) - 1) for a, b in zip(edges[::2], edges[1::2], strict=True)]


Inside = Callable[[FloatArray], FloatArray]


def ring_inside(patch: RingPatch, level: float, *insides: Inside) -> Curve:
    """The ring at ``level`` of ``patch``, cut to where the first of ``insides`` (signed
    distances of points, ≥ 0 inside) that holds part of it is ≥ 0: its longest stretch
    inside, the ends placed where the distance sampled at :data:`SAMPLES` points crosses 0
    (linearly between samples); the whole ring where none holds any of it."""
    ring = patch.ring(level)
    t = np.linspace(0.0, 1.0, SAMPLES)
    points = ring.point_at(t)
    for inside in insides:
        g = inside(points)
        runs = _runs(g >= 0.0)
        if runs:
            break
    else:
        return ring
    first, last = max(runs, key=lambda r: t[r[1]] - t[r[0]])

    def crossing(i: int, j: int) -> float:  # g[i] < 0 <= g[j], neighbours
        return float(t[i] + (t[j] - t[i]) * g[i] / (g[i] - g[j]))

    t0 = crossing(first - 1, first) if first > 0 else 0.0
    t1 = crossing(last + 1, last) if last < len(t) - 1 else 1.0
    return Chain([(ring, t0, t1)]) if t1 > t0 else ring


def fold_along(curve: Curve, below: Sequence[Strip], above: Sequence[Strip], size: float) -> float:
    """The largest angle (rad) between the normals of a strip of ``below`` and one of
    ``above`` at the points of ``curve`` (:data:`SAMPLES` along it) that lie on the former's
    upper edge and the latter's lower edge both (within :data:`ON_EDGE` of ``size``); NaN
    where no two share any, or where a normal is undefined at every shared point (a fan's
    apex)."""
    points = curve.point_at(np.linspace(0.0, 1.0, SAMPLES))
    near = ON_EDGE * size
    uppers = [strip.surface.curve_b.closest_point(points) for strip in below]
    lowers = [strip.surface.curve_a.closest_point(points) for strip in above]
    found = []
    for low, on_low in zip(below, uppers, strict=True):
        for up, on_up in zip(above, lowers, strict=True):
            both = (on_low.distances <= near) & (on_up.distances <= near)
            if low is up or not both.any():
                continue
            ones = np.ones(int(both.sum()))
            n_low = low.surface.normal_at(on_low.parameters[both], ones)
            n_up = up.surface.normal_at(on_up.parameters[both], 0.0 * ones)
            angle = angle_between(n_low, n_up)
            found += angle[np.isfinite(angle)].tolist()
    return max(found) if found else float("nan")


def half_boundaries(patch: RingPatch, pieces: Sequence[Strip], inside: Inside, on_design: Inside,
                    size: float) -> tuple[list[Curve], list[float]]:
    """The rings ``pieces`` lie between (their levels ``lo`` and ``hi`` on ``patch``), in
    order, each cut to the half (``inside``, :func:`ring_inside`) or, where none of it lies
    in the half (the first ring, inside the cap whose edge cuts the first strips), to the
    design (``on_design``); and the crease along each inner ring: :func:`fold_along` it of
    the pieces below and above it (NaN where no two meet along it)."""
    levels = sorted({p.lo for p in pieces} | {p.hi for p in pieces})
    rings = [ring_inside(patch, level, inside, on_design) for level in levels]
    creases = [fold_along(rings[k], [p for p in pieces if p.hi == levels[k]],
                          [p for p in pieces if p.lo == levels[k]], size)
               for k in range(1, len(levels) - 1)]
    return rings, creases


def cut_creases(boundaries: Sequence[Curve], strips: Sequence[Strip], size: float) -> list[float]:
    """The crease along each inner one of ``boundaries`` between ``strips`` cut from the
    strips between them (a trimmed face's, :mod:`.trimmed`): :func:`fold_along` it of every
    pair of strips that both keep part of it, measured on the cut strips themselves."""
    return [fold_along(curve, strips, strips, size) for curve in boundaries[1:-1]]
