"""True-shape nesting of flat parts onto fixed sheets, with sparrow (``spyrrow``) as the engine.

sparrow packs polygons into a *strip* of fixed height and minimises its length, keeping
a minimum separation between parts and from the strip's edges (its runs, the steps they
share and their check: :mod:`torsal.nodes.geometry.sparrow_runs`). Sheets have a length
too, and a strip cut into sheet lengths loses at every cut the parts that cross it. So
:func:`nest` fills the sheets one at a time:

1. a sheet's parts are chosen by area alone (:func:`_choose`: largest first, each that keeps
   the set within :data:`SHEET_TARGET` of the sheet's area), and sparrow packs them into a
   strip as tall as the sheet's usable height, ending as soon as it is no longer than the
   sheet; when it does not fit, another seed packs a set chosen at :data:`FOLLOW` of the
   density that strip reached (a target that follows the parts; later sheets keep it), up
   to :data:`SET_SEEDS` seeds;
2. when the parts left then cover no more than :data:`LAST_SHEET` of a sheet, they are
   packed as the last sheet *beside* it (two packings at once, one on each core): its
   length is what the offcut saves. Its parts reach sparrow standing across the strip when
   that strip will be shorter than it is tall (``across``): sparrow's search starts from the
   parts as given, and the Kaohsiung strips' last five reached 74 % density in 1.8 / 4.5 /
   14.9 CPU-s by seed standing against 4.2 / 11.0 / 18.2 lying (load 12);
3. a set sparrow could not get within the sheet's length gives the sheet the stretch of its
   strip holding the most part area (:func:`_window`), and the rest goes back to the pool.

What a sheet's set costs is about what sparrow's own strip of every part costs to reach
the same density: a sheet is a strip with the density of the layout, not more, and each
part is packed once (issue 31; profiled on the Kaohsiung strips, 18 parts about a third
of a sheet long, with CPU time per packing: the set of 13 fits the sheet in 8 CPU-s for
seed 0, the last sheet's 5 beside it reach their 74 % in 2-5 CPU-s standing; sparrow's own
strip of all 18 reaches the layout's 72.6 % in 5-12 CPU-s by seed when given the parts as
the layout turned them, 8-32 as drawn. Where the time went before: the second seed packed
beside the first, 8 CPU-s, and the last sheet lying, 19 CPU-s, its final layout shown only
when its search ended. Profiled again per packing, budget 45, seed 0, load 5-8: the set of
13, 7.1-7.3 CPU-s on two threads; the last sheet's 5 beside it, 14.6 CPU-s on two threads,
5.4 on one (243 steps: 74.7 and 73.9 % dense), so it runs on one, :data:`BESIDE_WORKERS`;
over four seeds a 5-part last sheet took 4.0-17.3 CPU-s on two threads, 3.6-8.1 on one, at
about the same density: sparrow's second thread is worth little on few parts, and under
load its threads wait for each other). Strips of every part cut into sheets were 10 points less
dense for such parts (every cut crosses four or five); parts small beside the sheet lose
little at a cut. So when the parts need more than :data:`FILL_SHEETS` sheets (many panels)
the strip of every part comes first, cut into sheet lengths as sparrow shortens it (:func:`_cut`:
each sheet starts a margin before the first part not yet placed and takes those that end
within it), and it is the layout when it keeps :data:`CUT_KEEPS` of the strip's density;
otherwise the sheets are filled one at a time as above. sparrow's first packing (before any
step of its search) is asked alone first: cut into sheets, it is the layout when it fills the
stock to :data:`SHEET_TARGET` (the development-and-panels panels: 84.5 % from its first
packing, in 1.2 CPU-s; its 20 steps more had given 84.7 % for 0.5-0.7 CPU-s more).
Not reached: parts sparrow packs
well below :data:`SHEET_TARGET` pay for the first set's failed packing before the target
follows them (50 random strips, annular sectors sparrow packs to only about 66 % in a strip:
sheet 1's set of 13 failed with both seeds at 72 %, 28 s, before the target followed the
parts; sparrow's strip of all 50 reaches their 65.5 % in 10.5 s at a load of 10).

The budget is counted in sparrow's steps (:data:`~torsal.nodes.geometry.sparrow_runs.STEPS_PER_SECOND`
per second of ``budget``), never the clock, and every packing is seeded (the seeds follow
``seed`` in the order the packings are asked for), so the same parts, sheet and seed give
the same layout on any machine, however busy. Every packing is checked afterwards with
shapely against the exact polygons in double precision (sparrow reports its placements in
single precision): a part closer to another than the spacing, or outside the usable sheet,
goes back to the pool. Each complete layout on the way that takes less stock than the last
(a sheet's strip as sparrow shortens it with the last sheet packed beside it) is told to
``found`` at once (the app redraws it).

Out of steps with parts left (many sheets, a small budget), what is left is packed into
one last strip and cut into sheet lengths. Stopping: ``stop()`` is polled about every 50 ms;
when it says yes, the best layout found so far is kept (a strip under way contributes its
best feasible packing), and the rest is placed on further sheets by bounding-rectangle
shelf packing so every part is still on a sheet. ``report(fraction)`` is told how far the
budget's steps are spent.
"""

