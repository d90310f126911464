"""True-shape nesting of flat parts onto fixed sheets, with sparrow (``spyrrow``) as the engine.

sparrow packs polygons into a *strip* of fixed height and minimises its length, keeping
a minimum separation between parts and from the strip's edges. Sheets have a length
too, so :func:`nest` first packs every part into one strip as tall as the sheet's usable
height and cuts it into sheet lengths as sparrow shortens it (:func:`_cut`: each sheet
starts a margin before the first part not yet placed and takes the parts that end within
it); each cut layout that takes less stock than the last is told to ``found`` at once (the
app redraws it), and so is, later, each one made of the sheets filled so far and the strip
of the parts left cut after them. When the best cut keeps :data:`CUT_KEEPS` of the strip's density, that is
the layout (many parts small beside the sheet: panels). Otherwise (parts a third of a
sheet long, as the Kaohsiung strips: every cut line crosses four or five of them and the
cut loses a tenth of the density) it fills the sheets one at a time ("pack, cut, re-pack"),
starting from that same strip, and keeps whichever takes less stock:

1. pack every part still to place into a strip as tall as the sheet's usable height;
2. the sheet is the stretch of that strip, a sheet long, that holds the most part area
   (:func:`_window`; not always its start): the parts wholly within it make its first set;
3. the parts that cross the stretch's ends (largest first, then the others) are tried
   one at a time, while the set stays below about the density the strip reached: the
   sheet's set plus one candidate is packed again, and the candidate stays when that
   strip ends within the sheet;
4. swaps, smallest part on the sheet first: the largest part left over that is larger
   but keeps the sheet's part area within what the strip's density would put on a sheet
   takes its place when the set so changed still fits the sheet (packed again as in 3). More area
   on the full sheet leaves less for the next, so the last one ends shorter;
5. what is left goes to the next sheet, from step 1. The last sheet is the strip of
   what remains, as short as sparrow makes it, packed again with further seeds while
   the budget lasts (the shortest is kept: its offcut goes back to stock).

Repeatability: the budget is counted in sparrow's *steps*, not seconds (see
:mod:`torsal.nodes.geometry.sparrow_worker`): :data:`STEPS_PER_SECOND` per second of
``budget``, shared among those packings by fixed rules, each packing ending at its
first failed attempt. sparrow is seeded and searches on :data:`WORKERS` threads, always
that many whatever the machine's cores (with another thread count its reports differ;
with the same one they come in the same order: checked on the Kaohsiung strips, the first
60 reports of two runs identical), so the same parts, sheet and seed give the same layout
on any machine, however busy — a busy one only takes longer. The clock is a safety net
(:data:`NET` times the budget): a packing it stops sets ``Nested.on_the_clock``, and that
layout may differ from run to run.
Identical packings asked again in the same process are answered from a cache.

Every packing is checked afterwards with shapely against the exact polygons in double
precision (sparrow reports its placements in single precision): a part closer to
another than the spacing, or outside the usable sheet, is moved on to the next sheet.
So every layout returned keeps its spacing and margin.

Where the time goes (profiled on the Kaohsiung strips, 18 parts, budget 45, issue 31): the
first strip of every part took 39 % of the run, four trials of a sheet's set 52 %, the last
sheet 8 %; within each, nearly all of it is sparrow's one failed attempt that ends the
packing (a failed attempt searches many times as long as the hundreds that succeed). Ending
a trial after a few reports of sparrow struggling at one width instead (deterministic, like
the steps) made each trial cheap but lost trials that would have fitted: no faster overall.
Packing the sheets as frames in one strip (a full-height bracket item per sheet) made one
call, but sparrow moved the huge item slowly: 2-3 times its time for the plain strip.
Measured next (two threads, load 3): the strip cut into sheets keeps 62 % of the Kaohsiung
strips' stock where the strip is 73.7 % dense, 58 % for 50 random strips at 67.8 %; filling
the cuts' holes with the last sheet's parts by a raster bottom-left search moved one part of
6-13 (no gain, 1-2 s each); and sparrow took 12.4 s to pack 13 Kaohsiung strips (69 % of a
sheet) into one sheet's length, more than the 5-13 s it takes to pack all 18 into a strip
72 % dense. Kaohsiung's 72 % of the stock needs its first sheet 72.7 % full: a sheet packed
by sparrow, which costs about the whole baseline, so its bar (1.5) is out of reach of
spyrrow 0.9's strip-only interface (no obstacles, no warm start).

Out of steps with parts left (many sheets, a small budget), what is left is packed into
one last strip and cut into sheet lengths: each sheet takes the parts that end within a
sheet's length of the first part not yet placed.

Stopping: ``stop()`` is polled about every 50 ms; when it says yes, the best layout
found so far is kept (a strip under way contributes its best feasible packing), and
the rest is placed on further sheets by bounding-rectangle shelf packing so every part
is still on a sheet. ``report(fraction)`` is told how far the budget's steps are spent.
"""

