"""What each ruling of a strip between two curves is: torsal, in a fan, or a crease.

Read from the output alone — the rulings' end points and parameters and the curves'
exact tangents there — never from the solver's own flags.

The sheet beside a ruling is one of three pieces, told by which ends the ruling shares
with its neighbour on that side: a cone through a point of A (the neighbour starts at
the same point, the edge on A stands still), a cone through a point of B, or a ruled
quad (both ends move). The sheet's normal next to the ruling is R × B' in a cone through
A, R × A' in a cone through B, and runs from R × A' at A to R × B' at B in a quad. So:

- Where both sides are the same cone (the ruling is inside a fan through a point, or is
  a strip's end ruling beside one) the sheet is a cone there, smooth and developable,
  and only one point of the apex's curve belongs to it: a **fan**. Valid when the
  sheet's warp (the cone's plane at both ends, :func:`.warp.curve_warp`, the node's
  WarpAngles) is within the tolerance: a cone is developable.
- Otherwise the ruling is **torsal** when the planes through it and the two curves'
  tangents agree (its *tangent warp*, :func:`.warp.curve_warp` with ``fans=False``, is
  within the tolerance): the sheet is smooth across it and both curves are tangent to
  it. Valid. (A cone joining torsal rulings does so at such a ruling.)
- Otherwise, where the pieces on its two sides are of different sorts (a cone through A
  beside a quad or a cone through B), the sheet's plane jumps across the ruling by its
  tangent warp: a **crease**, a fold line of the sheet. A ruling with no tangent warp
  (it runs along a curve's tangent: a fan turning back over itself there) is a crease too.
  Never valid.
- A ruling between two quads whose tangent warp exceeds the tolerance is a warped torsal
  ruling: torsal, not valid.

A ruling of zero length (the curves meet there: the strip tapers to a point) has no
plane at all: a fan when beside a cone, else torsal, and never valid.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from ..array_types import BoolArray, FloatArray, IntArray
from ..curve_base import Curve
from ..vec_ops import cross, norm
from .measure import rounding_of, within_tolerance
from .stack import Stack
from .warp import PARALLEL, ZERO, curve_warps

TORSAL, FAN, CREASE = "torsal", "fan", "crease"
#: The sorts of piece beside a ruling: none (a strip's end), a cone through a point of A,
#: of B, a quad, and a piece of no width (a ruling repeated).
_NONE, _CONE_A, _CONE_B, _QUAD, _EMPTY = range(5)


@dataclass(frozen=True)
class RulingKinds:
    """Per ruling of a strip: its kind, whether it is valid, and the angles that decided."""

    kind: list[str]  #: "torsal", "fan" or "crease"
    valid: BoolArray  #: torsal within the tolerance, or a fan whose cone has a defined plane
    #: how far the ruling is from torsal, rad, [0, π]: the angle between R × A' and R × B'
    #: with both curves' exact tangents (NaN where either is undefined)
    tangent_warp: FloatArray
    #: the angle the sheet's plane turns through across the ruling, rad: its tangent warp at
    #: a crease (π where the sheet turns back along a curve's tangent), 0 elsewhere
    crease_angle: FloatArray
    tip: BoolArray  #: rulings of zero length
    #: how many rulings are torsal and valid, where the maker counted them
    torsal_valid: int | None = field(default=None, repr=False, compare=False)

    @property
    def torsal_share(self) -> float:
        """The share of rulings that are torsal and valid (0 to 1; NaN for no rulings)."""
        n = len(self.kind)
        if n == 0:
            return float("nan")
        count = self.torsal_valid
        if count is None:
            count = int(np.count_nonzero(np.array([k == TORSAL for k in self.kind]) & self.valid))
        return float(count) / n


def piece_sorts(starts: FloatArray, ends: FloatArray, size: float | FloatArray) -> IntArray:
    """The sort of each of the ``n − 1`` pieces between consecutive rulings (a cone through
    a point of A or B, a quad, or empty), by which ends the two rulings share. A piece
    whose triangles have no area (beside a ruling of no length where the curves meet, the
    two rulings run along one chord) is empty: it is no sheet. (``size`` may be given per
    piece: the size of the strip each piece is of.)"""
    tol = ZERO * size
    same_a = norm(starts[1:] - starts[:-1]) <= tol
    same_b = norm(ends[1:] - ends[:-1]) <= tol
    # twice the area of the piece's polygon A_i, B_i, B_i+1, A_i+1 (a triangle's when an end is shared)
    area = norm(cross(ends[1:] - starts[:-1], ends[:-1] - starts[1:]))
    sort = np.full(len(same_a), _QUAD)
    sort[same_a] = _CONE_A
    sort[same_b] = _CONE_B
    sort[(same_a & same_b) | (area <= tol * size)] = _EMPTY
    return sort


def ruling_kinds(
    curve_a: Curve,
    curve_b: Curve,
    s: ArrayLike,
    t: ArrayLike,
    starts: ArrayLike,
    ends: ArrayLike,
    tolerance: float,
    sheet_warp: ArrayLike | None = None,
) -> RulingKinds:
    """The kind of each ruling ``A(s) → B(t)`` of a strip, as the module docstring tells.

    ``sheet_warp`` is :func:`.warp.curve_warp` of the same rulings where the caller has it
    (the warp of the sheet, a fan's apex taking the cone's plane). The tolerance is widened
    by what the rounding of the end points alone adds far from the origin, as the solver's
    check does.
    """
    return ruling_kinds_all([(curve_a, curve_b, s, t, starts, ends, tolerance, sheet_warp)])[0]


def ruling_kinds_all(strips: Sequence[tuple[Any, ...]]) -> list[RulingKinds]:
    """:func:`ruling_kinds` of every strip ``(curve_a, curve_b, s, t, starts, ends, tolerance,
    sheet_warp)``: the rulings of all strips judged at once (each strip's size, rounding and
    tolerance its own, its pieces its own)."""
    rows = []
    for curve_a, curve_b, s, t, starts, ends, tolerance, sheet_warp in strips:
        a = np.asarray(starts, dtype=float).reshape(-1, 3)
        b = np.asarray(ends, dtype=float).reshape(-1, 3)
        rows.append((curve_a, curve_b, s, t, a, b, float(tolerance), sheet_warp))
    results: list[RulingKinds | None] = [None] * len(rows)
    for index, row in enumerate(rows):
        if len(row[4]) == 0:  # (no rulings: nothing to judge)
            empty = np.empty(0)
            results[index] = RulingKinds([], np.empty(0, dtype=bool), empty, empty, np.empty(0, dtype=bool))
    judged = [row for row in rows if len(row[4])]
    if judged:
        done = iter(_judged(judged))
        results = [next(done) if result is None else result for result in results]
    return results  # type: ignore[return-value]  (every strip's is filled in)


def _judged(rows: list[tuple[Any, ...]]) -> list[RulingKinds]:
    """:func:`ruling_kinds_all` of strips with rulings, ``(curve_a, curve_b, s, t, a, b,
    tolerance, sheet_warp)`` with a and b as ``(n, 3)`` arrays."""
    missing = [row[:6] for row in rows if row[7] is None]
    sheets = iter(curve_warps(missing))
    sheet = np.concatenate([
        np.asarray(next(sheets) if row[7] is None else row[7], dtype=float).reshape(-1) for row in rows
    ])
    tangent = np.concatenate(curve_warps([row[:6] for row in rows], fans=False))
    stack = Stack.of([row[4] for row in rows])
    a, b = np.concatenate([row[4] for row in rows]), np.concatenate([row[5] for row in rows])
    n = len(a)
    high = np.maximum(stack.reduce_max(a), stack.reduce_max(b))
    size = stack.repeat(norm(high - np.minimum(stack.reduce_min(a), stack.reduce_min(b))))
    length = norm(b - a)
    tip = length <= ZERO * size
    tolerance = stack.repeat(np.array([row[6] for row in rows]))
    rounding = stack.repeat(rounding_of(stack, a, b))
    left, right = np.full(n, _NONE), np.full(n, _NONE)
    if n > 1:
        # the pieces between consecutive rulings of one strip (none across two strips)
        sorts = piece_sorts(a, b, size[:-1])
        within = np.ones(n - 1, dtype=bool)
        within[stack.offsets[1:-1] - 1] = False
        left[1:] = np.where(within, sorts, _NONE)
        right[:-1] = np.where(within, sorts, _NONE)
    # a piece of no width is no sheet: the ruling's other side decides
    left = np.where(left == _EMPTY, right, left)
    right = np.where(right == _EMPTY, left, right)
    one_side = (left == _NONE) | (right == _NONE)
    cone = np.isin(left, (_CONE_A, _CONE_B)) | np.isin(right, (_CONE_A, _CONE_B))
    same = (left == right) | one_side
    torsal = within_tolerance(tangent, tolerance, a, b, rounding)
    sheet_ok = within_tolerance(sheet, tolerance, a, b, rounding)
    fan = same & cone  # inside a cone (or a strip's end ruling beside one), or a tip beside one
    undefined = np.isnan(tangent) & ~tip
    crease = ~tip & ~fan & ~torsal & (undefined | ~same)
    kind = np.where(fan, FAN, np.where(crease, CREASE, TORSAL))
    valid = ~tip & np.where(fan, sheet_ok, torsal & ~crease)
    angle = np.where(crease, np.where(undefined, np.pi, tangent), 0.0)
    counts = np.add.reduceat(valid & ~fan & ~crease, stack.starts).tolist()  # (torsal and valid)
    columns = (stack.split(x) for x in (kind, valid, tangent, angle, tip))
    return [RulingKinds(k.tolist(), v, w, c, p, count)
            for k, v, w, c, p, count in zip(*columns, counts, strict=True)]


#: A rail's one-sided tangent at a ruling is taken this share of the ruling interval inside
#: the piece (its exact derivative there): at the ruling itself a rail whose pace stands still
#: on one side (a fan's apex next to it) has a derivative of 0 whatever the geometry.
INSIDE = 1e-9


@dataclass(frozen=True)
class SheetFolds:
    """Per ruling of a strip: how the sheet's tangent plane turns across and along it."""

    #: the angle (rad, [0, π]) between the planes of the pieces on the ruling's two sides
    #: (the dihedral angle of two flat triangles meeting at it): 0 where the sheet goes on
    #: smoothly (inside a cone, between torsal pieces), 0 at a strip's end ruling, NaN where
    #: a plane is undefined (a ruling of no length, one along a rail's tangent)
    across: FloatArray
    #: the largest turn of the tangent plane along the ruling on either side (rad): 0 beside
    #: cones and torsal pieces, a warped piece's warp
    along: FloatArray
    tip: BoolArray  #: rulings of no length (the rails meet: no plane, NaN above)

    def creases(self, fan: BoolArray, tolerance: float, starts: FloatArray, ends: FloatArray) -> BoolArray:
        """The ``fan`` rulings across which the sheet folds: their fold is not a number within
        ``tolerance`` (:func:`~.measure.within_tolerance`: NaN is never flat), tips aside."""
        return fan & ~self.tip & ~within_tolerance(self.across, tolerance, starts, ends)

    def flat(self, tolerance: float, starts: FloatArray, ends: FloatArray) -> BoolArray:
        """The rulings along and across which the sheet keeps one tangent plane within
        ``tolerance`` (both angles within it; never a tip)."""
        return ~self.tip & within_tolerance(np.maximum(self.across, self.along), tolerance, starts, ends)


