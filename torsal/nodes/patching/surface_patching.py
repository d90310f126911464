"""patching.SurfacePatching: a panel pattern tiled over a development and carried onto its surface."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from torsal.engine.node import LIST, In, Node, NodeWarning, Out
from torsal.engine.types import NUMBER, TEXT, describe
from torsal.nodes.common.checks import number
from torsal.nodes.common.placement import placement_frame, placement_inputs
from torsal.nodes.common.values import CURVE, DEVELOPMENT, SURFACE
from torsal.nodes.geometry.curves.line import Polyline
from torsal.nodes.geometry.development_placement import place
from torsal.nodes.geometry.patching import Pattern, TooManyPanels, tile_pattern
from torsal.nodes.geometry.pattern_cover import pattern_cover
from torsal.nodes.geometry.surface_base import Surface
from torsal.nodes.geometry.unroll import Development, unroll_surface
from torsal.nodes.geometry.watch import watched
from torsal.nodes.limits import MAX_PANELS
from torsal.nodes.patching.outlines import closed_polyline, corners, ring

#: Segments used to unroll the Surface when no Development is wired.
UNROLL_SEGMENTS = 48

#: Development vertices checked against the Surface, and how far off (share of size) is too far.
CHECK_SAMPLES = 16
CHECK_DISTANCE = 1e-3


def _development(value: Any) -> Development:
    """A kernel Development, also when it arrives wrapped (an object with ``.development``)."""
    inner = getattr(value, "development", value)
    if not isinstance(inner, Development):
        raise NodeWarning(
            f"Development {describe(value)} is not a development: wire IsoMapping's Map output here"
        )
    return inner


def _check_belongs(surface: Surface, development: Development) -> float:
    """Largest distance of a few of the development's 3D ruling ends from ``surface``, per size."""
    points = np.vstack([development.starts3d, development.ends3d])
    size = float(np.linalg.norm(np.ptp(points, axis=0))) or 1.0
    pick = np.linspace(0, len(points) - 1, min(CHECK_SAMPLES, len(points))).round().astype(int)
    return float(surface.closest_point(points[pick]).distances.max()) / size


def _panel_ids(count: int) -> list[str]:
    digits = max(3, len(str(count)))
    return [f"P-{i + 1:0{digits}d}" for i in range(count)]


#: What one call costs besides its copies, in pattern copies (checking the development
#: against the surface, the outline, the mapping of the panels to 3D).
_CALL_COPIES = 500


