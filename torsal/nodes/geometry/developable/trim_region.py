"""A trimmed design's region, as the cut of its strips sees it (:mod:`.trimmed`).

- :class:`Patch`: the underlying surface on the trim's (u, v) box, reparameterised to
  [0, 1]², which is rationalised as any design.
- :func:`signed_inside`: a point's signed distance from the trim loops, in the surface's
  (u, v) scaled by its mean speeds (about a distance along the surface).
- :func:`sharp_corners`, :func:`trim_corners`: the corners of a region, which a cut keeps
  (a sheet line through each, :func:`~.trimmed.cut_strip`).
- :func:`trim_points`: points along the trim loops, for the coverage.
- :func:`checked_densely`: a cut strip's deviation checked on dense samples besides its
  certificate.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import shapely
from numpy.typing import ArrayLike

from ..array_types import FloatArray
from ..surface_base import Surface
from ..trimmed_surface import TrimmedSurface
from .rationalise import Strip

#: Share of the trim's (u, v) box added on each side for the patch that is rationalised.
MARGIN = 0.02
#: Samples per trim loop span, for the coverage.
LOOP_SAMPLES = 8
#: A trim's corner: where its outline turns by more than this (rad). The sheet gets a line
#: through each corner the strip covers, whose cut ends at the corner exactly.
CORNER = 0.3
#: Samples along and across a cut strip where its distance from the design is checked
#: besides its certificate (:func:`checked_densely`).
CHECK = (161, 9)


class Patch(Surface):
    """``surface`` on the (u, v) box ``(u0, u1, v0, v1)``, reparameterised to [0, 1]²."""

    def __init__(self, surface: Surface, box: tuple[float, float, float, float]) -> None:
        self.surface = surface
        self.box = tuple(float(b) for b in box)
        self.closed_u = self.closed_v = False

    def __repr__(self) -> str:
        return f"Patch({self.surface!r}, {self.box})"

    def to_surface(self, u: ArrayLike, v: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """The underlying surface's (u, v) of the patch's."""
        u0, u1, v0, v1 = self.box
        return u0 + (u1 - u0) * np.asarray(u, dtype=float), v0 + (v1 - v0) * np.asarray(v, dtype=float)

    def from_surface(self, uv: ArrayLike) -> FloatArray:
        """The patch's (u, v) of the underlying surface's ``(n, 2)``."""
        u0, u1, v0, v1 = self.box
        uv = np.asarray(uv, dtype=float)
        return np.column_stack([(uv[:, 0] - u0) / (u1 - u0), (uv[:, 1] - v0) / (v1 - v0)])

    def derivatives(self, u: ArrayLike, v: ArrayLike, order: int = 1) -> list[FloatArray]:
        self._check_order(order)
        u0, u1, v0, v1 = self.box
        found = self.surface.derivatives(*self.to_surface(u, v), order)
        du, dv = u1 - u0, v1 - v0
        scale = [1.0, du, dv, du * du, du * dv, dv * dv][:len(found)]
        return [d * k for d, k in zip(found, scale, strict=True)]


def patch_of(design: TrimmedSurface) -> Patch:
    """The underlying surface on the trim's (u, v) box, :data:`MARGIN` larger each way
    (within the surface's own square)."""
    u0, v0, u1, v1 = design.region.bounds
    pad_u, pad_v = MARGIN * (u1 - u0), MARGIN * (v1 - v0)
    return Patch(design.surface, (max(0.0, u0 - pad_u), min(1.0, u1 + pad_u),
                                  max(0.0, v0 - pad_v), min(1.0, v1 + pad_v)))




def sharp_corners(region: shapely.Geometry, angle: float = CORNER) -> FloatArray:
    """The vertices of a polygon (or several) where its outline turns by more than
    ``angle`` (rad), (k, 2): the corners a cut must keep (:func:`cut_strip`)."""
    out = [np.empty((0, 2))]
    for polygon in getattr(region, "geoms", [region]):
        if polygon.is_empty or polygon.geom_type != "Polygon":
            continue
        for ring in (polygon.exterior, *polygon.interiors):
            xy = np.asarray(ring.coords)[:-1]
            step = np.diff(np.vstack([xy, xy[:1]]), axis=0)
            keep = np.linalg.norm(step, axis=1) > 1e-12 * max(float(np.ptp(xy, axis=0).max()), 1e-300)
            xy, step = xy[keep], step[keep]  # repeated vertices left out
            if len(xy) < 3:
                continue
            before = np.roll(step, 1, axis=0)  # the edge into each vertex
            cross = before[:, 0] * step[:, 1] - before[:, 1] * step[:, 0]
            turn = np.arctan2(np.abs(cross), np.einsum("ij,ij->i", before, step))
            out.append(xy[turn > angle])
    return np.concatenate(out)


def trim_corners(design: TrimmedSurface, margin: float = 0.0) -> FloatArray:
    """The corners (3D points on the design) of the region :func:`signed_inside` keeps with
    the same ``margin``."""
    speed = _speeds(design)
    region = shapely.transform(design.region, lambda xy: xy * speed)
    if margin > 0.0:
        region = region.buffer(margin, quad_segs=32)
    uv = sharp_corners(region) / speed
    return design.surface.point_at(uv[:, 0], uv[:, 1]) if len(uv) else np.empty((0, 3))


def _speeds(design: TrimmedSurface) -> FloatArray:
    """The surface's mean speeds along u and v (the scale of :func:`signed_inside`'s plan)."""
    u, v = np.meshgrid(np.linspace(0.0, 1.0, 17), np.linspace(0.0, 1.0, 17), indexing="ij")
    _, su, sv = design.surface.derivatives(u.ravel(), v.ravel(), 1)
    return np.array([np.linalg.norm(su, axis=1).mean(), np.linalg.norm(sv, axis=1).mean()])


def trim_points(design: TrimmedSurface) -> FloatArray:
    """Points along every trim loop, :data:`LOOP_SAMPLES` per span, on the design."""
    out = []
    for loop in design.loops:
        w = np.linspace(0.0, 1.0, LOOP_SAMPLES + 1)[:-1]
        dense = (loop[:-1, None] + w[None, :, None] * (loop[1:] - loop[:-1])[:, None]).reshape(-1, 2)
        out.append(design.surface.point_at(dense[:, 0], dense[:, 1]))
    return np.concatenate(out)


def checked_densely(design: Surface, strip: Strip) -> None:
    """``strip``'s deviation raised to the largest distance of :data:`CHECK` samples of it
    from the design, where that is larger. A cut strip's edge along the cut is a cubic
    through the cut points; where the rulings run nearly along the trim it can bulge past
    it between the certificate's samples (5.1 cm where 1.88 cm was certified, a ring strip
    of the double bump at 2 cm), so dense samples must agree too."""
    u, v = (a.ravel() for a in np.meshgrid(np.linspace(0.0, 1.0, CHECK[0]), np.linspace(0.0, 1.0, CHECK[1]),
                                           indexing="ij"))
    points = strip.surface.point_at(u, v)
    distance = design.closest_point(points, candidates=2, tolerance=1e-12).distances
    k = int(np.argmax(distance))
    if distance[k] > strip.deviation:
        strip.deviation, strip.where = float(distance[k]), points[k]


def signed_inside(design: TrimmedSurface, patch: Patch, margin: float = 0.0
                  ) -> Callable[[FloatArray], FloatArray]:
    """Points' signed distance from the trim loops, positive inside, plus ``margin``: each
    point projected onto the patch, its (u, v) scaled by the surface's mean speeds along u
    and v (so the distance is about one along the surface, in model units)."""
    speed = _speeds(design)
    region = shapely.transform(design.region, lambda xy: xy * speed)
    boundary = region.boundary

    def inside(points: FloatArray) -> FloatArray:
        found = patch.closest_point(points, candidates=1, tolerance=1e-9).parameters
        uv = np.column_stack(patch.to_surface(found[:, 0], found[:, 1])) * speed
        distance = shapely.distance(boundary, shapely.points(uv))
        return np.where(shapely.contains_xy(region, uv[:, 0], uv[:, 1]), distance, -distance) + margin

    return inside