def sheet_folds(rail_a: Curve, rail_b: Curve, u: ArrayLike, starts: ArrayLike, ends: ArrayLike) -> SheetFolds:
    """How the sheet of a strip turns across and along each ruling ``starts[i] → ends[i]``,
    its rails ``rail_a`` and ``rail_b`` run at one parameter with the rulings at ``u`` (a
    ruled strip's two edges, as :class:`~torsal.nodes.geometry.ruled.RuledSurface` holds
    them).

    Read from the geometry alone: each piece between consecutive rulings is a cone through
    a point of A (the two rulings share their start), of B, or a ruled quad
    (:func:`piece_sorts`; a piece of no width is skipped, the one beyond it counts). The
    piece's tangent plane along the ruling is the plane of the ruling and the moving
    rail's tangent: R × B' in a cone through A, R × A' in one through B, and R × A' at A
    and R × B' at B in a quad. The tangents are each rail's own one-sided ones, taken
    :data:`INSIDE` of the interval into the piece (direction only: the pace plays no
    part). ``across`` is the larger angle between the two sides' planes at the ruling's
    two ends: the fold of the sheet there; ``along`` the larger turn along it within
    either side (a quad's warp; 0 in a cone).

    Two flat triangles A0 A1 B0 and A1 B0 B1 between the segments A from (0, 0, 0) to
    (1, 0, 0) and B from (0, 1, 0) to (1, 1, h) fold along A1 B0 by atan(√2·h):

    >>> from torsal.nodes.geometry.curve_rail import CurveRail
    >>> from torsal.nodes.geometry.curves import Line
    >>> a, b = Line([0, 0, 0], [1, 0, 0]), Line([0, 1, 0], [1, 1, 0.1])
    >>> u, s, t = [0.0, 0.5, 1.0], [0.0, 1.0, 1.0], [0.0, 0.0, 1.0]
    >>> folds = sheet_folds(CurveRail(a, u, s), CurveRail(b, u, t), u, a.point_at(s), b.point_at(t))
    >>> float(folds.across[1].round(12)) == float(np.arctan(np.sqrt(2) * 0.1).round(12))
    True
    """
    a = np.asarray(starts, dtype=float).reshape(-1, 3)
    b = np.asarray(ends, dtype=float).reshape(-1, 3)
    u = np.asarray(u, dtype=float).reshape(-1)
    n = len(a)
    across, along = np.zeros(n), np.zeros(n)
    size = float(norm(np.ptp(np.concatenate([a, b]), axis=0))) if n else 0.0
    tip = norm(b - a) <= ZERO * size
    if n < 3:
        across[tip], along[tip] = np.nan, np.nan
        return SheetFolds(across, along, tip)
    sorts = piece_sorts(a, b, size)
    pieces = np.arange(n - 1)
    full = sorts != _EMPTY
    # the piece on each side of each inner ruling: the nearest one that is not empty
    left = np.maximum.accumulate(np.where(full, pieces, -1))[:-1]  # for rulings 1 … n − 2
    right = np.minimum.accumulate(np.where(full, pieces, n - 1)[::-1])[::-1][1:]
    inner = np.arange(1, n - 1)
    has = (left >= 0) & (right <= n - 2)
    inner, left, right = inner[has], left[has], right[has]
    # each rail's tangent inside each side's piece, next to the ruling (its far end on the
    # left, its near end on the right)
    def inside(k: IntArray, at: IntArray, sign: float) -> FloatArray:
        step = u[k + 1] - u[k]
        return u[at] + sign * np.minimum(np.maximum(INSIDE * step, 8.0 * np.spacing(np.abs(u[at]) + 1.0)),
                                         0.5 * step)

    x = np.concatenate([inside(left, left + 1, -1.0), inside(right, right, 1.0)])
    ta, tb = rail_a.derivative_at(x, 1), rail_b.derivative_at(x, 1)
    m = len(inner)
    r = (b - a)[inner]
    planes = []
    for side, piece in ((slice(0, m), left), (slice(m, 2 * m), right)):
        na, nb = _plane(r, ta[side]), _plane(r, tb[side])
        sort = sorts[piece][:, None]
        at_a = np.where(sort == _CONE_A, nb, na)  # (a cone through A has B's plane at both ends)
        at_b = np.where(sort == _CONE_B, na, nb)
        planes.append((at_a, at_b))
    (left_a, left_b), (right_a, right_b) = planes
    across[inner] = np.maximum(_angle(left_a, right_a), _angle(left_b, right_b))  # (NaN if either is)
    along[inner] = np.maximum(_angle(left_a, left_b), _angle(right_a, right_b))
    across[tip], along[tip] = np.nan, np.nan
    return SheetFolds(across, along, tip)