from __future__ import annotations

import itertools
import math
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import shapely
from numpy.typing import NDArray

from torsal.nodes.geometry.array_types import FloatArray
from torsal.nodes.geometry.packing import shelf_pack
from torsal.nodes.geometry.sparrow_runs import (
    FEWEST,
    PACKED,
    Budget,
    NestingFailed,
    Packing,
    strip,
    strips,
    valid,
)

__all__ = ["PACKED", "Nested", "NestingFailed", "nest", "place"]

#: A sheet's parts are chosen to cover this share of its area (the sheet as sparrow's
#: strip: its length and height less the margins plus the spacing). sparrow packs the
#: Kaohsiung strips' sets of 71-74 % into a sheet in about the time its strip of every part
#: takes to reach that density; denser sets often do not fit at all.
SHEET_TARGET = 0.72
#: A set that did not fit its sheet tells how dense sparrow packs these parts: the next seed's
#: set, and every later sheet's, is chosen at this share of the density its strip reached.
FOLLOW = 0.98
#: Seeds a sheet's set is packed with, one after the other: the next only when the last did
#: not fit (the first seed's packing is kept whenever it fits, so the same seed gives the same
#: layout). Side by side, as before, each took half the cores while the first seed's packing
#: and the last sheet's beside it ran (Kaohsiung: 36 CPU-s of sparrow, the set fitted at 59 s
#: and the layout ended at 93 s, load 14; one after the other 24 CPU-s, 40 s, 66 s, load 13-16).
SET_SEEDS = 2
#: Parts covering at most this share of a usable sheet are packed as the last sheet.
LAST_SHEET = 0.8
#: Share of the steps left that the last sheet, packed beside a sheet's set, is given.
LAST_RESERVE = 0.3
#: Threads sparrow searches on for the last sheet packed beside a sheet's set (the set keeps
#: :data:`~torsal.nodes.geometry.sparrow_runs.WORKERS`): its few parts gain little from a second
#: thread, and the set, which the layout waits for, gets the core it would have taken.
BESIDE_WORKERS = 1
#: Above this many sheets' worth of parts, the strip of every part cut into sheets comes first.
FILL_SHEETS = 3.0
#: Share of a sheet's steps the strip of every part gets in that case.
FIRST_SHARE = 0.35
#: The strip of every part, cut into sheets, is the layout when it keeps at least this
#: share of the strip's density.
CUT_KEEPS = 0.9
#: A layout on the way is told to ``found`` when it uses this much more of the stock than
#: the last one told (sparrow shortens a strip by a millimetre at a time: each would be
#: engraved and redrawn). The layout told last is, when it is the final one, not engraved
#: again: the panels' final (0.4 % above the first told) came at the end with 0.005.
TELL = 0.002
#: A better layout less than :data:`TELL` ahead is told when no other has come for this many
#: seconds (sparrow's last shortenings come in bursts, then it searches on without bettering:
#: the Kaohsiung strips' final layout, 0.18 % above the one told before it, was otherwise shown
#: only when the search ended, 15 s later).
SETTLE = 1.0


@dataclass(frozen=True)
class Nested:
    """Where each part goes: ``sheet[i]``, turned by ``angle[i]`` (degrees, counter-
    clockwise about the origin), then moved by ``shift[i]`` (mm on that sheet)."""

    sheet: NDArray[np.intp]
    angle: FloatArray
    shift: FloatArray
    sheets: int
    stopped: bool = False  #: stopped early: the best layout found by then
    seconds: float = 0.0
    on_the_clock: bool = False  #: a packing ran out of time before its steps: may differ run to run
    steps: int = 0  #: steps of sparrow's search taken


