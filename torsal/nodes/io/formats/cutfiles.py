"""Cut sheets for lasers and routers: flat panels checked, laid out on sheets, written out.

:func:`lay_out` turns closed flat outlines (model units) into a
:class:`~torsal.nodes.io.formats.cutlayout.CutLayout` in
millimetres: every outline is checked (:func:`panel_outline`, :func:`check_panels`),
grown by half the kerf (mitre joins, :func:`~torsal.nodes.geometry.offset2d.offset_polygon`)
and placed with ``gap`` between the cut contours and ``margin`` from the sheet's edges,
by true-shape nesting (:func:`~torsal.nodes.geometry.nesting.nest`, sparrow; the instant shelf
layout is kept when the search does not beat it) or by first-fit decreasing-height
*shelf* packing of the parts' minimum-area rectangles
(:func:`~torsal.nodes.geometry.packing.shelf_pack`). Each panel's ID is engraved inside it as
text outlines; seams between strips (:mod:`torsal.nodes.io.seams`) are engraved on both parts
with their ID and alignment ticks, and their two flat edge lengths are reported.

:func:`write_cut_files` writes one file per sheet (``name.dxf`` for one sheet,
``name-1.dxf``, ``name-2.dxf`` … for several), by the file's extension:

- **DXF** (ezdxf, AutoCAD 2010 / R2010, ``$INSUNITS`` = 4, millimetres): one closed
  LWPOLYLINE per cut contour on layer ``CUT`` (red), carrying the panel ID as XDATA
  of the application ``TORSAL``; the ID's letter outlines (closed) and the seam ticks
  (open) on layer ``ENGRAVE``; the sheet's border on ``SHEET`` and, when asked, the
  drawn (un-offset) outlines on ``REFERENCE`` — those two layers are not plotted (and
  are not to be cut); the drawing limits are the sheet.
- **SVG** (:mod:`torsal.nodes.io.formats.sheetviews`): ``width``/``height`` in mm with a
  matching ``viewBox``, no fill, hairlines (1 px at any zoom) in groups ``SHEET`` (grey),
  ``REFERENCE`` (green, when asked), ``CUT`` (red) and ``ENGRAVE`` (blue).

Text outlines come from ezdxf's TrueType renderer (``ezdxf.fonts.ttfonts``) drawing
DejaVu Sans — the font file matplotlib ships, so no system font is needed (ezdxf
itself bundles no TrueType font) — flattened to 1/400 of the cap height (0.025 mm for 10 mm letters).
"""

from __future__ import annotations

import dataclasses
import itertools
import math
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import numpy as np
import shapely
from numpy.typing import NDArray
from shapely.validation import explain_validity

from torsal.nodes.geometry.array_types import FloatArray
from torsal.nodes.geometry.curve_base import Curve
from torsal.nodes.geometry.curves import NurbsCurve, Polyline
from torsal.nodes.geometry.nesting import Nested, NestingFailed, nest, place
from torsal.nodes.geometry.offset2d import offset_polygon
from torsal.nodes.geometry.packing import DoesNotFit, shelf_pack
from torsal.nodes.geometry.polygons import signed_ring_area
from torsal.nodes.geometry.surface_base import Surface
from torsal.nodes.geometry.watch import watch_check, watch_progress, watched
from torsal.nodes.io import seams as seam_edges
from torsal.nodes.io.common import FileFailure, numbered, replacing, unit_scale, writable
from torsal.nodes.io.formats import sheetviews
from torsal.nodes.io.formats.cutlayout import (
    CUT,
    ENGRAVE,
    NESTINGS,
    REFERENCE,
    SHEET,
    SHELF,
    TRUE_SHAPE,
    CutLayout,
    Part,
    border,
)
from torsal.nodes.io.formats.labels import SMALLEST_TEXT_MM, place_label, text_outlines
from torsal.nodes.io.seams import Seam, SeamLengths

