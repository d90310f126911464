"""Cut sheets as the viewport shows them: at the model's scale, beside the model.

ExportCutSheet lays parts out in millimetres of the cut file; a study model's strips are
often scaled down first (1:50 in kaohsiung-cut-sheets.graph), so its sheets, drawn in
model units at the origin, would be a speck inside the roof. :class:`SheetPreview` draws
the same layout — each sheet's border, every cut contour, the engraved IDs, seam IDs and
ticks — scaled to the size of the 3D strips they come from and laid flat beside those
strips' bounding box (a fifth of its size away along +X, level with its front and its
lowest point, as IsoMapping's Placement "Beside model" does), so sheets and model are
seen together and never overlap. It draws through the preview protocol
(:mod:`torsal.nodes.common.preview`): a value with a ``preview_geometry`` method.

Without Strips the node knows no model: the sheets are drawn at the panels' own scale,
from the origin.

It also knows each part's 3D strip, when there is one: the viewport asks :meth:`SheetPreview.part_at`
which part lies under a point picked on the sheets, and highlights that part and its strip
on the model.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import shapely

from torsal.engine.types import ValueType
from torsal.nodes.common.preview import PreviewGeometry
from torsal.nodes.geometry.array_types import FloatArray
from torsal.nodes.geometry.surface_base import Surface
from torsal.nodes.io.formats.cutlayout import CutLayout, border

#: Space between the model's bounding box and the first sheet, as a share of the box's size.
BESIDE = 0.2


@dataclass(frozen=True)
class SheetPreview:
    """A cut layout placed in the model: a layout millimetre is ``scale`` model units,
    sheet 1's lower-left corner at ``origin``, the sheets side by side along +X in the XY
    plane."""

    layout: CutLayout
    scale: float
    origin: tuple[float, float, float] = (0.0, 0.0, 0.0)
    #: per part, the 3D strip it was unrolled from (None for a panel that has none); empty
    #: when no Strips are wired
    strips: tuple[object, ...] = ()

    def part_at(self, point: Sequence[float]) -> int | None:
        """The index of the part whose cut contour holds ``point`` (model units, on the
        sheets' plane; its height is not looked at), or None."""
        flat = (np.asarray(point, dtype=float)[:2] - np.asarray(self.origin[:2])) / self.scale
        for index, part in enumerate(self.layout.parts):
            local = flat - np.array([self.layout.offset(part.sheet), 0.0])
            if shapely.contains_xy(shapely.Polygon(part.outline), float(local[0]), float(local[1])):
                return index
        return None

    def strip_of(self, index: int) -> object | None:
        """Part ``index``'s 3D strip, or None."""
        return self.strips[index] if index < len(self.strips) else None

    def to_model(self, points: FloatArray, sheet: int) -> FloatArray:
        """Sheet ``sheet``'s points (mm) in the model."""
        flat = (np.asarray(points, dtype=float) + np.array([self.layout.offset(sheet), 0.0])) * self.scale
        return np.column_stack([flat, np.zeros(len(flat))]) + np.asarray(self.origin)

    def part_polylines(self) -> list[list[FloatArray]]:
        """Per part: its cut contour first, then its engraved letters and ticks, in the model."""
        out = []
        for part in self.layout.parts:
            closed = [part.outline, *part.label, *part.seam_labels]
            lines = [self.to_model(np.vstack([c, c[:1]]), part.sheet) for c in closed]
            lines += [self.to_model(t, part.sheet) for t in part.ticks]
            out.append(lines)
        return out

    def sheet_borders(self) -> list[FloatArray]:
        ring = border(self.layout)
        return [self.to_model(np.vstack([ring, ring[:1]]), s) for s in range(self.layout.sheets)]

    def bounds(self) -> FloatArray:
        """``(2, 3)``: the lowest and highest corner of the sheets in the model."""
        corners = np.vstack(self.sheet_borders())
        return np.vstack([corners.min(axis=0), corners.max(axis=0)])

    def preview_geometry(self) -> PreviewGeometry:
        return PreviewGeometry(polylines=[*self.sheet_borders(), *(p for lines in self.part_polylines()
                                                                    for p in lines)])

    def __repr__(self) -> str:
        return f"SheetPreview({self.layout!r} at 1 mm = {self.scale:.6g} model units)"


SHEET_PREVIEW = ValueType(
    "SheetPreview", (SheetPreview,),
    "Cut sheets drawn in the model: at the strips' scale, beside them.",
    summarize=lambda p: {"type": "SheetPreview", "scale": p.scale, "origin": list(p.origin),
                         "sheets": p.layout.sheets},
)


def _edge_length(surface: Surface, samples: int = 257) -> float:
    """Its two rails' lengths (v = 0 and v = 1), which unrolling keeps, measured along
    ``samples`` points each (to ~1e-5: enough to scale a picture)."""
    u = np.linspace(0.0, 1.0, samples)
    total = 0.0
    for v in (0.0, 1.0):
        points = np.asarray(surface.derivatives(u, np.full(samples, v), 0)[0], dtype=float)
        total += float(np.linalg.norm(np.diff(points, axis=0), axis=1).sum())
    return total


def _sampled_box(surface: Surface, samples: int = 9) -> FloatArray:
    """``(2, 3)``: a box around a grid of the surface's points (enough to stand beside)."""
    u, v = np.meshgrid(np.linspace(0.0, 1.0, samples), np.linspace(0.0, 1.0, samples))
    points = np.asarray(surface.derivatives(u.ravel(), v.ravel(), 0)[0], dtype=float)
    return np.vstack([points.min(axis=0), points.max(axis=0)])


def placed(layout: CutLayout, mm: float, developments: Sequence[object],
           strips: Sequence[object]) -> SheetPreview:
    """The layout placed beside ``strips`` at their scale (see the module); ``mm`` is one
    millimetre in model units. ``developments`` are the flat surfaces the layout's parts
    were cut from, ``strips`` the 3D strips they were unrolled from, in the same order."""
    pairs = [(d, s) for d, s in zip(developments, strips, strict=False)
             if isinstance(d, Surface) and isinstance(s, Surface)]
    if not pairs:
        return SheetPreview(layout, mm)
    per_part = tuple(s if isinstance(s, Surface) else None for s in strips)
    per_part = per_part if len(per_part) == len(layout.parts) else ()
    ratios = [_edge_length(s) / flat for d, s in pairs if (flat := _edge_length(d)) > 0]
    ratios = [r for r in ratios if np.isfinite(r) and r > 0]
    scale = mm * (float(np.median(ratios)) if ratios else 1.0)
    boxes = np.vstack([_sampled_box(s) for _, s in pairs])
    low, high = boxes.min(axis=0), boxes.max(axis=0)
    size = float(np.max(high - low)) or 1.0
    origin = (float(high[0] + BESIDE * size), float(low[1]), float(low[2]))
    return SheetPreview(layout, scale, origin, per_part)
