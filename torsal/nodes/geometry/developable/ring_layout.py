"""D-strips round a design's bumps: regions ringed by lines of curvature, cut where they meet.

Where both families of parameter lines cross the design's asymptotic directions (the
double bump with a valley: every line x = const at y = ±3, every line y = const near the
bumps' inflection circles, docs/geometry.md), strips between parameter lines crease there
whichever family bounds them. Boundaries along lines of curvature never do
(:mod:`.curvature_lines`). Round a bump one family of them rings its top, so:

1. Centres (:func:`bump_centres`): the interior extrema of the design's height over the
   plane fitted to it, where the design is elliptic (K > 0).
2. Regions (:func:`layout_regions`): in the design's plan each centre's cell (the points
   nearer it than any other centre), split in two halves by the line through the centre
   towards its nearest neighbour (so that no ring closes on itself: a half is swept by
   the angles of a half turn), and a cap round the centre inside the ring of curvature
   through :data:`CAP` of the way to the cell's edge (its umbilics lie near the top, where
   the rings stop being rings).
3. Strips: each half is marched with rings of curvature as boundaries
   (:class:`~.rings.RingPatch`, :func:`~.rings.march_rings`), the strips cut to the half
   (:mod:`.trimmed`'s cut), the rings running on outside it; the cap, elliptic, is
   rationalised as a trimmed face (:func:`~.trimmed.rationalise_trimmed`: parameter lines,
   which cross no asymptotic direction there). Where two regions meet, both strips reach
   :data:`~.trimmed.REACH` of the tolerance past the line between them (they overlap a
   little; they are not joined there).

:func:`ring_layout` returns the strips as a :class:`~.rationalise.Rationalisation` with
``family`` "rings", its boundaries and creases region by region (each cap's boundaries as
a trimmed face's, each half's rings; the creases measured on the cut strips,
:mod:`.ring_boundaries`), or raises
``ValueError`` where the rings cannot be traced (a line of curvature that turns along a
ray), or as soon as a half's strips are beyond the tolerance (checked on dense samples
too, :func:`~.trim_region.checked_densely`), leave the design's edge in it uncovered
(:func:`_covers`) or the halves' fans alone cover more of the design than asked (the
halves are marched before the caps) — Rationalise then keeps the parameter lines. Each
half's outermost ring is pushed beyond the half's corners (:func:`_reaching`), and its
strips' cut keeps the half's corners (:func:`~.rings.region_corners`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely
from scipy.ndimage import maximum_filter, minimum_filter

from ..array_types import FloatArray
from ..curve_base import Curve
from ..surface_base import Surface
from ..trimmed_surface import TrimmedSurface
from .certify import uncovered
from .curvature_lines import plan_scale, ring_family, trace_rings
from .fans import patch_areas
from .rationalise import Rationalisation, Strip
from .ring_boundaries import cut_creases, half_boundaries
from .rings import RingPatch, march_rings, region_corners, region_inside
from .trim_region import checked_densely
from .trimmed import rationalise_trimmed

#: Samples of the design per direction when looking for bumps.
SAMPLES = 41
#: A bump's top is this many samples from the design's edge at least.
INSET = 3
#: ... and stands out of its neighbourhood (the samples within :data:`NEAR`) by this share of
#: the design's height range at least.
PROMINENCE = 0.05
NEAR = 5
#: The cap's ring runs through this share of the way from the centre to its cell's edge.
CAP = 0.45
#: The rings run on this far (rad) past each end of a half turn (the strips are cut there).
OVERRUN = 0.15
#: Seed radii (rings traced) per half, from inside the cap's ring to this many times the
#: distance of the half's farthest corner (rings are not circles: the one through a corner
#: of the design crosses the seeds' ray farther out or nearer in).
SEEDS = 24
FARTHEST = 1.05
#: The outermost ring passes this share of each vertex's distance beyond the half's
#: vertices, the seeds tried farther out up to this many times (:func:`_reaching`).
BEYOND, REACHING = 0.01, 3
#: A half's strips are cut this share of the tolerance past its edges inside the design.
OVERLAP = 2.0
#: The halves' fans refuse the layout early when they cover more than the share asked of
#: the design's area times this (the strips' area exceeds the design's by their overlaps).
SPARE = 1.1


def bump_centres(design: Surface, scale: FloatArray) -> list[FloatArray]:
    """Plan points of the design's bumps (see the module), highest first."""
    g = np.linspace(0.0, 1.0, SAMPLES)
    u, v = (a.ravel() for a in np.meshgrid(g, g, indexing="ij"))
    points = design.point_at(u, v)
    middle = points.mean(axis=0)
    normal = np.linalg.svd(points - middle, full_matrices=False)[2][2]
    h = ((points - middle) @ normal).reshape(SAMPLES, SAMPLES)
    span = float(np.ptp(h))
    if not span > 0.0:
        return []
    found = []
    for sign in (1.0, -1.0):
        f = sign * h
        top = f == maximum_filter(f, size=2 * NEAR + 1, mode="nearest")
        low = minimum_filter(f, size=2 * NEAR + 1, mode="nearest")
        top &= f - low >= PROMINENCE * span
        top[:INSET], top[-INSET:], top[:, :INSET], top[:, -INSET:] = False, False, False, False
        for i, j in zip(*np.nonzero(top), strict=True):
            if design.curvature(g[i], g[j]).gaussian[0] > 0.0:
                found.append((float(f[i, j]), np.array([g[i], g[j]]) * scale))
    found.sort(key=lambda item: -item[0])
    return [p for _, p in found]


