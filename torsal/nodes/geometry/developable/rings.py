"""A region of a design whose strips ring a centre along lines of curvature (D-strips).

Round a bump the lines of curvature of one family ring its top (on a surface of
revolution: the parallels), and the rulings of a strip between two of them run along the
other family (the meridians). Such a strip never creases (:mod:`.curvature_lines`),
where strips between parameter lines from edge to edge do wherever those lines cross an
asymptotic direction (the double bump's y = ±3, docs/geometry.md).

:class:`RingPatch` is the design reparameterised so that its parameter lines along u are
those rings: at (s, t) the plan point c + R(t, θ)·(cos θ, sin θ), θ = θ0 + s·(θ1 − θ0),
R(t, ·) the ring traced from the seed radius r0 + t·(r1 − r0) on one ray (a bicubic
spline through the traced radii, scipy's ``RectBivariateSpline``), mapped to the
design's (u, v) by the plan's scale (:func:`~.curvature_lines.plan_scale`) and evaluated
on the design continued past its edges (:class:`~.outline_cut.ExtendedSurface`). Its
derivatives come from the spline's and the design's by the chain rule, so every
developable tool that marches parameter lines (:func:`~.rationalise._cover`) marches
rings on it; the strips are then cut to the region (:func:`region_inside`,
:func:`~.trimmed.cut_strip`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import shapely
from numpy.typing import ArrayLike
from scipy.interpolate import BSpline, RectBivariateSpline, make_interp_spline

from ..array_types import FloatArray
from ..curve_base import Curve
from ..curve_rail import ruled_between
from ..surface_base import Surface, broadcast_uv
from ..watch import watch_check
from .curvature_lines import trace_rings
from .guided import IsoBoundaries
from .outline_cut import ExtendedSurface
from .rationalise import AIM, CLOSE, TRIALS, Strip
from .ruling import ruling_developable
from .trim_region import sharp_corners
from .trimmed import cut_strip

#: A strip's trials stop once the widest width within the tolerance and the narrowest too
#: wide are this share of the former apart ...
SETTLE = 0.03
#: ... and with both known, a trial lies at least this share of the gap from either.
INSIDE = 0.2


#: Samples per ruling interval, and across, of an uncut trial strip whose distance from the
#: design where the region keeps it judges the trial first (:func:`_estimate`).
ESTIMATE = (4, 9)
#: Cuts of widths the estimates settle on, per strip, before the trials are judged by cuts.
ATTEMPTS = 3

#: Points of a ring (about four per traced angle of :class:`RingPatch`) that its quintic
#: passes through (:class:`Ring`).
RING_SAMPLES = 641


class Ring(Curve):
    """A ring of a :class:`RingPatch` as the quintic B-spline through :data:`RING_SAMPLES`
    of its points (scipy's ``make_interp_spline``): within 1e-9 of the patch's line where
    it runs over the design (3e-6 of a 20 m design where it runs over the design's
    continuation, whose derivatives turn at the design's edge), C⁴, so one smooth span to
    the tools that sample spans. The march (:func:`march_rings`) evaluates its rings
    thousands of times, a few points at a time; through the patch each call costs the
    spline of radii's six derivatives, the design's and the chain rule."""

    def __init__(self, spline: BSpline) -> None:
        self.spline = spline

    def derivatives(self, t: ArrayLike, order: int = 1) -> list[FloatArray]:
        t = np.atleast_1d(np.asarray(t, dtype=float)).ravel()
        return [self.spline(t, nu=k) for k in range(order + 1)]


class _Rings:
    """A patch's rings as boundaries (as :class:`~.guided.IsoBoundaries` of the patch along
    u), each level's :meth:`RingPatch.ring`."""

    def __init__(self, patch: RingPatch) -> None:
        self.patch = patch

    def at(self, level: float) -> Curve:
        return self.patch.ring(level)


class RingPatch(Surface):
    """The design on rings of curvature round ``centre`` (a plan point): u runs round
    them over the angles ``span`` (θ0, θ1), v across them from the ring through the seed
    radius ``seeds[0]`` to the one through ``seeds[-1]`` on the ray at angle ``start``."""

    def __init__(self, design: Surface, centre: ArrayLike, scale: ArrayLike, seeds: ArrayLike,
                 span: tuple[float, float], family: int, start: float, samples: int = 161) -> None:
        self.design = design
        self.extended = ExtendedSurface(design)
        self.centre = np.asarray(centre, dtype=float)
        self.scale = np.asarray(scale, dtype=float)
        self.span = (float(span[0]), float(span[1]))
        seeds = np.asarray(seeds, dtype=float)
        theta = np.linspace(*self.span, samples)
        radii = trace_rings(design, self.centre, seeds, theta, family, self.scale, start)
        levels = (seeds - seeds[0]) / (seeds[-1] - seeds[0])
        self.radius = RectBivariateSpline(levels, theta, radii, kx=3, ky=3)
        self._rings: dict[float, Ring] = {}

    def ring(self, level: float) -> Ring:
        """The ring at ``level`` (the parameter line along u) as a :class:`Ring`, made once
        per level: strips on both sides of it share the one curve."""
        level = float(level)
        found = self._rings.get(level)
        if found is None:
            t = np.linspace(0.0, 1.0, RING_SAMPLES)
            points = self.point_at(t, np.full(len(t), level))
            found = self._rings[level] = Ring(make_interp_spline(t, points, k=5))
        return found

    def __repr__(self) -> str:
        return f"RingPatch({self.design!r}, centre={self.centre.tolist()})"

    def plan(self, s: ArrayLike, t: ArrayLike, order: int = 0) -> list[FloatArray]:
        """Plan points at (s, t) and their derivatives to ``order`` (as :meth:`derivatives`)."""
        s, t = broadcast_uv(s, t)
        span = self.span[1] - self.span[0]
        theta = self.span[0] + s * span
        c, n = np.cos(theta)[:, None], np.sin(theta)[:, None]
        radial, angular = np.hstack([c, n]), np.hstack([-n, c])

        def r(dt: int, dth: int) -> FloatArray:
            return self.radius.ev(t, theta, dx=dt, dy=dth)[:, None]

        r0 = r(0, 0)
        out = [self.centre + r0 * radial]
        if order >= 1:
            r_th, r_t = r(0, 1), r(1, 0)
            out += [span * (r_th * radial + r0 * angular), r_t * radial]
        if order >= 2:
            out += [span * span * ((r(0, 2) - r0) * radial + 2.0 * r_th * angular),
                    span * (r(1, 1) * radial + r_t * angular), r(2, 0) * radial]
        return out

    def derivatives(self, u: ArrayLike, v: ArrayLike, order: int = 1) -> list[FloatArray]:
        self._check_order(order)
        p = [q / self.scale for q in self.plan(u, v, order)]  # the design's (u, v) and its derivatives
        d = self.extended.derivatives(p[0][:, 0], p[0][:, 1], order)
        out = [d[0]]
        if order == 0:
            return out

        def first(q: FloatArray) -> FloatArray:
            return q[:, :1] * d[1] + q[:, 1:] * d[2]

        out += [first(p[1]), first(p[2])]
        if order == 1:
            return out

        def second(a: FloatArray, b: FloatArray, ab: FloatArray) -> FloatArray:
            return (a[:, :1] * b[:, :1] * d[3] + (a[:, :1] * b[:, 1:] + a[:, 1:] * b[:, :1]) * d[4]
                    + a[:, 1:] * b[:, 1:] * d[5] + first(ab))

        return [*out, second(p[1], p[1], p[3]), second(p[1], p[2], p[4]), second(p[2], p[2], p[5])]


class RegionInside:
    """Points' signed distance from a region of a design's plan (see :func:`region_inside`),
    called as a function; :meth:`measured` gives their distance from the design too, from
    the same projection."""

    def __init__(self, design: Surface, region: shapely.Polygon, scale: ArrayLike, margin: float) -> None:
        self.design, self.region, self.margin = design, region, float(margin)
        self.scale = np.asarray(scale, dtype=float)

    def __call__(self, points: FloatArray) -> FloatArray:
        return self.measured(points)[0]

    def measured(self, points: FloatArray) -> tuple[FloatArray, FloatArray]:
        """The points' signed distance from the region and their distance from the design
        (the latter meaningful where the former is ≥ 0: a point beyond the design's edge
        is measured to the edge)."""
        found = self.design.closest_point(points, candidates=1, tolerance=1e-9).parameters
        p, su, sv = self.design.derivatives(found[:, 0], found[:, 1], 1)
        off = points - p
        e, f, g = (np.einsum("ij,ij->i", a, b) for a, b in ((su, su), (su, sv), (sv, sv)))
        a, b = np.einsum("ij,ij->i", su, off), np.einsum("ij,ij->i", sv, off)
        det = e * g - f * f
        plan = (found + np.column_stack([(g * a - f * b) / det, (e * b - f * a) / det])) * self.scale
        signed = np.minimum(_signed(self.region, plan) + self.margin, _signed_box(plan, self.scale))
        return signed, np.linalg.norm(off, axis=1)


def _signed_box(plan: FloatArray, scale: FloatArray) -> FloatArray:
    """Signed distance from the design's plan, a rectangle (closed form), positive inside."""
    out = np.maximum(-plan, plan - scale)  # how far past the nearer edge, per axis
    most = out.max(axis=1)
    return np.where(most <= 0.0, -most, -np.hypot(*np.maximum(out, 0.0).T))


def _signed(polygon: shapely.Polygon, plan: FloatArray) -> FloatArray:
    distance = shapely.distance(polygon.boundary, shapely.points(plan))
    return np.where(shapely.contains_xy(polygon, plan[:, 0], plan[:, 1]), distance, -distance)


def region_inside(design: Surface, region: shapely.Polygon, scale: ArrayLike, margin: float = 0.0
                  ) -> RegionInside:
    """Points' signed distance from ``region`` (a polygon in the design's plan), positive
    inside: ``margin`` beyond it where it lies inside the design (so neighbouring regions'
    strips overlap rather than leave a gap), none beyond the design's own edges. Each point
    is projected onto the design itself (not a patch of it, so a ring patch's overlaps do
    not matter); a point beyond the design's edge projects onto the edge, and the part of
    its offset along the design there is added (the first fundamental form solved)."""
    return RegionInside(design, region, scale, margin)


def region_corners(design: Surface, region: shapely.Polygon, scale: ArrayLike, margin: float = 0.0
                   ) -> FloatArray:
    """The corners (3D points on the design) of what :func:`region_inside` keeps with the
    same ``margin``: ``region`` grown by it (its convex corners rounded), within the design."""
    scale = np.asarray(scale, dtype=float)
    kept = region.buffer(margin, quad_segs=32) if margin > 0.0 else region
    plan = sharp_corners(kept.intersection(shapely.box(0.0, 0.0, *scale)))
    if len(plan) == 0:
        return np.empty((0, 3))
    uv = np.clip(plan / scale, 0.0, 1.0)
    return design.point_at(uv[:, 0], uv[:, 1])


def _whole(boundaries: _Rings | IsoBoundaries, lo: float, hi: float, segments: int, warp_tolerance: float
           ) -> Strip | None:
    """The strip between the rings at levels ``lo`` and ``hi``, uncut; None when it cannot
    be made."""
    check = watch_check()
    if check:
        check()
    a, b = boundaries.at(lo), boundaries.at(hi)
    try:
        result = ruling_developable(a, b, segments, warp_tolerance)
        surface = ruled_between(a, result.s, b, result.t)
    except ValueError:
        return None
    return Strip(lo, hi, result, surface, np.zeros(len(result.s)), 0.0, np.zeros(3))


def _cut(whole: Strip, design: Surface, inside: Callable[[FloatArray], FloatArray], tolerance: float,
         corners: FloatArray | None = None) -> list[Strip]:
    """``whole`` cut to the region, its pieces certified against the design itself."""
    pieces = cut_strip(whole, inside, design, tolerance, corners)
    for piece in pieces:  # each between the rings at lo and hi (:mod:`.ring_boundaries`)
        piece.lo, piece.hi = whole.lo, whole.hi
    return pieces


def _pieces(design: Surface, boundaries: _Rings | IsoBoundaries, lo: float, hi: float,
            inside: Callable[[FloatArray], FloatArray], tolerance: float, segments: int,
            warp_tolerance: float, corners: FloatArray | None = None) -> list[Strip] | None:
    """The strip between the rings at levels ``lo`` and ``hi``, cut to the region, its
    pieces certified against the design itself; None when it cannot be made."""
    whole = _whole(boundaries, lo, hi, segments, warp_tolerance)
    return None if whole is None else _cut(whole, design, inside, tolerance, corners)


def _estimate(whole: Strip, inside: RegionInside) -> float:
    """The largest distance from the design of the uncut strip ``whole`` at samples the
    region keeps (:data:`ESTIMATE` per ruling interval and across; 0 where it keeps none):
    what its cut pieces' certified deviation comes to, to within the samples' spacing,
    from one projection of a few thousand points instead of a cut."""
    surface = whole.surface
    u = np.asarray(surface.ruling_parameters, dtype=float)
    steps = np.linspace(0.0, 1.0, ESTIMATE[0] + 1)[:-1]
    along = np.concatenate([(u[:-1, None] + np.diff(u)[:, None] * steps).ravel(), u[-1:]])
    s, t = np.meshgrid(along, np.linspace(0.0, 1.0, ESTIMATE[1]), indexing="ij")
    signed, distance = inside.measured(surface.point_at(s.ravel(), t.ravel()))
    kept = signed >= 0.0
    return float(distance[kept].max()) if kept.any() else 0.0


def _next_width(w: float, deviation: float, tolerance: float, floor: float | None, floor_dev: float,
                bad: float, bad_dev: float, room: float, before: tuple[float, float] | None = None
                ) -> float | None:
    """The next trial width of :func:`march_rings` after width ``w`` gave ``deviation`` (NaN:
    no strip), or None when the trials are done: between the widest width within the
    tolerance (``floor``, its ``floor_dev``; None: none yet) and the narrowest too wide
    (``bad``, its ``bad_dev``; 2: none yet), ``room`` the most there is. With both known,
    the square law through both (a secant of √deviation), kept :data:`INSIDE` of the gap
    from either end, and done when the gap is within :data:`SETTLE` of the floor (a
    deviation that jumps with the width, a cut that gains or loses a piece, has no width at
    :data:`AIM` of the tolerance to close in on). With one side known, the square law from
    the last trial, or where the trial ``before`` it (its width and deviation) shows the
    deviation growing more slowly than that (a cut strip's deviation set by its cut edge,
    not its width), the secant of √deviation through the two, at most twice ``w``."""
    low = floor if floor is not None else 0.0
    top = min(bad, room)
    target = np.sqrt(AIM * tolerance)
    if floor is not None and bad <= room:
        gap = bad - low
        if gap <= SETTLE * low:
            return None
        a, b = np.sqrt(floor_dev), np.sqrt(bad_dev)
        share = (target - a) / (b - a) if np.isfinite(b) and b > a else 0.5
        return low + gap * float(np.clip(share, INSIDE, 1.0 - INSIDE))
    if not np.isfinite(deviation):
        return 0.5 * (low + top)
    ratio = np.sqrt(AIM * tolerance / deviation) if deviation > 0.0 else 2.0
    w_new = w * float(np.clip(ratio, 0.25, 2.0))
    if before is not None and np.isfinite(before[1]) and deviation < AIM * tolerance and w > before[0]:
        slope = (np.sqrt(deviation) - np.sqrt(before[1])) / (w - before[0])
        if slope > 0.0:
            w_new = max(w_new, min(w + (target - np.sqrt(deviation)) / slope, 2.0 * w))
    if not low < w_new < bad:
        w_new = 0.5 * (low + top)
    return min(w_new, room)


def march_rings(
    design: Surface, patch: RingPatch, inside: RegionInside, tolerance: float,
    segments: int = 24, warp_tolerance: float = 1e-7, max_strips: int = 64, first_width: float = 0.05,
    corners: FloatArray | None = None,
) -> tuple[list[Strip], float]:
    """Strips between rings of ``patch`` from its level 0 to 1, each as wide as the
    tolerance allows once cut to the region (``inside``): a few trials per strip, the width
    by the square law (deviation ∝ width²) inside the bracket of widths found too wide and
    within (:func:`_next_width`). The trials are judged first by the uncut strip's
    distance at samples the region keeps (:func:`_estimate`, a tenth of a cut's cost); the
    width they settle on is then cut and certified. Where its pieces are beyond the
    tolerance (a cut adds a cone where its pairing jumps, which the uncut strip has not)
    the estimates are held to the share of the tolerance they fell short by and the
    trials go on, up to :data:`ATTEMPTS` cuts; then judged by their cut pieces' certified
    deviation (the rings run on outside the region, where they are no lines of curvature
    of it).
    ``corners``: the region's corners (:func:`region_corners`), which the cut keeps.
    Returns the pieces and the largest deviation of a strip that had to be kept beyond the
    tolerance (0 when none)."""
    boundaries = _Rings(patch)
    out: list[Strip] = []
    lo, width, worst = 0.0, first_width, 0.0

    def estimated(hi: float) -> tuple[float, Strip | None]:
        whole = _whole(boundaries, lo, hi, segments, warp_tolerance)
        return (np.nan, None) if whole is None else (_estimate(whole, inside), whole)

    def certified(hi: float) -> tuple[float, list[Strip] | None]:
        pieces = _pieces(design, boundaries, lo, hi, inside, tolerance, segments, warp_tolerance, corners)
        return (np.nan, None) if pieces is None else (max((p.deviation for p in pieces), default=0.0), pieces)

    for _ in range(max_strips):
        if lo >= 1.0:
            break
        found: tuple[float, list[Strip]] | None = None
        bad, bad_dev, start, budget = 2.0, np.nan, width, tolerance
        for _attempt in range(ATTEMPTS):
            chosen, estimate, _ = _search(lo, start, estimated, budget, bad)
            if chosen is None:
                break
            pieces = _cut(chosen[1], design, inside, tolerance, corners)
            deviation = max((p.deviation for p in pieces), default=0.0)
            if deviation <= tolerance:
                found = (chosen[0], pieces)
                break
            # the estimate fell short: narrower, the estimates held to what this cut says
            # they fall short by
            w = chosen[0] - lo
            bad, bad_dev = w, deviation
            start = _next_width(w, deviation, tolerance, None, 0.0, bad, bad_dev, 1.0 - lo) or 0.5 * w
            budget = budget * min(estimate / deviation, 0.99) if estimate > 0.0 else 0.5 * budget
        if found is None:  # judged by the cut pieces from there
            good, _, tried = _search(lo, start, certified, tolerance, bad, bad_dev)
            if good is None:  # the narrowest tried, beyond the tolerance (said by its deviation)
                if tried is None:
                    raise ValueError("no strip between the rings could be made")
                good = (tried[0], tried[1])
                worst = max(worst, tried[2])
            found = good
        out += found[1]
        width = found[0] - lo
        lo = found[0]
    if lo < 1.0:
        raise ValueError(f"the rings need more than {max_strips} strips")
    return out, worst


def _search(lo: float, width: float, measure: Callable[[float], tuple[float, Any]], tolerance: float,
            bad: float = 2.0, bad_dev: float = np.nan
            ) -> tuple[tuple[float, Any] | None, float, tuple[float, Any, float] | None]:
    """The trials of one strip of :func:`march_rings` from level ``lo``, the first ``width``
    wide (below ``bad``, a width known too wide by ``bad_dev``; 2: none), each judged by
    ``measure(hi)`` (its deviation, NaN when no strip, and what it made): the widest within
    the tolerance (its level and what it made; None when none) and its deviation, and the
    narrowest tried (level, what it made, deviation; None when none)."""
    good: tuple[float, Any] | None = None
    good_dev = 0.0
    w = min(width, 1.0 - lo)
    tried: tuple[float, Any, float] | None = None
    before: tuple[float, float] | None = None
    for _trial in range(TRIALS * 2):
        hi = min(1.0, lo + w)
        deviation, made = measure(hi)
        if made is not None:
            tried = (hi, made, deviation) if tried is None or w < tried[0] - lo else tried
        if made is not None and deviation <= tolerance:
            if good is None or hi > good[0]:
                good, good_dev = (hi, made), deviation
            if hi >= 1.0 or deviation >= CLOSE * tolerance:
                break
        elif w < bad:
            bad, bad_dev = w, deviation
        following = _next_width(w, deviation, tolerance, (good[0] - lo) if good else None, good_dev, bad,
                                bad_dev, 1.0 - lo, before)
        if following is None or following <= 1e-6:
            break
        before, w = (w, deviation), following
    return good, good_dev, tried