from __future__ import annotations

import contextlib
import json
import math
import os
import queue
import subprocess
import sys
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import shapely
from numpy.typing import NDArray

from torsal.nodes.geometry.array_types import FloatArray
from torsal.nodes.geometry.packing import shelf_pack

#: Extra separation asked of sparrow (mm) so single-precision placements still keep
#: the spacing when checked in double precision.
SLACK = 0.02
#: How often a running packing looks at ``stop`` (s).
POLL = 0.05
#: Steps of sparrow's search per second of the budget (see :mod:`torsal.nodes.geometry.sparrow_worker`:
#: a step is one attempt to pack the strip shorter, a failed one counts 20). Roughly what
#: an unloaded machine does in a second on sheets of a dozen or more large parts (the
#: Kaohsiung strips: 30 s of budget took 35-130 s at a load of 1-8 on two cores); fewer
#: or smaller parts go faster.
STEPS_PER_SECOND = 40
#: Fewest steps a packing is given.
FEWEST = 20
#: Share of the steps left that the strip of every part still to place gets, when they
#: need more than one sheet; the trials that fill its sheet share the rest with the next.
FIRST_SHARE = 0.35
#: Share of the budget's steps that one trial (a sheet's set plus one part) gets at most;
#: it ends as soon as the set fits the sheet.
TRIAL_SHARE = 0.4
#: A sheet's set is tried only up to this share of the density the strip of all the
#: parts reached (a sheet has two ends a strip has not): denser trials fail, and a failed
#: trial is the slowest step there is.
SHEET_DENSITY = 0.95
#: Fewest steps a trial is worth: sparrow starts from a strip a sixth or so longer and
#: shortens it by 0.1 % a step.
FEWEST_TRIAL = 150
#: A trial ends at its first failed attempt: sparrow could not make it shorter, so it
#: probably does not fit (a failed attempt takes as long as hundreds that succeed).
#: Parts covering at most this share of a usable sheet probably fit on it: the last one.
LAST_SHEET = 0.8
#: Fewest steps left for another seed's packing of the last sheet (the shortest is kept).
RETRY = 100
#: Share of the steps kept for the last sheet, whose length decides what goes back to stock.
LAST_RESERVE = 0.3
#: The clock as a safety net only: a packing stops after this many times the whole
#: budget (plus :data:`GRACE` s), and the layout says it was stopped on the clock.
NET = 10.0
GRACE = 60.0
#: Threads sparrow searches on, whatever the machine: with a fixed count its reports come in
#: the same order for the same seed (they differ from one thread count to another).
WORKERS = 2
#: The strip of every part, cut into sheet lengths, is the layout when it keeps at least
#: this share of the strip's density; below, sheets are filled one at a time.
CUT_KEEPS = 0.9


#: Packings kept for identical jobs asked again in this process (the same graph solved
#: again, a test suite): job -> (packing, steps), at most :data:`CACHED` of them.
_PACKED: dict[str, tuple[dict[int, tuple[float, tuple[float, float]]] | None, int]] = {}
CACHED = 64


class NestingFailed(RuntimeError):
    """sparrow's worker failed (not installed, refused the parts): the message says how."""


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


class _Budget:
    """The shared steps, stop requests and progress of one :func:`nest` call."""

    def __init__(self, budget: float, stop: Callable[[], bool] | None,
                 report: Callable[[float], None] | None) -> None:
        self.start = time.perf_counter()
        self.steps = max(FEWEST, round(float(budget) * STEPS_PER_SECOND))
        self.used = 0
        self.net = NET * float(budget) + GRACE  # seconds, for every packing together
        self.stop = stop
        self.report = report
        self.stopped = False
        self.on_the_clock = False
        self.reported = 0.0

    def left(self) -> int:
        return self.steps - self.used

    def share(self, fraction: float) -> int:
        """``fraction`` of the steps left, at least :data:`FEWEST`."""
        return max(FEWEST, round(max(self.left(), 0) * fraction))

    def seconds(self) -> float:
        return max(1.0, self.net - (time.perf_counter() - self.start))

    def tick(self, running: int = 0) -> bool:
        """Report progress (``running``: steps of the packing under way); True when a stop
        was asked for."""
        fraction = min(0.99, (self.used + running) / self.steps)  # 1 when done
        if self.report is not None and fraction > self.reported:
            self.reported = fraction
            self.report(fraction)
        if not self.stopped and self.stop is not None and self.stop():
            self.stopped = True
        return self.stopped


