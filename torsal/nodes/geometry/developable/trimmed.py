"""Rationalising a trimmed design: strips over the trim's box, cut to the trim.

A Rhino brep face is a surface kept inside trim loops (:class:`~torsal.nodes.geometry.
trimmed_surface.TrimmedSurface`). Its strips must cover the kept part only, to the trim:

1. Box. The underlying surface is taken on the box of the trim loops in (u, v), a
   little larger (:class:`Patch`, reparameterised to [0, 1]²), and rationalised as any
   design (:func:`~torsal.nodes.geometry.developable.rationalise.rationalise`): the
   boundaries and strips are chosen there, the parts of the surface far outside the trim
   play no part.
2. The strip's own sheet. Between its rulings a strip's rails are paired at an
   interpolated pace, which twists a little; every point of rail A is paired instead
   with its developable partner on rail B (:func:`~torsal.nodes.geometry.torsal_pairing.
   torsal_partners`, as the ``.3dm`` export does), so every line across the sheet is
   torsal, not only the solved rulings (a cubic through the partners of sampled lines and
   of every line the cut keeps, :meth:`_Sheet.pin`).
3. Cut. The sheet's lines are sampled (:data:`PER_RULING` per ruling interval,
   :data:`ACROSS` points along each), each point projected onto the design and judged
   inside or outside the trim in (u, v) by its signed distance to the trim loops
   (shapely, :mod:`.trim_region`); along each line the kept interval is where that
   distance is ≥ 0 (each crossing found by false position from the samples either side).
   A line is added through each corner of the trim that the sheet covers (its cut ends at
   the corner exactly), and more lines wherever the cut point jumps from one line to the
   next (lines that sweep along the trim, as in a fan). The lines whose interval is not
   empty, in runs, make the cut strips; a run's ends are found by bisection to where the
   lines leave the trim.
4. Rails. A cut strip's two edges are chains of pieces: stretches of the strip's own
   rails (kept exactly, so neighbours still share their boundary) and stretches along
   the trim from corner to corner, a cubic in u through the lines' cut points (least
   squares with knots at the rulings where that stays within :data:`FIT` of the
   tolerance, else scipy's monotone PCHIP through them). Where a chain turns from a rail
   onto the trim, or at a corner of the trim, a ruling is added there, so the exported
   faces meet at the corner. Both edges then run at one pace by their summed length
   (:func:`~.cut_pace.by_length`), not by the sheet's u, which stands almost still where
   the pace crosses a jump of the pairing (:mod:`.cut_pace`).
5. Rulings: the strip's own rulings, cut to the trim, with the corner rulings and the two
   ends. The cut strip's deviation is certified again (:mod:`.certify`), on the kept part
   only, checked on dense samples too (:func:`~.trim_region.checked_densely`), and the
   trim loops' distance to the strips is the coverage.

A run of lines that splits in two (a strip crossing a notch of the trim, or a hole)
becomes separate strips from the first line past the split; between the last line
before and the first after, a sliver up to one sample step (:data:`PER_RULING`) wide is
left out, and the coverage measured says so where it matters.
"""

from __future__ import annotations

import copy
import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike
from scipy.interpolate import BSpline, PchipInterpolator, make_interp_spline, make_lsq_spline
from scipy.optimize import minimize_scalar

from ..array_types import FloatArray
from ..curve_base import Curve
from ..curve_rail import CurveRail
from ..ruled import RuledSurface
from ..surface_base import Surface
from ..torsal_pairing import torsal_partners
from ..trimmed_surface import TrimmedSurface
from .certify import certified_deviation, distances_to_strips
from .chain import Chain
from .cut_pace import TURN_BISECTIONS, by_length, jumps
from .fans import creased_runs, patch_areas
from .kinds import sheet_folds
from .rationalise import Rationalisation, Strip, rationalise
from .ruling import RulingResult
from .trim_region import checked_densely, patch_of, signed_inside, trim_corners, trim_points
from .warp import curve_warp

#: Lines of a strip's sheet sampled per ruling interval, and points along each line.
PER_RULING, ACROSS = 12, 41
#: Bisections of a cut strip's end (where its lines leave the trim).
HALVINGS = 24
#: Strips are cut this share of the tolerance outside the trim, so the trim is covered by
#: their inside, not only by their cut edges (which lie up to the deviation off the design).
REACH = 0.5
#: A cut strip's end line is this share of its neighbour's length at least (not a point).
TIP = 2e-3
#: Where the cut point of one sampled line to the next moves more than this many times the
#: median step (the sheet's lines sweep along the trim, a fan) or the tolerance, whichever
#: is larger, :data:`SPLIT` lines are put between them, up to :data:`REFINE` times.
JUMP, SPLIT, REFINE = 3.0, 4, 4
#: A line the cut keeps is pinned to its exact developable partner unless it lies within
#: this share of its ruling interval from a line that is (:meth:`_Sheet.pin`).
PIN_GAP = 1e-6
#: Steps of false position to each point where a line leaves the trim, from its samples.
ROOT_STEPS = 3
#: A cut edge along the trim is a least-squares cubic when it stays this share of the
#: tolerance from the cut points; otherwise the monotone cubic through them (PCHIP).
FIT = 0.05