#: Chord tolerance (mm) for curved outlines.
FLATTEN_MM = 0.01
#: Flatness (mm): an outline that leaves its best-fit plane by more is refused.
FLAT_MM = 0.01
#: Outline points closer than this share of the outline's size to the previous one are one point.
SAME_POINT = 1e-9

#: The finest an outline is sampled, as a fraction of the panel's size: 0.001 mm on a
#: 10 m panel, well below :data:`FLATTEN_MM`; it only bites on panels far larger than any
#: sheet, whose edges would otherwise be sampled to a millionth of their length.
FINEST_RELATIVE = 1e-7

SUFFIXES = (".dxf", ".svg")
#: Longest time budget (s) a true-shape nesting may be given.
MAX_BUDGET = 3600.0


class PanelProblem(FileFailure):
    """A panel the pre-export check refuses; the message names it."""


class SettingProblem(FileFailure):
    """A setting (sheet size, gap, kerf …) :func:`lay_out` refuses; the message names it."""


# ------------------------------------------------------------------ outlines and checks


def _vertices(curve: Curve, tolerance: float) -> FloatArray:
    """The outline's points, exact for polylines and degree-1 NURBS, else within ``tolerance``."""
    if isinstance(curve, Polyline):
        return np.asarray(curve.points, dtype=float)
    if isinstance(curve, NurbsCurve) and curve.degree == 1 and not curve.is_rational:
        return np.asarray(curve.control_points, dtype=float)
    return np.asarray(Polyline.from_curve(curve, tolerance).points, dtype=float)


def panel_outline(curve: Curve, scale: float) -> FloatArray:
    """A closed flat curve (model units) as an ``(n, 2)`` polygon in mm, counter-clockwise.

    Outlines in the XY plane keep their x and y; a flat outline in another plane is laid
    into XY by its best-fit plane. Raises ValueError (a sentence about "it") when the
    outline is open or not flat.
    """
    if not curve.closed:
        gap = float(np.linalg.norm(curve.end - curve.start)) * scale
        raise ValueError(f"is open: its ends are {gap:.4g} mm apart")
    points = _vertices(curve, FLATTEN_MM / scale) * scale
    if np.array_equal(points[0], points[-1]):
        points = points[:-1]
    keep = np.concatenate([[True], np.any(np.diff(points, axis=0) != 0, axis=1)])
    points = points[keep]
    if len(points) < 3:
        raise ValueError("has fewer than three distinct corners, so it encloses nothing")
    if np.ptp(points[:, 2]) > FLAT_MM:
        centre = points.mean(axis=0)
        _, _, axes = np.linalg.svd(points - centre)
        bend = float(np.abs((points - centre) @ axes[2]).max())
        if bend > FLAT_MM:
            raise ValueError(f"is not flat: it leaves its plane by {bend:.3g} mm")
        flat = (points - centre) @ axes[:2].T
    else:
        flat = points[:, :2].copy()
    return flat[::-1] if signed_ring_area(flat) < 0 else flat


