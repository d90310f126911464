"""Panelling a development and carrying the panels onto the surface: SurfacePatching.

A *pattern* is one tile of a panel layout: a few closed polygons in the plane and a
*period*, the rectangle by which the tile repeats (by default the polygons'
bounding rectangle; a running bond needs a period smaller than its bounds, because
its offset row overhangs). :func:`tile_pattern`

1. scales the pattern by ``scale`` about the period's lower-left corner and repeats
   it over the development's bounding rectangle, starting at that rectangle's
   lower-left corner (every copy that touches it);
2. clips every panel to the development outline (shapely; a panel cut in two
   becomes two pieces with their own IDs);
3. carries each flat panel onto the 3D surface through the development's map,
   with a vertex wherever the outline crosses a ruling or diagonal, so the 3D
   panel lies on the surface instead of cutting across it.

Rotation. ``rotation_deg`` turns the development (counter-clockwise, about its area
centroid) before tiling; the pattern grid stays aligned with the X and Y axes.
Flat panels are returned in the turned frame — the way they are nested on the sheet
— and the 3D panels follow, so on the surface the pattern turns by −rotation_deg
relative to the rulings. Equivalently: the 3D panels depend only on the total turn
of the development, so turning a development by α with
:meth:`~torsal.nodes.geometry.unroll.Development.rotated` and tiling it with rotation β
gives the same 3D panels as tiling the original with rotation α + β.

Waste is the share of sheet cut away: each panel that reaches the development is
cut from a sheet the size of its whole pattern polygon, so
waste = 1 − Σ clipped areas / Σ whole-panel areas.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field

import numpy as np
import shapely
from numpy.typing import ArrayLike

from .array_types import FloatArray, IntArray
from .polygons import signed_ring_area
from .unroll import Development
from .watch import watch_check

#: Clipped pieces smaller than this share of their whole panel (or of the development,
#: when the panel is larger than it) are slivers from edges that merely touch the
#: outline, and are dropped.
SLIVER = 1e-12


class TooManyPanels(ValueError):
    """The tiling would make more pattern copies than allowed; nothing was allocated.

    ``count`` is how many copies the tiling asked for (a float: it may be astronomical,
    or ∞), ``limit`` the cap it was checked against.
    """

    def __init__(self, count: float, limit: int) -> None:
        super().__init__(f"the pattern would be laid {count:.3g} times over the development; "
                         f"at most {limit:,} panels can be made at once")
        self.count = count
        self.limit = limit


@dataclass(frozen=True)
class Pattern(Sequence[FloatArray]):
    """One tile of a panel layout: closed polygons ``(k, 2)`` and the repeat rectangle.

    Behaves as the sequence of its polygons. ``period`` is ``[xmin, ymin, xmax, ymax]``
    of the rectangle the tile repeats by; polygons may overhang it.
    """

    polygons: tuple[FloatArray, ...]
    period: FloatArray

    def __getitem__(self, index):  # type: ignore[override]
        return self.polygons[index]

    def __len__(self) -> int:
        return len(self.polygons)

    def __iter__(self) -> Iterator[FloatArray]:
        return iter(self.polygons)


def staggered_pattern(width: float, height: float, offset: float) -> Pattern:
    """A running bond (Guggenheim-like): rows of ``width`` × ``height`` rectangles,
    every other row shifted by ``offset`` along x.

    The tile is two panels, [0, w] × [0, h] and [o, o + w] × [h, 2h] (o = offset
    modulo w), repeating by the period w × 2h, so the shifted row is made of whole
    panels (it overhangs the period by o, and the next tile's copy continues it).

    Example:
        >>> tile = staggered_pattern(2.0, 1.0, 0.5)
        >>> len(tile), tile.period.tolist()
        (2, [0.0, 0.0, 2.0, 2.0])
    """
    if not (width > 0 and height > 0):
        raise ValueError("panel width and height must be positive")
    o = float(np.mod(offset, width))
    box = np.array([[0.0, 0.0], [width, 0.0], [width, height], [0.0, height]])
    shifted = box + np.array([o, height])
    return Pattern((box, shifted), np.array([0.0, 0.0, width, 2.0 * height]))


@dataclass(frozen=True)
class Patching:
    """Panels on a development and on its surface.

    Per panel (one row each, ordered by tile row, pattern polygon, tile column — for a
    running bond, row by row from the bottom, left to right): ``panels_flat`` closed
    rings ``(k, 2)`` on the (turned) development, counter-clockwise from the vertex
    nearest the panel's lower-left corner, first vertex repeated at the end;
    ``panels_3d`` the same outlines on the surface, ``(m, 3)``,
    with the extra vertices where they cross rulings and diagonals; ``ids`` running
    numbers for engraving; ``tiles`` ``(p, q)`` tile indices; ``pattern_index`` the
    pattern polygon each came from; ``areas`` the flat areas; ``full_areas`` the areas
    of the uncut pattern polygons. ``pattern_bounds`` is the scaled period at the grid
    origin and ``development_bounds`` the turned development's bounding rectangle,
    both ``[xmin, ymin, xmax, ymax]``.
    """

    panels_flat: list[FloatArray] = field(repr=False)
    panels_3d: list[FloatArray] = field(repr=False)
    ids: IntArray
    tiles: IntArray
    pattern_index: IntArray
    areas: FloatArray
    full_areas: FloatArray
    waste: float
    development_area: float
    pattern_bounds: FloatArray
    development_bounds: FloatArray
    rotation_deg: float
    pivot: FloatArray

    @property
    def covered_area(self) -> float:
        """Summed flat area of the panels."""
        return float(self.areas.sum())


def _as_pattern(pattern: Pattern | Sequence[ArrayLike]) -> tuple[list[FloatArray], FloatArray]:
    if isinstance(pattern, Pattern):
        polys, period = [np.asarray(p, dtype=float) for p in pattern.polygons], pattern.period
    else:
        polys = [np.asarray(p, dtype=float) for p in pattern]
        period = None
    cleaned = []
    for p in polys:
        ring = p.reshape(-1, p.shape[-1])[:, :2]
        if len(ring) > 1 and np.allclose(ring[0], ring[-1]):
            ring = ring[:-1]  # drop the closing vertex
        if len(ring) < 3:
            raise ValueError("every pattern polygon needs at least three vertices")
        cleaned.append(ring)
    if not cleaned:
        raise ValueError("the pattern has no polygons")
    if period is None:
        pts = np.vstack(cleaned)
        period = np.concatenate([pts.min(axis=0), pts.max(axis=0)])
    period = np.asarray(period, dtype=float)
    if not (period[2] > period[0] and period[3] > period[1]):
        raise ValueError("the pattern's period rectangle has no area")
    return cleaned, period


def _canonical_ring(ring: FloatArray) -> FloatArray:
    """A closed ring, counter-clockwise, starting at the vertex nearest its bounding
    box's lower-left corner (so equal panels print equally, whatever the clipper did)."""
    open_ring = ring[:-1] if len(ring) > 1 and np.array_equal(ring[0], ring[-1]) else ring
    if signed_ring_area(open_ring) < 0:
        open_ring = open_ring[::-1]
    start = int(np.argmin(np.linalg.norm(open_ring - open_ring.min(axis=0), axis=1)))
    open_ring = np.roll(open_ring, -start, axis=0)
    return np.vstack([open_ring, open_ring[:1]])


def development_polygon(development: Development) -> shapely.Geometry:
    """The development's outline as a valid shapely polygon (repaired if it overlaps
    itself, in which case the overlap counts once)."""
    poly = shapely.Polygon(development.outline)
    return poly if poly.is_valid else shapely.make_valid(poly)


#: Pattern copies clipped to the outline between two looks at the cancel token (each
#: costs ≈ 0.2 ms against an outline of 3,000 points: ≈ 6 ms a block).
CLIP_BLOCK = 32


def _clipped(geoms: np.ndarray, outline: shapely.Geometry) -> np.ndarray:
    """Each copy cut to the outline, in blocks of :data:`CLIP_BLOCK` with a look at the
    cancel token before each (see :mod:`.watch`)."""
    check = watch_check()
    blocks = []
    for start in range(0, len(geoms), CLIP_BLOCK):
        if check:
            check()
        blocks.append(shapely.intersection(geoms[start:start + CLIP_BLOCK], outline))
    return np.concatenate(blocks) if blocks else np.empty(0, dtype=object)


def tile_pattern(
    pattern: Pattern | Sequence[ArrayLike],
    development: Development,
    scale: float = 1.0,
    rotation_deg: float = 0.0,
    pivot: ArrayLike | None = None,
    max_panels: int | None = None,
) -> Patching:
    """Tile ``pattern`` over ``development``, clip it, and map the panels to 3D.

    ``pattern`` is a :class:`Pattern` or a plain list of closed polygons (then the
    period is their bounding rectangle). ``scale`` multiplies the tile; ``rotation_deg``
    turns the development first, about ``pivot`` (default: its area centroid) — see
    the module docstring for what that does on the surface.

    ``max_panels`` caps the pattern copies (tiles × polygons, before clipping): a tiling
    that needs more raises :class:`TooManyPanels` before any copy is made.
    """
    if not (scale > 0 and math.isfinite(scale)):
        raise ValueError("scale must be a positive, finite number")
    polys, period = _as_pattern(pattern)
    centre = development.centroid if pivot is None else np.asarray(pivot, dtype=float)
    turned = development.rotated(rotation_deg, centre)
    outline = development_polygon(turned)
    xmin, ymin, xmax, ymax = turned.bounds

    with np.errstate(over="ignore", invalid="ignore"):
        tile = (period[2:] - period[:2]) * scale
        scaled = [(p - period[:2]) * scale for p in polys]
    allpts = np.vstack(scaled)
    if not (np.isfinite(allpts).all() and np.isfinite(tile).all() and (tile > 0).all()):
        raise ValueError(f"scale {scale:g} takes the pattern out of the range of floating-point numbers")
    low, high = allpts.min(axis=0), allpts.max(axis=0)
    # tile (p, q) sits at (xmin, ymin) + (p, q)·tile; keep every copy reaching the box
    with np.errstate(over="ignore", invalid="ignore"):
        first = np.ceil(-high / tile - 1e-12)
        last = np.floor((np.array([xmax - xmin, ymax - ymin]) - low) / tile)
    copies = float(np.prod(np.maximum(last - first + 1, 0.0))) * len(scaled)
    if max_panels is not None and not copies <= max_panels:  # counted before anything is made
        raise TooManyPanels(copies, max_panels)
    p_range = np.arange(first[0], last[0] + 1)
    q_range = np.arange(first[1], last[1] + 1)
    pq = np.stack(np.meshgrid(p_range, q_range, indexing="xy"), axis=-1).reshape(-1, 2)  # row by row
    corner = np.array([xmin, ymin])
    offsets = corner + pq * tile

    geoms, tiles, which, full = [], [], [], []
    for k, ring in enumerate(scaled):  # a loop over the few pattern polygons, vectorised over tiles
        geoms.append(shapely.polygons(ring[None, :, :] + offsets[:, None, :]))
        tiles.append(pq)
        which.append(np.full(len(pq), k))
        full.append(np.full(len(pq), abs(shapely.area(shapely.Polygon(ring)))))
    # order panels by tile row, pattern polygon, then tile column (a running bond: row by row)
    order = np.lexsort((np.concatenate(tiles)[:, 0], np.concatenate(which), np.concatenate(tiles)[:, 1]))
    geoms_all = np.concatenate(geoms)[order]
    tiles_all, which_all = np.concatenate(tiles)[order], np.concatenate(which)[order]
    full_all = np.concatenate(full)[order]

    clipped = _clipped(geoms_all, outline)
    parts, owner = shapely.get_parts(clipped, return_index=True)
    polygons = shapely.get_type_id(parts) == shapely.GeometryType.POLYGON.value
    parts, owner = parts[polygons], owner[polygons]
    areas = shapely.area(parts)
    development_area = float(shapely.area(outline))
    keep = areas > SLIVER * np.minimum(full_all[owner], development_area)
    parts, owner, areas = parts[keep], owner[keep], areas[keep]
    used = np.unique(owner)
    waste = 1.0 - float(areas.sum() / full_all[used].sum()) if used.size else 0.0

    rings = [_canonical_ring(shapely.get_coordinates(shapely.get_exterior_ring(g))) for g in parts]
    # the turned map carries turned flat points to the same 3D points
    _, panels_3d = turned.map.polylines_to_3d(rings)
    return Patching(
        panels_flat=rings,
        panels_3d=panels_3d,
        ids=np.arange(len(rings), dtype=np.int64),
        tiles=tiles_all[owner].astype(np.int64),
        pattern_index=which_all[owner].astype(np.int64),
        areas=areas,
        full_areas=full_all[owner],
        waste=waste,
        development_area=development_area,
        pattern_bounds=np.concatenate([corner, corner + tile]),
        development_bounds=np.array([xmin, ymin, xmax, ymax]),
        rotation_deg=float(rotation_deg),
        pivot=centre,
    )
