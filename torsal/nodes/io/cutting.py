"""Cut files for the shop: ExportCutSheet lays flat panels out on sheets and writes DXF or SVG."""

from __future__ import annotations

import math
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from torsal.engine.datatree import DataTree
from torsal.engine.node import LIST, TREE, In, Node, NodeWarning, Out
from torsal.engine.types import BOOLEAN, NUMBER, TEXT, ValueType
from torsal.nodes.common.checks import number
from torsal.nodes.common.values import CURVE, SURFACE
from torsal.nodes.geometry.surface_base import Surface
from torsal.nodes.geometry.watch import watched
from torsal.nodes.io import seams, sheet_preview
from torsal.nodes.io.common import FileFailure, file_errors, may_write, unit_name, unit_scale, write_target
from torsal.nodes.io.formats import cutfiles
from torsal.nodes.io.formats.cutfiles import CutLayout
from torsal.nodes.io.sheet_preview import SHEET_PREVIEW


def _nesting(value: Any) -> str:
    text = str(value or "").strip().replace(" ", "").replace("-", "").lower()
    for name in cutfiles.NESTINGS:
        if text == name.lower():
            return name
    raise NodeWarning(f"Nesting is {value!r}: use {' or '.join(cutfiles.NESTINGS)}")


def _seed(value: Any) -> int:
    seed = number("Seed", value)
    if not (math.isfinite(seed) and seed == int(seed) and 0 <= seed < 2**63):
        raise NodeWarning(f"Seed must be a whole number from 0, not {seed:g}")
    return int(seed)


def _layout_summary(layout: CutLayout) -> dict[str, Any]:
    return {
        "type": "CutLayout",
        "panels": len(layout.parts),
        "sheets": layout.sheets,
        "sheet": [layout.width, layout.height],
        "usage": round(layout.usage, 6),
        "stock_usage": round(layout.stock_usage, 6),
        "nesting": layout.nesting,
    }


@contextmanager
def refused_settings() -> Iterator[None]:
    """A setting lay_out refuses (one input value: SheetWidth, Gap, Kerf …) becomes a warning
    naming it, as nodes/common/checks.py has it; other failures stay what they are."""
    try:
        yield
    except cutfiles.SettingProblem as exc:
        raise NodeWarning(str(exc).rstrip(".")) from None


WRITE_IS_FALSE = ("Write is false: this node writes no files (its Layout still goes to --export and "
                  "Export…)")


def _usage(layout: CutLayout) -> str:
    return (f"{layout.stock_usage:.1%} of the stock used on {layout.sheets} sheet"
            f"{'s' if layout.sheets != 1 else ''}, the last to its parts' reach")


def _remarks(layout: CutLayout) -> list[str]:
    """The layout's notes, and its seams' worst edge-length difference."""
    notes = list(layout.notes)
    if layout.seams:
        worst = max(layout.seams, key=lambda s: s.difference)
        notes.append(f"{len(layout.seams)} seams; the largest edge-length difference is "
                     f"{worst.difference:.4g} mm ({worst.id}: {worst.part_a} | {worst.part_b})")
    return notes


CUT_LAYOUT = ValueType(
    "CutLayout", (CutLayout,),
    "Flat panels laid out on sheets, in mm: what a cut file holds.",
    summarize=_layout_summary,
)