def surface_outline(surface: Surface, tolerance: float) -> Polyline:
    """The boundary of a flat surface (IsoMapping's Development) as one closed polyline:
    its four edges in order (see :meth:`~torsal.nodes.geometry.surface_base.Surface.edges`),
    each within ``tolerance`` (model units, but never finer than :data:`FINEST_RELATIVE`
    of the panel's size); collapsed edges drop out, and so do points
    within :data:`SAME_POINT` of the outline's size of the one before (a fan's apex,
    where an edge stands still and its samples differ by rounding only: kept, they would
    zigzag across each other)."""
    edges = surface.edges()
    coarse = np.vstack([np.asarray(edge.point_at(np.linspace(0.0, 1.0, 9)), dtype=float) for edge in edges])
    tolerance = max(tolerance, FINEST_RELATIVE * float(np.ptp(coarse, axis=0).max()))
    pieces = []
    for index, edge in enumerate(edges):  # through every vertex of a polyline edge
        points = np.asarray(edge.point_at(seam_edges.edge_parameters(surface, index, tolerance)), dtype=float)
        pieces.append(points[:-1])  # (a collapsed edge, a tapering strip's tip, is one point)
    ring = np.vstack(pieces)
    size = float(np.ptp(ring, axis=0).max()) or 1.0
    keep = np.concatenate([[True], np.linalg.norm(np.diff(ring, axis=0), axis=1) > SAME_POINT * size])
    ring = ring[keep]
    if len(ring) > 1 and np.linalg.norm(ring[-1] - ring[0]) <= SAME_POINT * size:
        ring = ring[:-1]
    if len(ring) < 3:
        raise ValueError("has fewer than three distinct corners, so it encloses nothing")
    return Polyline(ring, closed=True)


def check_panels(
    outlines: Sequence[FloatArray], ids: Sequence[str], sources: Sequence[int] | None = None
) -> None:
    """Refuse outlines that cross themselves, repeated IDs and panels given twice (twice
    within one source, when ``sources`` are given)."""
    for outline, name in zip(outlines, ids, strict=True):
        polygon = shapely.Polygon(outline)
        if not polygon.is_valid:
            reason = explain_validity(polygon)
            where = ""
            if "[" in reason:
                x, y = (float(c) for c in reason[reason.find("[") + 1 : reason.find("]")].split()[:2])
                where = f" at ({x:.6g}, {y:.6g}) mm"
            raise PanelProblem(f"Panel {name}'s outline crosses or touches itself{where}")
        if not polygon.area > 0:
            raise PanelProblem(f"Panel {name} encloses no area")
    seen: dict[str, int] = {}
    for i, name in enumerate(ids):
        if name in seen:
            raise PanelProblem(f"Panels {seen[name] + 1} and {i + 1} are both called {name}: IDs must differ")
        seen[name] = i
    groups: dict[tuple[int, int, int, int], list[int]] = {}
    for i, outline in enumerate(outlines):
        polygon = shapely.Polygon(outline)
        size = math.sqrt(polygon.area)
        step = 1e-6 * size
        x, y = polygon.centroid.coords[0]
        source = 0 if sources is None else sources[i]
        key = (source, round(polygon.area / size / step), round(x / step), round(y / step))
        groups.setdefault(key, []).append(i)
    for members in groups.values():
        for a, b in itertools.pairwise(members):
            first, second = shapely.Polygon(outlines[a]), shapely.Polygon(outlines[b])
            if first.symmetric_difference(second).area <= 1e-9 * first.area:
                raise PanelProblem(
                    f"Panels {ids[a]} and {ids[b]} are the same outline in the same place "
                    "(a panel given twice)"
                )


# ------------------------------------------------------------------ layout


def _turn(points: FloatArray, angle: float) -> FloatArray:
    c, s = math.cos(angle), math.sin(angle)
    return points @ np.array([[c, s], [-s, c]])


def _long_side_angle(points: FloatArray) -> float:
    rectangle = np.asarray(shapely.Polygon(points).minimum_rotated_rectangle.exterior.coords)[:3]
    edges = np.diff(rectangle, axis=0)
    longest = edges[int(np.argmax(np.linalg.norm(edges, axis=1)))]
    return math.atan2(longest[1], longest[0])


def _turn_angle(outline: FloatArray, kerf: float, width: float, height: float, rotate: bool) -> float:
    """The turn that lays the outline's minimum-area rectangle along the sheet's long
    side (or across it, when only that fits); 0 when ``rotate`` is off."""
    if not rotate:
        return 0.0
    angle = -_long_side_angle(outline) + (math.pi / 2 if height > width else 0.0)
    for candidate in (angle, angle + math.pi / 2):
        cut = _grow(_turn(outline, candidate), kerf)
        if np.all(np.ptp(cut, axis=0) <= (width, height)):
            return candidate
    return angle


