"""The check of step 8 (:mod:`.ruling`) for the rulings of many strips at once.

Every output ruling A(s) → B(t) is measured from the curves: its end points and the
curves' exact tangents at (s, t), and its signed warp from those
(:func:`.warp.warp_angles`, NaN where no normal is defined); it is valid where that warp is
within the tolerance plus what the rounding of its end points alone can add
(:func:`within_tolerance`). The rulings of all the strips given are stacked in one array
(:class:`.stack.Stack`); only the curves are evaluated strip by strip, and only where a
ruling's end is not already at hand (a station's point of A, a chosen root on B). Each
strip's size and rounding are its own, so each ruling gets the values it gets when its
strip is measured alone.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ..array_types import BoolArray, FloatArray, IntArray
from ..vec_ops import _EPS, POSITION_ULPS, cross, flatnonzero, norm, position_rounding, unit
from .candidates import ROOT, Candidates
from .stack import Stack, evaluate_each
from .strip import SIDE, Strip
from .warp import _angles, _normals, in_plane_tangent, sizes, warp_angles

#: One strip's rulings to check: the strip, s, t, per ruling its station (−1 for an added
#: ruling), and the station's chosen candidate (−1 for none) among ``good``.
Rulings = tuple[Strip, FloatArray, FloatArray, IntArray, IntArray, Candidates]
#: A strip's checked rulings: starts, ends, signed warp, warp, valid.
Checked = tuple[FloatArray, FloatArray, FloatArray, FloatArray, BoolArray]


def check_rulings(strips: Sequence[Rulings]) -> list[Checked]:
    """The check of every strip's rulings: :func:`measured`'s starts, ends and signed warp,
    the warp, and whether it is valid (:func:`within_tolerance`)."""
    stack = Stack.of([s for _, s, _, _, _, _ in strips])
    starts, ends, signed = measured(strips, stack)
    warp = np.abs(signed)
    rounding = rounding_of(stack, starts, ends)
    tolerance = np.array([strip.tolerance for strip, *_ in strips])
    valid = within_tolerance(warp, stack.repeat(tolerance), starts, ends, stack.repeat(rounding))
    columns = (stack.split(a) for a in (starts, ends, signed, warp, valid))
    return list(zip(*columns, strict=True))


def within_tolerance(
    warp: FloatArray, tolerance: FloatArray | float, starts: FloatArray, ends: FloatArray,
    rounding: FloatArray | float | None = None,
) -> BoolArray:
    """The validity rule, its one home: a ruling from ``starts`` to ``ends`` is valid where its
    ``warp`` is a number within ``tolerance`` plus what the rounding of its end points alone
    can add to a warp measured from them (rad: the positions' rounding over the ruling's
    length). A NaN warp is never valid. The allowance is nothing at the origin; at site
    coordinates the ends are known to an ulp of their coordinates (1.2e-7 m at 1e9 m), so a
    tolerance below it could not be checked there.

    ``rounding`` is the ends' position rounding, per ruling or one for all; by default the
    larger of :func:`~..vec_ops.position_rounding` of ``starts`` and of ``ends`` (one strip).
    """
    if rounding is None:
        rounding = max(position_rounding(starts), position_rounding(ends))
    length = norm(ends - starts)
    allowance = rounding / np.where(length > 0.0, length, np.inf)  # (never a division by 0)
    with np.errstate(invalid="ignore"):  # NaN is never valid
        return warp <= tolerance + allowance


def rounding_of(stack: Stack, starts: FloatArray, ends: FloatArray) -> FloatArray:
    """The larger :func:`~..vec_ops.position_rounding` of each strip's ``starts`` and ``ends``
    (as ``max`` picks it: the first unless the second is larger)."""
    of_starts, of_ends = (
        POSITION_ULPS * _EPS * np.maximum(stack.reduce_max(np.abs(p)).max(axis=1), 0.0)
        for p in (starts, ends)
    )
    return np.where(of_ends > of_starts, of_ends, of_starts)


def measured(
    strips: Sequence[Rulings], stack: Stack
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The output rulings A(s) → B(t) of every strip, stacked, and their signed warp,
    measured from the curves: the end points and exact tangents at (s, t),
    :func:`.warp.warp_angles` of those (NaN where no normal is defined), with the tangent at
    a corner taken in the plane of the ruling where the corner straddles it
    (:func:`_corner_tangent`), and an end shared with every neighbouring ruling (the apex
    of a fan of flat triangles) taking the other end's plane. Nothing of the solve enters
    but the curves' evaluations at those very parameters (a station's, a refined root's),
    which are reused rather than repeated. Returns starts, ends and the signed warp."""
    s = np.concatenate([r[1] for r in strips])
    t = np.concatenate([r[2] for r in strips])
    k = len(s)
    owner = stack.owner()
    # each strip's stations and candidates, stacked, and where each strip's start
    station_stack = Stack([len(r[0].s) for r in strips])
    found = Stack([len(r[5].t) for r in strips])
    source = np.concatenate([r[3] for r in strips])
    station = source >= 0
    at = flatnonzero(station)
    rows = source[at] + station_stack.starts[owner[at]]
    a0 = np.concatenate([r[0].a0 for r in strips])
    a1 = np.concatenate([r[0].a1 for r in strips])
    starts, ta = np.empty((2, k, 3))
    starts[at], ta[at] = a0[rows], a1[rows]
    if len(at) < k:  # added rulings: A where no station is
        away = flatnonzero(~station)
        starts[away], ta[away] = evaluate_each([r[0].curve_a for r in strips], s[away], stack.groups(away), 1)
    # B where a station's chosen root still stands (a flat end or corner is re-evaluated);
    # ``chosen`` holds −1 (none) or a candidate's index
    chosen = np.concatenate([r[4] for r in strips])
    picked = chosen[rows]
    has = picked >= 0
    candidate = at[has]
    picked = picked[has] + found.starts[owner[candidate]]
    good_t = np.concatenate([r[5].t for r in strips])
    good_kind = np.concatenate([r[5].kind for r in strips])
    stands = (good_t[picked] == t[candidate]) & (good_kind[picked] == ROOT)
    kept, kept_root = candidate[stands], picked[stands]
    ends, tb = np.empty((2, k, 3))
    ends[kept] = np.concatenate([r[5].points for r in strips])[kept_root]
    tb[kept] = np.concatenate([r[5].tangents for r in strips])[kept_root]
    if len(kept) < k:
        again = np.ones(k, dtype=bool)
        again[kept] = False
        lost = flatnonzero(again)
        ends[lost], tb[lost] = evaluate_each([r[0].curve_b for r in strips], t[lost], stack.groups(lost), 1)
    ruling = ends - starts
    for (strip, *_), low, high in zip(strips, stack.starts.tolist(), stack.offsets[1:].tolist(), strict=True):
        if len(strip.kinks_a) or len(strip.kinks_b):  # (views: the corners' tangents written in place)
            _corners(strip, s[low:high], t[low:high], ruling[low:high], ta[low:high], tb[low:high])
    size = sizes(stack, starts, ends)
    normals = _normals(starts, ends, ta, tb, _fan_apex(s, stack), _fan_apex(t, stack), stack.repeat(size))
    return starts, ends, _angles(*normals, signed=True)