class _OnSheet(Curve):
    """A curve on a strip's sheet: at u = x the point ``w(x)`` of the way along the line
    from rail A's A(x) to B(τ(x)) (``tau``, ``w``: scipy splines in x), with exact
    derivatives (to order 3, the chain rule through τ and w)."""

    def __init__(self, a: Curve, b: Curve, tau: _Pace, w: BSpline) -> None:
        self.a, self.b, self.tau, self.w = a, b, tau, w

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        x = np.atleast_1d(np.asarray(t, dtype=float))
        a = self.a.derivatives(x, order)
        tau = [np.asarray(self.tau(x, nu=k), dtype=float)[:, None] for k in range(order + 1)]
        b = self.b.derivatives(tau[0][:, 0], order)
        along = [b[0], b[1] * tau[1] if order >= 1 else None,
                 b[2] * tau[1] ** 2 + b[1] * tau[2] if order >= 2 else None,
                 b[3] * tau[1] ** 3 + 3.0 * b[2] * tau[1] * tau[2] + b[1] * tau[3] if order >= 3 else None]
        across = [along[k] - a[k] for k in range(order + 1)]
        w = [np.asarray(self.w(x, nu=k), dtype=float)[:, None] for k in range(order + 1)]
        return [a[k] + sum(math.comb(k, j) * w[j] * across[k - j] for j in range(k + 1))
                for k in range(order + 1)]


@dataclass
class _Line:
    """One line across the sheet at u = ``x`` and its kept interval ``[lo, hi]`` along it,
    with the signed distance from the trim at its two ends (rails A and B)."""

    x: float
    lo: float
    hi: float
    ruling: int = -1  #: index of the strip's own ruling at this u, or −1
    g0: float = 0.0
    g1: float = 0.0
    kept: bool = False  #: a ruling of the cut strip (the strip's own, a corner or an end)
    corner: bool = False  #: through a corner of the trim (an edge along the trim turns here)


