"""Rationalising a freeform design into developable strips (developable.Rationalise).

Method
------
1. Direction. A strip's rulings are straight, so a ruling deviates least from the
   design where the design bends least along it: the rulings should run along the
   direction of least normal curvature and the strips' boundary curves across it.
   The boundaries follow the design's parameter lines: of the two families, first the
   one that needs fewer strips by the square law (see :func:`boundary_family`: normal
   curvature along the rulings and the extent the strips are stacked over) — unless its
   lines cross the design's asymptotic directions (where no torsal strip joins two
   neighbours) much more than the other's (:mod:`.asymptotic`: on a monkey saddle every
   line along x crosses one, the lines along y none), then the other first, and a family
   that crosses them where the other does not (:data:`ALONG`) is not tried; when its
   strips crease the sheet (more than :data:`SMOOTH` of their area in creasing fans,
   where the lines run along an asymptotic direction), the other family too, and the
   better is kept (:func:`_score`), lifted (step 2) or, when the lift creases more, on
   the design. A guide vector instead picks the family whose
   tangents run most nearly along it (the strips follow the guide), and guides give
   the blended family of :mod:`.guided`.
2. Lift. Without guides or a direction, the boundaries are lifted off the design by up
   to 0.8 of the tolerance, against the side the rulings sag to (:mod:`.offset`): the
   strips then deviate to both sides of the design and may be about √1.8 as wide, so
   the design needs about three quarters as many strips as with boundaries on it.
3. Strips. Between two neighbouring boundaries the strip is RulingDevelopable's
   (:func:`~torsal.nodes.geometry.developable.ruling_developable`): certified torsal rulings,
   flat fans where none exist, and its Surface is
   :func:`~torsal.nodes.geometry.curve_rail.ruled_between`, whose edges run on the boundary
   curves themselves — so two neighbours share their boundary exactly. Where its rulings
   cross the boundaries obliquely its ends would be cones through a boundary's end point
   (a fifth of a saddle turned to its outline); the strip is then run on past the
   design's edge and cut by it (:mod:`.outline_cut`): torsal to its ends, which follow the edge.
   A cut end deviates more than its cone (its rulings run on to the edge instead of
   bending to a boundary's end point), so where strips as wide as their cones allow keep
   more than :data:`RECUT` of their area in cones after cutting, the family is marched
   again with every trial strip cut (:func:`_recut`): narrower strips, smooth to the edge.
   In that march a strip that creases (its boundaries on either side of a line along an
   asymptotic direction, all flat fans) is kept about as narrow as the crease needs
   (:func:`_narrow_crease`) instead of as wide as the tolerance allows.
4. Placement. Marching from one edge of the design, each next boundary is placed so
   that the strip is as wide as the tolerance allows: a few trial strips, the width
   guessed from the square law (a straight ruling's sag grows as the width²) and kept
   inside the bracket of widths found too wide and within. A strip's deviation is
   certified (:mod:`.certify`): samples refined until the bound between them is within
   1 % of the tolerance, and the design's edge at the strip's two ends measured too. Where
   the tolerance would need strips narrower than ``min_width`` they are made that wide
   and listed. When more than ``max_strips`` would be needed, the design is instead
   split into ``max_strips`` evenly spaced strips, and the result reports the deviation
   reached.

Where both families of parameter lines cross asymptotic directions, strips between traced
lines of curvature that ring each of the design's bumps are tried first, by the caller
(:mod:`.freeform`). Here the boundaries are not traced along lines of curvature:
a family that follows them leaves the design through its sides; the strips'
ends are cut by the design's outline (:mod:`.outline_cut`, the D-strip models of Pottmann et
al. 2008), but a boundary that itself runs out through a side is not made. A field fitted
to the curvature directions but held to the design's edges (the level sets of one
function, tried) bent away from them near the edges and creased more than the parameter
lines on the test designs. Where a boundary runs along an asymptotic direction (a wave's
inflection) the strip still creases there.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace

import numpy as np
from numpy.typing import ArrayLike

from torsal.nodes.geometry.array_types import FloatArray
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curve_rail import ruled_between
from torsal.nodes.geometry.developable.asymptotic import asymptotic_crossings
from torsal.nodes.geometry.developable.certify import certified_deviation, crease_angle, end_gaps, uncovered
from torsal.nodes.geometry.developable.fans import patch_areas
from torsal.nodes.geometry.developable.guided import GuidedBoundaries, IsoBoundaries, guided_boundaries
from torsal.nodes.geometry.developable.last_strip import last_two
from torsal.nodes.geometry.developable.offset import LiftedBoundaries, lift_for
from torsal.nodes.geometry.developable.outline_cut import trim_ends
from torsal.nodes.geometry.developable.ruling import RulingResult, ruling_developable
from torsal.nodes.geometry.developable.strip_width import width_across
from torsal.nodes.geometry.developable.warp import curve_warp
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.geometry.surface_base import Surface, uv_grid
from torsal.nodes.geometry.watch import watch_check

#: The boundaries of a rationalisation: a curve on the design for every level in [0, 1].
Boundaries = IsoBoundaries | GuidedBoundaries | LiftedBoundaries

#: Dense samples per strip for its deviation: along the boundaries x across the strip.
DEVIATION_SAMPLES = (41, 7)


@dataclass
class Strip:
    """One strip between the boundaries at levels ``lo`` < ``hi`` (see :mod:`.guided`)."""

    lo: float
    hi: float
    result: RulingResult
    surface: RuledSurface
    warp: FloatArray  #: per ruling, recomputed from the curves' exact tangents (NaN undefined)
    #: certified largest distance from the design (:mod:`.certify`), and of the design's edge
    #: at the strip's two ends from the strip
    deviation: float
    where: FloatArray  #: (3,) the strip's point farthest from the design (of its samples)
    #: each ruling's parameter on the lower and the upper boundary (NaN where a ruling ends
    #: on a trim at the design's edge, :mod:`.outline_cut`)
    on_lower: FloatArray | None = None
    on_upper: FloatArray | None = None

    @property
    def width(self) -> float:
        """The strip's width across, between its two edges (:mod:`.strip_width`; its
        rulings may run nearly along them)."""
        return width_across(self.surface.curve_a, self.surface.curve_b)


@dataclass
class Rationalisation:
    """The strips in order across the design, their boundary curves and how far they are."""

    family: str  #: "u": the boundaries are isocurves running along u (fixed v), else along v
    strips: list[Strip]
    boundaries: list[Curve]  #: len(strips) + 1 curves; strip i lies between i and i + 1
    tolerance: float
    #: the strips that had to be made MinWidth wide though the tolerance asked for narrower
    narrow: list[int] = field(default_factory=list)
    edge_points: FloatArray | None = None  #: samples along the design's edges
    edge_gaps: FloatArray | None = None  #: each one's distance to the nearest strip
    creases: list[float] = field(default_factory=list)  #: fold angle (rad) per inner boundary
    #: why the strips ringing the design's bumps, tried first (:mod:`.freeform`), were not
    #: kept ("" when kept or not tried), and where that is (a point), when one place says it
    rings_refused: str = ""
    rings_where: FloatArray | None = None

    @property
    def coverage(self) -> float:
        """Largest distance of the design's edge from the strips (0 before it is measured)."""
        return float(self.edge_gaps.max()) if self.edge_gaps is not None and len(self.edge_gaps) else 0.0

    @property
    def deviation(self) -> float:
        return max(strip.deviation for strip in self.strips)

    @property
    def within(self) -> bool:
        return self.deviation <= self.tolerance

    @property
    def covered(self) -> bool:
        return self.coverage <= self.tolerance