def place(outline: FloatArray, angle: float, shift: Sequence[float]) -> FloatArray:
    """``outline`` turned by ``angle`` degrees about the origin, then moved by ``shift``."""
    a = math.radians(angle)
    c, s = math.cos(a), math.sin(a)
    return np.asarray(outline, dtype=float) @ np.array([[c, s], [-s, c]]) + np.asarray(shift, dtype=float)


def _choose(members: Sequence[int], area: FloatArray, cap: float) -> list[int]:
    """The parts for one sheet by area alone: largest first, each that keeps their total
    within ``cap`` (first fit decreasing; no swap of one chosen for one left would then
    fit: the one left did not fit before the smaller was chosen); at least the largest."""
    chosen, total = [], 0.0
    for i in sorted(members, key=lambda i: (-area[i], i)):
        if total + area[i] <= cap or not chosen:
            chosen.append(i)
            total += area[i]
    return chosen


def _window(polygons: dict[int, shapely.Polygon], area: FloatArray, width: float, margin: float) -> float:
    """Where along a packed strip a sheet of ``width`` should start to hold the most part
    area (parts wholly within it, ``margin`` from its ends); the first such place."""
    bounds = {i: p.bounds for i, p in polygons.items()}
    starts = sorted({0.0, *(max(0.0, b[0] - margin) for b in bounds.values()),
                     *(max(0.0, b[2] + margin - width) for b in bounds.values())})
    tolerance = 1e-9 * width

    def held(start: float) -> float:
        return sum(area[i] for i, b in bounds.items()
                   if b[0] >= start + margin - tolerance and b[2] <= start + width - margin + tolerance)

    return max(starts, key=lambda start: (held(start), -start))


def _cut(polygons: dict[int, shapely.Polygon], width: float, margin: float) -> list[tuple[float, list[int]]]:
    """A packed strip cut into sheets ``width`` long: (where the sheet starts along the strip,
    its parts) per sheet. Each sheet starts ``margin`` before the first part not yet placed
    and takes the parts that end ``margin`` before its end; empty when a part is longer."""
    bounds = {i: p.bounds for i, p in polygons.items()}
    left = sorted(bounds, key=lambda i: (bounds[i][0], i))
    sheets: list[tuple[float, list[int]]] = []
    while left:
        start = bounds[left[0]][0] - margin
        here = [i for i in left if bounds[i][2] - start <= width - margin]
        if not here:
            return []
        sheets.append((start, here))
        left = [i for i in left if i not in here]
    return sheets