class ExportCutSheet(Node):
    """Lay flat panels out on sheets and write cut files: DXF or SVG, in millimetres.

    Panels are closed flat outlines (SurfacePatching's PanelsFlat), Surfaces flat
    surfaces whose boundary is the outline (IsoMapping's Development), in model Units.
    Before anything is laid out each one is checked: an open, non-flat or
    self-crossing outline, a repeated ID, the same panel given twice, or a panel
    larger than the sheet stops the export with a message naming the panel.
    Each panel is grown by half the Kerf (mitred corners) so the cut part keeps its
    drawn size, and nested with Gap between the cut contours and Margin from the
    sheet's edges. Nesting TrueShape nests the parts' true outlines with sparrow,
    the state of the art in irregular strip packing, filling one sheet after the other
    and leaving the last one as short as it can (its offcut goes back to stock); it
    searches with the random Seed for about TimeBudget seconds of an unloaded machine —
    the search is counted in steps, not seconds, so the same graph gives the same layout
    on every run and machine, a busy machine only takes longer (up to ten times the
    budget and a minute, then it stops with a remark that the layout may differ) — and
    keeps the row layout when that takes less stock. In the app the search runs in the
    background (docs/anytime-results.md): the rows show at once, then each better true-shape
    layout replaces the last as the search finds it, with its usage in the node's message and
    the search's progress bar in the status bar, and the canvas and other solves never
    wait; Esc stops the search and keeps the best layout found so far. With Write true the
    node waits for its layout and writes that; ``torsal run --nesting-time S`` shows rows
    and searches for at most S s.
    Nesting Shelf (the default, so graphs made before TrueShape keep their layout)
    places the parts' bounding rectangles in rows, tallest first: instant, more
    sheets. TrueShape turns parts freely (Shelf lays them along the sheet); Grain
    true turns them only by 0° or 180° (the grain runs along the sheet's X in every
    part); Rotate false keeps them as drawn. Each ID is engraved inside its
    part as letter outlines, TextHeight tall or smaller where the panel is narrow.
    Wire the 3D strips the Surfaces were unrolled from into Strips (same order) and
    the edges neighbouring strips share become seams: each seam's ID (S1, S2 …) is
    engraved beside the edge on both parts, with alignment ticks every TickSpacing mm
    measured from the same end, and Seams / SeamDifferences report the two flat edges'
    lengths — a seam closes when they are equal.

    The file type follows Path's extension. DXF (R2010, units mm): one closed
    polyline per part on layer CUT, the letters on ENGRAVE, the sheet's border on
    SHEET and, with Reference true, the drawn (un-offset) outlines on REFERENCE —
    those two layers are not plotted and not to be cut. SVG: a page of the sheet's
    size in mm, no fill, colours by layer as laser software maps them (red CUT, blue
    ENGRAVE, grey SHEET border, green REFERENCE), each line a hairline drawn one pixel
    wide at any zoom (vector-effect non-scaling-stroke), so the file can be checked in a
    browser before cutting (docs/cut-sheets.md). ``torsal run --export … --preview``
    also writes a PNG of each sheet. One file per
    sheet: name.dxf for one sheet, name-1.dxf, name-2.dxf … for more (name-01 …
    from ten sheets on, so they sort). Nothing is written until Write is true and
    you have allowed the graph to write files; Path is relative to the graph's folder
    and must stay inside it. A file it replaces is kept as ``<name>.bak``.
    Layout also goes to ``torsal run --export ID.Layout=file.dxf`` (.svg, .3dm).
    The viewport draws Preview: each sheet's border, the cut contours, IDs and seam marks
    at the scale of the 3D Strips (so a 1:50 layout shows at the roof's size) and beside
    their bounding box, never inside the model; without Strips, at the panels' scale from
    the origin. Click a part on the sheets to highlight it with the strip it was cut from on
    the model, or a strip to highlight it with its part. Cuts and Sheets (model units, from
    the origin) are for wiring on.
    """

    type_id = "io.ExportCutSheet"
    nickname, aliases = "Cut", ("nest", "nesting", "cut sheet", "laser", "cutter", "dxf", "svg")
    inputs = (
        In("Path", TEXT, "P", "The .dxf or .svg file to write, relative to the graph's folder.", default=""),
        In("Panels", CURVE, "Pn", "Closed flat panel outlines, in model units.", access=TREE,
           optional=True),
        In("Surfaces", SURFACE, "S", "Flat surfaces (IsoMapping's Development): their boundary is cut.",
           access=TREE, optional=True),
        In("PanelIDs", TEXT, "ID", "One ID per panel, then per surface, engraved (default P-001 …).",
           access=TREE, optional=True),
        In("SheetWidth", NUMBER, "W", "Sheet width along X, mm.", default=2500.0),
        In("SheetHeight", NUMBER, "H", "Sheet height along Y, mm.", default=1250.0),
        In("Gap", NUMBER, "G", "Space between the parts' cut contours, mm.", default=10.0),
        In("Kerf", NUMBER, "K", "Width of the cut, mm; the contour moves out by half of it.", default=0.0),
        In("TextHeight", NUMBER, "Th", "Cap height of the engraved IDs, mm (0: no engraving).", default=10.0),
        In("Rotate", BOOLEAN, "Ro", "Turn panels to nest them (false: keep their direction).",
           default=True),
        In("Units", TEXT, "U", "The graph's model units (mm, cm, m, in, ft), those of Panels.", default="m"),
        In("Margin", NUMBER, "M", "Space kept free along the sheet's edges, mm (empty: the Gap).",
           optional=True),
        In("Nesting", TEXT, "N", "TrueShape (sparrow: true outlines, fewer sheets) or Shelf (bounding "
           "rectangles in rows: instant).", default=cutfiles.SHELF),
        In("Grain", BOOLEAN, "Gr", "Turn parts only by 0° or 180°, so the grain runs the same way in all.",
           default=False),
        In("TimeBudget", NUMBER, "T", "Size of TrueShape nesting's search, in seconds of an unloaded machine "
           "(at least 1; counted in steps, so the layout repeats).", default=10.0),
        In("Seed", NUMBER, "Sd", "Seed of TrueShape nesting's random search.", default=0),
        In("Reference", BOOLEAN, "Rf", "Also draw the drawn (un-offset) outlines on layer REFERENCE.",
           default=False),
        In("Strips", SURFACE, "St", "The 3D strips the Surfaces were unrolled from, in the same order: "
           "edges they share are seams.", access=TREE, optional=True),
        In("TickSpacing", NUMBER, "Ts", "Alignment ticks along each seam every this many mm (0: none).",
           default=50.0),
        In("Write", BOOLEAN, "Wr", "Set to true to write the files; while false nothing is written.",
           default=False),
    )
    outputs = (
        Out("Paths", TEXT, "P", "The files written, one per sheet (none while Write is false).",
            access=LIST),
        Out("Layout", CUT_LAYOUT, "L", "The panels on their sheets, for --export and Bake."),
        Out("Cuts", CURVE, "C", "The cut contours as laid out, sheets side by side, model units.",
            access=LIST, preview=False),
        Out("Sheets", CURVE, "S", "The sheets' outlines, side by side along X, model units.", access=LIST,
            preview=False),
        Out("Usage", NUMBER, "U", "Share of the sheets' area used by panels, 0 to 1."),
        Out("Seams", TEXT, "Sm", "Per seam: its ID, the two parts and their edges' lengths (mm).",
            access=LIST),
        Out("SeamDifferences", NUMBER, "Sd", "Per seam, the difference of its two flat edges' lengths, mm.",
            access=LIST),
        Out("Preview", SHEET_PREVIEW, "Pv", "The sheets as the viewport draws them: borders, cuts and IDs at "
            "the Strips' scale, beside them (docs/cut-sheets.md)."),
    )

    def solve(
        self,
        path: Any,
        panels: DataTree,
        surfaces: DataTree,
        ids: DataTree,
        width: Any,
        height: Any,
        gap: Any,
        kerf: Any,
        text_height: Any,
        rotate: Any,
        units: Any,
        margin: Any,
        nesting: Any,
        grain: Any,
        budget: Any,
        seed: Any,
        reference: Any,
        strips: DataTree,
        tick_spacing: Any,
        write: Any,
    ) -> tuple[Any, ...]:
        curves = panels.all_items() + surfaces.all_items()
        # each branch is one drawing (one strip's development): a part of one branch may
        # coincide with a part of another in the plane and still be a separate part
        sources = [b for b, branch in enumerate(panels.branches + surfaces.branches) for _ in branch]
        if not curves:
            raise NodeWarning("There are no panels: wire closed flat curves into Panels or flat surfaces "
                              "into Surfaces")
        names = None if ids.is_empty() else [None if i is None else str(i) for i in ids.all_items()]
        if names is not None and None in names:
            raise NodeWarning(f"PanelIDs has an empty (null) item at position {names.index(None) + 1}: give "
                              "every panel an ID, or leave PanelIDs unwired for P-001 …")
        found: list[seams.Seam] = []
        if not strips.is_empty():
            solids = strips.all_items()
            if len(solids) != len(surfaces.all_items()):
                raise NodeWarning(f"Strips has {len(solids)} items for {len(surfaces.all_items())} Surfaces: "
                                  "give the 3D strip of each development, in the same order")
            wrong = next((k for k, x in enumerate(solids) if not isinstance(x, Surface)), None)
            if wrong is not None:
                what = "empty (null)" if solids[wrong] is None else "not a surface"
                raise NodeWarning(f"Strips item {wrong + 1} is {what}: give the 3D strip of each "
                                  "development, in the same order")
            offset = len(panels.all_items())
            found = [seams.Seam(f.id, f.a + offset, f.edge_a, f.b + offset, f.edge_b, f.reversed)
                     for f in seams.find_seams(solids)]
        spacing = number("TickSpacing", tick_spacing)
        if not (math.isfinite(spacing) and spacing >= 0):
            raise NodeWarning(f"TickSpacing must be 0 or a positive length in mm, not {spacing:g}")
        try:
            model_units = unit_name(units)
        except FileFailure as exc:  # one input value: refused, as checks.py has it
            raise NodeWarning(str(exc)) from None
        chosen = _nesting(nesting)
        # in the app, TrueShape answers with rows at once and searches in the background
        # (torsal/engine/improve.py); a node that writes files waits for its layout
        later = chosen == cutfiles.TRUE_SHAPE and self.anytime and not write
        settings = {
            "width": number("SheetWidth", width), "height": number("SheetHeight", height),
            "gap": number("Gap", gap), "kerf": number("Kerf", kerf),
            "text_height": number("TextHeight", text_height), "rotate": bool(rotate), "units": model_units,
            "sources": sources, "margin": None if margin is None else number("Margin", margin),
            "grain": bool(grain), "budget": number("TimeBudget", budget), "seed": _seed(seed),
            "reference": bool(reference), "seams": found, "tick_spacing": spacing,
        }
        with file_errors():
            with refused_settings(), watched(self.check_cancelled, self.progress):
                layout = cutfiles.lay_out(
                    curves, names, nesting=cutfiles.SHELF if later else chosen,
                    stop=lambda: self.token.cancelled, report=self.progress, **settings,
                )
            files = []
            if write:
                target = write_target(self, path)
                if may_write(self, cutfiles.numbered(target, layout.sheets)):
                    files = [str(p) for p in cutfiles.write_cut_files(layout, target)]
            else:
                self.remark(WRITE_IS_FALSE)
        for note in _remarks(layout):
            self.remark(note)
        back = unit_scale("mm", model_units)
        developments = [None] * len(panels.all_items()) + surfaces.all_items()
        solids = [None] * len(panels.all_items()) + ([] if strips.is_empty() else strips.all_items())

        def outputs(layout: CutLayout, files: list[str]) -> tuple[Any, ...]:
            return (
                files,
                layout,
                cutfiles.placed_curves(layout, scale=back),
                cutfiles.sheet_outlines(layout, scale=back),
                layout.usage,
                [f"{s.id}: {s.part_a} {s.length_a:.3f} mm | {s.part_b} {s.length_b:.3f} mm"
                 for s in layout.seams],
                [s.difference for s in layout.seams],
                sheet_preview.placed(layout, back, developments, solids),
            )

        if later:
            shelf = layout
            self.remark(f"TrueShape nesting searches in the background: rows shown meanwhile "
                        f"({_usage(shelf)})")

            def improve(stop, publish, progress):  # type: ignore[no-untyped-def]
                """Each true-shape layout that takes less stock than the last shown, published as
                the search finds it (the rows first), and the search's final one."""
                shown = [shelf.stock_usage]

                def show(layout: CutLayout, what: str) -> None:
                    # the final one again when no better: its message says the search has ended
                    if layout.stock_usage > shown[0] or (not what and shelf.stock_usage < layout.stock_usage
                                                         == shown[0]):
                        shown[0] = layout.stock_usage
                        publish(outputs(layout, []), [f"TrueShape nesting{what}: {_usage(layout)}",
                                                      WRITE_IS_FALSE, *_remarks(layout)])

                try:
                    nested = cutfiles.lay_out(
                        curves, names, nesting=cutfiles.TRUE_SHAPE, stop=stop, report=progress,
                        found=lambda layout: show(layout, ", searching"), **settings)
                except (cutfiles.FileFailure, ValueError):
                    return
                show(nested, "")

            self.improve_later(improve)
        return outputs(layout, files)
