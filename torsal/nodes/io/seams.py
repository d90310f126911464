"""Seams between strips: which edges of two strips meet, and the marks that say so on the cut parts.

Strips made between shared curves (RulingDevelopable between neighbouring edge curves)
meet along those curves. :func:`find_seams` finds such pairs of edges in 3D: two
strips' edges are a seam when every point of each lies within ``tolerance`` (a share of
the strips' size) of the other. Each seam gets an ID, engraved on both flat parts
beside the edge, with alignment ticks at the same distances along the edge from the
same 3D end on both parts, so the assembler can match the parts tick to tick.

:func:`seam_report` measures, per seam, the lengths of the two flat edges (mm at the
drawing's scale): a seam closes when they are equal.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import shapely
from scipy.spatial import cKDTree

from torsal.nodes.geometry.array_types import FloatArray
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.surface_base import Surface

#: Samples per edge for the seam search: coarse points against a fine polyline.
COARSE, FINE = 41, 4001
#: Edges closer than this share of the strips' size are one seam.
SEAM_TOLERANCE = 1e-3
#: Length of an alignment tick, mm.
TICK_MM = 4.0
#: How far from an edge (mm) a point is tested to tell the panel's side: well beyond the
#: 0.01 mm by which a cut outline, drawn within that tolerance, may miss the edge's vertices.
SIDE_MM = 0.1
#: Most ticks along one seam edge (a smaller TickSpacing is refused).
MAX_TICKS = 10_000


@dataclass(frozen=True)
class Seam:
    """Edge ``edge_a`` of panel ``a`` meets edge ``edge_b`` of panel ``b``; ``reversed``
    when the two edges run in opposite directions along their shared curve."""

    id: str
    a: int
    edge_a: int
    b: int
    edge_b: int
    reversed: bool


@dataclass(frozen=True)
class SeamLengths:
    """A seam's two flat edge lengths (mm) and their difference."""

    id: str
    part_a: str
    part_b: str
    length_a: float
    length_b: float

    @property
    def difference(self) -> float:
        return abs(self.length_a - self.length_b)


def find_seams(strips: Sequence[Surface], tolerance: float = SEAM_TOLERANCE) -> list[Seam]:
    """Pairs of edges of different strips that coincide in 3D (see the module), named S1, S2 …
    in the strips' order."""
    coarse_t, fine_t = np.linspace(0.0, 1.0, COARSE), np.linspace(0.0, 1.0, FINE)
    coarse = [[edge.point_at(coarse_t) for edge in strip.edges()] for strip in strips]
    fine = [[edge.point_at(fine_t) for edge in strip.edges()] for strip in strips]
    every = np.vstack([p for edges in coarse for p in edges])
    size = float(np.ptp(every, axis=0).max()) or 1.0
    limit = tolerance * size
    trees = [[cKDTree(points) for points in edges] for edges in fine]
    seams: list[Seam] = []
    for i in range(len(strips)):
        for j in range(i + 1, len(strips)):
            for a in range(4):
                if np.ptp(coarse[i][a], axis=0).max() <= limit:  # a collapsed edge (an apex)
                    continue
                for b in range(4):
                    if np.ptp(coarse[j][b], axis=0).max() <= limit:
                        continue
                    if trees[j][b].query(coarse[i][a])[0].max() > limit:
                        continue
                    if trees[i][a].query(coarse[j][b])[0].max() > limit:
                        continue
                    start_a, start_b, end_b = coarse[i][a][0], coarse[j][b][0], coarse[j][b][-1]
                    reverse = bool(np.linalg.norm(start_a - end_b) < np.linalg.norm(start_a - start_b))
                    seams.append(Seam(f"S{len(seams) + 1}", i, a, j, b, reverse))
    return seams


def edge_parameters(surface: Surface, edge: int, tolerance: float) -> FloatArray:
    """Parameters along edge ``edge`` of ``surface`` (see :meth:`Surface.edges`) for a
    polyline within ``tolerance`` of it that also passes through every vertex of the
    ruled surface's rail on that edge (an unrolled strip's edges are polylines)."""
    curve = surface.edges()[edge]
    t = np.asarray(curve.tessellate(tolerance), dtype=float)
    rail = getattr(surface, {0: "curve_a", 2: "curve_b"}.get(edge, ""), None)
    if isinstance(rail, Curve):
        breaks = np.clip(np.asarray(rail._breakpoints(), dtype=float), 0.0, 1.0)
        t = np.unique(np.concatenate([t, 1.0 - breaks if edge == 2 else breaks]))
    return t