class RingsRefused(ValueError):
    """The rings do not meet the tolerance: ``where`` (a point) and how far off (``off``)."""

    def __init__(self, message: str, where: FloatArray, off: float) -> None:
        super().__init__(message)
        self.where, self.off = np.asarray(where, dtype=float), float(off)


@dataclass
class Half:
    """One half of a centre's cell: the region (plan polygon) its rings sweep over the
    angles ``span`` about ``centre``, seeded on the ray at ``start``."""

    centre: FloatArray
    region: shapely.Geometry
    span: tuple[float, float]
    start: float
    seeds: FloatArray
    family: int  #: the centre's family of rings (0: k1's lines of curvature, 1: k2's)


@dataclass
class Layout:
    """The caps (plan polygons) and halves of :func:`layout_regions`."""

    caps: list[shapely.Geometry]
    halves: list[Half]


def _half_plane(centre: FloatArray, direction: FloatArray, size: float) -> shapely.Polygon:
    """The half-plane left of the line through ``centre`` along ``direction`` (a big square)."""
    d = direction / np.linalg.norm(direction)
    left = np.array([-d[1], d[0]])
    a, b = centre - size * d, centre + size * d
    return shapely.Polygon([a, b, b + size * left, a + size * left])


def layout_regions(design: Surface, centres: list[FloatArray], scale: FloatArray) -> Layout:
    """Each centre's cell split into a cap and two halves (see the module)."""
    outline = shapely.box(0.0, 0.0, *scale)
    size = 4.0 * float(np.hypot(*scale))
    caps: list[shapely.Geometry] = []
    halves: list[Half] = []
    for i, c in enumerate(centres):
        cell = outline
        for j, other in enumerate(centres):
            if j != i:  # the side of the bisector nearer c
                middle, away = 0.5 * (c + other), other - c
                cell = cell.intersection(_half_plane(middle, np.array([-away[1], away[0]]), size))
        others = [o for j, o in enumerate(centres) if j != i]
        right = np.array([1.0, 0.0])
        towards = (min(others, key=lambda o: float(np.linalg.norm(o - c))) - c) if others else right
        phi = float(np.arctan2(towards[1], towards[0]))
        reach = float(cell.exterior.distance(shapely.Point(c)))
        rho = CAP * reach
        family = ring_family(design, c, rho, scale)
        theta = np.linspace(phi, phi + 2.0 * np.pi, 361)
        ring = trace_rings(design, c, np.array([rho]), theta, family, scale, start=phi + 0.5 * np.pi)[0]
        cap = shapely.Polygon(c + ring[:, None] * np.column_stack([np.cos(theta), np.sin(theta)]))
        if not cap.is_valid:
            raise ValueError("the ring of curvature round a bump crosses itself")
        cap = cap.intersection(cell)
        caps.append(cap)
        for side in (1.0, -1.0):
            half = cell.intersection(_half_plane(c, side * np.array([np.cos(phi), np.sin(phi)]), size))
            region = half.difference(cap)
            if region.is_empty or region.area <= 0.0:
                continue
            far = float(np.max(np.linalg.norm(np.asarray(region.exterior.coords) - c, axis=1)))
            a = phi if side > 0 else phi + np.pi
            seeds = np.linspace(0.9 * float(ring.min()), FARTHEST * far, SEEDS)
            halves.append(Half(c, region, (a - OVERRUN, a + np.pi + OVERRUN), a + 0.5 * np.pi, seeds, family))
    return Layout(caps, halves)