def boundary_family(surface: Surface, direction: ArrayLike | None = None, samples: int = 17) -> str:
    """Which isocurves bound the strips: "u" (curves along u at fixed v) or "v".

    Without ``direction``: the family that needs fewer strips by the square law. A
    strip of width w whose rulings bend away from the design with normal curvature k
    deviates by about k·w²/8, so the strips stacked across the boundaries number about
    ∫ √(|k| / 8·tol) ds along the rulings' direction; the family with the smaller mean
    of that integral (tolerance aside) wins. So the rulings lie along the flatter way
    *and* the strips are stacked across the shorter extent (a long horseshoe roof gets
    strips along its length, not hundreds of slices across it). With a guide vector:
    the family whose unit tangents are most nearly parallel to it.
    """
    u, v = uv_grid(samples, samples)
    _, su, sv, suu, _, svv = surface.derivatives(u, v, 2)
    if direction is not None:
        d = np.asarray(direction, dtype=float)
        d = d / np.linalg.norm(d)

        def along(t: FloatArray) -> float:
            return float(np.mean(np.abs(t @ d) / np.maximum(np.linalg.norm(t, axis=1), 1e-300)))

        return "u" if along(su) >= along(sv) else "v"
    n = np.cross(su, sv)
    n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)

    def count(second: FloatArray, first: FloatArray) -> float:
        speed2 = np.maximum(np.einsum("ij,ij->i", first, first), 1e-300)
        k = np.einsum("ij,ij->i", second, n) / speed2
        return float(np.mean(np.sqrt(np.abs(k) * speed2)))  # √|k| · |S'|, the integrand in ds

    # rulings along v (between u-boundaries) bend by the normal curvature along Sv
    return "u" if count(svv, sv) <= count(suu, su) else "v"