def _grow(outline: FloatArray, kerf: float) -> FloatArray:
    return offset_polygon(outline, kerf / 2) if kerf else outline


def lay_out(
    curves: Sequence[Curve | Surface],
    ids: Sequence[str] | None = None,
    width: float = 2500.0,
    height: float = 1250.0,
    gap: float = 10.0,
    kerf: float = 0.0,
    text_height: float = 10.0,
    rotate: bool = True,
    units: str = "m",
    sources: Sequence[int] | None = None,
    *,
    margin: float | None = None,
    nesting: str = SHELF,
    grain: bool = False,
    budget: float = 10.0,
    seed: int = 0,
    reference: bool = False,
    stop: Callable[[], bool] | None = None,
    report: Callable[[float], None] | None = None,
    seams: Sequence[Seam] = (),
    tick_spacing: float = 50.0,
    found: Callable[[CutLayout], None] | None = None,
) -> CutLayout:
    """Check the panels and place them on as many sheets as they need (see the module).

    A panel is a closed flat curve, or a flat surface whose boundary is cut. ``sources``
    (one number per panel, e.g. its data-tree branch) says which panels come from the
    same drawing: only those can be "the same outline given twice"; panels of separate
    developments may lie on top of each other in the plane and are still separate parts.
    ``gap`` is the space between parts, ``margin`` the space from the sheet's edges (the
    gap when None). ``nesting`` is :data:`TRUE_SHAPE` (sparrow, ``budget`` nominal seconds,
    ``seed``; ``stop`` and ``report`` as in :func:`~torsal.nodes.geometry.nesting.nest`) or
    :data:`SHELF`. ``grain``: parts turn only by 0° or 180°; ``rotate`` False: not at all.
    ``seams`` (:func:`~torsal.nodes.io.seams.find_seams`, between flat surfaces among the panels)
    are engraved on both parts with their ID and ticks every ``tick_spacing`` mm.
    ``found`` is told each better true-shape layout the search finds on the way (engraved;
    a stop abandons the one being engraved). Stopped, a search with ``found`` keeps the last
    layout it told (at once: Esc does not wait for engraving), or raises
    :class:`StoppedBeforeALayout` when it told none (what the caller shows stays).
    """
    edge = gap if margin is None else margin
    for name, value in (("SheetWidth", width), ("SheetHeight", height)):
        if not (math.isfinite(value) and value > 0):
            raise SettingProblem(f"{name} must be a positive length in mm, not {value:g}")
    for name, value in (("Gap", gap), ("Margin", edge)):
        if not (math.isfinite(value) and value >= 0):
            raise SettingProblem(f"{name} must be zero or a positive length in mm, not {value:g}")
    if not (math.isfinite(kerf) and kerf >= 0):
        raise SettingProblem(f"Kerf must be zero or a positive width in mm, not {kerf:g}")
    if kerf >= min(width, height):
        raise SettingProblem(f"A kerf of {kerf:g} mm is wider than the {width:g} × {height:g} mm sheet")
    if not (math.isfinite(text_height) and text_height >= 0):
        raise SettingProblem(f"TextHeight must be zero or a positive height in mm, not {text_height:g}")
    if 2 * edge >= min(width, height):
        what = "gap" if margin is None else "margin"
        raise SettingProblem(
            f"A {what} of {edge:g} mm on each side leaves no room on a {width:g} × {height:g} mm sheet"
        )
    if nesting not in NESTINGS:
        raise SettingProblem(f"Nesting is {nesting!r}: use {' or '.join(NESTINGS)}")
    if nesting == TRUE_SHAPE and not (math.isfinite(budget) and 0 < budget <= MAX_BUDGET):
        raise SettingProblem(f"TimeBudget must be between 1 and {MAX_BUDGET:g} s, not {budget:g}")
    if not curves:
        raise FileFailure("There are no panels to lay out")
    names = [f"P-{i:03d}" for i in range(1, len(curves) + 1)] if ids is None else [str(i) for i in ids]
    if len(names) != len(curves):
        raise PanelProblem(
            f"There are {len(names)} panel IDs for {len(curves)} panels: give one ID per panel"
        )
    started = time.perf_counter()
    scale = unit_scale(units, "mm")
    outlines = []
    check = watch_check()
    for curve, name in zip(curves, names, strict=True):
        if check:  # a surface's outline takes ~10 ms
            check()
        if curve is None:
            raise PanelProblem(f"Panel {name} is empty (null)")
        try:
            if isinstance(curve, Surface):
                curve = surface_outline(curve, FLATTEN_MM / scale)
            outlines.append(panel_outline(curve, scale))
        except ValueError as exc:
            raise PanelProblem(f"Panel {name} {exc}") from None
    check_panels(outlines, names, sources)

    room_w, room_h = width - 2 * edge, height - 2 * edge
    cuts, drawn, boxes, turns, lows = [], [], [], [], []
    for outline, name in zip(outlines, names, strict=True):
        turn = _turn_angle(outline, kerf, room_w, room_h, rotate and not grain)
        panel = _turn(outline, turn)
        cut = _grow(panel, kerf)
        low, high = cut.min(axis=0), cut.max(axis=0)
        turns.append(turn)
        lows.append(low)
        if np.any(high - low > (room_w, room_h)):
            w, h = high - low
            what = "gap" if margin is None else "margin"
            raise PanelProblem(
                f"Panel {name} is {w:.1f} × {h:.1f} mm{' with its kerf' if kerf else ''}, larger than the "
                f"{width:g} × {height:g} mm sheet less the {edge:g} mm {what} on each side"
            )
        cuts.append(cut - low)
        drawn.append(panel - low)
        boxes.append(high - low)
    try:
        shelf_of, corners = shelf_pack(np.array(boxes), (width, height), gap, edge)
    except DoesNotFit as exc:  # already ruled out above; kept for rounding at the edge
        raise PanelProblem(f"Panel {names[exc.index]} does not fit on the sheet: {exc}") from None
    shelf_cuts = [c + corner for c, corner in zip(cuts, corners, strict=True)]
    outline_cuts, outline_drawn = cuts, drawn

    def build(nested: Nested | None, notes: list[str], stopped: bool, on_the_way: bool = False) -> CutLayout:
        """The layout: ``nested`` (None: the shelf rows), engraved; ``on_the_way``: a layout
        the search found before its end (not cancelled by the node's token)."""
        cuts, drawn = outline_cuts, outline_drawn
        use_shelf = nested is None
        if nested is not None:
            nested_cuts = [place(c, a, t) for c, a, t in zip(cuts, nested.angle, nested.shift, strict=True)]
            # the shelf layout is instant: keep it when the search did not beat it (rectangles)
            if _stock(shelf_of, shelf_cuts) < _stock(nested.sheet, nested_cuts):
                use_shelf = True
                notes.append("Shelf packing uses less stock than the true-shape nesting found in its time: "
                             "the parts are laid out in rows")
            else:
                cuts, sheet_of = nested_cuts, nested.sheet
                drawn = [place(d, a, t) for d, a, t in zip(drawn, nested.angle, nested.shift, strict=True)]

                def move(i: int, points: FloatArray) -> FloatArray:
                    return place(_turn(points, turns[i]) - lows[i], nested.angle[i], nested.shift[i])
        if use_shelf:
            cuts, sheet_of = shelf_cuts, shelf_of
            drawn = [d + corner for d, corner in zip(drawn, corners, strict=True)]

            def move(i: int, points: FloatArray) -> FloatArray:
                return _turn(points, turns[i]) - lows[i] + corners[i]
        parts = []
        # Esc stopped the search: its best layout is engraved to the end (one on the way is
        # abandoned instead: see better)
        check = None if stopped else watch_check()
        with watched(check, watch_progress()):
            marks, lengths = _seam_marks(curves, names, drawn, seams, scale, tick_spacing, text_height, move,
                                         notes)
            for i, name in enumerate(names):
                if check:  # a label may take tens of ms (its pole of inaccessibility, the font's first load)
                    check()
                tick_list, seam_glyphs = marks.get(i, ([], []))
                label, size = place_label(name, drawn[i], text_height, engraved(tick_list, seam_glyphs))
                if text_height > 0 and not label:
                    notes.append(f"Panel {name} is too narrow for its ID at {SMALLEST_TEXT_MM:g} mm: "
                                 "not engraved")
                parts.append(Part(name, int(sheet_of[i]), cuts[i], drawn[i], label, size, tuple(tick_list),
                                  tuple(seam_glyphs)))
        if stopped:
            notes.append("Nesting was stopped: this is the best layout found by then")
        return CutLayout(width, height, gap, kerf, tuple(parts), int(sheet_of.max()) + 1, units, tuple(notes),
                         margin=margin, nesting=SHELF if use_shelf else TRUE_SHAPE, reference=reference,
                         stopped=stopped, seconds=time.perf_counter() - started, seams=tuple(lengths))

    if nesting == SHELF:
        return build(None, [], False)
    orientations = None if rotate and not grain else [0.0, 180.0] if rotate else [0.0]

    shown: list[tuple[Nested, CutLayout]] = []  # the last layout on the way told to found

    def abandon() -> None:
        if stop is not None and stop():
            raise _Abandoned

    def better(nested: Nested) -> None:
        """A layout on the way, engraved, for ``found``; abandoned when a stop is asked for
        (engraving 18 strips with their seams takes seconds: Esc would wait for it)."""
        if found is not None:
            try:
                with watched(abandon):
                    layout = build(nested, [], False, on_the_way=True)
            except _Abandoned:
                return
            shown[:] = [(nested, layout)]
            found(layout)

    try:
        nested = nest(cuts, width, height, edge, gap, orientations, budget, seed, stop, report,
                      better if found is not None else None)
    except NestingFailed as exc:
        raise FileFailure(f"TrueShape nesting failed: {exc} (Nesting = Shelf still works)") from None
    notes: list[str] = []
    if nested.on_the_clock:
        notes.append("TrueShape nesting ran out of time before its steps (a very busy machine): this "
                     "layout may differ from run to run")
    if shown:  # the layout found already engraved (a stop keeps the last one shown: at once)
        before, layout = shown[0]
        if nested.stopped or all(np.array_equal(getattr(before, k), getattr(nested, k))
                                 for k in ("sheet", "angle", "shift")):
            stopped = ["Nesting was stopped: this is the best layout found by then"] if nested.stopped else []
            return dataclasses.replace(layout, notes=(*notes, *layout.notes, *stopped),
                                       stopped=nested.stopped, seconds=time.perf_counter() - started)
    return build(nested, notes, nested.stopped)


