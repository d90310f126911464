"""Warp angles: how far a ruling is from being torsal (developable).

A ruling R from a point of edge A to a point of edge B, with unit edge tangents T1 and
T2 at its two ends, has end normals N1 = R × T1 and N2 = R × T2: the normals of the
sheet's tangent planes at its ends. A developable sheet has one tangent plane along the
whole ruling, so N1 ∥ N2, i.e. det[R, T1, T2] = 0 (the ruling is *torsal*).

- The **warp angle** is the angle between the normal *vectors* N1 and N2, in [0, π]:
  the turn of the tangent plane along the ruling (the normal along a ruled surface is
  linear in the ruling parameter, so it turns monotonically from N1 to N2, through less
  than π). On z = xy along x = 0 from y = −L to L it is 2·atan(L), past π/2 for L > 1.
  Divided by |R| it is the warp factor in rad/m. With both edges running the same way
  and rulings that do not cross, a good ruling has a warp near 0; a warp near π also
  makes the ruling's two planes the same plane, but the sheet is folded back on itself
  there (its rulings cross, or its edge of regression runs between the two edges) —
  that is not a developable strip, and it counts as warped by π.
- The **signed warp** is the same angle with a sign: the turn from N1 to N2 about R,
  in (−π, π].

Where no tangent plane is defined the warp is NaN, never 0: a ruling of zero length, a
ruling along an edge's tangent (R × T = 0: the sheet has no width there), or a NaN in
the input. One degenerate end is defined, by the geometry: where an edge *stands still*
— its tangent is zero because consecutive rulings share that end point, as in a fan of
triangles through one point (a cone's apex, a flat fan closing a strip) — the sheet next
to the ruling is the fan's triangles, whose plane contains the ruling and the *other*
edge's tangent. That end's normal is the other end's, so a fan ruling's warp is 0 (its
triangles are flat) when the other end has a normal, and NaN when it does not. The first
and last rulings of a strip have one neighbour: an end they share with it is a fan's apex
too (the sheet beside them is that fan; the curve's tangent there belongs to no sheet next
to them).
The same holds at a point the caller knows is on the edge of regression (``apex_a``,
``apex_b``; a tangent developable's curve, where the ruling runs along the tangent).
"""

from __future__ import annotations

from collections.abc import Sequence
from math import isfinite

import numpy as np
from numpy.typing import ArrayLike

from torsal.nodes.geometry.array_types import BoolArray

from ..curve_base import Curve, FloatArray
from ..curves.shared_knots import derivative_each
from ..vec_ops import cross, dot, extent, flatnonzero, norm, unit
from .stack import Stack

#: Below this share of the strip's size a ruling has no length and a tangent is zero
#: (the edge stands still there).
ZERO = 1e-12
#: A normal R × T̂ shorter than this share of |R| has no direction: the ruling runs
#: within 1e-9 rad of the edge's tangent. Nearer, rounding decides the normal: its
#: direction moves by about 1e-15/θ rad per ulp of the end's parameter (measured: 4e-6 rad
#: at θ = 2.6e-10, a partner root of two nearly coplanar curves where B's tangent line
#: passes within 1e-9 of A), so no warp measured there could be checked.
PARALLEL = 1e-9


def _mask(value: ArrayLike | None, n: int) -> BoolArray | None:
    if value is None:
        return None
    if isinstance(value, np.ndarray) and value.dtype == bool and value.shape == (n,):
        return value  # (the usual case: np.broadcast_to costs more than the rest of a row's test)
    return np.broadcast_to(np.asarray(value, dtype=bool), (n,))


def _size(start: FloatArray, end: FloatArray) -> float:
    """The diagonal of the bounding box of the finite ones of the points ``start`` and ``end``."""
    if not len(start):
        return 0.0
    points = np.concatenate([start, end])
    size = float(norm(extent(points)))
    if isfinite(size):  # (a NaN or an infinite coordinate would not leave it finite)
        return size
    points = points[np.isfinite(points).all(axis=1)]
    return float(norm(extent(points))) if len(points) else 0.0


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