class _Sheet:
    """A strip's sheet: the line at u from rail A's point to its developable partner on B
    (found at the lines measured, a monotone cubic in u between them)."""

    def __init__(self, strip: Strip, inside: Callable[[FloatArray], FloatArray]) -> None:
        surface = strip.surface
        self.a, self.b = surface.curve_a, surface.curve_b
        self.u = np.asarray(surface.ruling_parameters, dtype=float)
        self.lines = np.asarray(surface.ruling_lines, dtype=float)
        self.inside = inside  # signed distance of 3D points from the trim (≥ 0 inside)
        self.w = np.linspace(0.0, 1.0, ACROSS)
        self.x, self.ruling = _columns(self.u)
        # in a fan (two rulings through one point) the sheet is the cone of lines from that
        # point to the other rail, at the strip's own pace: no partner to look for
        size = float(np.ptp(self.lines.reshape(-1, 3), axis=0).max()) or 1.0
        self.apex = (np.abs(np.diff(self.lines, axis=0)).max(axis=2) <= 1e-12 * size).any(axis=1)
        tau = self._partners(self.x)
        tau[self.ruling >= 0] = self.u
        self.tau = _Pace(self.x, np.maximum.accumulate(tau), self.u)
        # the pace crosses each jump of the pairing on a ramp placed by the pairing alone
        self.ramps = jumps(self._partners, self.x, tau, self.u, self.apex)
        ends = np.unique(self.ramps)
        ends = ends[~np.isin(ends, self.x)]
        if len(ends):
            self.tau = self.tau.pinned(ends, self._partners(ends))

    def _partners(self, x: FloatArray) -> FloatArray:
        """Rail B's parameter of the developable partner of A(x) (x itself in a fan)."""
        between = np.minimum(np.searchsorted(self.u, x, side="right") - 1, len(self.apex) - 1)
        return np.where(self.apex[between], x, torsal_partners(self.a, self.b, self.u, x)[0])

    def pin(self, x: FloatArray) -> None:
        """The pace through the exact partners at ``x`` too (the cubic between sampled lines
        misses them by a warp of up to ~2e-6 rad; every line is pinned before it is measured),
        but for an x within :data:`PIN_GAP` of its interval from a node (the cubic would swing)
        or on a ramp across a jump of the pairing (:mod:`.cut_pace`: a cone's lines there)."""
        nodes = np.unique(self.tau.nodes())
        new = np.unique(np.asarray(x, dtype=float))
        lo, hi = self.ramps[None, :, 0], self.ramps[None, :, 1]
        new = new[~((new[:, None] > lo) & (new[:, None] < hi)).any(axis=1)]
        k = np.clip(np.searchsorted(self.u, new, side="right") - 1, 0, len(self.u) - 2)
        at = np.clip(np.searchsorted(nodes, new), 1, len(nodes) - 1)
        gap = np.minimum(np.abs(new - nodes[at - 1]), np.abs(nodes[at] - new))
        new = new[gap > PIN_GAP * (self.u[k + 1] - self.u[k])]
        if len(new):
            self.tau = self.tau.pinned(new, self._partners(new))

    def turn(self, x0: float, x1: float, g0: float, g1: float, upper: bool) -> float:
        """Where the signed distance at one rail's end of the lines (``upper``: B's) crosses
        0 between the lines at ``x0`` and ``x1`` (``g0``, ``g1`` there): interpolated, but
        across a ramp of the pace (a cone that sweeps the rail along the trim, where the
        distance is far from linear in x) by :data:`~.cut_pace.TURN_BISECTIONS` bisections on
        the lines themselves."""
        if not ((self.ramps[:, 0] < x1) & (self.ramps[:, 1] > x0)).any():
            return _crossing(x0, x1, g0, g1)
        for _ in range(TURN_BISECTIONS):
            middle = 0.5 * (x0 + x1)
            g = float(self.inside(self.ends(np.array([middle]))[int(upper)])[0])
            x0, x1 = (middle, x1) if (g >= 0.0) == (g0 >= 0.0) else (x0, middle)
        return 0.5 * (x0 + x1)

    def ends(self, x: FloatArray) -> tuple[FloatArray, FloatArray]:
        """Both ends of the lines at ``x``: the strip's rulings exactly at their u."""
        x = np.asarray(x, dtype=float)
        start, end = self.a.point_at(x), self.b.point_at(self.tau(x))
        k = np.minimum(np.searchsorted(self.u, x), len(self.u) - 1)
        hit = self.u[k] == x
        start[hit], end[hit] = self.lines[k[hit], 0], self.lines[k[hit], 1]
        return start, end

    def distances(self, x: FloatArray) -> FloatArray:
        """The signed distance from the trim at :data:`ACROSS` points along each line at ``x``."""
        start, end = self.ends(x)
        points = start[:, None] + self.w[None, :, None] * (end - start)[:, None]
        return self.inside(points.reshape(-1, 3)).reshape(len(x), len(self.w))

    def kept(self, x: FloatArray) -> tuple[FloatArray, list[list[tuple[float, float]]]]:
        """The signed distances along the lines at ``x`` (:meth:`distances`) and each line's
        kept intervals: where the samples change sign, the crossing found by
        :data:`ROOT_STEPS` steps of false position between them (the distance is not linear
        along a line near a corner of the trim, where it is the nearer of two edges')."""
        x = np.asarray(x, dtype=float)
        self.pin(x)
        g = self.distances(x)
        keep = g >= 0.0
        k, j = np.nonzero(keep[:, 1:] != keep[:, :-1])
        lo, hi, g_lo, g_hi = self.w[j], self.w[j + 1], g[k, j], g[k, j + 1]
        if len(k):
            start, end = self.ends(x[k])
            for _ in range(ROOT_STEPS):
                w = lo + (hi - lo) * g_lo / (g_lo - g_hi)
                found = self.inside(start + w[:, None] * (end - start))
                same = (found >= 0.0) == (g_lo >= 0.0)
                lo, g_lo = np.where(same, w, lo), np.where(same, found, g_lo)
                hi, g_hi = np.where(same, hi, w), np.where(same, g_hi, found)
        cut = lo + (hi - lo) * g_lo / (g_lo - g_hi)
        runs = []
        per_row = np.split(cut, np.searchsorted(k, np.arange(1, len(x))))  # (k is in row order)
        for row, crossings in enumerate(per_row):
            bounds = ([self.w[0]] if keep[row, 0] else []) + crossings.tolist()
            bounds += [self.w[-1]] if keep[row, -1] else []
            runs.append([(float(bounds[i]), float(bounds[i + 1])) for i in range(0, len(bounds) - 1, 2)])
        return g, runs

    def sample(self, corners: FloatArray, tolerance: float) -> None:
        """The lines the cut is made from: :func:`_columns`' lines, a line through each of
        the trim's ``corners`` (3D points on the design) that lies on the sheet within the
        tolerance (its cut there ends at the corner: ``self.corner``, NaN elsewhere), a
        line at each end of the pace's ramps (:mod:`.cut_pace`), and more lines where the
        cut point jumps from one line to the next (see :data:`JUMP`). Sets ``x``,
        ``ruling``, ``corner``, the signed distances ``g`` along them and their kept
        intervals ``runs``."""
        self.corner = np.full(len(self.x), np.nan)
        at, w = self._corner_lines(np.asarray(corners, dtype=float).reshape(-1, 3), tolerance)
        # lines at the ramps' ends too: a cut edge along the trim turns there, not before
        ramps = np.unique(self.ramps)
        self._insert(np.concatenate([at, ramps]), np.concatenate([w, np.full(len(ramps), np.nan)]))
        for _ in range(REFINE):
            cut = self._cut_points()
            step = np.linalg.norm(np.diff(cut, axis=0), axis=2).max(axis=1)
            known = np.isfinite(step)
            if not known.any():
                break
            limit = max(JUMP * float(np.median(step[known])), tolerance)
            wide = np.flatnonzero(known & (step > limit))
            if len(wide) == 0:
                break
            share = np.arange(1, SPLIT)[None, :] / SPLIT
            more = (self.x[wide, None] + share * (self.x[wide + 1] - self.x[wide])[:, None]).ravel()
            self._insert(more, np.full(len(more), np.nan))

    def _insert(self, x: FloatArray, corner: FloatArray) -> None:
        """Lines at ``x`` added to the sampled ones (in order, none twice), with their
        corners' w (NaN: none); sets ``g`` for all."""
        old = getattr(self, "g", None)
        new = np.setdiff1d(x, self.x)
        if old is None or len(new):
            order = np.argsort(np.concatenate([self.x, new]), kind="stable")
            g_new, runs_new = self.kept(new) if len(new) else (np.empty((0, len(self.w))), [])
            if old is None:
                old, self.runs = self.kept(self.x)
            self.g = np.concatenate([old, g_new])[order]
            runs = self.runs + runs_new
            self.runs = [runs[i] for i in order]
            self.ruling = np.concatenate([self.ruling, np.full(len(new), -1)])[order]
            self.corner = np.concatenate([self.corner, np.full(len(new), np.nan)])[order]
            self.x = np.concatenate([self.x, new])[order]
        where = np.searchsorted(self.x, x)
        self.corner[where[np.isfinite(corner)]] = corner[np.isfinite(corner)]

    def _corner_lines(self, corners: FloatArray, tolerance: float) -> tuple[FloatArray, FloatArray]:
        """The u and w of the line of the sheet nearest each corner, for the corners within
        ``tolerance`` of a line strictly between the rails (the nearest sampled line, then
        scipy's bounded scalar search between its neighbours)."""
        if len(corners) == 0:
            return np.empty(0), np.empty(0)
        start, end = self.ends(self.x)
        near = np.array([np.argmin(_to_lines(c, start, end)[0]) for c in corners])
        at, w = [], []
        for c, k in zip(corners, near, strict=True):
            lo, hi = self.x[max(k - 1, 0)], self.x[min(k + 1, len(self.x) - 1)]
            for _ in range(2):  # again once the pace passes through the exact partner there
                found = minimize_scalar(lambda x, c=c: _to_lines(c, *self.ends(np.array([x])))[0][0],
                                        bounds=(lo, hi), method="bounded", options={"xatol": 1e-12})
                self.pin(np.array([found.x]))
            d, t = _to_lines(c, *self.ends(np.array([found.x])))
            if d[0] <= tolerance and 0.0 < t[0] < 1.0:
                at.append(float(found.x))
                w.append(float(t[0]))
        return np.array(at), np.array(w)

    def _cut_points(self) -> FloatArray:
        """The two ends of each line's kept part (its outermost runs), (n, 2, 3); NaN where
        nothing of a line is kept."""
        out = np.full((len(self.x), 2, 3), np.nan)
        start, end = self.ends(self.x)
        for k, kept in enumerate(self.runs):
            if kept:
                w = np.array([kept[0][0], kept[-1][1]])[:, None]
                out[k] = start[k] + w * (end[k] - start[k])
        return out


