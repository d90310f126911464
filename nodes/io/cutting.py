"""Cut files for the shop: ExportCutSheet lays flat panels out on sheets and writes DXF or SVG."""

from __future__ import annotations

from typing import Any

from engine.datatree import DataTree
from engine.node import LIST, TREE, In, Node, NodeError, NodeWarning, Out
from engine.types import BOOLEAN, NUMBER, TEXT, ValueType, register_type
from nodes.curves.convert import number
from nodes.io import cutfiles
from nodes.io.common import file_errors, may_write, unit_name, unit_scale, write_target
from nodes.io.cutfiles import CutLayout
from nodes.types import CURVE, SURFACE


def _layout_summary(layout: CutLayout) -> dict[str, Any]:
    return {
        "type": "CutLayout",
        "panels": len(layout.parts),
        "sheets": layout.sheets,
        "sheet": [layout.width, layout.height],
        "usage": round(layout.usage, 6),
    }


CUT_LAYOUT = register_type(ValueType(
    "CutLayout", (CutLayout,),
    "Flat panels laid out on sheets, in mm: what a cut file holds.",
    summarize=_layout_summary,
))


class ExportCutSheet(Node):
    """Lay flat panels out on sheets and write cut files: DXF or SVG, in millimetres.

    Panels are closed flat outlines (SurfacePatching's PanelsFlat), Surfaces flat
    surfaces whose boundary is the outline (IsoMapping's Development), in model Units.
    Before anything is laid out each one is checked: an open, non-flat or
    self-crossing outline, a repeated ID, the same panel given twice, or a panel
    larger than the sheet stops the export with a message naming the panel.
    Each panel is turned to lie along the sheet (unless Rotate is false), grown by
    half the Kerf so the cut part keeps its drawn size, and placed by shelf packing
    (rows of parts, tallest first) with Gap between parts and from the sheet's
    edges. Its ID is engraved inside it as letter outlines, TextHeight tall or
    smaller where the panel is narrow.

    The file type follows Path's extension. DXF (R2010, units mm): one closed
    polyline per part on layer CUT, the letters on ENGRAVE. SVG: a page of the
    sheet's size in mm, red hairline cuts, black engraving, no fill. One file per
    sheet: name.dxf for one sheet, name-1.dxf, name-2.dxf … for more (name-01 …
    from ten sheets on, so they sort). Nothing is written until Write is true and
    you have allowed the graph to write files; Path is relative to the graph's folder
    and must stay inside it. A file it replaces is kept as ``<name>.bak``.
    Layout also goes to ``torsal run --export ID.Layout=file.dxf`` (.svg, .3dm).
    """

    type_id = "io.ExportCutSheet"
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
        In("Gap", NUMBER, "G", "Space between parts and from the sheet's edges, mm.", default=10.0),
        In("Kerf", NUMBER, "K", "Width of the cut, mm; the contour moves out by half of it.", default=0.0),
        In("TextHeight", NUMBER, "Th", "Cap height of the engraved IDs, mm (0: no engraving).", default=10.0),
        In("Rotate", BOOLEAN, "Ro", "Turn panels to lie along the sheet (false: keep their direction).",
           default=True),
        In("Units", TEXT, "U", "The graph's model units (mm, cm, m, in, ft), those of Panels.", default="m"),
        In("Write", BOOLEAN, "Wr", "Set to true to write the files; while false nothing is written.",
           default=False),
    )
    outputs = (
        Out("Paths", TEXT, "P", "The files written, one per sheet (none while Write is false).",
            access=LIST),
        Out("Layout", CUT_LAYOUT, "L", "The panels on their sheets, for --export and Bake."),
        Out("Cuts", CURVE, "C", "The cut contours as laid out, sheets side by side, model units.",
            access=LIST),
        Out("Sheets", CURVE, "S", "The sheets' outlines, side by side along X, model units.", access=LIST),
        Out("Usage", NUMBER, "U", "Share of the sheets' area used by panels, 0 to 1."),
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
            raise NodeError(f"PanelIDs has an empty (null) item at position {names.index(None) + 1}")
        with file_errors():
            model_units = unit_name(units)
            layout = cutfiles.lay_out(
                curves, names,
                width=number("SheetWidth", width), height=number("SheetHeight", height),
                gap=number("Gap", gap), kerf=number("Kerf", kerf),
                text_height=number("TextHeight", text_height), rotate=bool(rotate), units=model_units,
                sources=sources,
            )
            files = []
            if write:
                target = write_target(self, path)
                if may_write(self, cutfiles.numbered(target, layout.sheets)):
                    files = [str(p) for p in cutfiles.write_cut_files(layout, target)]
            else:
                self.remark("Write is false: nothing written")
        for note in layout.notes:
            self.remark(note)
        back = unit_scale("mm", model_units)
        return (
            files,
            layout,
            cutfiles.placed_curves(layout, scale=back),
            cutfiles.sheet_outlines(layout, scale=back),
            layout.usage,
        )