def _plane(r: FloatArray, tangent: FloatArray) -> FloatArray:
    """The unit normal R × T of the plane of each ruling and a tangent (NaN where they are
    parallel within :data:`~.warp.PARALLEL` or either is zero)."""
    n = cross(r, tangent)
    length = norm(n)
    defined = length > PARALLEL * norm(r) * norm(tangent)
    return np.where(defined[:, None], n / np.where(defined, length, 1.0)[:, None], np.nan)


def _angle(n1: FloatArray, n2: FloatArray) -> FloatArray:
    """The angle between unit normals, rad, [0, π] (NaN where either is)."""
    return np.arctan2(norm(cross(n1, n2)), np.einsum("ij,ij->i", n1, n2))


@dataclass(frozen=True)
class FanKinds:
    """Per ruling of a strip whose solve marked its fans: "torsal", "fan" or "crease"."""

    kind: list[str]  #: "torsal" (not a fan), "fan" (the sheet does not fold across it), "crease"
    crease: BoolArray  #: the fan rulings across which the sheet folds beyond the tolerance
    flat: BoolArray  #: the sheet keeps one plane along and across the ruling (within the tolerance)
    fold: FloatArray  #: the angle the sheet folds through across the ruling, rad (:class:`SheetFolds`)


def fan_kinds(
    rail_a: Curve, rail_b: Curve, u: ArrayLike, starts: ArrayLike, ends: ArrayLike, fan: BoolArray,
    tolerance: float, placed: tuple[FloatArray, FloatArray] | None = None,
) -> FanKinds:
    """Which of a strip's ``fan`` rulings (the flat triangles and cones its solve closed it
    with) are fans and which creases, from the strip's rails and rulings (as
    :func:`sheet_folds` takes them): a fan ruling across which the sheet's plane turns by more
    than ``tolerance`` is a crease; one inside a cone through one point, or between two
    triangles in one plane, is a fan. Other rulings are torsal. ``placed``: the rulings'
    ends where they are put in the world (the rounding of their coordinates widens the
    tolerance, :func:`~.measure.within_tolerance`); the angles are the same there.

    A zigzag of triangles between two skew segments is all creases but its end rulings:

    >>> from torsal.nodes.geometry.curve_rail import CurveRail
    >>> from torsal.nodes.geometry.curves import Line
    >>> a, b = Line([0, 0, 0], [1, 0, 0]), Line([0, 1, 0], [1, 1, 0.1])
    >>> u, s, t = [0.0, 1 / 3, 2 / 3, 1.0], [0.0, 0.5, 0.5, 1.0], [0.0, 0.0, 1.0, 1.0]
    >>> fan = np.ones(4, dtype=bool)
    >>> fan_kinds(CurveRail(a, u, s), CurveRail(b, u, t), u, a.point_at(s), b.point_at(t), fan, 1e-7).kind
    ['fan', 'crease', 'crease', 'fan']
    """
    a = np.asarray(starts, dtype=float).reshape(-1, 3)
    b = np.asarray(ends, dtype=float).reshape(-1, 3)
    fan = np.asarray(fan, dtype=bool)
    folds = sheet_folds(rail_a, rail_b, u, a, b)
    world_a, world_b = placed if placed is not None else (a, b)
    crease = folds.creases(fan, tolerance, world_a, world_b)
    flat = folds.flat(tolerance, world_a, world_b)
    kind = np.where(crease, CREASE, np.where(fan, FAN, TORSAL)).tolist()
    return FanKinds(kind, crease, flat, folds.across)