class _Pace:
    """The partner parameter τ(x) between the strip's rulings: on each ruling interval the
    cubic spline through its samples (where it stays monotone, else the monotone PCHIP), so
    a fan's pace next to a torsal one does not ripple across the ruling between them."""

    def __init__(self, x: FloatArray, tau: FloatArray, rulings: FloatArray) -> None:
        self.rulings = rulings
        self.known: list[tuple[FloatArray, FloatArray]] = []  # per ruling interval: its x, τ
        self.pieces: list[Any] = []
        for lo, hi in itertools.pairwise(rulings):
            mine = (x >= lo) & (x <= hi)
            self.known.append((x[mine], tau[mine]))
            self.pieces.append(_monotone(x[mine], tau[mine]))

    def nodes(self) -> FloatArray:
        """Every x the pace passes through its τ at."""
        return np.concatenate([x for x, _ in self.known])

    def pinned(self, x: FloatArray, tau: FloatArray) -> _Pace:
        """This pace through (``x``, ``tau``) too (x between the rulings, none a node yet;
        each τ kept between its neighbours' so the pace stays monotone): a new pace, the
        intervals without a new node shared with this one."""
        out = copy.copy(self)
        out.known, out.pieces = list(self.known), list(self.pieces)
        which = np.clip(np.searchsorted(self.rulings, x, side="right") - 1, 0, len(self.pieces) - 1)
        for k in np.unique(which):
            xs, ys = self.known[k]
            add = which == k
            order = np.argsort(np.concatenate([xs, x[add]]), kind="stable")
            merged_x, merged = np.concatenate([xs, x[add]])[order], np.concatenate([ys, tau[add]])[order]
            old = (np.arange(len(order)) < len(xs))[order]
            low = np.maximum.accumulate(np.where(old, merged, -np.inf))
            high = np.minimum.accumulate(np.where(old, merged, np.inf)[::-1])[::-1]
            out.known[k] = (merged_x, np.clip(merged, low, high))
            out.pieces[k] = _monotone(*out.known[k])
        return out

    def __call__(self, x: ArrayLike, nu: int = 0) -> FloatArray:
        x = np.asarray(x, dtype=float)
        flat = np.atleast_1d(x)
        which = np.clip(np.searchsorted(self.rulings, flat, side="right") - 1, 0, len(self.pieces) - 1)
        out = np.empty(len(flat))
        for k in np.unique(which):
            mine = which == k
            out[mine] = self.pieces[k](flat[mine], nu)
        return out.reshape(x.shape) if x.ndim else out[0]