class _Abandoned(Exception):
    """A layout on the way whose engraving was abandoned: a stop was asked for."""


def _stock(sheet_of: NDArray[np.intp], cuts: Sequence[FloatArray]) -> tuple[int, float]:
    """What a layout takes from stock: its sheets, and how far the last one's parts reach."""
    last = int(sheet_of.max())
    return last + 1, max(float(c[:, 0].max()) for c, s in zip(cuts, sheet_of, strict=True) if s == last)


def _seam_marks(curves, names, drawn, seams, scale, spacing, text_height, move, notes):  # type: ignore[no-untyped-def]
    """Per part index, (ticks, seam-ID outlines) as laid out; and each seam's lengths. Every
    tick is placed first, then the seams' IDs, each clear of the ticks and IDs already on
    its part (moved along the edge or smaller, :func:`~torsal.nodes.io.seams.seam_label`)."""
    marks: dict[int, tuple[list[FloatArray], list[FloatArray]]] = {}
    lengths: list[SeamLengths] = []
    sides_of = []
    for seam in seams:
        sides = []
        for index, edge_index in ((seam.a, seam.edge_a), (seam.b, seam.edge_b)):
            surface = curves[index] if 0 <= index < len(curves) else None
            if not isinstance(surface, Surface):
                break
            flat = seam_edges.edge_polyline(surface, edge_index, FLATTEN_MM / scale) * scale
            sides.append((index, flat))
        if len(sides) != 2:
            notes.append(f"Seam {seam.id} joins panels that are not flat surfaces: not marked")
            continue
        (a, edge_a), (b, edge_b) = sides
        lengths.append(SeamLengths(seam.id, names[a], names[b], seam_edges.length(edge_a),
                                   seam_edges.length(edge_b)))
        placed = [(a, move(a, edge_a), False), (b, move(b, edge_b), seam.reversed)]
        sides_of.append((seam, placed))
        for index, edge, reverse in placed:
            ticks, _ = marks.setdefault(index, ([], []))
            try:
                ticks += seam_edges.ticks(edge, drawn[index], spacing, reverse)
            except ValueError as exc:
                raise FileFailure(f"Seam {seam.id}: {exc}") from None
    for seam, placed in sides_of:
        glyphs = text_outlines(seam.id)
        for index, edge, _ in placed:
            ticks, letters = marks[index]
            label = seam_edges.seam_label(seam.id, edge, drawn[index], 0.6 * text_height, glyphs,
                                          engraved(ticks, letters))
            if text_height > 0 and not label:
                notes.append(f"Seam {seam.id}'s ID does not fit beside its edge on panel {names[index]}")
            letters += label
    return marks, lengths