def _normals(
    starts: ArrayLike,
    ends: ArrayLike,
    tangents_a: ArrayLike,
    tangents_b: ArrayLike,
    apex_a: ArrayLike | None,
    apex_b: ArrayLike | None,
    size: float | None = None,
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """:func:`end_normals` and the rulings' lengths (both ends' normals computed as one
    ``(2, n, 3)`` array); ``size`` is :func:`_size` of the ends where the caller has it."""
    start = np.asarray(starts, dtype=float).reshape(-1, 3)
    end = np.asarray(ends, dtype=float).reshape(-1, 3)
    ruling = end - start
    n = len(ruling)
    ta = np.asarray(tangents_a, dtype=float).reshape(-1, 3)
    tb = np.asarray(tangents_b, dtype=float).reshape(-1, 3)
    if size is None:
        size = _size(start, end)
    if ta.shape == tb.shape == ruling.shape:  # the lengths of the rulings and tangents at once
        vectors = np.concatenate([ruling, ta, tb]).reshape(3, n, 3)
        lengths = norm(vectors)
        length, speeds, tangents = lengths[0], lengths[1:], vectors[1:]
        units = tangents / np.where(speeds > 0, speeds, 1.0)[..., None]
    else:  # one tangent for all rulings: its length as measured alone (einsum rounds a lone row its own way)
        length = norm(ruling)
        speed_a, speed_b = norm(ta), norm(tb)
        unit_a = ta / np.where(speed_a > 0, speed_a, 1.0)[:, None]
        unit_b = tb / np.where(speed_b > 0, speed_b, 1.0)[:, None]
        units = np.stack([np.broadcast_to(unit_a, ruling.shape), np.broadcast_to(unit_b, ruling.shape)])
        speeds = np.stack([np.broadcast_to(speed_a, (n,)), np.broadcast_to(speed_b, (n,))])
    still = speeds <= ZERO * size  # (still_a, still_b)
    mask_a, mask_b = _mask(apex_a, n), _mask(apex_b, n)
    if mask_a is not None:
        still[0] |= mask_a
    if mask_b is not None:
        still[1] |= mask_b
    normals = cross(ruling, units)
    has = norm(normals) > PARALLEL * length
    if still.any():
        usable = has | still
        defined = (length > ZERO * size) & usable[0] & usable[1] & ~(still[0] & still[1])
        # a standing end takes the other end's normal (both ends at once: the pair swapped)
        normals = np.where(still[..., None], normals[::-1], normals)
    else:  # (no end stands: each has its own normal or none)
        defined = (length > ZERO * size) & has[0] & has[1]
    if not defined.all():
        normals[:, ~defined] = np.nan
    return normals[0], normals[1], ruling, length


def end_normals(
    starts: ArrayLike,
    ends: ArrayLike,
    tangents_a: ArrayLike,
    tangents_b: ArrayLike,
    apex_a: ArrayLike | None = None,
    apex_b: ArrayLike | None = None,
) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The end normals N1 = R × T̂1 and N2 = R × T̂2 of each ruling, and the rulings R.

    Rows where no tangent plane is defined (see the module docstring) are NaN in both
    normals. A zero tangent (the edge stands still: a fan's apex), or an end flagged in
    ``apex_a``/``apex_b``, takes the other end's normal.
    """
    n1, n2, ruling, _ = _normals(starts, ends, tangents_a, tangents_b, apex_a, apex_b)
    return n1, n2, ruling


def warp_angles(
    starts: ArrayLike,
    ends: ArrayLike,
    tangents_a: ArrayLike,
    tangents_b: ArrayLike,
    signed: bool = False,
    *,
    apex_a: ArrayLike | None = None,
    apex_b: ArrayLike | None = None,
) -> FloatArray:
    """Warp angle of each ruling ``starts[i] → ends[i]`` given the edge tangents at its ends.

    Args:
        starts, ends: ``(n, 3)`` ruling end points (on edge A and edge B).
        tangents_a, tangents_b: ``(n, 3)`` edge tangents there (any length; both edges
            oriented the same way). A zero tangent means the edge stands still there (a
            fan's apex): that end takes the other end's plane.
        signed: ``False`` for the warp angle in [0, π] (the angle between the normal
            vectors N1 and N2); ``True`` for the angle from N1 to N2 about the ruling, in
            (−π, π].
        apex_a, apex_b: optional ``(n,)`` flags for ends known to lie on the edge of
            regression (there the ruling may run along the tangent); they take the
            other end's plane, as a fan's apex does.

    Returns NaN where no tangent plane is defined: a zero-length ruling, a ruling along
    an edge tangent, both ends standing still, or NaN input. Computed as ``atan2`` of the
    cross and dot products of the normals, which keeps full relative accuracy for tiny
    angles (``arccos`` of a dot product would not).

    >>> warp_angles([[0, 0, 0]], [[0, 1, 0]], [[1, 0, 0]], [[1, 0, 1]]).round(6).tolist()
    [0.785398]
    >>> warp_angles([[0, 0, 0]], [[0, 1, 0]], [[1, 0, 0]], [[-1, 0, 0]]).round(6).tolist()
    [3.141593]
    """
    return _angles(*_normals(starts, ends, tangents_a, tangents_b, apex_a, apex_b), signed)


def _angles(
    n1: FloatArray, n2: FloatArray, ruling: FloatArray, length: FloatArray, signed: bool
) -> FloatArray:
    """The warp angles from the end normals, rulings and lengths of :func:`_normals`
    (:func:`warp_angles`)."""
    normal_cross = cross(n1, n2)
    normal_dot = dot(n1, n2)
    if signed:
        return np.arctan2(dot(normal_cross, ruling) / np.where(length > 0, length, 1.0), normal_dot)
    return np.arctan2(norm(normal_cross), normal_dot)


def consistently_oriented(
    starts: FloatArray,
    ends: FloatArray,
    tangents_a: FloatArray,
    tangents_b: FloatArray,
    size: FloatArray | float | None = None,
) -> BoolArray:
    """Where the signed warp is a number within (−π/2, π/2): the end normals are defined
    and point to the same side, ``|warp_angles(..., signed=True)| < π/2`` (the rules of
    :func:`end_normals`, without the angles: only N1·N2 > 0 is needed). ``(n, 3)`` arrays.
    ``size`` is the size lengths are zero against (per row, for rows of several strips),
    else that of all the rows: the diagonal of the box of their ends."""
    ruling = ends - starts
    n = len(ruling)
    zero = (ZERO * (_size(starts, ends) if size is None else size)) ** 2
    if tangents_a.shape != ruling.shape or tangents_b.shape != ruling.shape:  # (broadcast ones)
        tangents_a = np.broadcast_to(tangents_a, ruling.shape)
        tangents_b = np.broadcast_to(tangents_b, ruling.shape)
    vectors = np.concatenate([ruling, tangents_a, tangents_b]).reshape(3, n, 3)  # both ends at once
    squares = dot(vectors, vectors)
    rr, tt, tangents = squares[0], squares[1:], vectors[1:]
    normals = cross(ruling, tangents)
    # |R × T̂| > PARALLEL·|R|, squared and times |T|²
    has = dot(normals, normals) > PARALLEL**2 * rr * tt
    still = tt <= zero
    facing = dot(normals[0], normals[1]) > 0
    if not still.any():  # (the usual case)
        return (rr > zero) & has[0] & has[1] & facing
    defined = (rr > zero) & (has[0] | still[0]) & (has[1] | still[1]) & ~(still[0] & still[1])
    # a standing end takes the other end's normal: then N1·N2 = |N|² > 0
    return defined & (facing | still[0] | still[1])


def edge_tangents(points: ArrayLike) -> FloatArray:
    """Tangents of the polyline through ``points`` ``(n, 3)``: second-order central
    differences inside, one-sided at the two ends (unit length).

    Zero where the polyline stands still at a point it shares with a neighbouring row (a
    fan's apex); NaN where it has no direction for another reason (it doubles back, so
    the points on either side coincide, or it has fewer than two points).
    """
    p = np.asarray(points, dtype=float)
    if len(p) < 2:
        return np.full_like(p, np.nan)
    gradient = np.gradient(p, axis=0)
    finite = p[np.isfinite(p).all(axis=1)]
    size = float(norm(np.ptp(finite, axis=0))) if len(finite) else 0.0
    still = norm(gradient) <= ZERO * size
    step = norm(np.diff(p, axis=0)) <= ZERO * size
    shared = np.concatenate([[False], step]) | np.concatenate([step, [False]])
    tangents = unit(gradient)
    tangents[still & shared] = 0.0
    tangents[still & ~shared] = np.nan
    return tangents


def warp_of_rulings(starts: ArrayLike, ends: ArrayLike, signed: bool = False) -> FloatArray:
    """Warp angles of a ruled strip known only by its rulings, in order along the strip.

    The edge tangents are those of the two edge polylines (through the starts and
    through the ends; :func:`edge_tangents`), so this reports the warp of *any* output —
    a loft, an optimised strip, an imported surface — without its defining curves. The
    tangents are second-order accurate in the ruling spacing, so on a smooth developable
    the reported warp is O(h²), not 0; use :func:`warp_angles` with exact tangents where
    they are known. Inside a fan (rulings through one point) the polyline stands still at
    the point, so the fan's rulings are measured in the plane of their triangles: 0 when
    the other edge has a tangent there (see the module docstring).
    """
    a = np.asarray(starts, dtype=float)
    b = np.asarray(ends, dtype=float)
    return warp_angles(a, b, edge_tangents(a), edge_tangents(b), signed=signed)


def in_plane_tangent(
    ruling: FloatArray, other: FloatArray, left: FloatArray, right: FloatArray
) -> FloatArray:
    """The edge direction at a corner that lies in the plane of the ruling and the other
    edge's tangent, where there is one.

    At a corner of an edge (a polyline vertex, a kinked NURBS) the tangent jumps from
    ``left`` to ``right``; every direction between them is tangent to the corner, so a
    ruling ending there is torsal when the plane through the ruling and the other end's
    tangent ``other`` separates ``left`` from ``right`` (a cone with its apex at the
    corner). This returns that in-plane blend of ``left`` and ``right`` where their
    determinants have opposite signs, and otherwise whichever of them gives the smaller
    warp — among those that orient the sheet's normals consistently (R × other and
    R × tangent to one side), which decides when both lie in the plane (a planar piece
    fanned from the corner). All arguments are ``(n, 3)``; the result is unit length.
    """
    left = unit(np.asarray(left, dtype=float))
    right = unit(np.asarray(right, dtype=float))
    f_left = dot(ruling, cross(other, left))
    f_right = dot(ruling, cross(other, right))
    straddles = f_left * f_right < 0
    denominator = np.where(straddles, f_right - f_left, 1.0)
    blend = (f_right[:, None] * left - f_left[:, None] * right) / denominator[:, None]
    normal = cross(ruling, other)
    left_agrees = dot(normal, cross(ruling, left)) >= 0
    right_agrees = dot(normal, cross(ruling, right)) >= 0
    take_left = np.where(left_agrees != right_agrees, left_agrees, np.abs(f_left) <= np.abs(f_right))
    pick = np.where(take_left[:, None], left, right)
    return unit(np.where(straddles[:, None], blend, pick))


#: A jump of the unit tangent larger than this (rad) at a breakpoint is a corner.
CORNER_ANGLE = 1e-7
#: Parameter offset for one-sided tangents beside a corner.
_SIDE = 1e-11
#: A parameter this close to a breakpoint sits on it.
_AT_BREAK = 1e-10


def _corner_sides(curve: Curve, t: FloatArray) -> tuple[BoolArray, FloatArray, FloatArray] | None:
    """Which parameters ``t`` sit on a corner of ``curve`` (a breakpoint where the unit
    tangent jumps), and the one-sided tangents there (left, right; undefined elsewhere);
    None when the curve has no breakpoint inside (and no seam), so no corner."""
    breaks = np.asarray(curve._breakpoints(), dtype=float)
    if len(breaks) == 2 and breaks[0] <= 0.0 and breaks[1] >= 1.0 and not curve.closed:
        return None  # (one smooth span, the usual case: nothing inside)
    inner = breaks[(breaks > 0.0) & (breaks < 1.0)]
    if curve.closed:
        inner = np.concatenate([inner, [0.0]])
    if not len(inner):
        return None
    n = len(t)
    left = np.zeros((n, 3))
    right = np.zeros((n, 3))
    corner = np.zeros(n, dtype=bool)
    inner = np.sort(inner)
    # the nearest breakpoint of each parameter: one of its two neighbours in the sorted list
    above = np.clip(np.searchsorted(inner, t), 0, len(inner) - 1)
    below = np.clip(above - 1, 0, len(inner) - 1)
    pair = np.stack([below, above])
    if curve.closed:  # the seam (0, the first breakpoint) is also next to 1
        pair = np.vstack([pair, np.zeros((1, n), dtype=pair.dtype)])
    distance = np.abs(t[None, :] - inner[pair])
    if curve.closed:
        distance = np.minimum(distance, 1.0 - distance)
    pick = np.argmin(distance, axis=0)
    nearest = pair[pick, np.arange(n)]
    near = distance[pick, np.arange(n)] <= _AT_BREAK
    if not near.any():
        return corner, left, right
    b = inner[nearest[near]]
    below, above = b - _SIDE, b + _SIDE
    if curve.closed:
        below = np.where(below < 0.0, below + 1.0, below)
    d = curve.derivatives(np.concatenate([below, above]), 1)[1]
    lt, rt = unit(d[: len(b)]), unit(d[len(b) :])
    jump = np.arctan2(norm(cross(lt, rt)), dot(lt, rt)) > CORNER_ANGLE
    rows = flatnonzero(near)
    corner[rows] = jump
    left[rows], right[rows] = lt, rt
    return corner, left, right


def _interior_of_fans(points: FloatArray, size: float | FloatArray, stack: Stack | None = None) -> BoolArray:
    """Rows whose point is shared with every neighbouring row (both inside, the one
    neighbour of the first and last rows): in a fan through it. ``points`` ``(k, n, 3)``:
    ``k`` edges' points (both ends of the rulings at once), a ``(k, n)`` mask. With
    ``stack`` the rows are those of several strips (``size`` per row), each its own."""
    if stack is None:
        same = norm(points[:, 1:] - points[:, :-1]) <= ZERO * size
        inside = np.zeros(points.shape[:2], dtype=bool)
        inside[:, 1:-1] = same[:, :-1] & same[:, 1:]
        if same.shape[1]:  # the first and last rulings have one neighbour each
            inside[:, 0] |= same[:, 0]
            inside[:, -1] |= same[:, -1]
        return inside
    # same[:, i]: row i − 1 is at row i's point (False across a strip's bounds)
    same = np.zeros((len(points), points.shape[1] + 1), dtype=bool)
    same[:, 1:-1] = norm(points[:, 1:] - points[:, :-1]) <= ZERO * size[1:]
    same[:, stack.offsets] = False
    inside = same[:, :-1] & same[:, 1:]
    first, last = stack.starts, stack.offsets[1:] - 1
    inside[:, first] = same[:, first + 1]  # the first and last rulings have one neighbour each
    inside[:, last] |= same[:, last]
    return inside


def curve_warp(
    curve_a: Curve, curve_b: Curve, s: ArrayLike, t: ArrayLike, starts: ArrayLike, ends: ArrayLike,
    signed: bool = False,
    fans: bool = True,
) -> FloatArray:
    """Warp angles (as :func:`warp_angles`, [0, π] or signed, NaN where undefined) of the
    rulings ``starts[i] → ends[i]`` of a strip between two curves, in order along it,
    measured with the curves' exact tangents at the rulings' parameters ``s`` on A and
    ``t`` on B — independently of how the rulings were found.

    At a corner of a curve (its tangent jumps from ``left`` to ``right``) the tangent is
    the one in the plane of the ruling and the other end's tangent where the corner
    straddles that plane (:func:`in_plane_tangent`: a cone through the corner), and where
    that tangent runs along the ruling, the one-sided tangent that gives the least
    defined warp (every direction of the corner's cone touches it). A ruling
    inside a fan (its end shared with every neighbouring ruling) is measured in the
    plane of the fan's triangles (the curve's tangent at the fan's apex plays no part);
    with ``fans=False`` it is measured with both curves' tangents there too (how far the
    ruling is from torsal, whatever sheet lies beside it: see :mod:`.kinds`).
    """
    s = np.asarray(s, dtype=float).reshape(-1)
    t = np.asarray(t, dtype=float).reshape(-1)
    a = np.asarray(starts, dtype=float).reshape(-1, 3)
    b = np.asarray(ends, dtype=float).reshape(-1, 3)
    ta = curve_a.derivative_at(s, 1)  # (the tangents alone: a polynomial curve skips the points)
    tb = curve_b.derivative_at(t, 1)
    sides_a, sides_b = _corner_sides(curve_a, s), _corner_sides(curve_b, t)
    size = _size(a, b)
    if not fans:
        apex_a = apex_b = np.zeros(len(a), dtype=bool)
    elif a.shape == b.shape:  # both edges' fans at once
        apex_a, apex_b = _interior_of_fans(np.concatenate([a, b]).reshape(2, -1, 3), size)
    else:
        apex_a, apex_b = _interior_of_fans(a[None], size)[0], _interior_of_fans(b[None], size)[0]
    if sides_a is None and sides_b is None:  # (smooth curves: no corner to look at)
        return _angles(*_normals(a, b, ta, tb, apex_a, apex_b, size), signed)
    n = len(s)
    no_corner = np.zeros(n, dtype=bool), np.zeros((n, 3)), np.zeros((n, 3))
    (corner_a, left_a, right_a), (corner_b, left_b, right_b) = sides_a or no_corner, sides_b or no_corner
    ruling = b - a
    if corner_a.any():
        ta = ta.copy()
        ta[corner_a] = in_plane_tangent(ruling[corner_a], tb[corner_a], left_a[corner_a], right_a[corner_a])
    if corner_b.any():
        tb = tb.copy()
        tb[corner_b] = in_plane_tangent(ruling[corner_b], ta[corner_b], left_b[corner_b], right_b[corner_b])
    warp = _angles(*_normals(a, b, ta, tb, apex_a, apex_b, size), signed)
    # at a corner whose chosen tangent runs along the ruling (a fan's edge on a side of
    # the corner), any other direction of the corner's cone is a tangent too: take the
    # one-sided tangents there and keep the least warp that is defined
    retry = flatnonzero(np.isnan(warp) & (corner_a | corner_b))
    if len(retry):
        options_a = (ta[retry], np.where(corner_a[retry, None], left_a[retry], ta[retry]),
                     np.where(corner_a[retry, None], right_a[retry], ta[retry]))
        options_b = (tb[retry], np.where(corner_b[retry, None], left_b[retry], tb[retry]),
                     np.where(corner_b[retry, None], right_b[retry], tb[retry]))
        best = np.full(len(retry), np.nan)
        for one in options_a:
            for other in options_b:
                w = warp_angles(a[retry], b[retry], one, other, signed,
                                apex_a=apex_a[retry], apex_b=apex_b[retry])
                better = ~np.isnan(w) & (np.isnan(best) | (np.abs(w) < np.abs(best)))
                best = np.where(better, w, best)
        warp[retry] = best
    return warp


def curve_warps(
    strips: Sequence[tuple[Curve, Curve, FloatArray, FloatArray, FloatArray, FloatArray]],
    fans: bool = True,
) -> list[FloatArray]:
    """:func:`curve_warp` of every strip ``(curve_a, curve_b, s, t, starts, ends)`` (and
    ``fans``): the rulings of the strips between smooth curves measured at once (each
    strip's size and fans its own), the others strip by strip."""
    warps: list[FloatArray | None] = [None] * len(strips)
    smooth: list[tuple[int, FloatArray, FloatArray]] = []
    tangents_at: list[tuple[Curve, FloatArray]] = []  # (A at s, B at t for each smooth strip)
    for index, (curve_a, curve_b, s, t, starts, ends) in enumerate(strips):
        s = np.asarray(s, dtype=float).reshape(-1)
        t = np.asarray(t, dtype=float).reshape(-1)
        a = np.asarray(starts, dtype=float).reshape(-1, 3)
        b = np.asarray(ends, dtype=float).reshape(-1, 3)
        corners = _corner_sides(curve_a, s) is not None or _corner_sides(curve_b, t) is not None
        if corners or a.shape != b.shape:
            warps[index] = curve_warp(curve_a, curve_b, s, t, a, b, fans=fans)
        else:
            smooth.append((index, a, b))
            tangents_at += [(curve_a, s), (curve_b, t)]
    if smooth:
        # the tangents alone (a polynomial curve skips the points), the curves that share
        # knots evaluated together
        tangents = derivative_each([curve for curve, _ in tangents_at], [x for _, x in tangents_at], 1)
        ta, tb = np.concatenate(tangents[::2]), np.concatenate(tangents[1::2])
        a, b = (np.concatenate([row[i] for row in smooth]) for i in (1, 2))
        stack = Stack.of([row[1] for row in smooth])
        size = stack.repeat(sizes(stack, a, b))
        if fans:
            apex_a, apex_b = _interior_of_fans(np.concatenate([a, b]).reshape(2, -1, 3), size, stack)
        else:
            apex_a = apex_b = np.zeros(len(a), dtype=bool)
        joined = _angles(*_normals(a, b, ta, tb, apex_a, apex_b, size), False)
        for (index, *_), warp in zip(smooth, stack.split(joined), strict=True):
            warps[index] = warp
    return warps  # type: ignore[return-value]  (every strip's is filled in)