def _corners(
    strip: Strip, s: FloatArray, t: FloatArray, ruling: FloatArray, ta: FloatArray, tb: FloatArray
) -> None:
    """The tangents ``ta``, ``tb`` of one strip's rulings at a corner of its curves, in place."""
    if len(strip.kinks_b):
        at_b = np.isin(t, strip.kinks_b)
        if at_b.any():
            left = strip.curve_b.derivatives(t[at_b] - SIDE, 1)[1]
            tb[at_b] = _corner_tangent(ruling[at_b], ta[at_b], left, tb[at_b])
    if len(strip.kinks_a):
        at_a = np.min(np.abs(s[:, None] - strip.kinks_a[None, :]), axis=1) <= 1e-12
        if at_a.any():
            around = np.clip(np.concatenate([s[at_a] - SIDE, s[at_a] + SIDE]), 0.0, 1.0)
            sides = strip.curve_a.derivatives(around, 1)[1]
            ta[at_a] = _corner_tangent(ruling[at_a], tb[at_a], *np.split(sides, 2))


def _corner_tangent(ruling: FloatArray, other: FloatArray, left: FloatArray, right: FloatArray) -> FloatArray:
    """The tangent of a curve at a corner for rulings ending there: the in-plane blend of
    :func:`.warp.in_plane_tangent`, or, where that runs along the ruling (no normal), the
    one-sided tangent that gives a defined normal with the smaller warp."""
    tangent = in_plane_tangent(ruling, other, left, right)
    along = norm(cross(ruling, tangent)) <= 1e-10 * norm(ruling)
    if along.any():
        r, o = ruling[along], other[along]
        sides = unit(left[along]), unit(right[along])
        zero = np.zeros_like(r)
        warps = [warp_angles(zero, r, o, side) for side in sides]
        pick_left = ~np.isnan(warps[0]) & (np.isnan(warps[1]) | (warps[0] <= warps[1]))
        tangent[along] = np.where(pick_left[:, None], sides[0], sides[1])
    return tangent


def _fan_apex(parameters: FloatArray, stack: Stack) -> BoolArray:
    """Rulings whose end is shared with every neighbouring ruling of their strip (both
    inside the strip, the one neighbour of its first and last rulings): the apex of a fan."""
    same = np.zeros(len(parameters) + 1, dtype=bool)  # same[i]: ruling i − 1 ends where i does
    same[1:-1] = parameters[1:] == parameters[:-1]
    same[stack.starts] = False  # (a strip's first ruling has no neighbour before it)
    same[stack.offsets[1:]] = False
    apex = same[:-1] & same[1:]
    apex[stack.starts] = same[stack.starts + 1]  # the first and last rulings have one neighbour each
    apex[stack.offsets[1:] - 1] |= same[stack.offsets[1:] - 1]
    return apex
