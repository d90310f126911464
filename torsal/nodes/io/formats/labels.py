"""Part IDs engraved on cut sheets: letter outlines (DejaVu Sans, from matplotlib's fonts)
placed inside a panel as large as it allows (used by :mod:`torsal.nodes.io.formats.cutfiles`)."""

from __future__ import annotations

import gc
import importlib.util
import math
import threading
from concurrent.futures import Future, wait
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
import shapely
from shapely.ops import polylabel

from torsal.nodes.geometry.array_types import FloatArray
from torsal.nodes.geometry.watch import watch_check
from torsal.nodes.io.common import FileFailure

#: Smallest engraving (cap height, mm) tried before a label is declared not to fit.
SMALLEST_TEXT_MM = 2.0
#: Where DejaVu Sans lies in the matplotlib package (found without importing matplotlib).
FONT_IN_MATPLOTLIB = Path("mpl-data") / "fonts" / "ttf" / "DejaVuSans.ttf"
#: Seconds between looks at the cancel token while the font loads (see :func:`_font`).
LOOK_EVERY = 0.01


def font_file() -> Path:
    """DejaVu Sans as matplotlib ships it, found without importing matplotlib (0.1-0.5 s)."""
    spec = importlib.util.find_spec("matplotlib")
    if spec is not None and spec.origin is not None:
        path = Path(spec.origin).parent / FONT_IN_MATPLOTLIB
        if path.is_file():
            return path
    raise FileFailure("The engraving font (DejaVu Sans, shipped with matplotlib) is not installed: install "
                      "matplotlib, or set TextHeight to 0 to export without engraved IDs")


def _load_font() -> Any:
    from ezdxf.fonts.ttfonts import TTFontRenderer
    from fontTools.ttLib import TTFont

    return TTFontRenderer(TTFont(font_file()))


def _load_font_quietly() -> Any:
    """:func:`_load_font` without the full garbage collection it would set off.

    Importing ezdxf and parsing the font make ~50,000 objects that live as long as the
    process (modules, classes, glyph tables), four times the heap of a fresh process:
    enough to set off a full collection in the middle of the load, 70-350 ms that hold
    the interpreter lock, so no other thread (a node looking at its cancel token, the
    canvas) runs meanwhile. So the collector waits during the load, and the objects it
    made then go to the collector's permanent generation (:func:`gc.freeze`), which no
    later collection walks. The price: whatever was cyclic garbage at that moment stays
    (once a process, a fraction of a second's worth)."""
    paused = gc.isenabled()
    gc.disable()
    try:
        return _load_font()
    finally:
        gc.freeze()
        if paused:
            gc.enable()


_LOADING_LOCK = threading.Lock()


@cache
def _loading() -> Future[Any]:
    """The font, loading on a thread of its own (once a process)."""
    future: Future[Any] = Future()

    def load() -> None:
        try:
            future.set_result(_load_font_quietly())
        except BaseException as exc:  # handed to the caller by future.result()
            future.set_exception(exc)

    threading.Thread(target=load, name="torsal-engraving-font", daemon=True).start()
    return future


def _font() -> Any:
    """ezdxf's TrueType renderer of DejaVu Sans. The first call imports ezdxf and parses the
    font (0.2-0.7 s, one call that cannot look at the cancel token), so that work runs on a
    thread of its own while this one looks at the token every :data:`LOOK_EVERY` s: Esc
    stops a node during it (the load goes on and serves the next call)."""
    with _LOADING_LOCK:
        future = _loading()
    check = watch_check()
    if check is not None:
        while not future.done():
            check()
            wait([future], timeout=LOOK_EVERY)
    return future.result()


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


def _along_axis(polygon: shapely.Polygon, centroid: FloatArray) -> list[FloatArray]:
    """Middles of the panel's cross-sections at a few places along its long axis (through
    the centroid): where a label can go on a long narrow part besides its centre."""
    ring = np.asarray(polygon.exterior.coords)
    axes = np.linalg.svd(ring - centroid, full_matrices=False)[2]
    long, across = axes[0], axes[1]
    span = float(np.ptp((ring - centroid) @ long))
    reach = float(np.ptp((ring - centroid) @ across)) + 1.0
    out = []
    for share in (-0.3, 0.3, -0.15, 0.15, -0.42, 0.42):
        foot = centroid + share * span * long
        chord = polygon.intersection(shapely.LineString([foot - reach * across, foot + reach * across]))
        if not chord.is_empty:
            out.append(np.asarray(chord.centroid.coords[0]))
    return out


def place_label(text: str, panel: FloatArray, height: float,
                avoid: shapely.Geometry | None = None) -> tuple[tuple[FloatArray, ...], float]:
    """The ID's outlines centred on the panel's centroid, or else on its pole of
    inaccessibility (the inside point farthest from the edges), or else moved along the
    panel's long axis, as large as ``height`` (cap height, mm) allows while staying inside
    the panel with a margin of a tenth of the height and clear of ``avoid`` (the seam labels
    and ticks already engraved on it); (), 0 when even :data:`SMALLEST_TEXT_MM` does not fit."""
    if height <= 0:  # nothing engraved: the font is not even loaded (its first load takes a second)
        return (), 0.0
    glyphs = text_outlines(text)
    if not glyphs:
        return (), 0.0
    every = np.vstack(glyphs)
    low, high = every.min(axis=0), every.max(axis=0)
    polygon = shapely.Polygon(panel)
    centroid = np.asarray(polygon.centroid.coords[0])
    centres: list[FloatArray | None] = [centroid, None]  # None: the pole, found when first needed (~40 ms)
    size = min(float(height), float(np.ptp(panel, axis=0).max()))  # no taller than the panel
    while size >= SMALLEST_TEXT_MM:
        k = 0
        while k < len(centres):
            centre = centres[k]
            if centre is None:
                found = polylabel(polygon, tolerance=max(1e-3, 1e-4 * math.sqrt(polygon.area)))
                centre = centres[k] = np.asarray(found.coords[0])
                if avoid is not None:  # somewhere else along the part when the middle is taken
                    centres += _along_axis(polygon, centroid)
            corner = centre - (low + high) / 2 * size
            box = shapely.box(*(corner + low * size), *(corner + high * size)).buffer(0.1 * size)
            if polygon.contains(box) and (avoid is None or not box.intersects(avoid)):
                return tuple(g * size + corner for g in glyphs), size
            k += 1
        size *= 0.8
    return (), 0.0