def ring_layout(design: Surface, tolerance: float, max_strips: int = 64, segments: int = 24,
                warp_tolerance: float = 1e-7, min_width: float = 0.0, max_fans: float = 1.0
                ) -> Rationalisation:
    """Strips round the design's bumps along rings of curvature (see the module); refused
    as soon as the halves' fans alone cover more than ``max_fans`` of the design's area."""
    scale = plan_scale(design)
    centres = bump_centres(design, scale)
    if not centres:
        raise ValueError("the design has no bump to ring")
    layout = layout_regions(design, centres, scale)
    if any(cap.is_empty or cap.geom_type != "Polygon" for cap in layout.caps):
        raise ValueError("a bump's cap is not one region")
    on_design = region_inside(design, shapely.box(0.0, 0.0, *scale), scale)
    size = float(np.hypot(*scale))
    # the halves first: a layout refused there costs no cap
    area = design.area(rtol=1e-4) if max_fans < 1.0 else np.inf  # (no test asked for)
    rings: list[Strip] = []
    ring_bounds: list[Curve] = []
    ring_creases: list[float] = []
    for half in layout.halves:
        patch = _reaching(design, half, scale)
        inside = region_inside(design, half.region, scale, OVERLAP * tolerance)
        corners = region_corners(design, half.region, scale, OVERLAP * tolerance)
        pieces, _ = march_rings(design, patch, inside, tolerance, segments, warp_tolerance,
                                max(1, max_strips - len(rings)), corners=corners)
        for strip in pieces:
            checked_densely(design, strip)
        _covers(design, half, pieces, scale, tolerance)
        rings += pieces
        fans = _fan_area(rings)
        if np.isfinite(area) and fans > max_fans * SPARE * area:
            raise ValueError(f"the rings' fans already cover {fans / area:.3g} of the design")
        bounds, folds = half_boundaries(patch, pieces, inside, on_design, size)
        ring_bounds += bounds
        ring_creases += folds
    strips: list[Strip] = []
    narrow: list[int] = []
    boundaries: list[Curve] = []
    creases: list[float] = []
    for cap in layout.caps:
        loop = np.asarray(cap.exterior.coords) / scale
        found = rationalise_trimmed(TrimmedSurface(design, loop), tolerance, max_strips, segments=segments,
                                    warp_tolerance=warp_tolerance, min_width=min_width)
        narrow += [len(strips) + k for k in found.narrow]
        strips += found.strips
        boundaries += found.boundaries
        creases += cut_creases(found.boundaries, found.strips, size)
    strips += rings  # in strip order: the caps' regions, then the halves'
    boundaries += ring_bounds
    creases += ring_creases
    if len(strips) > max_strips:
        raise ValueError(f"the rings need {len(strips)} strips, more than {max_strips}")
    points, gaps = uncovered(design, [s.surface for s in strips])
    return Rationalisation("rings", strips, boundaries, float(tolerance), narrow, points, gaps, creases)


def _fan_area(strips: list[Strip]) -> float:
    """The strips' area between rulings of which one or both are a fan's."""
    return sum(float(patch_areas(s.result.starts, s.result.ends)[s.result.fan[:-1] | s.result.fan[1:]].sum())
               for s in strips)


def _reaching(design: Surface, half: Half, scale: FloatArray) -> RingPatch:
    """The half's ring patch, its outermost ring beyond every vertex of the half (by
    :data:`BEYOND` of the vertex's distance from the centre): the seeds are spread farther
    out (by the largest ratio of a vertex's distance to the ring's on its ray) until it
    is, at most :data:`REACHING` times. A ring is no circle: the one through the seed as
    far out as the farthest vertex may pass inside another vertex (the double bump's
    corner at 2 cm, by 4.6 cm), and leave it uncovered."""
    seeds = np.asarray(half.seeds, dtype=float)
    corners = np.asarray(half.region.exterior.coords) - half.centre
    rho = np.hypot(corners[:, 0], corners[:, 1])
    theta = half.span[0] + np.mod(np.arctan2(corners[:, 1], corners[:, 0]) - half.span[0], 2.0 * np.pi)
    swept = (theta >= half.span[0]) & (theta <= half.span[1])
    for _ in range(REACHING):
        patch = RingPatch(design, half.centre, scale, seeds, half.span, half.family, half.start)
        outer = patch.radius.ev(np.ones(int(swept.sum())), theta[swept])
        short = float(np.max(rho[swept] * (1.0 + BEYOND) / outer, initial=0.0))
        if short <= 1.0:
            break
        seeds = np.linspace(seeds[0], seeds[-1] * short, len(seeds))
    return patch


def _covers(design: Surface, half: Half, pieces: list[Strip], scale: FloatArray, tolerance: float) -> None:
    """Raises :class:`RingsRefused` when a half's strips are beyond the tolerance or leave the
    design's edge within the half uncovered by more than it (its strips' cut ends short of
    a corner of the design: the rest of the layout is then not made, the parameter lines
    are kept)."""
    far = max(pieces, key=lambda s: s.deviation, default=None)
    if far is not None and far.deviation > tolerance:
        raise RingsRefused(f"a strip between them is {far.deviation:.4g} from the design", far.where,
                           far.deviation)
    points, gaps = uncovered(design, [s.surface for s in pieces])
    found = design.closest_point(points, candidates=1, tolerance=1e-9).parameters * scale
    mine = shapely.contains_xy(half.region.buffer(1e-9 * float(np.hypot(*scale))), found[:, 0], found[:, 1])
    if np.any(gaps[mine] > tolerance):
        k = int(np.flatnonzero(mine)[np.argmax(gaps[mine])])
        raise RingsRefused(f"they leave the design's edge uncovered by {gaps[k]:.4g}", points[k],
                           float(gaps[k]))