class Unmade(ValueError):
    """No strip between two boundaries: its rulings' partners do not run one way."""


def strip_between(
    design: Surface, boundaries: Boundaries, lo: float, hi: float, segments: int = 24,
    warp_tolerance: float = 1e-7, tolerance: float | None = None, trim: bool = True,
) -> Strip:
    """The strip between the boundaries at levels ``lo`` and ``hi``, with its warp and its
    deviation certified against ``tolerance`` (:mod:`.certify`; without one, the bound on
    the first grid of samples). With ``trim``, end cones are replaced by the strip run on
    past the design's edge and cut by it (:mod:`.outline_cut`) where that has less fan area."""
    check = watch_check()
    if check:
        check()
    a, b = boundaries.at(lo), boundaries.at(hi)
    result = ruling_developable(a, b, segments, warp_tolerance)
    trimmed = None
    if trim and np.any(result.fan[[0, -1]]) and isinstance(boundaries, IsoBoundaries | LiftedBoundaries):
        lift = boundaries.lift if isinstance(boundaries, LiftedBoundaries) else None
        trimmed = trim_ends(design, boundaries.family, lift, lo, hi, result, (a, b), warp_tolerance)
        if trimmed is not None and not trimmed.result.fan_share < result.fan_share:
            trimmed = None
    try:
        if trimmed is not None:  # the ends run past the design's edge and are cut by it
            result = trimmed.result
            surface = ruled_between(trimmed.curve_a, result.s, trimmed.curve_b, result.t)
        else:
            surface = ruled_between(a, result.s, b, result.t)
    except ValueError as exc:  # partners that run back (a wide trial over a sharp bump)
        raise Unmade(str(exc)) from exc
    if trimmed is not None:
        warp = result.warp
    else:
        warp = curve_warp(a, b, result.s, result.t, result.starts, result.ends)
    reference = tolerance if tolerance is not None else np.inf
    deviation = certified_deviation(design, surface, reference)
    bound, where = deviation.bound, deviation.where
    if deviation.sampled <= reference:  # and the design's edge at the strip's two ends
        gap, at = end_gaps(design, surface, a, b)
        bound, where = (gap, at) if gap > bound else (bound, where)
    on = (trimmed.on_a, trimmed.on_b) if trimmed is not None else (result.s, result.t)
    return Strip(lo, hi, result, surface, np.asarray(warp, dtype=float), bound, where, *on)


#: Strips are widened to about this share of the tolerance (deviation grows as width²).
AIM = 0.97
#: Trial strips per accepted strip while marching, at most (then the widest within).
TRIALS = 6
#: A strip within the tolerance and this close to it is wide enough: marching moves on.
CLOSE = 0.95