def engraved(ticks: Sequence[FloatArray], letters: Sequence[FloatArray]) -> shapely.Geometry | None:
    """What is already engraved on a part, for a label to keep clear of: its ticks, and the
    envelope of its letters."""
    shapes = [shapely.LineString(t) for t in ticks]
    if letters:
        shapes.append(shapely.MultiPoint(np.vstack(letters)).envelope)
    return shapely.GeometryCollection(shapes) if shapes else None


# ------------------------------------------------------------------ writers


def write_dxf(layout: CutLayout, path: Path) -> list[Path]:
    """One DXF R2010 file per sheet (see the module); returns the files written."""
    import ezdxf
    from ezdxf import units

    files = numbered(writable(path), layout.sheets)
    for sheet, file in enumerate(files):
        doc = ezdxf.new("R2010", units=units.MM)
        doc.header["$MEASUREMENT"] = 1
        doc.header["$LIMMIN"] = (0.0, 0.0)
        doc.header["$LIMMAX"] = (layout.width, layout.height)
        doc.layers.add(CUT, color=1)
        doc.layers.add(ENGRAVE, color=7)
        for name, colour in ((SHEET, 8), (REFERENCE, 3)):  # drawn, never cut: not plotted
            doc.layers.add(name, color=colour).dxf.plot = 0
        doc.appids.add("TORSAL")
        space = doc.modelspace()
        space.dxf_layout.dxf.limmin = (0.0, 0.0)  # saving syncs the header from the layout
        space.dxf_layout.dxf.limmax = (layout.width, layout.height)
        space.add_lwpolyline(border(layout).tolist(), close=True, dxfattribs={"layer": SHEET})
        for part in layout.on_sheet(sheet):
            if layout.reference:
                space.add_lwpolyline(part.panel.tolist(), close=True, dxfattribs={"layer": REFERENCE})
            contour = space.add_lwpolyline(part.outline.tolist(), close=True, dxfattribs={"layer": CUT})
            contour.set_xdata("TORSAL", [(1000, part.id)])
            for glyph in part.label + part.seam_labels:
                space.add_lwpolyline(glyph.tolist(), close=True, dxfattribs={"layer": ENGRAVE})
            for tick in part.ticks:
                space.add_lwpolyline(tick.tolist(), close=False, dxfattribs={"layer": ENGRAVE})
        replacing(file, doc.saveas)
    return files