def edge_polyline(surface: Surface, edge: int, tolerance: float) -> FloatArray:
    """Edge ``edge`` of a flat surface as ``(n, 2)`` points (its x and y), within
    ``tolerance`` of it and through every vertex of a ruled surface's rail on it: an
    unrolled strip's edges are polylines (IsoMapping's Development), and samples between
    their vertices alone would cut the corners and measure the edge short."""
    curve = surface.edges()[edge]
    points = np.asarray(curve.point_at(edge_parameters(surface, edge, tolerance)), dtype=float)[:, :2]
    # a sample that repeats a vertex to rounding would give a step with no direction
    steps = np.linalg.norm(np.diff(points, axis=0), axis=1)
    size = float(np.ptp(points, axis=0).max()) or 1.0
    keep = np.r_[True, steps > 1e-9 * size]
    if not keep[-1]:  # the end repeats the point before it: keep the end itself
        before = np.flatnonzero(keep)[-1]
        keep[before] = before == 0
        keep[-1] = True
    return points[keep]


def length(points: FloatArray) -> float:
    return float(np.linalg.norm(np.diff(points, axis=0), axis=1).sum())


def ticks(edge: FloatArray, panel: FloatArray, spacing: float, reverse: bool = False) -> list[FloatArray]:
    """Alignment ticks along ``edge`` (mm, on ``panel``'s boundary): a short segment into the
    panel every ``spacing`` mm of arc length from the edge's start (its end when
    ``reverse``), none within half a spacing of the far end."""
    if spacing <= 0:
        return []
    points = edge[::-1] if reverse else edge
    steps = np.linalg.norm(np.diff(points, axis=0), axis=1)
    along = np.concatenate([[0.0], np.cumsum(steps)])
    total = along[-1]
    if total / spacing > MAX_TICKS:
        raise ValueError(f"a tick every {spacing:g} mm along a {total:.0f} mm seam makes more than "
                         f"{MAX_TICKS:,} ticks: give a larger TickSpacing")
    stations = np.arange(spacing, total - 0.5 * spacing, spacing)
    polygon = shapely.Polygon(panel)
    out = []
    for s in stations:
        k = min(int(np.searchsorted(along, s, side="right")) - 1, len(points) - 2)
        direction = points[k + 1] - points[k]
        norm = float(np.linalg.norm(direction))
        if norm == 0:
            continue
        foot = points[k] + (s - along[k]) / norm * direction
        normal = np.array([-direction[1], direction[0]]) / norm
        if not polygon.contains(shapely.Point(foot + SIDE_MM * normal)):
            normal = -normal
        out.append(np.array([foot, foot + TICK_MM * normal]))
    return out


#: Where along a seam's edge its ID is tried, as shares of the edge's length, in order.
LABEL_STATIONS = (0.5, 0.35, 0.65, 0.2, 0.8, 0.1, 0.9)


def seam_label(text: str, edge: FloatArray, panel: FloatArray, height: float,
               glyphs: tuple[FloatArray, ...],
               avoid: shapely.Geometry | None = None) -> tuple[FloatArray, ...]:
    """The seam ID's letter outlines (``glyphs`` at cap height 1) beside ``edge``, inside
    the panel and clear of ``avoid`` (labels and ticks already engraved on it), as tall as
    ``height`` allows (down to a fifth of it): beside the edge's middle, else moved along
    the edge (:data:`LABEL_STATIONS`), else smaller; () when it does not fit anywhere."""
    if not glyphs or height <= 0:
        return ()
    del text
    every = np.vstack(glyphs)
    low, high = every.min(axis=0), every.max(axis=0)
    steps = np.linalg.norm(np.diff(edge, axis=0), axis=1)
    along = np.concatenate([[0.0], np.cumsum(steps)])
    polygon = shapely.Polygon(panel)
    stations = []
    for share in LABEL_STATIONS:
        at = along[-1] * share
        k = min(int(np.searchsorted(along, at, side="right")) - 1, len(edge) - 2)
        direction = edge[k + 1] - edge[k]
        norm = float(np.linalg.norm(direction)) or 1.0
        foot = edge[k] + (at - along[k]) / norm * direction
        normal = np.array([-direction[1], direction[0]]) / norm
        if not polygon.contains(shapely.Point(foot + SIDE_MM * normal)):
            normal = -normal
        stations.append((foot, normal))
    size = min(height, float(np.ptp(panel, axis=0).max()))  # no taller than the panel
    while size >= height / 5:
        for foot, normal in stations:
            for away in (1.2, 2.0, 3.0):
                centre = foot + normal * (TICK_MM + away * size * max(1.0, (high - low).max() / 2))
                corner = centre - (low + high) / 2 * size
                box = shapely.box(*(corner + low * size), *(corner + high * size)).buffer(0.1 * size)
                if polygon.contains(box) and (avoid is None or not box.intersects(avoid)):
                    return tuple(g * size + corner for g in glyphs)
        size *= 0.8
    return ()