def _march(
    design: Surface, boundaries: Boundaries, start: float, end: float, tolerance: float, max_strips: int,
    segments: int, warp_tolerance: float, progress: Callable[[float], None] | None = None,
    min_width: float = 0.0, narrow: list[int] | None = None, first: int = 0, trim: bool = False,
    settle_last: bool = True,
) -> list[Strip] | None:
    """Strips from the boundary at level ``start`` to the one at ``end``, each as wide as
    the tolerance allows: each next boundary is placed by a few trials (a secant on the
    square law deviation ∝ width², kept inside the bracket of widths found too wide and
    within). Where the tolerance would need a strip narrower than ``min_width`` (its width
    across, :mod:`.strip_width`), the strip is made ``min_width`` wide instead and its index
    (counted from ``first``) added to ``narrow``; a last strip narrower than that (what was
    left) is merged into the one before it or given MinWidth from it (:func:`.last_strip.last_two`;
    not with ``settle_last`` False: a trimmed design's box, whose strips the trim cuts later).
    None when more than ``max_strips`` would be needed.
    With ``trim`` every trial strip is cut at the design's edge where that is smoother
    (:mod:`.outline_cut`), so its width is the cut strip's."""
    strips: list[Strip] = []
    lo, width = start, end - start
    while lo < end:
        if len(strips) >= max_strips:
            return None
        good: Strip | None = None
        bad = end - lo + 1.0  # the smallest width known too wide (none yet)
        w = min(width, end - lo)
        strip = None
        for trial in range(TRIALS * 4):
            try:
                strip = strip_between(design, boundaries, lo, min(end, lo + w), segments, warp_tolerance,
                                      tolerance, trim=trim)
            except Unmade:  # too wide to be made: narrower
                bad = min(bad, w)
                w = 0.5 * (((good.hi - lo) if good is not None else 0.0) + bad)
                continue
            if strip.deviation <= tolerance:
                good = strip if good is None or strip.hi > good.hi else good
                if strip.hi >= end:
                    break
            else:
                bad = min(bad, w)
            if good is not None and (trial >= TRIALS - 1 or good.deviation >= CLOSE * tolerance):
                break
            if strip.width < 0.5 * min_width:
                break  # narrower than MinWidth can be made: settled below
            lift = float(getattr(boundaries, "height", 0.0))  # lifted boundaries: their sag is dev + lift
            if strip.deviation <= lift * 1.01:
                ratio = np.sqrt(2.0)  # the lift alone: the sag is not seen yet
            else:
                ratio = np.sqrt((AIM * tolerance + lift) / max(strip.deviation + lift, 1e-300))
            w_new = w * float(np.clip(ratio, 0.25, 2.0))
            floor = (good.hi - lo) if good is not None else 0.0
            if not floor < w_new < bad:
                w_new = 0.5 * (floor + min(bad, end - lo))
            w = min(w_new, end - lo)
            if w <= 1e-9:
                break
        settled = good if good is not None and good.width >= min_width else None
        if settled is None:
            # the tolerance needs a strip narrower than MinWidth (or none was found): one
            # MinWidth wide, by the width per level of the last trial
            if not min_width > 0.0:
                return None
            w = min(end - lo, _level_step(boundaries, lo, end, min_width))
            settled = None
            for _ in range(8):
                try:
                    settled = strip_between(design, boundaries, lo, lo + w if lo + w < end else end, segments,
                                            warp_tolerance, tolerance, trim=trim)
                    break
                except Unmade:
                    w *= 0.5
            if settled is None:
                return None
            if settled.deviation > tolerance and narrow is not None:
                narrow.append(first + len(strips))
        elif trim and settled.result.creased_share > CREASING and settled.hi < end:
            settled = _narrow_crease(design, boundaries, settled, end, tolerance, segments, warp_tolerance,
                                     min_width)
        strips.append(settled)
        width = settled.hi - lo
        lo = settled.hi
        if progress is not None:
            progress(lo)
    if settle_last and min_width > 0.0 and len(strips) >= 2 and strips[-1].width < min_width:

        def make(a: float, b: float) -> Strip | None:
            try:
                return strip_between(design, boundaries, a, b, segments, warp_tolerance, tolerance, trim=trim)
            except Unmade:
                return None

        strips[-2:] = last_two(make, strips[-2], strips[-1], end, tolerance, min_width)
    return strips



#: Halvings that place a boundary next to a creasing stretch (:func:`_narrow_crease`).
CREASE_STEPS = 7


def _creases(boundaries: Boundaries, lo: float, hi: float, segments: int, warp_tolerance: float) -> bool:
    """Whether the strip between the levels ``lo`` and ``hi`` creases over more than
    :data:`CREASING` of its area (its rulings only, uncut and uncertified: cheap)."""
    try:
        result = ruling_developable(boundaries.at(lo), boundaries.at(hi), segments, warp_tolerance)
    except ValueError:
        return True
    return result.creased_share > CREASING


