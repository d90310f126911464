"""True-shape nesting of flat parts onto fixed sheets, with sparrow (``spyrrow``) as the engine.

sparrow packs polygons into a *strip* of fixed height and minimises its length, keeping
a minimum separation between parts and from the strip's edges. Sheets have a length
too, so :func:`nest` fills them one at a time ("pack, cut, re-pack"):

1. pack every part still to place into a strip as tall as the sheet's usable height;
2. the parts that end within the sheet's usable length make that sheet's first set;
3. the parts that cross the sheet's end (largest first, then the others) are tried one
   at a time: the sheet's set plus one candidate is packed again, and the candidate
   stays when that strip still ends within the sheet;
4. what is left goes to the next sheet, from step 1. The last sheet is the strip of
   what remains, as short as sparrow makes it (its offcut goes back to stock).

The time budget is shared among those packings (at least one second each: sparrow
counts whole seconds). Every packing is checked afterwards with shapely against the
exact polygons in double precision (sparrow reports its placements in single
precision): a part closer to another than the spacing, or outside the usable sheet,
is moved on to the next sheet. So every layout returned keeps its spacing and margin.

Repeatability: sparrow is seeded, but its search runs against the clock, so how far it
gets — and so the layout — can differ from run to run on a busy machine, even with the
same seed. A seed fixes the random choices, not the number of them made.

Out of time with parts left (many sheets, a short budget), what is left is packed into
one last strip and cut into sheet lengths: each sheet takes the parts that end within a
sheet's length of the first part not yet placed.

Stopping: ``stop()`` is polled about every 50 ms; when it says yes, the best layout
found so far is kept (a strip under way contributes its best feasible packing), and
the rest is placed on further sheets by bounding-rectangle shelf packing so every part
is still on a sheet. ``report(fraction)`` is told how far the budget is spent.
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

from nodes.geometry.packing import shelf_pack

FloatArray = NDArray[np.float64]

#: Extra separation asked of sparrow (mm) so single-precision placements still keep
#: the spacing when checked in double precision.
SLACK = 0.02
#: How often a running packing looks at ``stop`` and reports progress (s).
POLL = 0.05
#: Shortest packing sparrow runs (s; it counts whole seconds).
SHORTEST = 1
#: Parts covering at most this share of a usable sheet probably fit on it: the last one.
LAST_SHEET = 0.8
#: Share of the budget kept for the last sheet, whose length decides what goes back to stock.
LAST_RESERVE = 0.3


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


def place(outline: FloatArray, angle: float, shift: Sequence[float]) -> FloatArray:
    """``outline`` turned by ``angle`` degrees about the origin, then moved by ``shift``."""
    a = math.radians(angle)
    c, s = math.cos(a), math.sin(a)
    return np.asarray(outline, dtype=float) @ np.array([[c, s], [-s, c]]) + np.asarray(shift, dtype=float)


class _Clock:
    """The shared budget, stop requests and progress of one :func:`nest` call."""

    def __init__(self, budget: float, stop: Callable[[], bool] | None,
                 report: Callable[[float], None] | None) -> None:
        self.start = time.perf_counter()
        self.budget = max(float(budget), SHORTEST)
        self.stop = stop
        self.report = report
        self.stopped = False

    def left(self) -> float:
        return self.budget - (time.perf_counter() - self.start)

    def tick(self) -> bool:
        """Report progress; True when a stop was asked for."""
        if self.report is not None:
            self.report(min(0.99, (time.perf_counter() - self.start) / self.budget))  # 1 when done
        if not self.stopped and self.stop is not None and self.stop():
            self.stopped = True
        return self.stopped


def _strip(shapes: Sequence[FloatArray], members: Sequence[int], height: float, spacing: float,
           orientations: Sequence[float] | None, seconds: int, seed: int,
           clock: _Clock, enough: float = 0.0) -> dict[int, tuple[float, tuple[float, float]]] | None:
    """Pack ``members`` into a strip of ``height``: {part: (angle, shift)}, or None when
    stopped before sparrow found a feasible packing. A packing no longer than ``enough``
    ends the search at once (a sheet's length: shorter is no better).

    sparrow cannot be interrupted, so it runs in a worker process
    (:mod:`nodes.geometry.sparrow_worker`) that a stop ends at once; the best feasible
    packing it reported by then is kept."""
    job = {
        "shapes": [[i, shapes[i].tolist()] for i in members], "height": float(height),
        "spacing": float(spacing) + SLACK if spacing > 0 else None,
        "orientations": None if orientations is None else [float(a) for a in orientations],
        "seconds": int(seconds), "seed": int(seed),
    }
    root = str(Path(__file__).resolve().parents[2])
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [root, os.environ.get("PYTHONPATH")]))}
    worker = subprocess.Popen(
        [sys.executable, "-m", "nodes.geometry.sparrow_worker"], stdin=subprocess.PIPE,
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
    best = None
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
                    best = json.loads(line)
                    if best[0] <= enough:
                        finished = True
                try:
                    line = lines.get_nowait()
                except queue.Empty:
                    break
            else:  # the worker closed its output: it has ended, or is about to
                finished = True
                with contextlib.suppress(subprocess.TimeoutExpired):
                    worker.wait(timeout=5.0)
            if clock.tick():
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
    if ended and worker.returncode != 0 and best is None:
        last = (problem.strip().splitlines() or ["no message"])[-1]
        raise NestingFailed(f"the nesting engine (sparrow) stopped with {last}")
    if best is None:
        return None
    return {int(i): (float(a), (float(x), float(y))) for i, a, x, y in best[1]}


def _valid(polygons: dict[int, shapely.Polygon], room: shapely.Polygon, spacing: float) -> list[int]:
    """The parts of a packing that keep the spacing and stay in ``room``, largest first
    (a part too close to one already kept is left out)."""
    kept: list[int] = []
    for i in sorted(polygons, key=lambda k: -polygons[k].area):
        polygon = polygons[i]
        if not room.covers(polygon):
            continue
        if any(polygon.distance(polygons[j]) < spacing for j in kept):
            continue
        kept.append(i)
    return kept


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
) -> Nested:
    """Nest ``shapes`` (closed polygons in mm, each given once) onto sheets of
    ``width`` × ``height`` mm, ``margin`` from the sheet's edges and ``spacing`` apart.

    ``orientations`` lists the allowed turns in degrees (``None``: free rotation).
    Every shape must fit the usable sheet in some allowed turn (the caller checks).
    """
    clock = _Clock(budget, stop, report)
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

    def seconds(share: float) -> int:
        """``share`` of this sheet's part of the time left: the time left split among the
        sheets the remaining parts need at least (their area over the usable sheet)."""
        sheets_left = max(1.0, math.ceil(sum(area[i] for i in remaining) / usable))
        return max(SHORTEST, round(max(clock.left(), 0.0) / sheets_left * share))

    while remaining and not clock.stopped and clock.left() > 0:
        # likely the last sheet: all the time left, since its length is what the offcut saves
        last = sum(area[i] for i in remaining) <= LAST_SHEET * usable
        packing = _strip(centred, remaining, strip_height, spacing, orientations,
                         seconds(1.0 if last else 0.35), attempt_seed, clock)
        attempt_seed += 1
        if packing is None:
            break
        polygons = polygons_of(packing)
        inside = {i: p for i, p in polygons.items() if p.bounds[2] <= width - margin}
        kept = _valid(inside, room, spacing)
        chosen = {i: packing[i] for i in kept}
        if len(kept) < len(remaining):
            crossing = sorted((i for i in remaining if i not in chosen and i in polygons
                               and polygons[i].bounds[0] < width - margin), key=lambda i: -area[i])
            others = sorted((i for i in remaining if i not in chosen and i not in crossing),
                            key=lambda i: -area[i])
            free = room_length * (height - 2 * margin) - sum(area[i] for i in chosen)
            for candidate in crossing + others:
                rest = sum(area[i] for i in remaining if i not in chosen)
                # the next sheet is likely the last: keep a share of the budget for it
                reserve = LAST_RESERVE * clock.budget if rest <= LAST_SHEET * usable else 0.0
                if clock.stopped or clock.left() - reserve < SHORTEST or not chosen:
                    break
                if area[candidate] > free:
                    continue
                members = [*chosen, candidate]
                trial = _strip(centred, members, strip_height, spacing, orientations,
                               seconds(0.15), attempt_seed, clock, enough=room_length + 2 * spacing)
                attempt_seed += 1
                if trial is None or len(trial) != len(members):
                    continue
                trial_polygons = polygons_of(trial)
                if max(p.bounds[2] for p in trial_polygons.values()) > width - margin:
                    continue
                if len(_valid(trial_polygons, room, spacing)) == len(members):
                    chosen = trial
                    free -= area[candidate]
        if not chosen:  # sparrow spread even the first part past the sheet: place one alone
            largest = max(remaining, key=lambda i: area[i])
            alone = _strip(centred, [largest], strip_height, spacing, orientations, SHORTEST,
                           attempt_seed, clock)
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
    if remaining and not clock.stopped:  # out of time: one strip of the rest, cut into sheet lengths
        packing = _strip(centred, remaining, strip_height, spacing, orientations, SHORTEST,
                         attempt_seed, clock)
        polygons = polygons_of(packing) if packing is not None else {}
        open_room = shapely.box(margin, margin, math.inf, height - margin)
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
    return Nested(sheet_of, angle, shift, sheet, clock.stopped, time.perf_counter() - clock.start)
