"""A cut layout: panels placed on sheets, in millimetres, and the layers it is drawn on.

:func:`~torsal.nodes.io.formats.cutfiles.lay_out` makes a :class:`CutLayout`;
:mod:`.cutfiles` writes it as DXF and :mod:`.sheetviews` as SVG and PNG previews, both on
the layers named here: ``CUT`` (the cut contours), ``ENGRAVE`` (IDs, seam IDs and ticks),
``SHEET`` (the sheet's border) and ``REFERENCE`` (the drawn outlines, when asked).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from torsal.nodes.geometry.array_types import FloatArray
from torsal.nodes.geometry.polygons import ring_areas
from torsal.nodes.io.seams import SeamLengths

#: Space between sheets (mm) where sheets are shown side by side (previews, .3dm).
SHEET_SPACING_MM = 100.0

#: The layers a layout is drawn on (DXF layers, SVG groups).
CUT, ENGRAVE, SHEET, REFERENCE = "CUT", "ENGRAVE", "SHEET", "REFERENCE"
#: Nesting methods: sparrow's true-shape nesting, or rows of bounding rectangles.
TRUE_SHAPE, SHELF = "TrueShape", "Shelf"
NESTINGS = (TRUE_SHAPE, SHELF)


@dataclass(frozen=True)
class Part:
    """One panel placed on a sheet; coordinates in mm on that sheet."""

    id: str
    sheet: int  #: 0-based sheet number
    outline: FloatArray  #: (n, 2) the cut contour (the panel grown by half the kerf), counter-clockwise
    panel: FloatArray  #: (n, 2) the panel as drawn, where it is cut out
    label: tuple[FloatArray, ...]  #: closed letter outlines of the ID, (m, 2) each
    text_height: float  #: cap height of the label, mm (0 without a label)
    ticks: tuple[FloatArray, ...] = ()  #: open (2, 2) alignment ticks along its seams, engraved
    seam_labels: tuple[FloatArray, ...] = ()  #: closed letter outlines of its seams' IDs


@dataclass(frozen=True)
class CutLayout:
    """Panels laid out on sheets of ``width`` × ``height`` mm, ready to write."""

    width: float
    height: float
    gap: float  #: space between parts (mm)
    kerf: float
    parts: tuple[Part, ...]
    sheets: int
    model_units: str = "m"
    notes: tuple[str, ...] = ()  #: things worth telling (labels that did not fit ...)
    margin: float | None = None  #: space from the sheet's edges (mm); None: the gap
    nesting: str = SHELF
    reference: bool = False  #: also draw the drawn (un-offset) outlines on layer REFERENCE
    stopped: bool = False  #: the nesting was stopped early and kept its best layout so far
    seconds: float = 0.0  #: time the layout took
    seams: tuple[SeamLengths, ...] = ()  #: per seam, its two flat edges' lengths (mm)

    def on_sheet(self, sheet: int) -> list[Part]:
        return [p for p in self.parts if p.sheet == sheet]

    @property
    def edge(self) -> float:
        """The space kept free along the sheet's edges (mm)."""
        return self.gap if self.margin is None else self.margin

    @property
    def panel_area(self) -> float:
        return float(ring_areas([p.panel for p in self.parts]).sum())

    @property
    def usage(self) -> float:
        """Share of the sheets' area that ends up in the panels (0 to 1)."""
        if not self.sheets:
            return 0.0
        return self.panel_area / (self.sheets * self.width * self.height)

    @property
    def last_length(self) -> float:
        """How far along X the last sheet's cut contours reach (mm): the rest is offcut."""
        last = self.on_sheet(self.sheets - 1)
        return max((float(p.outline[:, 0].max()) for p in last), default=0.0)

    @property
    def stock_usage(self) -> float:
        """Share of the stock used by panels, the last sheet counted only up to
        :attr:`last_length` (its offcut goes back to stock)."""
        if not self.sheets:
            return 0.0
        stock = (self.sheets - 1) * self.width * self.height + self.last_length * self.height
        return self.panel_area / stock if stock > 0 else 0.0

    def offset(self, sheet: int) -> float:
        """Where sheet ``sheet`` starts along X when the sheets are shown side by side (mm)."""
        return sheet * (self.width + SHEET_SPACING_MM)

    def __repr__(self) -> str:
        return (
            f"CutLayout({len(self.parts)} panels on {self.sheets} sheets of "
            f"{self.width:g} × {self.height:g} mm)"
        )


def border(layout: CutLayout) -> FloatArray:
    """The sheet's outline (mm), counter-clockwise from the origin."""
    w, h = layout.width, layout.height
    return np.array([[0.0, 0.0], [w, 0.0], [w, h], [0.0, h]])