def _narrow_crease(
    design: Surface, boundaries: Boundaries, strip: Strip, end: float, tolerance: float, segments: int,
    warp_tolerance: float, min_width: float,
) -> Strip:
    """A narrower strip from ``strip.lo`` in place of ``strip``, which creases (its two
    boundaries lie on either side of a line along an asymptotic direction, a monkey
    saddle's straight line x = 0, and no torsal strip joins them). Marched as wide as the
    tolerance allows, the creasing strip kept all its width in flat fans wherever the march
    happened to reach the crease; here it is kept about as narrow as the crease needs.
    Near that line the rulings run nearly along the boundaries, so a strip ending close to
    it is cut at the design's edge too far from it (or keeps cones): where the crease
    begins past the middle of ``strip``, the widest strip from ``strip.lo`` found :func:`_clean`
    (halvings, :data:`CREASE_STEPS`) if one as wide as half ``strip`` is; otherwise the strip to the
    nearest start from which the next strip, as wide as the last clean one found or
    ``strip``, is clean. ``strip`` itself when neither is found, within the tolerance and
    MinWidth."""
    lo, w = strip.lo, strip.hi - strip.lo

    def clean(a: float, b: float) -> Strip | None:
        return _clean(design, boundaries, a, b, tolerance, segments, warp_tolerance, min_width)

    if not _creases(boundaries, lo, lo + 0.5 * w, segments, warp_tolerance):
        ok, bad, best = 0.5 * w, w, clean(lo, lo + 0.5 * w)  # the widest clean strip before the crease
        for _ in range(CREASE_STEPS if best is not None else 0):
            middle = 0.5 * (ok + bad)
            found = clean(lo, lo + middle)
            ok, bad, best = (middle, bad, found) if found is not None else (ok, middle, best)
        if best is not None:
            return best
    probe = w  # the crease begins near lo: its strip ends where the next one is clean
    if lo + w + probe > end or clean(lo + w, lo + w + probe) is None:
        return strip
    bad, ok = 0.0, w  # the latest end found with the next strip not clean, the earliest found clean
    for _ in range(CREASE_STEPS):
        middle = 0.5 * (ok + bad)
        if clean(lo + middle, lo + middle + probe) is None:
            bad = middle
        else:
            ok = middle
    ok = max(ok, _level_step(boundaries, lo, end, min_width))
    if ok > 0.9 * w:
        return strip
    try:
        narrower = strip_between(design, boundaries, lo, lo + ok, segments, warp_tolerance, tolerance,
                                 trim=True)
    except Unmade:
        return strip
    return narrower if narrower.deviation <= tolerance and narrower.width >= min_width else strip


#: A strip is clean (:func:`_clean`) with at most this share of its area in fans.
CLEAN = 0.02


def _clean(
    design: Surface, boundaries: Boundaries, lo: float, hi: float, tolerance: float, segments: int,
    warp_tolerance: float, min_width: float,
) -> Strip | None:
    """The strip between ``lo`` and ``hi`` cut at the design's edge, when it is within the
    tolerance, at least MinWidth and has at most :data:`CLEAN` of its rulings' area in fans."""
    try:
        strip = strip_between(design, boundaries, lo, hi, segments, warp_tolerance, tolerance, trim=True)
    except Unmade:
        return None
    good = strip.deviation <= tolerance and strip.width >= min_width and fan_area([strip]) <= CLEAN
    return strip if good else None


def _level_step(boundaries: Boundaries, lo: float, end: float, width: float) -> float:
    """The step in level from ``lo`` that puts the next boundary about ``width`` away (the
    median distance at five points along, by the distance a small step moves them)."""
    step = min(0.01, end - lo)
    t = np.linspace(0.1, 0.9, 5)
    moved = np.linalg.norm(boundaries.at(lo + step).point_at(t) - boundaries.at(lo).point_at(t), axis=1)
    rate = float(np.median(moved)) / step
    return width / rate if rate > 0 else end - lo


