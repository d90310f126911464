"""Rectangles onto sheets: first-fit decreasing-height shelf packing.

Parts are packed by their bounding rectangles, tallest first. Each sheet is filled in
horizontal shelves from the bottom up: a part goes on the first shelf, of the first
sheet, that has room for it (its height no more than the shelf's, its width within
what is left of the row); otherwise it opens a new shelf above the last one, and when
no sheet has height left, a new sheet. ``gap`` separates parts from each other and
from the sheet's edges. Rectangles never overlap by construction; the waste is that of
a shelf packing (typically 10–30 % more than a true nesting for ragged parts).

>>> sheet, corner = shelf_pack([[4, 2], [3, 1], [5, 2]], (10, 6), gap=0.5)
>>> sheet.tolist(), corner.tolist()
([0, 0, 0], [[0.5, 3.0], [6.0, 0.5], [0.5, 0.5]])
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray


class DoesNotFit(ValueError):
    """A part is larger than the usable sheet; ``index`` says which."""

    def __init__(self, index: int, message: str) -> None:
        super().__init__(message)
        self.index = index


@dataclass
class _Shelf:
    y: float
    height: float
    x: float  # where the next part on this shelf starts


@dataclass
class _Sheet:
    shelves: list[_Shelf] = field(default_factory=list)
    top: float = 0.0  # where the next shelf starts


def shelf_pack(
    sizes: ArrayLike, sheet: tuple[float, float], gap: float = 0.0, margin: float | None = None
) -> tuple[NDArray[np.intp], NDArray[np.float64]]:
    """Sheet number and lower-left corner of each ``(width, height)`` rectangle, ``gap``
    apart and ``margin`` (the gap when None) from the sheet's edges.

    Raises :class:`DoesNotFit` for a rectangle wider or taller than the sheet less two margins.
    """
    wh = np.asarray(sizes, dtype=float).reshape(-1, 2)
    width, height = float(sheet[0]), float(sheet[1])
    edge = gap if margin is None else float(margin)
    if not (width > 2 * edge and height > 2 * edge):
        raise ValueError(f"A {width:g} × {height:g} sheet leaves no room inside a margin of {edge:g}.")
    too_big = (wh[:, 0] > width - 2 * edge) | (wh[:, 1] > height - 2 * edge)
    if too_big.any():
        i = int(np.flatnonzero(too_big)[0])
        raise DoesNotFit(
            i,
            f"Part {i} is {wh[i, 0]:g} × {wh[i, 1]:g}, larger than the {width:g} × {height:g} sheet "
            f"less a margin of {edge:g} on each side.",
        )
    order = np.lexsort((-wh[:, 0], -wh[:, 1]))  # tallest first, then widest
    sheets: list[_Sheet] = []
    sheet_of = np.zeros(len(wh), dtype=np.intp)
    corner = np.zeros((len(wh), 2))
    for i in order.tolist():
        w, h = wh[i]
        placed = False
        for s, current in enumerate(sheets):
            for shelf in current.shelves:
                if h <= shelf.height and shelf.x + w <= width - edge:
                    sheet_of[i], corner[i] = s, (shelf.x, shelf.y)
                    shelf.x += w + gap
                    placed = True
                    break
            if not placed and current.top + h <= height - edge:
                current.shelves.append(_Shelf(current.top, h, edge + w + gap))
                sheet_of[i], corner[i] = s, (edge, current.top)
                current.top += h + gap
                placed = True
            if placed:
                break
        if not placed:
            sheets.append(_Sheet([_Shelf(edge, h, edge + w + gap)], edge + h + gap))
            sheet_of[i], corner[i] = len(sheets) - 1, (edge, edge)
    return sheet_of, corner
