"""Strips run on past the design's edge and trimmed by it (D-strips cut by the outline).

Why
---
The rulings of a smooth strip between two neighbouring boundaries run in the direction
conjugate to the boundaries (Pottmann, Schiftner, Bo et al. 2008). Where that direction
crosses the boundaries obliquely — a saddle whose lines of curvature run at 30° to its
edges, a wave whose crests cross the grid — the rulings near an end of the strip reach
the design's edge on one boundary long before the other: the end admits no torsal ruling
between the two curves and is closed by a cone through one curve's end point
(:mod:`.end_cones`), which is smooth but bends away from the design and takes about
w·cot α / L of a strip w wide and L long whose rulings cross it at α (a fifth of a saddle).
Nor can the end be closed torsally between a boundary and the design's edge: on
z = (a·x² + c·y²)/2 the plane of the tangents at A(s) on y = 0 and E(r) on x = 0 holds the
ruling A(s) → E(r) only where a·s² = c·r², which has no root where the design bends
opposite ways along and across (a·c < 0, a saddle).

How
---
So the strip runs on past the edge and is cut by it, as the D-strip models cut their
strips by the outline:

1. Extension: the design is continued beyond its parameter square by its second-order
   Taylor expansion at the nearest point of the square (C2 across the edge: the boundary
   curves stay smooth there), the lift δ of :mod:`.offset` by its first order. The
   continuation only steers the rulings of the part that is cut away.
2. The two boundaries, run on past both ends by ``E`` (enough to hold the strip's end
   cones), are solved as one strip (RulingDevelopable).
3. A ruling that leaves the design is cut where it crosses the *wall* at that edge — the
   surface swept by the design's (lifted) edge along the design's normal (Newton on the
   three unknowns: along the ruling, along the edge, along the normal); a ruling wholly
   outside is dropped. A cut ruling is a piece of a torsal ruling: its tangent plane is
   the whole ruling's, so the end stays torsal. Exact torsal rulings are added through the
   two points where a boundary meets the wall (a root of the coplanarity function on the
   other curve, by scipy's ``brentq``).
4. Rails: each boundary's part on the design, joined at the end where the other side's
   rulings were cut with the *trim curve* through the crossing points: a cubic Hermite
   curve (scipy's ``CubicHermiteSpline``) whose tangent at each crossing is the line where
   the strip's tangent plane there meets the wall's, so a cut ruling's tangent plane holds
   the rail's tangent and its recomputed warp is zero again. The strip tapers to a point at
   the corner where a boundary meets the wall: that point is the strip's first (or last)
   ruling, of no length, a fan's (no plane is defined there); a cut ruling a hundredth of
   a station's spacing from it leaves that fan a sliver of no account.

The rest of the strip is the plain one between the two boundaries; two neighbours still
share their boundary exactly (both rails run on the same curve), and the trimmed end lies
on the wall, so the design's edge is covered to the strip's deviation there.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from scipy.interpolate import CubicHermiteSpline

from ..array_types import BoolArray, FloatArray
from ..curve_base import Curve
from ..surface_base import Surface
from ..vec_ops import differenced
from .offset import Lift, LiftedIsoCurve, _normal_jet
from .ruling import RulingResult

#: The farthest the boundaries are run on past each end, in the family's parameter.
EXTEND_MAX = 0.5
#: The run past the end as a multiple of the plain strip's end cone (in parameter).
EXTEND_BY = 1.3
#: Newton steps for a ruling's crossing with the wall, and the residual (share of the
#: ruling's length) below which a crossing is accepted.
NEWTON_STEPS = 30
CROSSING = 1e-10
#: Where the ruling added next to a tip is, as a share of the way to the nearest station:
#: the sliver between it and the tip (a fan) is then about NEAR_TIP of a station's piece.
NEAR_TIP = 1e-2


class ExtendedSurface(Surface):
    """``design`` continued beyond [0, 1]² by its second-order Taylor expansion at the
    nearest point of the square (the design itself inside)."""

    def __init__(self, design: Surface) -> None:
        self.design = design

    def __repr__(self) -> str:
        return f"ExtendedSurface({self.design!r})"

    def derivatives(self, u, v, order: int = 1) -> list[FloatArray]:
        self._check_order(order)
        u, v = np.broadcast_arrays(np.atleast_1d(np.asarray(u, float)).ravel(),
                                   np.atleast_1d(np.asarray(v, float)).ravel())
        uc, vc = np.clip(u, 0.0, 1.0), np.clip(v, 0.0, 1.0)
        p, su, sv, suu, suv, svv = self.design.derivatives(uc, vc, 2)
        a, b = (u - uc)[:, None], (v - vc)[:, None]
        out = [p + su * a + sv * b + 0.5 * (suu * a * a + 2.0 * suv * a * b + svv * b * b)]
        if order >= 1:
            out += [su + suu * a + suv * b, sv + suv * a + svv * b]
        if order >= 2:
            out += [suu, suv, svv]
        return out


@dataclass(frozen=True)
class _ExtendedLift:
    """δ of :mod:`.offset` continued beyond [0, 1]² by its first order (C1 across the edge)."""

    lift: Lift

    def __call__(self, u: FloatArray, v: FloatArray, du: int = 0, dv: int = 0) -> FloatArray:
        spline = self.lift.spline
        if spline is None:
            return np.zeros_like(u)
        uc, vc = np.clip(u, 0.0, 1.0), np.clip(v, 0.0, 1.0)
        at = np.column_stack([uc, vc])
        if du or dv:
            return spline(at, nu=(du, dv)) if du + dv == 1 else np.zeros_like(u)
        return spline(at) + spline(at, nu=(1, 0)) * (u - uc) + spline(at, nu=(0, 1)) * (v - vc)


class _Hermite(Curve):
    """The cubic Hermite curve through ``points`` with ``tangents`` at parameters ``x``."""

    exact_derivatives = True  # a spline's own derivatives (vec_ops.differenced)

    def __init__(self, x: FloatArray, points: FloatArray, tangents: FloatArray) -> None:
        self.spline = CubicHermiteSpline(x, points, tangents)

    def __repr__(self) -> str:
        return f"_Hermite({len(self.spline.x)} points)"

    def derivatives(self, t, order: int = 1) -> list[FloatArray]:
        t = np.atleast_1d(np.asarray(t, float)).ravel()
        return [self.spline(t, k) for k in range(order + 1)]

    def _breakpoints(self) -> FloatArray:
        return np.asarray(self.spline.x, dtype=float).copy()


class Joined(Curve):
    """Curves end to end, each on its share of [0, 1] by length (a corner at each joint)."""

    def __init__(self, pieces: list[Curve]) -> None:
        self.pieces = pieces
        lengths = np.array([np.linalg.norm(np.diff(c.point_at(np.linspace(0, 1, 33)), axis=0), axis=1).sum()
                            for c in pieces])
        self.cuts = np.concatenate([[0.0], np.cumsum(lengths) / lengths.sum()])
        self.cuts[-1] = 1.0

    def __repr__(self) -> str:
        return f"Joined({len(self.pieces)} pieces)"

    @property
    def exact_derivatives(self) -> bool:
        """As exact as its pieces (vec_ops.differenced)."""
        return not any(differenced(piece) for piece in self.pieces)

    def at(self, piece: int, t: FloatArray) -> FloatArray:
        """This curve's parameter for parameters ``t`` of piece ``piece``."""
        return self.cuts[piece] + np.asarray(t, float) * (self.cuts[piece + 1] - self.cuts[piece])

    def derivatives(self, t, order: int = 1) -> list[FloatArray]:
        t = np.atleast_1d(np.asarray(t, float)).ravel()
        out = [np.empty((len(t), 3)) for _ in range(order + 1)]
        which = np.clip(np.searchsorted(self.cuts, t, side="right") - 1, 0, len(self.pieces) - 1)
        for k, piece in enumerate(self.pieces):
            rows = which == k
            if np.any(rows):
                width = self.cuts[k + 1] - self.cuts[k]
                ders = piece.derivatives((t[rows] - self.cuts[k]) / width, order)
                for j in range(order + 1):
                    out[j][rows] = ders[j] / width**j
        return out

    def _breakpoints(self) -> FloatArray:
        inner = [self.at(k, piece._breakpoints()) for k, piece in enumerate(self.pieces)]
        return np.unique(np.concatenate([self.cuts, *inner]))