def _even(
    design: Surface, boundaries: Boundaries, count: int, segments: int, warp_tolerance: float,
    tolerance: float, progress: Callable[[float], None] | None = None,
) -> list[Strip]:
    """About ``count`` strips between evenly spaced boundaries (when the tolerance needs
    more), at least one in each band between guides, the bands' shares by their widths."""
    levels = boundaries.levels
    widths = np.diff(levels)
    shares = np.maximum(1, np.floor(widths / widths.sum() * count + 0.5).astype(int))
    pieces = [np.linspace(a, b, k + 1) for a, b, k in zip(levels[:-1], levels[1:], shares, strict=True)]
    cuts = np.unique(np.concatenate(pieces))
    strips = []
    for lo, hi in itertools.pairwise(cuts):
        strips.append(strip_between(design, boundaries, float(lo), float(hi), segments, warp_tolerance,
                                    tolerance, trim=False))
        if progress is not None:
            progress(float(hi))
    return strips


#: The family the square law prefers is tried second when the other's parameter lines cross
#: the design's asymptotic directions less than this share as much (:mod:`.asymptotic`).
CROSSINGS = 0.5
#: The other family is not tried at all when its lines cross asymptotic directions more than
#: ALONG times as much as the first's plus ALONE (a monkey saddle's lines along x, 0.52,
#: against 0 for those along y; the wave's along y, 0.21, against 0 along x).
ALONG, ALONE = 4.0, 0.05

#: A rationalisation with at most this share of its area in creasing fans is kept without
#: trying the next family of boundaries (lifted, then on the design; each way).
SMOOTH = 0.02



def fan_area(strips: Sequence[Strip]) -> float:
    """The share of the strips' summed area between rulings of which one or both are a
    fan's (flat triangles, creasing or not, and the cones that close a strip's end)."""
    fan = total = 0.0
    for strip in strips:
        areas = patch_areas(strip.result.starts, strip.result.ends)
        pieces = strip.result.fan[:-1] | strip.result.fan[1:]
        fan += float(areas[pieces].sum())
        total += float(areas.sum())
    return fan / total if total > 0 else 0.0


def creased_area(strips: Sequence[Strip]) -> float:
    """The share of the strips' summed area in fans that crease the sheet: each strip's own
    creased share (:attr:`~.ruling.RulingResult.creased_share`, as its solve or its cut
    measured it) of its area."""
    creased = total = 0.0
    for strip in strips:
        area = float(patch_areas(strip.result.starts, strip.result.ends).sum())
        total += area
        creased += strip.result.creased_share * area
    return creased / total if total > 0 else 0.0


def _score(strips: Sequence[Strip], tolerance: float) -> tuple[float, ...]:
    """Smaller is better: beyond the tolerance first, then creased area (to 2 %), then strips."""
    over = max(0.0, max(s.deviation for s in strips) - tolerance)
    return (over, round(creased_area(strips) / 0.02), float(len(strips)))


def _cover(
    design: Surface, family_of: Boundaries, tolerance: float, max_strips: int, segments: int,
    warp_tolerance: float, progress: Callable[[float], None] | None, min_width: float, trim: bool = False,
    settle_last: bool = True,
) -> tuple[list[Strip], list[int]]:
    """The strips of one family of boundaries: each band between guides marched, or
    ``max_strips`` evenly spaced when the tolerance needs more; and the narrow ones. With
    ``trim`` the strips are marched cut at the design's edge (:func:`_march`)."""
    strips: list[Strip] | None = []
    narrow: list[int] = []
    for start, end in itertools.pairwise(family_of.levels):  # a boundary on every guide
        assert strips is not None
        band = _march(design, family_of, float(start), float(end), tolerance, max_strips - len(strips),
                      segments, warp_tolerance, progress, min_width, narrow, len(strips), trim, settle_last)
        if band is None:
            strips = None
            break
        strips.extend(band)
    if strips is None:  # the tolerance needs more than max_strips: that many, evenly spaced
        return _even(design, family_of, max_strips, segments, warp_tolerance, tolerance), []
    return strips, narrow