def write_svg(layout: CutLayout, path: Path) -> list[Path]:
    """One SVG file per sheet (:mod:`torsal.nodes.io.formats.sheetviews`); returns the files written."""
    return sheetviews.write_svg(layout, path)


def write_cut_files(layout: CutLayout, path: Path) -> list[Path]:
    """DXF or SVG by ``path``'s extension, one file per sheet."""
    suffix = path.suffix.lower()
    if suffix == ".dxf":
        return write_dxf(layout, path)
    if suffix == ".svg":
        return write_svg(layout, path)
    raise FileFailure(f"A cut sheet is written as .dxf or .svg, not {suffix or 'a file without extension'}")


def sheet_outlines(layout: CutLayout, scale: float = 1.0) -> list[Polyline]:
    """The sheets as closed rectangles side by side along X, lengths multiplied by ``scale``."""
    out = []
    for sheet in range(layout.sheets):
        x = layout.offset(sheet)
        corners = np.array([[x, 0, 0], [x + layout.width, 0, 0], [x + layout.width, layout.height, 0],
                            [x, layout.height, 0]])
        out.append(Polyline(corners * scale, closed=True))
    return out


def placed_curves(layout: CutLayout, which: str = "outline", scale: float = 1.0) -> list[Polyline]:
    """Each part's cut contour (``"outline"``), drawn panel (``"panel"``) as closed
    polylines at the sheets' side-by-side positions, lengths multiplied by ``scale``."""
    out = []
    for part in layout.parts:
        points = getattr(part, which) + np.array([layout.offset(part.sheet), 0.0])
        out.append(Polyline(np.column_stack([points, np.zeros(len(points))]) * scale, closed=True))
    return out