@dataclass
class Trimmed:
    """A strip trimmed by the design's edge: its rails, its rulings (``result``: parameters
    on the rails), which of them are the point the strip tapers to, and where each ruling's
    ends lie on the two boundaries (their parameter there; NaN on a trim)."""

    curve_a: Curve
    curve_b: Curve
    result: RulingResult
    point: BoolArray  #: a "ruling" of no length: the point the strip tapers to (a fan's)
    on_a: FloatArray
    on_b: FloatArray


class _Wall:
    """The surface swept by the design's lifted edge at ``edge`` (0 or 1 in the family's
    parameter) along the design's normal: W(w, α) = L(w) + α·N(w)."""

    def __init__(self, surface: Surface, family: str, lift: _ExtendedLift, edge: float) -> None:
        self.surface, self.family, self.lift, self.edge = surface, family, lift, float(edge)

    def at(self, w: FloatArray, alpha: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """The wall's point, its tangent along the edge (approximately: the lift's and the
        normal's turn left out, second order in the tolerance) and the normal."""
        fixed = np.full_like(w, self.edge)
        u, v = (fixed, w) if self.family == "u" else (w, fixed)
        ders = self.surface.derivatives(u, v, 2)
        n = _normal_jet(ders)[0]
        point = ders[0] + (self.lift(u, v) + alpha)[:, None] * n
        along = ders[2] if self.family == "u" else ders[1]
        return point, along, n

    def normal(self, w: float) -> FloatArray:
        """The wall's normal at the edge's point ``w`` (on the lifted design)."""
        _, along, n = self.at(np.array([float(w)]), np.zeros(1))
        return np.cross(along[0], n[0])

    def cross(self, starts: FloatArray, rulings: FloatArray,
              w0: float) -> tuple[FloatArray, FloatArray] | None:
        """λ where starts + λ·rulings meets the wall and the wall's normal there, or None."""
        lam = np.full(len(starts), 0.5)
        w = np.full(len(starts), float(w0))
        alpha = np.zeros(len(starts))
        for _ in range(NEWTON_STEPS):
            point, along, n = self.at(w, alpha)
            residual = starts + lam[:, None] * rulings - point
            jacobian = np.stack([rulings, -along, -n], axis=2)
            try:
                step = np.linalg.solve(jacobian, -residual[:, :, None])[:, :, 0]
            except np.linalg.LinAlgError:
                return None
            lam, w, alpha = lam + step[:, 0], w + step[:, 1], alpha + step[:, 2]
            if float(np.abs(step[:, 0]).max()) <= 1e-15:
                break
        point, along, n = self.at(w, alpha)
        off = np.linalg.norm(starts + lam[:, None] * rulings - point, axis=1)
        if not (np.all(np.isfinite(lam)) and np.all(off <= CROSSING * np.linalg.norm(rulings, axis=1))):
            return None
        return lam, np.cross(along, n)


@dataclass
class _Row:
    """One row of the trimmed strip: each end's parameter on its boundary (NaN where the
    ruling was cut at the wall), its point, the trim's direction there (cut ends only)."""

    sa: float
    pa: FloatArray
    tb: float
    pb: FloatArray
    fan: bool = False
    station: bool = False
    point: bool = False  #: a point the strip tapers to, not a ruling
    da: FloatArray | None = None
    db: FloatArray | None = None


def _cone(plain: RulingResult, at_end: bool) -> tuple[str, int] | None:
    """The plain strip's end cone at its start (or end): ``("b", k)`` when it is the cone
    through B's end point over A's first k rows (their partners lie past B's end), ``("a",
    k)`` the other way round; None where the end is not one cone joined to a torsal ruling
    through its apex (:mod:`.end_cones`)."""
    fan = plain.fan[::-1] if at_end else plain.fan
    s = 1.0 - plain.s[::-1] if at_end else plain.s
    t = 1.0 - plain.t[::-1] if at_end else plain.t
    if not fan[0] or fan.all():
        return None
    k = int(np.argmax(~fan))
    if k >= 2 and np.all(t[:k + 1] == 0.0) and np.all(np.diff(s[:k + 1]) > 0.0):
        return "b", k
    if k >= 2 and np.all(s[:k + 1] == 0.0) and np.all(np.diff(t[:k + 1]) > 0.0):
        return "a", k
    return None


def _partners(fixed: Curve, moving: Curve, params: FloatArray, start: tuple[float, float], slope: float,
              fixed_is_a: bool) -> FloatArray | None:
    """The torsal partners on ``moving`` (run on past its end) of the points of ``fixed`` at
    ``params`` (in order from the ruling ``start`` outwards), by Newton's method on the
    coplanarity function, all at once, started on the branch's tangent line at ``start``;
    None where one does not converge, the partners run back or the sheet's normals flip."""
    p0, x0 = start
    x = x0 + slope * (params - p0)
    f0, f1 = fixed.derivatives(params, 1)
    scale = 1.0 + float(np.abs(params - p0).max())
    for _ in range(NEWTON_STEPS):
        m0, m1, m2 = moving.derivatives(x, 2)
        r = (m0 - f0) if fixed_is_a else (f0 - m0)
        g = np.einsum("ij,ij->i", r, np.cross(f1, m1))
        dg = np.einsum("ij,ij->i", r, np.cross(f1, m2))
        with np.errstate(divide="ignore", invalid="ignore"):
            step = g / dg
        if not np.all(np.isfinite(step)):
            return None
        x = x - step
        if float(np.abs(step).max()) <= 1e-14 * scale:
            break
    else:
        return None
    m0, m1 = moving.derivatives(x, 1)
    r = (m0 - f0) if fixed_is_a else (f0 - m0)
    n1, n2 = np.cross(r, f1), np.cross(r, m1)
    run = np.diff(np.concatenate([[x0], x])) * np.diff(np.concatenate([[p0], params]))
    if not (np.all(np.einsum("ij,ij->i", n1, n2) > 0.0) and np.all(run > 0.0)):
        return None
    return x


def trim_ends(
    design: Surface, family: str, lift: Lift | None, lo: float, hi: float, plain: RulingResult,
    rails: tuple[Curve, Curve], warp_tolerance: float,
) -> Trimmed | None:
    """The plain strip ``plain`` between the boundaries at levels ``lo`` and ``hi`` (the
    parameter lines along ``family``, lifted by ``lift``) with each end cone replaced by
    torsal rulings run on past the design's edge and cut by it (see the module); None where
    neither end can be (the plain strip then stands). ``rails`` are the two boundaries, the
    plain strip's curves."""
    surface = ExtendedSurface(design)
    delta = _ExtendedLift(lift if lift is not None else Lift(None))
    a, b = (LiftedIsoCurve(surface, family, level, delta) for level in (lo, hi))
    n = len(plain.s)
    rows = [_Row(float(plain.s[k]), plain.starts[k], float(plain.t[k]), plain.ends[k], bool(plain.fan[k]),
                 bool(plain.stations[k])) for k in range(n)]
    changed = False
    for at_end in (True, False):  # (the tail first: the head's rows then keep their indices)
        cone = _cone(plain, at_end)
        if cone is None:
            continue
        side, k = cone
        end = _cut_end(rows, side, k, at_end, a, b, _Wall(surface, family, delta, 1.0 if at_end else 0.0),
                       lo, hi)
        if end is None:
            continue
        changed = True
        rows = rows[:n - 1 - k] + end if at_end else end + rows[k + 1:]
    if not changed:
        return None
    curves = rails  # (the boundaries themselves: the same points as a and b on the design)
    edges = {0.0: 0.0, 1.0: 1.0}
    corners = {(side, e): c.point_at(np.array([e]))[0]
               for side, c in zip("ab", curves, strict=True) for e in edges}
    rails = [_rail(rows, side, c, edges, corners) for side, c in zip("ab", curves, strict=True)]
    if rails[0] is None or rails[1] is None:
        return None
    (curve_a, s), (curve_b, t) = rails
    if np.any(np.diff(s) < 0.0) or np.any(np.diff(t) < 0.0):
        return None
    on_a = np.array([row.sa for row in rows])
    on_b = np.array([row.tb for row in rows])
    starts = np.array([row.pa for row in rows])
    ends = np.array([row.pb for row in rows])
    fan = np.array([row.fan for row in rows])
    result = _result(plain, curve_a, curve_b, s, t, starts, ends, fan,
                     np.array([row.station for row in rows]), warp_tolerance)
    return Trimmed(curve_a, curve_b, result, np.array([row.point for row in rows]), on_a, on_b)


def _cut_end(rows: list[_Row], side: str, k: int, at_end: bool, a: Curve, b: Curve, wall: _Wall,
             lo: float, hi: float) -> list[_Row] | None:
    """The rows that replace an end cone of ``k`` rows (``side`` as :func:`_cone`): the point
    the strip tapers to, the cone's stations with their torsal partners past the edge cut at
    the wall, and the torsal ruling through the cone's apex (with the trim's direction)."""
    order = list(range(len(rows) - 1, len(rows) - 2 - k, -1)) if at_end else list(range(k + 1))
    apex_row = rows[order[k]]
    # the two torsal rulings next to the cone give the branch's slope
    inner = rows[order[k] + (-1 if at_end else 1)]
    fixed_is_a = side == "b"  # a cone through B's end: A's stations need partners past B's end
    def get(r: _Row) -> tuple[float, float]:
        return (r.sa, r.tb) if fixed_is_a else (r.tb, r.sa)

    p0, x0 = get(apex_row)
    p1, x1 = get(inner)
    if p1 == p0:
        return None
    edge = 1.0 if at_end else 0.0
    stations = [get(rows[j])[0] for j in order[1:k]][::-1]  # from the apex outwards
    # and one ruling next to the tip, so the sliver between it and the tip is negligible
    params = np.array([*stations, edge + NEAR_TIP * (stations[-1] - edge)])
    fixed, moving = (a, b) if fixed_is_a else (b, a)
    found = _partners(fixed, moving, params, (p0, x0), (x1 - x0) / (p1 - p0), fixed_is_a)
    if found is None or not np.all((found > 1.0) if at_end else (found < 0.0)):
        return None
    f0, f1 = fixed.derivatives(params, 1)
    m0 = moving.point_at(found)
    rulings = m0 - f0
    crossing = wall.cross(f0, rulings, hi if fixed_is_a else lo)
    if crossing is None:
        return None
    lam, wall_normal = crossing
    if np.any(lam < 0.0) or np.any(lam > 1.0):
        return None
    cuts = f0 + lam[:, None] * rulings
    planes = np.cross(rulings, f1)
    directions = np.cross(planes, wall_normal)
    cut_rows = []
    for i, (p, point, start, direction) in enumerate(zip(params, cuts, f0, directions, strict=True)):
        station = i < len(stations)
        if fixed_is_a:
            cut_rows.append(_Row(float(p), start, float("nan"), point, station=station, db=direction))
        else:
            cut_rows.append(_Row(float("nan"), point, float(p), start, station=station, da=direction))
    # the torsal ruling through the apex, with the trim's direction where it meets the wall
    apex = _Row(apex_row.sa, apex_row.pa, apex_row.tb, apex_row.pb, False, apex_row.station)
    plane = np.cross(apex.pb - apex.pa, a.derivatives(np.array([apex.sa]), 1)[1][0])
    direction = np.cross(plane, wall.normal(hi if fixed_is_a else lo))
    if fixed_is_a:
        apex.db = direction
    else:
        apex.da = direction
    corner = (a if fixed_is_a else b).point_at(np.array([edge]))[0]
    tip = _Row(edge, corner, float("nan"), corner, fan=True, point=True) if fixed_is_a else \
        _Row(float("nan"), corner, edge, corner, fan=True, point=True)
    return [apex, *cut_rows, tip] if at_end else [tip, *cut_rows[::-1], apex]


def _rail(rows: list[_Row], side: str, curve: Curve, edge_s: dict[float, float],
          corners: dict[tuple[str, float], FloatArray]) -> tuple[Curve, FloatArray] | None:
    """One side's rail — its boundary between the two walls, with a trim curve ahead and/or
    behind where that side's rulings were cut — and every row's parameter on it."""
    params = np.array([row.sa if side == "a" else row.tb for row in rows])
    points = np.array([row.pa if side == "a" else row.pb for row in rows])
    directions = [row.da if side == "a" else row.db for row in rows]
    on = np.flatnonzero(~np.isnan(params))
    if len(on) < 2:
        return None
    first, last = int(on[0]), int(on[-1])
    if np.isnan(params[first + 1:last]).any():
        return None
    pieces: list[Curve] = []
    trims: list[tuple[FloatArray, int]] = []  # (x of the trim's rows, index of its first row)
    if first > 0:  # a trim ahead: the cut rows, then the boundary's corner
        chain = np.vstack([points[:first], corners[(side, 0.0)][None]])
        trim, x = _trim(chain, [*directions[:first], directions[first]])
        if trim is None:
            return None
        pieces.append(trim)
        trims.append((x[:-1], 0))
    lo_s, hi_s = edge_s[0.0], edge_s[1.0]
    pieces.append(curve)
    if last < len(rows) - 1:
        chain = np.vstack([corners[(side, 1.0)][None], points[last + 1:]])
        trim, x = _trim(chain, [directions[last], *directions[last + 1:]])
        if trim is None:
            return None
        pieces.append(trim)
        trims.append((x[1:], last + 1))
    joined = Joined(pieces)
    out = np.empty(len(rows))
    body = 1 if first > 0 else 0
    out[first:last + 1] = joined.at(body, (params[first:last + 1] - lo_s) / (hi_s - lo_s))
    for x, start in trims:
        piece = 0 if start == 0 else len(pieces) - 1
        out[start:start + len(x)] = joined.at(piece, x)
    return joined, np.clip(out, 0.0, 1.0)


def _trim(points: FloatArray, directions: list[FloatArray | None]) -> tuple[Curve | None, FloatArray]:
    """The trim curve through ``points`` (in order), its tangent at each along the given
    direction (where there is one; else the chord's), scaled to the chords around it."""
    chords = np.linalg.norm(np.diff(points, axis=0), axis=1)
    if len(points) < 2 or not np.all(chords > 0.0):
        return None, np.zeros(len(points))
    x = np.concatenate([[0.0], np.cumsum(chords)]) / chords.sum()
    if len(points) > 2:
        rough = np.gradient(points, x, axis=0)
    else:
        rough = np.repeat(np.diff(points, axis=0) / x[1], 2, axis=0)
    tangents = rough.copy()
    for k, d in enumerate(directions):
        if d is None or not np.all(np.isfinite(d)) or not np.linalg.norm(d) > 0.0:
            continue
        unit = d / np.linalg.norm(d)
        speed = float(np.dot(rough[k], unit))
        tangents[k] = unit * (speed if speed != 0.0 else np.linalg.norm(rough[k]))
    return _Hermite(x, points, tangents), x


def _result(full: RulingResult, curve_a: Curve, curve_b: Curve, s: FloatArray, t: FloatArray,
            starts: FloatArray, ends: FloatArray, fan: BoolArray, stations: BoolArray,
            warp_tolerance: float) -> RulingResult:
    """The trimmed strip's rulings as a :class:`RulingResult` (warps recomputed on its rails)."""
    from .fans import fan_shares
    from .warp import curve_warp

    warp = curve_warp(curve_a, curve_b, s, t, starts, ends)
    signed = curve_warp(curve_a, curve_b, s, t, starts, ends, signed=True)
    share, creased = fan_shares(starts, ends, fan)
    return replace(full, s=s, t=t, starts=starts, ends=ends, warp=warp, signed_warp=signed,
                   valid=np.isfinite(warp) & (warp <= warp_tolerance), stations=stations, fan=fan,
                   fan_share=share, creased_share=creased,
                   message=None if not fan.any() else full.message)
