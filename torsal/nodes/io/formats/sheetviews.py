"""Cut sheets a person can look at: the SVG files, and PNG previews of the sheets.

**SVG** (one file per sheet): ``width``/``height`` in mm with a matching ``viewBox`` (1
user unit = 1 mm, y pointing down as SVG wants), no fill, paths in groups by layer, with
the colours laser software maps to operations: ``CUT`` red (``#ff0000``, cut through),
``ENGRAVE`` blue (``#0000ff``, vector engraving: IDs, seam IDs and ticks), ``SHEET`` grey
(the border, not to be cut) and ``REFERENCE`` green (the drawn outlines, when asked).

Strokes are *hairlines* as CorelDRAW and Illustrator print drivers mean it: the thinnest
line the output draws at any zoom, written as ``vector-effect="non-scaling-stroke"`` with a
width of :data:`HAIRLINE_PX` px — so a browser, Inkscape or ``rsvg-convert`` shows every
cut line one pixel wide however far the 2.5 m sheet is zoomed out (a 0.01 mm stroke in
sheet units, the older convention, renders invisible). A driver that wants the width in
sheet units instead gets it with ``hairline_mm`` (e.g. 0.01): then the strokes scale with
the drawing and are invisible on screen at sheet scale (docs/cut-sheets.md).

**PNG previews** (:func:`write_previews`): one image per sheet, drawn with matplotlib
(the object API, no pyplot state, safe on a worker thread), the same colours.
"""

from __future__ import annotations

from pathlib import Path
from xml.sax.saxutils import quoteattr

import numpy as np

from torsal.nodes.geometry.array_types import FloatArray
from torsal.nodes.io.common import numbered, replacing, writable
from torsal.nodes.io.formats.cutlayout import CUT, ENGRAVE, REFERENCE, SHEET, CutLayout, border

#: Width of a hairline on screen (px), whatever the zoom.
HAIRLINE_PX = 1.0
#: Layer colours, as laser software reads them.
COLOURS = {SHEET: "#969696", REFERENCE: "#00a000", CUT: "#ff0000", ENGRAVE: "#0000ff"}
#: Width of a preview image (px) along the sheet's longer side.
PREVIEW_PX = 1600


def _svg_path(points: FloatArray, height: float) -> str:
    flipped = np.column_stack([points[:, 0], height - points[:, 1]])
    coords = " ".join(f"{x:.6f},{y:.6f}" for x, y in flipped.tolist())
    return f"M {coords} Z"


def svg_text(layout: CutLayout, sheet: int, hairline_mm: float | None = None) -> str:
    """The SVG document of one sheet: hairlines of :data:`HAIRLINE_PX` on screen, or
    ``hairline_mm`` wide in sheet units when given (see the module)."""
    w, h = layout.width, layout.height
    if hairline_mm is None:
        stroke = f'stroke-width="{HAIRLINE_PX:g}" vector-effect="non-scaling-stroke"'
        effect = ' vector-effect="non-scaling-stroke"'  # not inherited: on every path too
    else:
        stroke, effect = f'stroke-width="{float(hairline_mm):g}"', ""

    def group(name: str) -> str:
        return f'  <g id="{name}" fill="none" stroke="{COLOURS[name]}" {stroke}>'

    lines = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{w:g}mm" height="{h:g}mm" '
        f'viewBox="0 0 {w:g} {h:g}">',
        f"  <title>Torsal cut sheet {sheet + 1} of {layout.sheets}</title>",
        group(SHEET),
        f'    <path{effect} d="{_svg_path(border(layout), h)}"/>',
        "  </g>",
    ]
    parts = layout.on_sheet(sheet)
    if layout.reference:
        lines.append(group(REFERENCE))
        for part in parts:
            d = _svg_path(part.panel, h)
            lines.append(f'    <path{effect} data-panel={quoteattr(part.id)} d="{d}"/>')
        lines.append("  </g>")
    lines.append(group(CUT))
    for part in parts:
        lines.append(f'    <path{effect} data-panel={quoteattr(part.id)} d="{_svg_path(part.outline, h)}"/>')
    lines.append("  </g>")
    lines.append(group(ENGRAVE))
    for part in parts:
        if part.label or part.seam_labels or part.ticks:
            d = " ".join([_svg_path(g, h) for g in part.label + part.seam_labels]
                         + [_svg_path(t, h)[:-2] for t in part.ticks])
            lines.append(f'    <path{effect} data-panel={quoteattr(part.id)} d="{d}"/>')
    lines += ["  </g>", "</svg>", ""]
    return "\n".join(lines)


def write_svg(layout: CutLayout, path: Path, hairline_mm: float | None = None) -> list[Path]:
    """One SVG file per sheet (see the module); returns the files written."""
    files = numbered(writable(path), layout.sheets)
    for sheet, file in enumerate(files):
        text = svg_text(layout, sheet, hairline_mm)
        replacing(file, lambda temporary, text=text: temporary.write_text(text, encoding="utf-8"))
    return files


def preview_paths(files: list[Path]) -> list[Path]:
    """Where the previews of cut files go: each sheet's file with ``.png`` for its suffix."""
    return [file.with_suffix(".png") for file in files]


def write_previews(layout: CutLayout, files: list[Path], pixels: int = PREVIEW_PX) -> list[Path]:
    """A PNG per sheet beside its cut file (``roof-1.dxf`` → ``roof-1.png``), ``pixels``
    along the sheet's longer side: border grey, cuts red, engraving blue, each part's ID
    as engraved. Returns the images written."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.collections import LineCollection
    from matplotlib.figure import Figure

    dpi = 100.0
    scale = pixels / max(layout.width, layout.height)
    images = preview_paths(files)
    for sheet, image in enumerate(images):
        figure = Figure(figsize=(layout.width * scale / dpi, layout.height * scale / dpi), dpi=dpi)
        FigureCanvasAgg(figure)
        axes = figure.add_axes((0.0, 0.0, 1.0, 1.0))
        axes.set_xlim(0.0, layout.width)
        axes.set_ylim(0.0, layout.height)
        axes.set_axis_off()
        closed = [np.vstack([border(layout), border(layout)[:1]])]
        axes.add_collection(LineCollection(closed, colors=COLOURS[SHEET], linewidths=2.0))
        parts = layout.on_sheet(sheet)
        cuts = [np.vstack([p.outline, p.outline[:1]]) for p in parts]
        axes.add_collection(LineCollection(cuts, colors=COLOURS[CUT], linewidths=1.0))
        marks = [np.vstack([g, g[:1]]) for p in parts for g in p.label + p.seam_labels]
        marks += [t for p in parts for t in p.ticks]
        if marks:
            axes.add_collection(LineCollection(marks, colors=COLOURS[ENGRAVE], linewidths=0.6))

        def draw(temporary: Path, figure: Figure = figure) -> None:
            figure.savefig(temporary, format="png", dpi=dpi, facecolor="white")

        replacing(image, draw)
    return images