def _strip(shapes: Sequence[FloatArray], members: Sequence[int], height: float, spacing: float,
           orientations: Sequence[float] | None, steps: int, seed: int,
           budget: _Budget, enough: float = 0.0, failures: int = 1,
           better: Callable[[dict[int, tuple[float, tuple[float, float]]]], None] | None = None,
           ) -> dict[int, tuple[float, tuple[float, float]]] | None:
    """Pack ``members`` into a strip of ``height`` in at most ``steps`` steps and
    ``failures`` failed attempts: {part: (angle, shift)}, or None when stopped before
    sparrow found a feasible packing. A packing no longer than ``enough`` ends the search
    at once (a sheet's length: shorter is no better).

    sparrow cannot be interrupted, so it runs in a worker process
    (:mod:`torsal.nodes.geometry.sparrow_worker`) that a stop ends at once; the best feasible
    packing it reported by then is kept. ``better`` is told each shorter packing as it
    arrives (not those of a cached job)."""
    job = {
        # to a micrometre: below what sparrow's single precision holds on a sheet, and
        # rounding noise (a far site) then asks the same job
        "shapes": [[i, np.round(shapes[i], 3).tolist()] for i in members], "height": float(height),
        "spacing": float(spacing) + SLACK if spacing > 0 else None,
        "orientations": None if orientations is None else [float(a) for a in orientations],
        "steps": int(steps), "failures": int(failures), "enough": float(enough),
        "seconds": budget.seconds(), "seed": int(seed), "workers": WORKERS,
    }
    key = json.dumps({k: v for k, v in job.items() if k != "seconds"})
    if key in _PACKED:
        cached, used = _PACKED[key]
        budget.used += used
        budget.tick()
        if better is not None and cached is not None:
            better(dict(cached))
        return None if cached is None else dict(cached)
    # -P: the current folder is not searched, so a folder of the user's that holds its own
    # `torsal` (or anything else) cannot stand in for the worker's modules; the folder that
    # holds this very `torsal` package goes first on the path instead.
    root = str(Path(__file__).resolve().parents[3])
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [root, os.environ.get("PYTHONPATH")]))}
    worker = subprocess.Popen(
        [sys.executable, "-P", "-m", "torsal.nodes.geometry.sparrow_worker"], stdin=subprocess.PIPE,
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env, text=True,
    )
    lines: queue.Queue[str | None] = queue.Queue()

    def read() -> None:
        assert worker.stdout is not None
        for line in worker.stdout:
            lines.put(line)
        lines.put(None)

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    best, used, complete, clocked = None, 0, False, False
    try:
        assert worker.stdin is not None
        worker.stdin.write(json.dumps(job))
        worker.stdin.close()
        finished = False
        while not finished:
            try:
                line = lines.get(timeout=POLL)
            except queue.Empty:
                line = ""
            while line is not None:
                if line.strip():
                    message = json.loads(line)
                    if message[0] == "step":
                        used = int(message[1])
                    elif message[0] == "end":
                        used, complete, clocked = int(message[1]), True, bool(message[2])
                        budget.on_the_clock |= clocked
                    else:
                        best = message
                        if better is not None:
                            better({int(i): (float(a), (float(x), float(y))) for i, a, x, y in best[1]})
                try:
                    line = lines.get_nowait()
                except queue.Empty:
                    break
            else:  # the worker closed its output: it has ended, or is about to
                finished = True
                with contextlib.suppress(subprocess.TimeoutExpired):
                    worker.wait(timeout=5.0)
            if budget.tick(used):
                finished = True
    finally:
        ended = worker.poll() is not None
        if not ended:
            worker.kill()
        worker.wait()
        reader.join(timeout=1.0)
        problem = worker.stderr.read() if worker.stderr is not None and ended else ""
        if worker.stderr is not None:
            worker.stderr.close()
    budget.used += used
    if ended and worker.returncode != 0 and best is None:
        last = (problem.strip().splitlines() or ["no message"])[-1]
        raise NestingFailed(f"the nesting engine (sparrow) stopped with {last}")
    packing = None if best is None else {int(i): (float(a), (float(x), float(y))) for i, a, x, y in best[1]}
    if complete and not clocked:  # what any later run of this job would find
        while len(_PACKED) >= CACHED:
            _PACKED.pop(next(iter(_PACKED)))
        _PACKED[key] = (packing, used)
    return packing