class SurfacePatching(Node):
    """Lay a panel pattern over a development and carry the panels onto the 3D surface.

    The Pattern is one tile of the panel layout: closed curves in the XY plane (use
    StaggeredPattern for a running bond). Scaled by Scale, the tile is repeated over
    the development's bounding rectangle, starting at its lower-left corner; each
    panel is clipped to the development's outline (a panel cut in two becomes two
    panels). PanelsFlat are the outlines to cut from flat sheet; Panels3D the same
    panels on the surface, with a vertex wherever an outline crosses a ruling or a
    strip diagonal, so they follow the surface. A point of a flat panel and its 3D image correspond
    exactly (the development is an isometry of the triangulated strip), so the 3D
    panels map back onto the flat ones.

    Rotation (degrees) turns the development counter-clockwise about its area
    centroid before the pattern — which stays aligned with X and Y, the sheet's
    edges — is laid over it; PanelsFlat and DevelopmentBounds are in that turned
    frame, as the sheets are nested. On the surface the pattern therefore turns the
    other way relative to the rulings: at Rotation 0 the pattern's Y axis runs along
    the first ruling (from its start to its end) and panel rows run square to it;
    at Rotation α a panel's row edge makes the angle α with that square direction,
    dropping towards the rulings' starts as it runs along the strip (from the first
    ruling towards the last). On an upright cylinder unrolled from its base, rows
    descend with slope tan α; at 90° they run along the rulings.

    Tile is the rectangle the pattern repeats by; by default the pattern's bounding
    rectangle. A running bond overhangs its tile, so wire StaggeredPattern's Tile;
    the node remarks when the pattern leaves gaps in its tile.

    Development is IsoMapping's Map output. Surface is the 3D developable it was
    unrolled from: the node checks they belong together, and with no Development
    wired it unrolls the Surface itself (48 segments). Waste is the share of sheet
    cut off: each panel is cut from a sheet the size of its whole pattern panel.

    Placement says where the flat outputs (PatternBounds, DevelopmentBounds,
    PanelsFlat) are shown, so they do not cut through the 3D model: 0 Beside model (the
    default) lays the (turned) development's frame flat beside the surface's bounding
    box in +X, a fifth of its size away, at the height of its lowest point and level
    with its front (least y); 1 Origin leaves them where the development was unrolled
    (turned by Rotation); 2 On plane carries that frame onto Plane. Each is a rigid
    motion: PanelAreas, Waste and the panels' shapes stay the same, and Panels3D do not
    move. With Rotation 0 and the same Placement as IsoMapping, the flat panels lie
    on IsoMapping's Development.

    At most 20,000 pattern copies are laid over one development (a guard against a
    Scale typo: 1e-9 for 1 asks for billions); the node says so instead of stalling.
    """

    type_id = "patching.SurfacePatching"
    nickname, aliases = "Patch", ("panel", "panels", "panelling", "paneling", "Paneling Tools")
    inputs = (
        In("Surface", SURFACE, "S", "The 3D developable the Development was unrolled from.",
           optional=True),
        In("Development", DEVELOPMENT, "D",
           "The development to panel: IsoMapping's Map output (not its flat Development surface).",
           optional=True),
        In("Pattern", CURVE, "P", "One tile of the panel layout: closed curves in the XY plane.",
           access=LIST),
        In("Tile", CURVE, "T", "Rectangle the pattern repeats by (default: its bounding rectangle).",
           optional=True),
        In("Scale", NUMBER, "Sc", "Scale factor of the pattern (positive).", default=1.0),
        In("Rotation", NUMBER, "R", "Turn of the development under the pattern, degrees, counter-clockwise.",
           default=0.0),
        *placement_inputs("PatternBounds, DevelopmentBounds and PanelsFlat"),
    )
    outputs = (
        Out("PatternBounds", CURVE, "Pb", "The scaled tile at the corner of the development's bounds."),
        Out("DevelopmentBounds", CURVE, "Db", "Bounding rectangle of the (turned) development."),
        Out("PanelsFlat", CURVE, "Pf", "Panel outlines on the development, clipped to it.", access=LIST),
        Out("Panels3D", CURVE, "P3", "The same panels on the 3D surface.", access=LIST),
        Out("PanelIDs", TEXT, "ID", "Panel numbers to engrave: P-001, P-002, … row by row.",
            access=LIST),
        Out("PanelAreas", NUMBER, "A", "Area of each flat panel, model units².", access=LIST),
        Out("Waste", NUMBER, "W", "Share of sheet cut off, 0 to 1."),
    )

    # a list of Scales (or of developments) multiplies the capped copies of one call: one
    # solve lays at most four calls' worth at the cap (each call also costs about what
    # _CALL_COPIES copies do)
    max_work = 4 * MAX_PANELS
    work_unit = "pattern copies"

    def call_work(self, surface: Any, development: Any, pattern: list[Any], tile: Any, scale: Any,
                  rotation: Any, placement: Any = 0, plane: Any = None) -> int:
        """The pattern copies one call lays, over-counted for any Rotation (the square on
        the development's diagonal), before anything is made; at most :data:`MAX_PANELS`
        (a call past that is refused by its own check)."""
        if development is None or not pattern:
            return _CALL_COPIES
        rings = [ring("Pattern", curve)[0] for curve in pattern]
        corners = ring("Tile", tile)[0] if tile is not None else np.vstack(rings)
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):  # Scale 0: solve refuses it
            size = np.ptp(corners[:, :2], axis=0) * float(scale)
            xmin, ymin, xmax, ymax = _development(development).bounds
            reach = math.hypot(xmax - xmin, ymax - ymin)
            copies = float(np.prod(reach / size + 2.0)) * len(rings)
        if not (np.all(size > 0) and math.isfinite(copies)):
            return 1
        return int(min(copies, MAX_PANELS)) + _CALL_COPIES

    def solve(self, surface: Any, development: Any, pattern: list[Any], tile: Any, scale: Any,
              rotation: Any, placement: Any = 0,
              plane: Any = None) -> tuple[Polyline, Polyline, list[Polyline], list[Polyline], list[str],
                                      list[float], float]:
        dev = self._resolve(surface, development)
        polygons, period = self._pattern(pattern, tile)
        s = number("Scale", scale)
        if s <= 0:
            raise NodeWarning(f"Scale must be positive, not {s:g}")
        extent = float(np.max(np.abs(np.concatenate([np.ravel(p) for p in polygons] + [period]))))
        if not math.isfinite(4 * (s * extent) * (s * extent)):  # areas too (float ** 2 would raise)
            raise NodeWarning(f"Scale is {s:g}: the scaled pattern would be larger than any number "
                              "can hold; give a Scale near 1 (the pattern's own size)")
        angle = number("Rotation", rotation)
        if dev.overlaps:
            self.warn("The development overlaps itself in the plane: it cannot be cut from one sheet, "
                      "and where it overlaps a panel may land on either layer; unroll fewer turns")
        try:
            with watched(self.check_cancelled, self.progress):
                patching = tile_pattern(Pattern(tuple(polygons), period), dev, s, angle,
                                        max_panels=MAX_PANELS)
        except TooManyPanels as exc:
            times = f"{exc.count:,.0f}" if exc.count < 1e9 else f"{exc.count:.3g}"
            raise NodeWarning(
                f"Scale is {s:g}: the pattern would be laid {times} times over the development; "
                f"at most {exc.limit:,} panels can be made at once (raise Scale, or give larger "
                "panels)"
            ) from None
        except ValueError as exc:
            raise NodeWarning(str(exc).rstrip(".")) from None
        if not patching.panels_flat:
            self.warn("No panel reaches the development: check Scale and the pattern's position")
        self.check_cancelled()  # the panels made into polylines: ≈ 10 ms each set of the example's
        frame = placement_frame(self, placement, plane, np.vstack([dev.starts3d, dev.ends3d]),
                                patching.development_bounds)
        flat = [closed_polyline(place(frame, p)) for p in patching.panels_flat]
        self.check_cancelled()
        panels_3d = [closed_polyline(p) for p in patching.panels_3d]
        return (
            closed_polyline(place(frame, corners(patching.pattern_bounds))),
            closed_polyline(place(frame, corners(patching.development_bounds))),
            flat,
            panels_3d,
            _panel_ids(len(patching.panels_flat)),
            patching.areas.tolist(),
            float(patching.waste),
        )

    def _resolve(self, surface: Any, development: Any) -> Development:
        if surface is not None and not isinstance(surface, Surface):
            raise NodeWarning(f"Surface {describe(surface)} is not a surface")
        if development is None:
            if surface is None:
                raise NodeWarning("Give a Development (IsoMapping's Map output) or a developable Surface")
            try:
                dev = unroll_surface(surface, UNROLL_SEGMENTS)
            except ValueError as exc:
                raise NodeWarning(f"The Surface cannot be unrolled: {str(exc).rstrip('.')}") from None
            self.remark(f"No Development wired: the Surface was unrolled here with {UNROLL_SEGMENTS} "
                        "segments (wire IsoMapping to choose)")
            return dev
        dev = _development(development)
        if surface is not None:
            off = _check_belongs(surface, dev)
            if off > CHECK_DISTANCE:
                self.warn(f"The Development's rulings lie up to {off:.2g} of its size off the Surface: "
                          "it was not unrolled from this Surface; wire the same surface into IsoMapping")
        return dev

    def _pattern(self, pattern: list[Any], tile: Any) -> tuple[list[np.ndarray], np.ndarray]:
        if not pattern:
            raise NodeWarning("Pattern is empty: give one tile of closed panel outlines")
        rings, lifted = [], False
        for i, curve in enumerate(pattern):
            flat, off = ring(f"Pattern curve {i}", curve)
            rings.append(flat)
            lifted |= off
        if tile is None:
            points = np.vstack(rings)
            period = np.concatenate([points.min(axis=0), points.max(axis=0)])
        else:
            corners, off = ring("Tile", tile)
            lifted |= off
            period = np.concatenate([corners.min(axis=0), corners.max(axis=0)])
        if lifted:
            self.remark("The pattern does not lie in the XY plane: it is read from above (z ignored)")
        if not (period[2] > period[0] and period[3] > period[1]):
            raise NodeWarning("The pattern's tile has no area: give panels with width and height")
        self._check_cover(rings, period)
        return rings, period

    def _check_cover(self, rings: list[np.ndarray], period: np.ndarray) -> None:
        """Remark on gaps, warn on overlaps, comparing the panels' area with the tile's."""
        cover = pattern_cover(rings, period)
        if cover.gaps:
            self.remark(
                f"The pattern covers {cover.share:.0%} of its tile, so the tiling leaves gaps "
                "(a running bond overhangs its tile: wire StaggeredPattern's Tile into Tile)"
            )
        elif cover.overlaps:
            self.warn(f"The pattern's panels add up to {cover.share:.0%} of its tile, so repeated "
                      "panels overlap: give a larger Tile or smaller panels")
