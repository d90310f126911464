"""Rationalising a freeform design into developable strips (developable.Rationalise).

Method (a first version)
------------------------
1. Direction. A strip's rulings are straight, so a ruling deviates least from the
   design where the design bends least along it: the rulings should run along the
   direction of least normal curvature and the strips' boundary curves across it.
   The boundaries are taken as isocurves of the design: of the two parameter
   families, the one that needs fewer strips by the square law (see
   :func:`boundary_family`: normal curvature along the rulings and the extent the
   strips are stacked over). A guide vector instead picks the family whose tangents
   run most nearly along it (the strips follow the guide).
2. Strips. Between two neighbouring boundaries the strip is RulingDevelopable's
   (:func:`~torsal.nodes.geometry.developable.ruling_developable`): certified torsal rulings,
   flat fans where none exist, and its Surface is
   :func:`~torsal.nodes.geometry.curve_rail.ruled_between`, whose edges run on the boundary
   curves themselves — so two neighbours share their boundary exactly.
3. Placement. Marching from one edge of the design, each next boundary is placed so
   that the strip is as wide as the tolerance allows: a few trial strips, the width
   guessed from the square law (a straight ruling's deviation grows as the width²) and
   kept inside the bracket of widths found too wide and within. A strip's deviation is
   the largest distance of a dense grid of its points from the design, by the design's
   own closest-point search. When more than ``max_strips`` would be needed, the design
   is instead split into ``max_strips`` evenly spaced strips, and the result reports
   the deviation reached.

What this version does not do (yet): boundaries are isocurves, not curves traced along
principal directions or optimised (the issue's least-squares route), so on a design
whose parameter lines are far from its curvature lines the strips are narrower than they
need be.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from torsal.nodes.geometry.array_types import FloatArray
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curve_rail import ruled_between
from torsal.nodes.geometry.developable.guided import GuidedBoundaries, IsoBoundaries, guided_boundaries
from torsal.nodes.geometry.developable.ruling import RulingResult, ruling_developable
from torsal.nodes.geometry.developable.warp import curve_warp
from torsal.nodes.geometry.ruled import RuledSurface
from torsal.nodes.geometry.surface_base import Surface, uv_grid
from torsal.nodes.geometry.watch import watch_check

#: The boundaries of a rationalisation: a curve on the design for every level in [0, 1].
Boundaries = IsoBoundaries | GuidedBoundaries

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
    deviation: float  #: largest distance of the strip's dense samples from the design


@dataclass
class Rationalisation:
    """The strips in order across the design, their boundary curves and how far they are."""

    family: str  #: "u": the boundaries are isocurves running along u (fixed v), else along v
    strips: list[Strip]
    boundaries: list[Curve]  #: len(strips) + 1 curves; strip i lies between i and i + 1
    tolerance: float

    @property
    def deviation(self) -> float:
        return max(strip.deviation for strip in self.strips)

    @property
    def within(self) -> bool:
        return self.deviation <= self.tolerance


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


def strip_deviation(
    design: Surface, strip: RuledSurface, samples: tuple[int, int] = DEVIATION_SAMPLES
) -> float:
    """Largest distance from a grid of points of ``strip`` to ``design`` (closest points)."""
    nu, nv = samples
    u, v = uv_grid(nu, nv)
    points = strip.point_at(u, v)
    return float(design.closest_point(points).distances.max())


def strip_between(
    design: Surface, boundaries: Boundaries, lo: float, hi: float, segments: int = 24,
    warp_tolerance: float = 1e-7,
) -> Strip:
    """The strip between the boundaries at levels ``lo`` and ``hi``, with its warp and deviation."""
    check = watch_check()
    if check:
        check()
    a, b = boundaries.at(lo), boundaries.at(hi)
    result = ruling_developable(a, b, segments, warp_tolerance)
    surface = ruled_between(a, result.s, b, result.t)
    warp = curve_warp(a, b, result.s, result.t, result.starts, result.ends)
    return Strip(lo, hi, result, surface, np.asarray(warp, dtype=float), strip_deviation(design, surface))


#: Strips are widened to about this share of the tolerance (deviation grows as width²).
AIM = 0.97
#: Trial strips per accepted strip while marching, at most (then the widest within).
TRIALS = 6
#: A strip within the tolerance and this close to it is wide enough: marching moves on.
CLOSE = 0.95


def _march(
    design: Surface, boundaries: Boundaries, start: float, end: float, tolerance: float, max_strips: int,
    segments: int, warp_tolerance: float, progress: Callable[[float], None] | None = None,
) -> list[Strip] | None:
    """Strips from the boundary at level ``start`` to the one at ``end``, each as wide as
    the tolerance allows: each next boundary is placed by a few trials (a secant on the
    square law deviation ∝ width², kept inside the bracket of widths found too wide and
    within). None when more than ``max_strips`` would be needed."""
    strips: list[Strip] = []
    lo, width = start, end - start
    while lo < end:
        if len(strips) >= max_strips:
            return None
        good: Strip | None = None
        bad = end - lo + 1.0  # the smallest width known too wide (none yet)
        w = min(width, end - lo)
        for trial in range(TRIALS * 4):
            strip = strip_between(design, boundaries, lo, min(end, lo + w), segments, warp_tolerance)
            if strip.deviation <= tolerance:
                good = strip if good is None or strip.hi > good.hi else good
                if strip.hi >= end:
                    break
            else:
                bad = min(bad, w)
            if good is not None and (trial >= TRIALS - 1 or good.deviation >= CLOSE * tolerance):
                break
            ratio = np.sqrt(AIM * tolerance / max(strip.deviation, 1e-300))
            w_new = w * float(np.clip(ratio, 0.25, 2.0))
            floor = (good.hi - lo) if good is not None else 0.0
            if not floor < w_new < bad:
                w_new = 0.5 * (floor + min(bad, end - lo))
            w = min(w_new, end - lo)
            if w <= 1e-6:
                return None
        if good is None:
            return None
        strips.append(good)
        width = good.hi - lo
        lo = good.hi
        if progress is not None:
            progress(lo)
    return strips


def _even(
    design: Surface, boundaries: Boundaries, count: int, segments: int, warp_tolerance: float,
    progress: Callable[[float], None] | None = None,
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
        strips.append(strip_between(design, boundaries, float(lo), float(hi), segments, warp_tolerance))
        if progress is not None:
            progress(float(hi))
    return strips


def rationalise(
    design: Surface,
    tolerance: float,
    max_strips: int = 64,
    direction: ArrayLike | None = None,
    segments: int = 24,
    warp_tolerance: float = 1e-7,
    progress: Callable[[float], None] | None = None,
    guides: Sequence[Curve] = (),
) -> Rationalisation:
    """Developable strips within ``tolerance`` of ``design`` (see the module).

    With ``guides`` (curves on or near the design from edge to edge) the boundaries run
    through them and blend between them (:mod:`.guided`); ``direction`` is then unused.
    Raises ``ValueError`` for a design closed across the boundaries (cut it first) and for
    guides that cannot be followed (saying which). ``progress`` is called with the share
    of the design covered so far (0 to 1).
    """
    if not (tolerance > 0.0 and np.isfinite(tolerance)):
        raise ValueError(f"the tolerance must be a positive distance, not {tolerance!r}")
    if guides:
        family_of: Boundaries = guided_boundaries(design, guides)
    else:
        family = boundary_family(design, direction)
        closed_across = design.closed_v if family == "u" else design.closed_u
        if closed_across:
            raise ValueError(
                "the surface is closed across the strips' direction: cut it open (e.g. split it at its "
                "seam into two patches) and rationalise each patch"
            )
        family_of = IsoBoundaries(design, family)
    strips: list[Strip] | None = []
    levels = family_of.levels
    for start, end in itertools.pairwise(levels):  # a boundary on every guide, each band marched
        assert strips is not None
        band = _march(design, family_of, float(start), float(end), tolerance, int(max_strips) - len(strips),
                      segments, warp_tolerance, progress)
        if band is None:
            strips = None
            break
        strips.extend(band)
    if strips is None:  # the tolerance needs more than max_strips: that many, evenly spaced
        strips = _even(design, family_of, int(max_strips), segments, warp_tolerance)
    params = [strips[0].lo] + [s.hi for s in strips]
    boundaries = [family_of.at(p) for p in params]
    return Rationalisation(family_of.family, strips, boundaries, float(tolerance))