def nest(
    shapes: Sequence[FloatArray],
    width: float,
    height: float,
    margin: float = 10.0,
    spacing: float = 10.0,
    orientations: Sequence[float] | None = None,
    budget: float = 10.0,
    seed: int = 0,
    stop: Callable[[], bool] | None = None,
    report: Callable[[float], None] | None = None,
    found: Callable[[Nested], None] | None = None,
) -> Nested:
    """Nest ``shapes`` (closed polygons in mm, each given once) onto sheets of
    ``width`` × ``height`` mm, ``margin`` from the sheet's edges and ``spacing`` apart.

    ``orientations`` lists the allowed turns in degrees (``None``: free rotation).
    Every shape must fit the usable sheet in some allowed turn (the caller checks).
    ``found`` is told each complete layout on the way that uses :data:`TELL` more of the
    stock than the last it was told, and a better one that uses less more when no other has
    come for :data:`SETTLE` seconds, before the end (from this call's threads).
    """
    run = Budget(budget, stop, report)
    n = len(shapes)
    # sparrow keeps the spacing from the strip's edges too: widen the strip by it
    strip_height = height - 2 * margin + 2 * spacing
    room_length = width - 2 * margin
    sheet_length = room_length + 2 * spacing  # a sheet, as sparrow measures its strip
    room = shapely.box(margin, margin, width - margin, height - margin).buffer(1e-9, join_style="mitre")
    # sparrow turns about the origin: centre each shape there (smaller rounding)
    centres = [np.asarray(s, dtype=float).mean(axis=0) for s in shapes]
    centred = [np.asarray(s, dtype=float) - c for s, c in zip(shapes, centres, strict=True)]
    area = np.array([shapely.Polygon(s).area for s in centred])
    usable = room_length * (height - 2 * margin)
    # a strip of every part, however loosely packed, ends well before this (a finite box:
    # shapely cannot tell what an infinite one covers when a part touches its edge)
    far = width + 2 * sum(float(np.ptp(c, axis=0).max()) + 2 * spacing for c in centred)
    open_room = shapely.box(margin, margin, far, height - margin).buffer(1e-9, join_style="mitre")
    seeds = itertools.count(int(seed))  # each packing its own seed, in the order they are asked for
    lock = threading.Lock()  # packings side by side tell their layouts from two threads

    # the sheets filled for good: part -> (sheet, angle, shift)
    placed: dict[int, tuple[int, float, FloatArray]] = {}
    remaining = list(range(n))

    def put(i: int, sheet: int, angle: float, t: Sequence[float], start: float, into: dict) -> None:
        # placed = R(shape - centre) + t + lift = R(shape) + (t + lift - R(centre))
        lift = np.add(t, (margin - spacing - start, margin - spacing))
        into[i] = (sheet, angle, lift - place(centres[i][None, :], angle, (0, 0))[0])

    def polygons_of(packing: Packing, start: float = 0.0) -> dict[int, shapely.Polygon]:
        lift = (margin - spacing - start, margin - spacing)  # strip origin -> sheet
        return {i: shapely.Polygon(place(centred[i], a, np.add(t, lift))) for i, (a, t) in packing.items()}

    def cut_into_sheets(packing: Packing, first: int, into: dict) -> int | None:
        """``packing`` (every part valid, or None) cut into sheets from sheet ``first`` into
        ``into``; the sheets it takes."""
        polygons = polygons_of(packing)
        if len(valid(polygons, open_room, spacing)) < len(polygons):
            return None
        sheets = _cut(polygons, width, margin)
        for k, (start, members) in enumerate(sheets):
            for i in members:
                put(i, first + k, *packing[i], start, into)
        return len(sheets) or None

    def nested(layout: dict[int, tuple[int, float, FloatArray]], stopped: bool = False) -> Nested:
        sheet_of = np.array([layout[i][0] for i in range(n)], dtype=np.intp)
        return Nested(sheet_of, np.array([layout[i][1] for i in range(n)]),
                      np.array([layout[i][2] for i in range(n)], dtype=float).reshape(n, 2),
                      int(sheet_of.max()) + 1, stopped, time.perf_counter() - run.start, run.on_the_clock,
                      run.used)

    def stock(layout: Nested) -> tuple[int, float]:
        return _stock(shapes, layout.sheet, layout.angle, layout.shift, layout.sheets)

    best: list[tuple[tuple[int, float], Nested]] = []  # the layout on the way taking least stock
    told = [-math.inf]  # the stock usage of the last layout told to found
    settling: list[threading.Timer] = []  # tells the best layout when no better has come for SETTLE s

    def settled(candidate: Nested, usage: float) -> None:
        with lock:
            if found is not None and best and best[0][1] is candidate and usage > told[0]:
                told[0] = usage
                found(candidate)

    def offer(packings: Sequence[Packing]) -> None:
        """The sheets filled so far, then each of ``packings`` (together every part left)
        cut into sheet lengths: kept, and told to ``found``, when it takes less stock."""
        with lock:
            layout = dict(placed)
            for packing in packings:
                first = 1 + max((s for s, _, _ in layout.values()), default=-1)
                taken = cut_into_sheets(packing, first, layout)
                if taken is None:
                    return
            if len(layout) < n:
                return
            candidate = nested(layout)
            used = stock(candidate)
            if best and used >= best[0][0]:
                return
            best[:] = [(used, candidate)]
            usage = float(area.sum()) / (((used[0] - 1) * width + used[1]) * height)
            for waiting in settling:
                waiting.cancel()
            if found is not None and usage >= told[0] + TELL:
                told[0] = usage
                found(candidate)
            elif found is not None:
                settling[:] = [threading.Timer(SETTLE, settled, (candidate, usage))]
                settling[0].daemon = True
                settling[0].start()

    def sheets_left() -> float:
        return max(1.0, math.ceil(sum(area[i] for i in remaining) / usable))

    def across(members: Sequence[int]) -> float:
        """90 (degrees) when the last sheet's ``members`` should reach sparrow standing across its
        strip: free rotation, their strip expected shorter than it is tall, and the parts lying
        along it, each short enough to stand in it; else 0."""
        if orientations is not None:
            return 0.0
        reach = np.array([np.ptp(centred[i], axis=0) for i in members])
        short = float(area[list(members)].sum()) / (SHEET_TARGET * strip_height) < strip_height
        along = reach[:, 0].sum() > reach[:, 1].sum() and (reach[:, 0] <= strip_height - 2 * spacing).all()
        return 90.0 if short and along else 0.0

    def length(packing: Packing) -> float:
        """How long sparrow's strip of ``packing`` is (to the far separation)."""
        return max(p.bounds[2] for p in polygons_of(packing).values()) - margin + 2 * spacing

    sheet = 0  # the next sheet to fill
    target = SHEET_TARGET  # a sheet's set, as a share of its area (follows the parts: FOLLOW)
    if area.sum() > FILL_SHEETS * usable:
        # many sheets: the strip of every part cut into sheets. sparrow's first packing alone first (no
        # step of its search): cut into sheets, it is the layout when it fills the stock to SHEET_TARGET
        first_seed = next(seeds)
        packing = strip(centred, remaining, strip_height, spacing, orientations, 0, first_seed, run,
                        better=lambda p: offer([p]))
        (count, last), _ = best[0] if best else ((0, 0.0), None)
        if packing is not None and best and float(area.sum()) / (((count - 1) * width + last) * height) \
                >= SHEET_TARGET:
            remaining = []  # best holds the layout
        elif not run.stopped:  # the same strip searched on (the same seed: the same first packing),
            # kept when its cut keeps the strip's density
            steps = max(FEWEST, round(run.left() / sheets_left() * FIRST_SHARE))
            packing = strip(centred, remaining, strip_height, spacing, orientations, steps, first_seed, run,
                            better=lambda p: offer([p]))
        if remaining and packing is not None and best:
            polygons = polygons_of(packing)
            reach = max(p.bounds[2] for p in polygons.values()) - (margin - spacing) + spacing
            density = float(area.sum()) / (reach * strip_height)
            (count, last), _ = best[0]
            if float(area.sum()) / (((count - 1) * width + last) * height) >= CUT_KEEPS * density:
                remaining = []  # best holds the layout
    while remaining and not run.stopped and run.left() >= FEWEST:
        if sum(area[i] for i in remaining) <= LAST_SHEET * usable:  # the last sheet: all the steps left
            run.last_round = True
            packing = strip(centred, remaining, strip_height, spacing, orientations, run.left(), next(seeds),
                            run, better=lambda p: offer([p]), turn=across(remaining))
            if packing is None or (taken := cut_into_sheets(packing, sheet, placed)) is None:
                break
            sheet += taken
            remaining = []
            break
        chosen = _choose(remaining, area, target * sheet_length * strip_height)
        others = [i for i in remaining if i not in chosen]
        last = sum(area[i] for i in others) <= LAST_SHEET * usable
        reserve = round(LAST_RESERVE * run.left()) if last else 0
        run.last_round = last  # progress: this round places every part left
        # the set packed with up to SET_SEEDS seeds, one after the other: the first seed's packing is the
        # sheet when it fits, else the first that fits
        tries = SET_SEEDS
        seen: list[Packing | None] = [None] * (tries + 1)  # the latest packing of each; the last sheet's
        fits = threading.Event()  # the first seed's packing fits the sheet

        def saw(k: int, packing: Packing, seen: list[Packing | None] = seen, fits: threading.Event = fits,
                last: bool = last) -> None:
            seen[k] = packing
            if k == 0 and max(p.bounds[2] for p in polygons_of(packing).values()) <= width - margin:
                fits.set()
            if last and seen[-1] is not None:
                for one in ([seen[k]] if k < len(seen) - 1 else seen[:-1]):
                    if one is not None:
                        offer([one, seen[-1]])

        steps = max(FEWEST, run.left() - reserve)
        # the other seeds' steps are not counted (as when they were packed side by side with the first)
        jobs: list[dict] = [{"members": chosen, "steps": steps, "seed": next(seeds), "enough": sheet_length,
                             "better": lambda p, k=k: saw(k, p), "halt": None if k == 0 else fits.is_set,
                             "counted": k == 0} for k in range(tries)]
        if last:  # packed beside this sheet's set
            jobs.append({"members": others, "steps": max(FEWEST, reserve), "seed": next(seeds),
                         "better": lambda p, k=tries: saw(k, p), "turn": across(others),
                         "workers": BESIDE_WORKERS})
        # another seed only when the first does not fit (side by side, each would have half the cores:
        # the first seed's fit, the layout kept, came later, and the last sheet's beside it)
        packings: list[Packing | None] = [None] * len(jobs)
        first = [0, *range(tries, len(jobs))]
        for k, packing in zip(first, strips(centred, [jobs[k] for k in first], strip_height, spacing,
                                            orientations, run), strict=True):
            packings[k] = packing
        if packings[0] is None:
            break
        packing = packings[0]
        for k in range(1, tries):
            if fits.is_set() or run.stopped or packings[k - 1] is None:
                break
            # a target that follows the parts: the density the last set's strip reached
            members = jobs[k - 1]["members"]
            reached = float(area[members].sum()) / (length(packings[k - 1]) * strip_height)
            if reached < target:
                target = FOLLOW * reached
                jobs[k]["members"] = _choose(remaining, area, target * sheet_length * strip_height)
            packings[k] = strip(centred, height=strip_height, spacing=spacing, orientations=orientations,
                                budget=run, **jobs[k])
            if packings[k] is not None and max(
                    p.bounds[2] for p in polygons_of(packings[k]).values()) <= width - margin:
                packing, chosen = packings[k], jobs[k]["members"]
                break
        polygons = polygons_of(packing)
        if max(p.bounds[2] for p in polygons.values()) > width - margin:
            # not within the sheet: the stretch of the strip holding the most part area
            start = _window(polygons, area, width, margin)
            polygons = polygons_of(packing, start)
        else:
            start = 0.0
        kept = valid({i: p for i, p in polygons.items() if p.bounds[2] <= width - margin}, room, spacing)
        if not kept:  # sparrow spread even the first part past the sheet: place one alone
            largest = max(remaining, key=lambda i: area[i])
            alone = strip(centred, [largest], strip_height, spacing, orientations, FEWEST, next(seeds), run)
            if alone is None or len(valid(polygons_of(alone), room, spacing)) != 1:
                break
            packing, kept, start = alone, [largest], 0.0
        with lock:
            for i in kept:
                put(i, sheet, *packing[i], start, placed)
        sheet += 1
        remaining = [i for i in remaining if i not in placed]
        if last and packings[-1] is not None and set(packings[-1]) == set(remaining):  # the set's complement
            with lock:
                layout = dict(placed)
                taken = cut_into_sheets(packings[-1], sheet, layout)
                if taken is not None:
                    placed.update(layout)
                    sheet += taken
                    remaining = []
    if remaining and not run.stopped:  # out of steps: one strip of the rest, cut into sheet lengths
        run.last_round = True
        packing = strip(centred, remaining, strip_height, spacing, orientations, FEWEST, next(seeds), run)
        if packing is not None:
            with lock:
                layout = dict(placed)
                taken = cut_into_sheets(packing, sheet, layout)
                if taken is not None:
                    placed.update(layout)
                    sheet += taken
                    remaining = []
    if remaining:  # stopped: the rest on further sheets by their bounding rectangles
        boxes = [np.ptp(centred[i], axis=0) for i in remaining]
        extra, corner = shelf_pack(np.array(boxes), (width, height), max(margin, spacing))
        for k, i in enumerate(remaining):
            low = np.asarray(shapes[i], dtype=float).min(axis=0)
            placed[i] = (sheet + int(extra[k]), 0.0, corner[k] - low)
    for waiting in settling:  # nothing is told after the end
        waiting.cancel()
        waiting.join()
    if report is not None:
        report(1.0)
    if len(placed) == n:
        final = nested(placed, run.stopped)
        # the best layout on the way when the final one takes no less stock: it was told already
        # (engraved and shown), and the two are then the same packings, cut alike but for where the
        # first sheet starts (its usage differed in the last digit: never the same layout again)
        if not best or stock(final) < (best[0][0][0], best[0][0][1] - 1e-9 * width):
            return final
    kept_layout = best[0][1]
    return Nested(kept_layout.sheet, kept_layout.angle, kept_layout.shift, kept_layout.sheets, run.stopped,
                  time.perf_counter() - run.start, run.on_the_clock, run.used)


def _stock(shapes: Sequence[FloatArray], sheet_of: NDArray[np.intp], angle: FloatArray, shift: FloatArray,
           sheets: int) -> tuple[int, float]:
    """What a layout takes from stock: its sheets, and how far the last one's parts reach."""
    reach = max(float(place(shapes[i], angle[i], shift[i])[:, 0].max())
                for i in range(len(shapes)) if sheet_of[i] == sheets - 1)
    return sheets, reach
