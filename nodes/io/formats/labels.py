"""Part IDs engraved on cut sheets: letter outlines (DejaVu Sans, from matplotlib's fonts)
placed inside a panel as large as it allows (used by :mod:`nodes.io.formats.cutfiles`)."""

from __future__ import annotations

import math
from functools import cache
from pathlib import Path

import numpy as np
import shapely
from shapely.ops import polylabel

from nodes.geometry.array_types import FloatArray

#: Smallest engraving (cap height, mm) tried before a label is declared not to fit.
SMALLEST_TEXT_MM = 2.0

@cache
def _font():  # type: ignore[no-untyped-def]
    import matplotlib
    from ezdxf.fonts.ttfonts import TTFontRenderer
    from fontTools.ttLib import TTFont

    return TTFontRenderer(TTFont(Path(matplotlib.get_data_path()) / "fonts" / "ttf" / "DejaVuSans.ttf"))


@cache
def text_outlines(text: str) -> tuple[FloatArray, ...]:
    """Closed letter outlines of ``text`` at cap height 1, baseline on y = 0, from x = 0."""
    contours = []
    for glyph in _font().get_text_glyph_paths(text, cap_height=1.0):
        for sub in glyph.sub_paths():
            points = np.array([(v.x, v.y) for v in sub.flattening(distance=2.5e-3)], dtype=float)
            if len(points) > 1 and np.array_equal(points[0], points[-1]):
                points = points[:-1]
            if len(points) >= 3:
                contours.append(points)
    return tuple(contours)


def place_label(text: str, panel: FloatArray, height: float) -> tuple[tuple[FloatArray, ...], float]:
    """The ID's outlines centred on the panel's centroid, or else on its pole of
    inaccessibility (the inside point farthest from the edges), as large as ``height``
    (cap height, mm) allows while staying inside the panel with a margin of a tenth of
    the height; (), 0 when even :data:`SMALLEST_TEXT_MM` does not fit."""
    glyphs = text_outlines(text)
    if not glyphs or height <= 0:
        return (), 0.0
    every = np.vstack(glyphs)
    low, high = every.min(axis=0), every.max(axis=0)
    polygon = shapely.Polygon(panel)
    pole = polylabel(polygon, tolerance=max(1e-3, 1e-4 * math.sqrt(polygon.area)))
    centres = [np.asarray(polygon.centroid.coords[0]), np.asarray(pole.coords[0])]
    size = min(float(height), float(np.ptp(panel, axis=0).max()))  # no taller than the panel
    while size >= SMALLEST_TEXT_MM:
        for centre in centres:
            corner = centre - (low + high) / 2 * size
            box = shapely.box(*(corner + low * size), *(corner + high * size))
            if polygon.contains(box.buffer(0.1 * size)):
                return tuple(g * size + corner for g in glyphs), size
        size *= 0.8
    return (), 0.0