def _valid(polygons: dict[int, shapely.Polygon], room: shapely.Polygon, spacing: float) -> list[int]:
    """The parts of a packing that keep the spacing and stay in ``room``, largest first
    (a part too close to one already kept is left out)."""
    order = sorted(polygons, key=lambda k: -polygons[k].area)
    tree = shapely.STRtree([polygons[i] for i in order])  # only near pairs are measured
    kept: list[int] = []
    taken: set[int] = set()
    for rank, i in enumerate(order):
        polygon = polygons[i]
        if not room.covers(polygon):
            continue
        near = tree.query(polygon, predicate="dwithin", distance=spacing)
        if any(int(k) in taken and int(k) != rank and polygon.distance(polygons[order[int(k)]]) < spacing
               for k in near):
            continue
        kept.append(i)
        taken.add(rank)
    return kept


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
    ``found`` is told each complete layout that takes less stock than the last it was told
    (the strip of every part cut into sheets, as sparrow shortens it), before the end.
    """
    run = _Budget(budget, stop, report)
    n = len(shapes)
    # sparrow keeps the spacing from the strip's edges too: widen the strip by it
    strip_height = height - 2 * margin + 2 * spacing
    room_length = width - 2 * margin
    room = shapely.box(margin, margin, width - margin, height - margin).buffer(1e-9, join_style="mitre")
    # sparrow turns about the origin: centre each shape there (smaller rounding)
    centres = [np.asarray(s, dtype=float).mean(axis=0) for s in shapes]
    centred = [np.asarray(s, dtype=float) - c for s, c in zip(shapes, centres, strict=True)]
    area = np.array([shapely.Polygon(s).area for s in centred])
    sheet_of = np.full(n, -1, dtype=np.intp)
    angle = np.zeros(n)
    shift = np.zeros((n, 2))
    remaining = list(range(n))
    sheet = 0
    attempt_seed = int(seed)

    def polygons_of(packing: dict[int, tuple[float, tuple[float, float]]]) -> dict[int, shapely.Polygon]:
        lift = (margin - spacing, margin - spacing)  # strip origin -> sheet
        return {i: shapely.Polygon(place(centred[i], a, np.add(t, lift))) for i, (a, t) in packing.items()}

    usable = room_length * (height - 2 * margin)
    # a strip of every part, however loosely packed, ends well before this (a finite box:
    # shapely cannot tell what an infinite one covers when a part touches its edge)
    far = width + 2 * sum(float(np.ptp(c, axis=0).max()) + 2 * spacing for c in centred)
    open_room = shapely.box(margin, margin, far, height - margin).buffer(1e-9, join_style="mitre")

    def length(packing: dict[int, tuple[float, tuple[float, float]]]) -> float:
        """How far a packing of every part left reaches; infinite when one is missing or
        too close to another in double precision."""
        polygons = polygons_of(packing)
        if len(polygons) < len(remaining) or len(_valid(polygons, open_room, spacing)) < len(polygons):
            return math.inf
        return max(p.bounds[2] for p in polygons.values())

    def steps(share: float, reserve: float = 0.0) -> int:
        """``share`` of this sheet's part of the steps left (less ``reserve``): the steps
        split among the sheets the remaining parts need at least (their area over the
        usable sheet)."""
        sheets_left = max(1.0, math.ceil(sum(area[i] for i in remaining) / usable))
        return max(FEWEST, round(max(run.left() - reserve, 0.0) / sheets_left * share))

    #: the strip of every part cut into sheets, the least stock so far: ((sheets, reach), layout)
    cut: list[tuple[tuple[int, float], Nested]] = []

    def cut_into_sheets(packing: dict[int, tuple[float, tuple[float, float]]]) -> None:
        """Keep (and tell ``found``) the sheets filled so far and the strip ``packing`` of
        every part left cut into sheet lengths after them, when that takes less stock than
        the layout kept."""
        polygons = polygons_of(packing)
        if len(polygons) < len(remaining) or len(_valid(polygons, open_room, spacing)) < len(polygons):
            return
        sheets = _cut(polygons, width, margin)
        if not sheets:
            return
        start, members = sheets[-1]
        stock = (sheet + len(sheets), max(polygons[i].bounds[2] for i in members) - start)
        if cut and stock >= cut[0][0]:
            return
        cut_sheet, cut_angle, cut_shift = sheet_of.copy(), angle.copy(), shift.copy()
        for k, (start, members) in enumerate(sheets):
            for i in members:
                a, t = packing[i]
                cut_sheet[i], cut_angle[i] = sheet + k, a
                lift = np.add(t, (margin - spacing - start, margin - spacing))
                cut_shift[i] = lift - place(centres[i][None, :], a, (0, 0))[0]
        layout = Nested(cut_sheet, cut_angle, cut_shift, stock[0], seconds=time.perf_counter() - run.start,
                        steps=run.used)
        cut[:] = [(stock, layout)]
        if found is not None:
            found(layout)

    cut_is_enough = False
    while remaining and not run.stopped and run.left() >= FEWEST:
        # likely the last sheet: all the steps left, since its length is what the offcut saves
        last = sum(area[i] for i in remaining) <= LAST_SHEET * usable
        first = sheet == 0
        packing = _strip(centred, remaining, strip_height, spacing, orientations,
                         steps(1.0 if last else FIRST_SHARE), attempt_seed, run,
                         better=cut_into_sheets)
        attempt_seed += 1
        if packing is None:
            break
        # the last sheet's length is what goes back to stock: try other seeds while steps last
        while last and not run.stopped and run.left() >= RETRY:
            again = _strip(centred, remaining, strip_height, spacing, orientations, run.left(),
                           attempt_seed, run, better=cut_into_sheets)
            attempt_seed += 1
            if again is not None and length(again) < length(packing):
                packing = again
        polygons = polygons_of(packing)
        # how densely sparrow packed them all: a sheet's set is tried up to about as dense
        reach = max(p.bounds[2] for p in polygons.values()) - (margin - spacing) + spacing
        density = sum(area[i] for i in packing) / (reach * strip_height)
        if first and cut:
            (count, cut_reach), _ = cut[0]
            usage = float(area.sum()) / (((count - 1) * width + cut_reach) * height)
            # the cut strip keeps nearly its density: filling sheets one at a time (trials
            # that end on sparrow's slowest step, a failed attempt) would gain little
            if usage >= CUT_KEEPS * density:
                cut_is_enough = True
                break
        # the sheet is the stretch of the strip holding the most area, not always its start
        start = _window(polygons, area, width, margin)
        if start > 0:
            packing = {i: (a, (t[0] - start, t[1])) for i, (a, t) in packing.items()}
            polygons = polygons_of(packing)
        inside = {i: p for i, p in polygons.items() if p.bounds[2] <= width - margin}
        kept = _valid(inside, room, spacing)
        chosen = {i: packing[i] for i in kept}
        if len(kept) < len(remaining):
            crossing = sorted((i for i in remaining if i not in chosen and i in polygons
                               and polygons[i].bounds[0] < width - margin
                               and polygons[i].bounds[2] > margin), key=lambda i: -area[i])
            others = sorted((i for i in remaining if i not in chosen and i not in crossing),
                            key=lambda i: -area[i])
            full = density * (room_length + 2 * spacing) * strip_height  # part area at the strip's density
            free = SHEET_DENSITY * full - sum(area[i] for i in chosen)

            def fitted(members: list[int], trial_steps: int) -> dict | None:
                """``members`` packed onto the sheet by one sparrow trial, or None if they
                do not all fit inside it (less its margin, ``spacing`` apart)."""
                nonlocal attempt_seed
                trial = _strip(centred, members, strip_height, spacing, orientations,
                               trial_steps, attempt_seed, run, enough=room_length + 2 * spacing)
                attempt_seed += 1
                if trial is None or len(trial) != len(members):
                    return None
                trial_polygons = polygons_of(trial)
                if max(p.bounds[2] for p in trial_polygons.values()) > width - margin:
                    return None
                return trial if len(_valid(trial_polygons, room, spacing)) == len(members) else None

            for candidate in crossing + others:
                rest = sum(area[i] for i in remaining if i not in chosen)
                # the next sheet is likely the last: keep a share of the budget for it
                reserve = LAST_RESERVE * run.steps if rest <= LAST_SHEET * usable else 0.0
                trial_steps = round(min(run.left() - reserve, run.steps * TRIAL_SHARE))
                if run.stopped or trial_steps < FEWEST_TRIAL or not chosen:
                    break
                if area[candidate] > free:
                    continue
                trial = fitted([*chosen, candidate], trial_steps)
                if trial is not None:
                    chosen = trial
                    free -= area[candidate]
            # swaps: the largest part left for the smallest on the sheet, while the sheet stays
            # no denser than the strip was (the leftovers' sheet gets shorter)
            for out in sorted(chosen, key=lambda i: (area[i], i)):
                room_for = full - sum(area[i] for i in chosen) + area[out]
                left_over = [i for i in remaining if i not in chosen and area[out] < area[i] <= room_for]
                if not left_over:
                    continue
                swap_in = max(left_over, key=lambda i: (area[i], -i))
                rest = sum(area[i] for i in remaining if i not in chosen) - area[swap_in] + area[out]
                reserve = LAST_RESERVE * run.steps if rest <= LAST_SHEET * usable else 0.0
                trial_steps = round(min(run.left() - reserve, run.steps * TRIAL_SHARE))
                if run.stopped or trial_steps < FEWEST_TRIAL:
                    break
                trial = fitted([*(i for i in chosen if i != out), swap_in], trial_steps)
                if trial is not None:
                    chosen = trial
        if not chosen:  # sparrow spread even the first part past the sheet: place one alone
            largest = max(remaining, key=lambda i: area[i])
            alone = _strip(centred, [largest], strip_height, spacing, orientations, FEWEST,
                           attempt_seed, run)
            if alone is None or len(_valid(polygons_of(alone), room, spacing)) != 1:
                break
            chosen = alone
        for i, (a, t) in chosen.items():
            sheet_of[i], angle[i] = sheet, a
            # placed = R(shape - centre) + t + lift = R(shape) + (t + lift - R(centre))
            lift = np.add(t, (margin - spacing, margin - spacing))
            shift[i] = lift - place(centres[i][None, :], a, (0, 0))[0]
        remaining = [i for i in remaining if sheet_of[i] < 0]
        sheet += 1
    if cut_is_enough:
        remaining = []
    if remaining and not run.stopped:  # out of steps: one strip of the rest, cut into sheet lengths
        packing = _strip(centred, remaining, strip_height, spacing, orientations, FEWEST,
                         attempt_seed, run)
        polygons = polygons_of(packing) if packing is not None else {}
        if len(polygons) == len(remaining) and len(_valid(polygons, open_room, spacing)) == len(polygons):
            left = sorted(polygons, key=lambda i: polygons[i].bounds[0])
            while left:
                start = polygons[left[0]].bounds[0] - margin  # this sheet's cut-off along the strip
                here = [i for i in left if polygons[i].bounds[2] - start <= width - margin]
                if not here:  # turned longer than the sheet: the shelf below takes the rest
                    break
                for i in here:
                    a, t = packing[i]
                    sheet_of[i], angle[i] = sheet, a
                    lift = np.add(t, (margin - spacing - start, margin - spacing))
                    shift[i] = lift - place(centres[i][None, :], a, (0, 0))[0]
                left = [i for i in left if i not in here]
                sheet += 1
            remaining = [i for i in remaining if sheet_of[i] < 0]
    if remaining:  # stopped: the rest on further sheets by their bounding rectangles
        boxes = [np.ptp(centred[i], axis=0) for i in remaining]
        extra, corner = shelf_pack(np.array(boxes), (width, height), max(margin, spacing))
        for k, i in enumerate(remaining):
            sheet_of[i] = sheet + int(extra[k])
            shift[i] = corner[k] - np.asarray(shapes[i], dtype=float).min(axis=0)
        sheet += int(extra.max()) + 1
    if report is not None:
        report(1.0)
    seconds = time.perf_counter() - run.start
    if cut and (cut_is_enough or cut[0][0] <= _stock(shapes, sheet_of, angle, shift, sheet)):
        return Nested(cut[0][1].sheet, cut[0][1].angle, cut[0][1].shift, cut[0][1].sheets, run.stopped,
                      seconds, run.on_the_clock, run.used)
    return Nested(sheet_of, angle, shift, sheet, run.stopped, seconds, run.on_the_clock, run.used)


def _stock(shapes: Sequence[FloatArray], sheet_of: NDArray[np.intp], angle: FloatArray, shift: FloatArray,
           sheets: int) -> tuple[int, float]:
    """What a layout takes from stock: its sheets, and how far the last one's parts reach."""
    reach = max(float(place(shapes[i], angle[i], shift[i])[:, 0].max())
                for i in range(len(shapes)) if sheet_of[i] == sheets - 1)
    return sheets, reach