def _monotone(x: FloatArray, tau: FloatArray) -> BSpline | PchipInterpolator:
    """The cubic spline through (x, τ) where it stays monotone, else the monotone PCHIP."""
    spline = make_interp_spline(x, tau, k=min(3, len(x) - 1))
    check = np.linspace(x[0], x[-1], 8 * len(x))
    return spline if (np.diff(spline(check)) >= 0.0).all() else PchipInterpolator(x, tau)


def _to_lines(point: FloatArray, start: FloatArray, end: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The distance from ``point`` to each segment ``start → end``, and the share along it of
    the segment's point nearest it."""
    along = end - start
    t = np.einsum("ij,ij->i", point - start, along) / np.maximum(np.einsum("ij,ij->i", along, along), 1e-300)
    t = np.clip(t, 0.0, 1.0)
    return np.linalg.norm(start + t[:, None] * along - point, axis=1), t


def _smooth(x: FloatArray, w: FloatArray, knots: FloatArray, lengths: FloatArray, limit: float
            ) -> BSpline | PchipInterpolator:
    """A cubic in x fitted to ``w`` by least squares with knots at the strip's rulings
    (``knots``) inside ``x``'s range, through the two end values exactly: where the trim's
    line of cut lies across the sheet (no need to pass through the samples: every point of
    the sheet lies on a torsal line). Where that cubic strays more than ``limit`` from a cut
    point (``lengths``: the lines' lengths; a corner of the trim, or lines that sweep along
    it), the monotone cubic through the cut points instead (scipy's PCHIP: no overshoot)."""
    if len(x) < 6:
        return make_interp_spline(x, w, k=min(3, len(x) - 1))
    spline = _least_squares(x, w, knots)
    if float(np.max(np.abs(spline(x) - w) * lengths)) <= limit:
        return spline
    return PchipInterpolator(x, w)


def _least_squares(x: FloatArray, w: FloatArray, knots: FloatArray) -> BSpline:
    """The least-squares cubic of :func:`_smooth`."""
    inner = knots[(knots > x[0]) & (knots < x[-1])]
    inner = inner[(inner - x[0] > 1e-9) & (x[-1] - inner > 1e-9)]
    full = np.concatenate([[x[0]] * 4, inner, [x[-1]] * 4])
    try:
        spline = make_lsq_spline(x, w, full, k=3)
    except (ValueError, np.linalg.LinAlgError):
        return make_interp_spline(x, w, k=3)
    c = np.array(spline.c)
    c[0], c[-1] = w[0], w[-1]
    return BSpline(full, c, 3)


def _runs(g: FloatArray, w: FloatArray) -> list[tuple[float, float]]:
    """The intervals of w where the sampled ``g`` ≥ 0, its zeros interpolated linearly."""
    keep = g >= 0.0
    if not keep.any():
        return []
    change = np.flatnonzero(keep[1:] != keep[:-1])
    cuts = w[change] + (w[change + 1] - w[change]) * g[change] / (g[change] - g[change + 1])
    bounds = [w[0]] if keep[0] else []
    bounds += cuts.tolist()
    if keep[-1]:
        bounds.append(w[-1])
    return [(float(bounds[i]), float(bounds[i + 1])) for i in range(0, len(bounds) - 1, 2)]


def _columns(u: FloatArray) -> tuple[FloatArray, np.ndarray]:
    """:data:`PER_RULING` lines per ruling interval, the rulings' own u among them, and
    each one's ruling index (−1 between rulings)."""
    steps = np.linspace(0.0, 1.0, PER_RULING + 1)[:-1]
    x = np.concatenate([(u[:-1, None] + np.diff(u)[:, None] * steps).ravel(), u[-1:]])
    ruling = np.full(len(x), -1)
    ruling[::PER_RULING] = np.arange(len(u))
    return x, ruling


def _crossing(x0: float, x1: float, g0: float, g1: float) -> float:
    """Where a quantity sampled ``g0`` at ``x0`` and ``g1`` at ``x1`` (opposite signs) is 0."""
    return x0 + (x1 - x0) * g0 / (g0 - g1) if g0 != g1 else 0.5 * (x0 + x1)


def _lines_at(sheet: _Sheet, x: FloatArray, near: list[tuple[float, float]]) -> list[_Line]:
    """Lines at ``x`` (added ends and corners), each with its kept interval nearest the
    interval in ``near``; a line whose samples miss the trim keeps the point of it nearest
    inside (an interval of no length)."""
    if len(x) == 0:
        return []
    g, runs = sheet.kept(np.asarray(x, dtype=float))
    out = []
    for xi, row, kept, (lo, hi) in zip(x, g, runs, near, strict=True):
        if kept:
            a, b = min(kept, key=lambda iv: abs(0.5 * (iv[0] + iv[1]) - 0.5 * (lo + hi)))
        else:
            a = b = float(sheet.w[int(np.argmax(row))])
        out.append(_Line(float(xi), a, b, -1, float(row[0]), float(row[-1]), True))
    return out


def _runs_of_lines(sheet: _Sheet) -> list[list[_Line]]:
    """The runs of lines whose kept interval is one piece, each ended where its lines leave
    the trim (by interpolating the largest signed distance along the lines) when the
    neighbouring line is wholly outside."""
    x, ruling, g = sheet.x, sheet.ruling, sheet.g
    found = [_at_corner(kept, w) for kept, w in zip(sheet.runs, sheet.corner, strict=True)]
    most = g.max(axis=1)
    runs: list[list[_Line]] = []
    open_: list[list[_Line]] = []
    previous: list[tuple[float, float]] = []
    tips: list[tuple[list[_Line], float, bool]] = []  # run, x of its end, at its end (not start)
    for k, kept in enumerate(found):
        same = len(kept) == len(previous) and all(a[0] < b[1] and b[0] < a[1]
                                                   for a, b in zip(kept, previous, strict=True))
        corner = bool(np.isfinite(sheet.corner[k]))
        lines = [_Line(float(x[k]), lo, hi, int(ruling[k]), float(g[k, 0]), float(g[k, -1]),
                       bool(ruling[k] >= 0 or corner), corner) for lo, hi in kept]
        if same:
            for run, line in zip(open_, lines, strict=True):
                run.append(line)
        else:
            if not kept:
                tips += [(run, _crossing(x[k - 1], x[k], most[k - 1], most[k]), True) for run in open_]
            runs += open_
            open_ = [[line] for line in lines]
            if kept and not previous and k > 0:
                tips += [(run, _crossing(x[k - 1], x[k], most[k - 1], most[k]), False) for run in open_]
        previous = kept
    runs += open_
    for run in runs:
        run[0].kept = run[-1].kept = True
    added = _lines_at(sheet, np.array([t[1] for t in tips]),
                      [((run[-1] if ahead else run[0]).lo, (run[-1] if ahead else run[0]).hi)
                       for run, _, ahead in tips])
    # a line at an end shrinks to a point: the end line is taken where it is TIP of its
    # neighbour's length instead (a face needs lines of some length across to have normals)
    longest = [max(_kept(line) for line in run) for run, _, _ in tips]
    short = [k for k, line in enumerate(added) if _kept(line) < TIP * longest[k]]
    where = []
    for k in short:
        run, _, ahead = tips[k]
        edge, line = (run[-1] if ahead else run[0]), added[k]
        share = (TIP * longest[k] - _kept(line)) / max(_kept(edge) - _kept(line), 1e-300)
        where.append(line.x + (edge.x - line.x) * min(max(share, 0.0), 1.0))
    for toward in (0.0, 0.5, 0.8):  # a line still outside (a point): closer to the run's edge
        shift = [x + toward * ((tips[k][0][-1] if tips[k][2] else tips[k][0][0]).x - x)
                 for k, x in zip(short, where, strict=True)]
        moved = _lines_at(sheet, np.array(shift), [(added[k].lo, added[k].hi) for k in short])
        for k, line in zip(short, moved, strict=True):
            added[k] = line
        short_again = [i for i, k in enumerate(short) if _kept(added[k]) <= 0.0]
        short, where = [short[i] for i in short_again], [where[i] for i in short_again]
        if not short:
            break
    for (run, _, ahead), line in zip(tips, added, strict=True):
        edge = run[-1] if ahead else run[0]
        if _kept(line) > 0.0 and (line.x - edge.x) * (1 if ahead else -1) > 0.0:  # (a point: none)
            run.append(line) if ahead else run.insert(0, line)
            edge.kept = edge.ruling >= 0  # the end is the new line (a ruling stays one)
    return [run for run in runs if len(run) >= 2]


def _at_corner(kept: list[tuple[float, float]], w: float) -> list[tuple[float, float]]:
    """``kept`` with the end nearest ``w`` (a corner of the trim on this line) moved to it,
    when that end is within two samples of it (otherwise the corner is not this line's)."""
    if not kept or not np.isfinite(w):
        return kept
    ends = np.array(kept, dtype=float)
    i, j = np.unravel_index(np.argmin(np.abs(ends - w)), ends.shape)
    if abs(ends[i, j] - w) > 2.0 / (ACROSS - 1):
        return kept
    ends[i, j] = w
    return [(float(a), float(b)) for a, b in ends if b > a]


def _kept(line: _Line) -> float:
    return line.hi - line.lo


def _corners(sheet: _Sheet, run: list[_Line]) -> list[_Line]:
    """``run`` with a line added wherever one of its edges turns from a rail onto the trim
    or back (where the signed distance at the rail crosses 0, :meth:`_Sheet.turn`)."""
    where: list[float] = []
    near: list[tuple[float, float]] = []
    sides: list[bool] = []
    for before, after in itertools.pairwise(run):
        for upper in (False, True):
            if _on_rail(before, upper) == _on_rail(after, upper):
                continue
            g0, g1 = (before.g1, after.g1) if upper else (before.g0, after.g0)
            if g0 * g1 > 0.0:
                continue
            where.append(sheet.turn(before.x, after.x, g0, g1, upper))
            near.append((before.lo, before.hi) if _on_rail(before, upper) else (after.lo, after.hi))
            sides.append(upper)
    added = _lines_at(sheet, np.array(where), near)
    for line, upper in zip(added, sides, strict=True):
        if upper:
            line.hi = 1.0
        else:
            line.lo = 0.0
    out = sorted(run + added, key=lambda line: line.x)
    return [line for k, line in enumerate(out) if k == 0 or line.x > out[k - 1].x]


def _on_rail(line: _Line, upper: bool) -> bool:
    return line.hi >= 1.0 - 1e-12 if upper else line.lo <= 1e-12


def _chain(sheet: _Sheet, run: list[_Line], upper: bool, limit: float) -> tuple[Chain, FloatArray]:
    """One edge of a cut strip (``upper``: the B side) as a :class:`Chain` run at the pace of
    the sheet's u: stretches of the strip's own rail (w = 0 or 1 exactly, so neighbours
    still share their boundary) and of the trim (w a cubic in u through the cut, one from
    each corner of the trim to the next); and each
    line's parameter on it. Both edges run at the same pace, so at any parameter the strip
    joins two points of one line of the sheet: torsal between the rulings too. ``limit``:
    how far a stretch along the trim may stray from the cut points (:func:`_smooth`)."""
    x = np.array([line.x for line in run])
    start, end = sheet.ends(x)
    lengths = np.linalg.norm(end - start, axis=1)
    w = np.array([line.hi if upper else line.lo for line in run])
    rail = np.array([_on_rail(line, upper) for line in run])
    along = rail[:-1] & rail[1:]  # each interval between lines: along the rail, else the trim
    pieces: list[tuple[Curve, float, float]] = []
    first = 0
    while first < len(run) - 1:
        last = first + 1
        while last < len(run) - 1 and along[last] == along[first] and not run[last].corner:
            last += 1
        span = slice(first, last + 1)
        across = (_Constant(1.0 if upper else 0.0) if along[first]
                  else _smooth(x[span], w[span], sheet.u, lengths[span], limit))
        pieces.append((_OnSheet(sheet.a, sheet.b, sheet.tau, across), float(x[first]), float(x[last])))
        first = last
    chain = Chain(pieces)
    return chain, (x - x[0]) / (x[-1] - x[0])


class _Constant:
    """A constant w along a rail (0 on A, 1 on B), called as a scipy spline is."""

    def __init__(self, value: float) -> None:
        self.value = value

    def __call__(self, x: FloatArray, nu: int = 0) -> FloatArray:
        return np.full(np.shape(x), self.value if nu == 0 else 0.0)


def cut_strip(strip: Strip, inside: Callable[[FloatArray], FloatArray], design: Surface,
              tolerance: float, corners: FloatArray | None = None) -> list[Strip]:
    """``strip`` cut to where ``inside`` ≥ 0 (see the module): none, one or several strips.
    ``corners``: the trim's corners, points on the design (:func:`sharp_corners`), where
    the cut keeps a corner of the trim rather than rounding it."""
    sheet = _Sheet(strip, inside)
    sheet.sample(np.empty((0, 3)) if corners is None else corners, tolerance)
    pieces = []
    for run in _runs_of_lines(sheet):
        run = _corners(sheet, run)
        keep = np.array([line.kept for line in run])
        try:
            lower, s = _chain(sheet, run, False, FIT * tolerance)
            upper, _ = _chain(sheet, run, True, FIT * tolerance)
            breaks = np.concatenate([s[keep], lower.knots, upper.knots])
            lower, upper, s = by_length(lower, upper, s, breaks, sheet.ramps, run[0].x, run[-1].x)
            t = s
            surface = _ruled(lower, upper, s[keep])
        except ValueError:  # a run too short to make a strip of
            continue
        starts, ends = surface.ruling_lines[:, 0], surface.ruling_lines[:, 1]
        run = [line for line in run if line.kept]
        pieces.append(_strip(strip, run, surface, lower, upper, s[keep], t[keep], starts, ends, design,
                             tolerance, sheet.ramps))
    return pieces


def _ruled(lower: Curve, upper: Curve, at: FloatArray) -> RuledSurface:
    """The strip between two edges run at one pace (:func:`~.cut_pace.by_length`), its rulings at ``at``:
    the rails are the chains themselves at their own parameters (a ruling's parameter is
    its chain parameter), so between rulings the strip joins the two points of one line of
    the sheet, as it does at them."""
    if len(at) < 2 or not (np.diff(at) > 0.0).all():
        raise ValueError("a cut strip needs two rulings or more, in order")
    surface = RuledSurface(CurveRail(lower, at, at), CurveRail(upper, at, at))
    surface.ruling_parameters = np.asarray(at, dtype=float)
    surface.ruling_lines = np.stack([lower.point_at(at), upper.point_at(at)], axis=1)
    return surface


def _strip(strip: Strip, run: list[_Line], surface: RuledSurface, a: Curve, b: Curve, s: FloatArray,
           t: FloatArray, starts: FloatArray, ends: FloatArray, design: Surface, tolerance: float,
           ramps: FloatArray) -> Strip:
    own = strip.result
    index = np.array([line.ruling for line in run])
    station = index >= 0
    fan = np.zeros(len(run), dtype=bool)
    fan[station] = own.fan[index[station]]
    # a line on a ramp of the pace (a corner where an edge turns onto the trim as the cone
    # there sweeps the rail, :mod:`.cut_pace`) runs through the cone's apex: a fan's ruling
    x = np.array([line.x for line in run])[:, None]
    fan |= ((x > ramps[None, :, 0]) & (x < ramps[None, :, 1])).any(axis=1)
    stations = np.zeros(len(run), dtype=bool)
    stations[station] = own.stations[index[station]]
    warp = np.asarray(curve_warp(a, b, s, t, starts, ends), dtype=float)
    areas = patch_areas(starts, ends)
    total = float(areas.sum()) or 1.0
    # creasing where the sheet folds, not by shared apexes (a ramp's line shares none: cut_pace)
    folded = sheet_folds(surface.curve_a, surface.curve_b, s, starts, ends).creases(fan, 1e-7, starts, ends)
    creased = float(areas[creased_runs(fan[:-1] | fan[1:], folded)].sum()) / total
    shared = fan[:-1] & fan[1:]
    result = RulingResult(s, t, starts, ends, warp, warp.copy(), np.isfinite(warp) & (warp <= 1e-7), None,
                          stations, fan, float(areas[shared].sum()) / total, creased)
    deviation = certified_deviation(design, surface, tolerance)
    return Strip(float(run[0].x), float(run[-1].x), result, surface, warp, deviation.bound, deviation.where)


def rationalise_trimmed(design: TrimmedSurface, tolerance: float, *args: Any, **options: Any
                        ) -> Rationalisation:
    """Strips within ``tolerance`` of a trimmed design, inside its trim (see the module);
    the other arguments as :func:`~torsal.nodes.geometry.developable.rationalise.rationalise`."""
    patch = patch_of(design)
    # the box's edges lie outside the trim: the strips are cut by the trim, not by them
    base = rationalise(patch, tolerance, *args, cut_at_edge=False, **options)
    inside = signed_inside(design, patch, REACH * tolerance)
    corners = trim_corners(design, REACH * tolerance)
    strips: list[Strip] = []
    narrow: list[int] = []
    for k, strip in enumerate(base.strips):
        cut = cut_strip(strip, inside, patch, tolerance, corners)
        for piece in cut:
            checked_densely(patch, piece)
        if k in base.narrow:
            narrow += list(range(len(strips), len(strips) + len(cut)))
        strips += cut
    if not strips:
        raise ValueError("no strip lies inside the trim: the trim loops are too small for the tolerance")
    points = trim_points(design)
    gaps = distances_to_strips(points, [s.surface for s in strips])
    return Rationalisation(base.family, strips, base.boundaries, float(tolerance), narrow, points, gaps,
                           base.creases)