def _trimmed(design: Surface, family_of: Boundaries, strip: Strip, segments: int, warp_tolerance: float,
             tolerance: float) -> tuple[Strip, bool]:
    """``strip`` with its end cones replaced by its run past the design's edge, cut there
    (:mod:`.outline_cut`), when that is within the tolerance (or no farther than the strip);
    and whether the cut strip was smoother but too far from the design (a narrower strip
    may be cut within the tolerance, :func:`_recut`)."""
    if not np.any(strip.result.fan[[0, -1]]) or not isinstance(family_of, IsoBoundaries | LiftedBoundaries):
        return strip, False
    try:
        cut = strip_between(design, family_of, strip.lo, strip.hi, segments, warp_tolerance, tolerance)
    except Unmade:
        return strip, False
    if cut.result.fan_share < strip.result.fan_share:
        if cut.deviation <= max(tolerance, strip.deviation):
            return cut, False
        return strip, True
    return strip, False


#: When more than this share of the strips' area is in cones at their ends (fans that do not
#: crease) after their ends are cut at the design's edge, the family is marched again with
#: every trial strip cut (:func:`_recut`).
RECUT = 0.05
#: ... and the strips marched cut are kept when their fan area is at most this share of
#: the first strips' (fewer strips with cones at their ends otherwise).
RECUT_GAIN = 0.5
#: ... and when their creased area grows by at most this share of the fan area they remove,
#: with no more strips creased over more than :data:`CREASING` of their area (narrower
#: strips may meet an asymptotic stretch elsewhere: the canopy example's last strip creased).
RECUT_CREASED = 0.25
CREASING = 0.1


def _area(strips: Sequence[Strip]) -> float:
    return float(sum(patch_areas(s.result.starts, s.result.ends).sum() for s in strips))


def _recut(
    design: Surface, family_of: Boundaries, strips: list[Strip], too_far: list[Strip], narrow: list[int],
    tolerance: float, max_strips: int, segments: int, warp_tolerance: float, min_width: float,
) -> tuple[list[Strip], list[int]]:
    """The strips of ``family_of`` marched with every trial strip cut at the design's
    edge, where the strips found with cones at their ends and cut afterwards keep much of
    their area in those cones: a strip cut at the edge deviates more there than its cone
    (its rulings run on to the edge instead of bending towards a boundary's end), so where
    the rulings cross the boundaries at a small angle (a monkey saddle's, near its edges)
    the widths found with cones are too wide to be cut within the tolerance, and the cones
    stand. Marched cut, the strips are narrower and smooth to the edge; they are kept when
    they are within the tolerance, their fan area is at most :data:`RECUT_GAIN` of the
    first's and they crease little more (:data:`RECUT_CREASED`). ``too_far`` are the strips
    whose cut was smoother but beyond the tolerance: only their cones count."""
    first = fan_area(strips)
    if not too_far or not isinstance(family_of, IsoBoundaries | LiftedBoundaries):
        return strips, narrow
    # the fans that a narrower cut can remove: the cones at the ends of the strips cut too far
    cones = (fan_area(too_far) - creased_area(too_far)) * _area(too_far) / max(_area(strips), 1e-300)
    if cones <= RECUT:
        return strips, narrow
    again, narrow_again = _cover(design, family_of, tolerance, max_strips, segments, warp_tolerance, None,
                                 min_width, trim=True)

    def creasing(of: Sequence[Strip]) -> int:  # strips with more than a tenth of their area creased
        return sum(s.result.creased_share > CREASING for s in of)

    if (max(s.deviation for s in again) <= max(tolerance, max(s.deviation for s in strips))
            and len(narrow_again) <= len(narrow) and fan_area(again) <= RECUT_GAIN * first
            and creased_area(again) - creased_area(strips) <= RECUT_CREASED * (first - fan_area(again))
            and creasing(again) <= creasing(strips)):
        return again, narrow_again
    return strips, narrow


def _on_boundary(strip: Strip, side: str) -> RulingResult:
    """The strip's rulings that end on its ``side`` boundary, with their parameters there
    (a trimmed strip's rails run on past its boundaries, :mod:`.outline_cut`)."""
    s = strip.on_lower if strip.on_lower is not None else strip.result.s
    t = strip.on_upper if strip.on_upper is not None else strip.result.t
    keep = np.isfinite(t if side == "upper" else s)
    r = strip.result
    return replace(r, s=s[keep], t=t[keep], starts=r.starts[keep], ends=r.ends[keep])


