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
too, :func:`_checked`) or leave the design's edge in it uncovered (:func:`_covers`) —
Rationalise then keeps the parameter lines.
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
from .rationalise import Rationalisation, Strip
from .ring_boundaries import cut_creases, half_boundaries
from .rings import RingPatch, march_rings, region_inside
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
#: A half's strips are cut this share of the tolerance past its edges inside the design.
OVERLAP = 2.0
#: Samples along x across each strip where its distance from the design is checked besides
#: its certificate (:func:`_checked`).
CHECK = (161, 9)


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
                warp_tolerance: float = 1e-7, min_width: float = 0.0) -> Rationalisation:
    """Strips round the design's bumps along rings of curvature (see the module)."""
    scale = plan_scale(design)
    centres = bump_centres(design, scale)
    if not centres:
        raise ValueError("the design has no bump to ring")
    layout = layout_regions(design, centres, scale)
    on_design = region_inside(design, shapely.box(0.0, 0.0, *scale), scale)
    size = float(np.hypot(*scale))
    strips: list[Strip] = []
    narrow: list[int] = []
    boundaries: list[Curve] = []
    creases: list[float] = []
    for cap in layout.caps:
        if cap.is_empty or cap.geom_type != "Polygon":
            raise ValueError("a bump's cap is not one region")
        loop = np.asarray(cap.exterior.coords) / scale
        found = rationalise_trimmed(TrimmedSurface(design, loop), tolerance, max_strips, segments=segments,
                                    warp_tolerance=warp_tolerance, min_width=min_width)
        narrow += [len(strips) + k for k in found.narrow]
        strips += found.strips
        boundaries += found.boundaries
        creases += cut_creases(found.boundaries, found.strips, size)
    for half in layout.halves:
        patch = RingPatch(design, half.centre, scale, half.seeds, half.span, half.family, half.start)
        inside = region_inside(design, half.region, scale, OVERLAP * tolerance)
        pieces, _ = march_rings(design, patch, inside, tolerance, segments, warp_tolerance,
                                max(1, max_strips - len(strips)))
        for strip in pieces:
            _checked(design, strip)
        _covers(design, half, pieces, scale, tolerance)
        strips += pieces
        rings, folds = half_boundaries(patch, pieces, inside, on_design, size)
        boundaries += rings
        creases += folds
    if len(strips) > max_strips:
        raise ValueError(f"the rings need {len(strips)} strips, more than {max_strips}")
    points, gaps = uncovered(design, [s.surface for s in strips])
    return Rationalisation("rings", strips, boundaries, float(tolerance), narrow, points, gaps, creases)



def _checked(design: Surface, strip: Strip) -> None:
    """``strip``'s deviation raised to the largest distance of :data:`CHECK` samples of it
    from the design, where that is larger. A cut strip's edge along the cut is a cubic
    through the cut points; where the rulings run nearly along the design's edge (rings
    near a corner) it can bulge past the edge between the certificate's samples (5.1 cm
    where 1.88 cm was certified, the double bump at 2 cm), so the layout is kept only when
    dense samples agree too."""
    u, v = (a.ravel() for a in np.meshgrid(np.linspace(0.0, 1.0, CHECK[0]), np.linspace(0.0, 1.0, CHECK[1]),
                                           indexing="ij"))
    points = strip.surface.point_at(u, v)
    found = design.closest_point(points, candidates=2, tolerance=1e-12)
    distance = found.distances
    k = int(np.argmax(distance))
    if distance[k] > strip.deviation:
        strip.deviation, strip.where = float(distance[k]), points[k]


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