def label_curves(layout: CutLayout, scale: float = 1.0) -> list[list[Polyline]]:
    """Each part's engraved letter outlines (its ID, its seams' IDs) and seam ticks, placed
    as :func:`placed_curves` places them."""
    out = []
    for part in layout.parts:
        shift = (layout.offset(part.sheet), 0.0)
        out.append([
            Polyline(np.column_stack([g + shift, np.zeros(len(g))]) * scale, closed=True)
            for g in part.label + part.seam_labels
        ] + [Polyline(np.column_stack([t + shift, np.zeros(len(t))]) * scale) for t in part.ticks])
    return out


def layout_entries(layout: CutLayout) -> list[Any]:
    """The layout as .3dm entries (mm): sheets side by side on ``Sheets``, cut contours on
    ``CUT`` named by panel ID (user strings ``PanelID`` and ``Sheet``), letters on ``ENGRAVE``."""
    from torsal.nodes.io.formats.threedm import Entry

    sheets = sheet_outlines(layout)
    entries = [Entry(rectangle, "Sheets", f"Sheet {i + 1}") for i, rectangle in enumerate(sheets)]
    for part, contour, letters in zip(layout.parts, placed_curves(layout), label_curves(layout), strict=True):
        strings = (("PanelID", part.id), ("Sheet", str(part.sheet + 1)))
        entries.append(Entry(contour, CUT, part.id, strings))
        entries.extend(Entry(letter, ENGRAVE, f"{part.id} label", strings) for letter in letters)
    return entries


#: Layer colours (red cuts, black engraving, grey sheets) for .3dm files of a layout.
LAYOUT_COLOURS = {CUT: (255, 0, 0, 255), ENGRAVE: (0, 0, 0, 255), "Sheets": (150, 150, 150, 255)}