def rationalise(
    design: Surface,
    tolerance: float,
    max_strips: int = 64,
    direction: ArrayLike | None = None,
    segments: int = 24,
    warp_tolerance: float = 1e-7,
    progress: Callable[[float], None] | None = None,
    guides: Sequence[Curve] = (),
    min_width: float = 0.0,
    cut_at_edge: bool = True,
) -> Rationalisation:
    """Developable strips within ``tolerance`` of ``design`` (see the module).

    With ``guides`` (curves on or near the design from edge to edge) the boundaries run
    through them and blend between them (:mod:`.guided`); ``direction`` is then unused.
    Raises ``ValueError`` for a design closed across the boundaries (cut it first) and for
    guides that cannot be followed (saying which). ``progress`` is called with the share
    of the design covered so far (0 to 1). Strips are at least ``min_width`` wide (at
    their rulings' median length) even where the tolerance would need narrower ones (listed in ``narrow``).
    With ``cut_at_edge`` (the default) a strip's end cones give way to the strip run on past
    the design's edge and cut by it, where that is smoother (:mod:`.outline_cut`); a caller
    that cuts the strips itself (a trimmed face, :mod:`.trimmed`) turns it off.
    """
    if not (tolerance > 0.0 and np.isfinite(tolerance)):
        raise ValueError(f"the tolerance must be a positive distance, not {tolerance!r}")
    if design.closed_u or design.closed_v:
        raise ValueError(
            "the surface is closed (a tube or a ring): cut it first — split it at its seam into open "
            "patches (cut it open) and rationalise each patch"
        )
    if guides:
        candidates: list[Boundaries] = [guided_boundaries(design, guides)]
    elif direction is not None:
        candidates = [IsoBoundaries(design, boundary_family(design, direction))]
    else:  # the family the square law prefers first; the other when the first creases the sheet
        first = boundary_family(design)
        other = "v" if first == "u" else "u"
        crossings = {f: asymptotic_crossings(design, f) for f in (first, other)}
        if crossings[other] < CROSSINGS * crossings[first]:
            first, other = other, first  # the square law's family runs along asymptotic directions
        families = (first, other)
        if crossings[other] > ALONG * crossings[first] + ALONE:
            families = (first,)  # the other runs along them where the first does not: not tried
        candidates = []
        for f in families:  # each family lifted (where it bends across), then on the design
            lifted = LiftedBoundaries(design, f, lift_for(design, f, tolerance))
            candidates += [lifted] if lifted.lift.spline is not None else []
            candidates.append(IsoBoundaries(design, f))
    best: tuple[tuple[float, ...], Boundaries, list[Strip], list[int]] | None = None
    for k, family_of in enumerate(candidates):
        strips, narrow = _cover(design, family_of, tolerance, int(max_strips), segments, warp_tolerance,
                                progress if k == 0 else None, min_width, settle_last=cut_at_edge)
        score = _score(strips, tolerance)
        if best is None or score < best[0]:
            best = (score, family_of, strips, narrow)
        if score[0] == 0.0 and creased_area(strips) <= SMOOTH:
            break  # within the tolerance and smooth enough: the next family is not tried
    assert best is not None
    _, family_of, strips, narrow = best
    # the strips' widths are found with their ends closed by cones (cheaper to certify);
    # the kept strips' ends are then cut at the design's edge where that is smoother
    if cut_at_edge:
        cut = [_trimmed(design, family_of, strip, segments, warp_tolerance, tolerance) for strip in strips]
        strips = [strip for strip, _ in cut]
        too_far = [strip for strip, far in cut if far]
        strips, narrow = _recut(design, family_of, strips, too_far, narrow, tolerance, int(max_strips),
                                segments, warp_tolerance, min_width)
    for strip in strips:
        if strip.deviation > tolerance:  # beyond it, refined against its own deviation too
            again = certified_deviation(design, strip.surface, 1.5 * strip.deviation)
            strip.deviation, strip.where = max(strip.deviation, again.bound), again.where
    params = [strips[0].lo] + [s.hi for s in strips]
    boundaries = [family_of.at(p) for p in params]
    points, gaps = uncovered(design, [s.surface for s in strips])
    creases = [crease_angle(_on_boundary(low, "upper"), boundaries[i + 1], _on_boundary(up, "lower"),
                            boundaries[i + 1])
               for i, (low, up) in enumerate(itertools.pairwise(strips))]
    return Rationalisation(family_of.family, strips, boundaries, float(tolerance), narrow, points, gaps,
                           creases)
