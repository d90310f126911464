"""sparrow's strip packings for :func:`torsal.nodes.geometry.nesting.nest`: the budget of
steps they share, one packing in a worker process (:func:`strip`, or several at once:
:func:`strips`), and the check of a packing in double precision (:func:`valid`).

Repeatability: the budget is counted in sparrow's *steps*, not seconds (see
:mod:`torsal.nodes.geometry.sparrow_worker`): :data:`STEPS_PER_SECOND` per second of
``budget``. sparrow is seeded and searches on a fixed number of threads (:data:`WORKERS`, or
what the job says), whatever the machine's cores (with another thread count its reports differ;
with the same one they come in the same order), so a job gives the same packing on any machine, however
busy — a busy one only takes longer. Packings run side by side (:func:`strips`) are separate
jobs, each as repeatable. The clock is a safety net (:data:`NET` times the budget): a
packing it stops sets ``Budget.on_the_clock``, and that layout may differ from run to run.
Identical packings asked again in the same process are answered from a cache.
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
from pathlib import Path

import numpy as np
import shapely

from torsal.nodes.geometry.array_types import FloatArray

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
#: The clock as a safety net only: a packing stops after this many times the whole
#: budget (plus :data:`GRACE` s), and the layout says it was stopped on the clock.
NET = 10.0
GRACE = 60.0
#: How much shorter each step of sparrow's search makes a feasible strip (its reports: 0.1 %):
#: a packing that ends at a length (``enough``) is expected to take the steps from its
#: latest length to that one.
SHRINK = 0.001
#: Threads sparrow searches on, whatever the machine: with a fixed count its reports come in
#: the same order for the same seed (they differ from one thread count to another).
WORKERS = 2

#: A packing: {part: (angle in degrees, shift)} in the strip.
Packing = dict[int, tuple[float, tuple[float, float]]]

#: Packings kept for identical jobs asked again in this process (the same graph solved
#: again, a test suite): job -> (packing, steps), at most :data:`CACHED` of them.
PACKED: dict[str, tuple[Packing | None, int]] = {}
CACHED = 64


class NestingFailed(RuntimeError):
    """sparrow's worker failed (not installed, refused the parts): the message says how."""



class Budget:
    """The shared steps, stop requests and progress of one :func:`nest` call.

    Progress is the steps taken over the steps the nesting is expected to take: every step of
    the budget while parts will be left after the packings under way; in the last round (set by
    the caller: :attr:`last_round`), only those already taken and those the packings under way
    are expected to take (:meth:`tick`), so a nesting whose sheets fit early is not shown at a
    fraction of its budget until it ends. Packings side by side count together."""

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
        self.last_round = False  #: the packings under way place every part left
        self.running: dict[int, tuple[int, int]] = {}  # packing -> (steps taken, steps expected)
        #: each packing run (not cached): (seed, parts, steps taken, worker CPU-s or None when it was
        #: ended early, seconds from this budget's start to its start and to its end)
        self.runs: list[tuple[int, int, int, float | None, float, float]] = []
        self.lock = threading.Lock()  # packings side by side (strips) share it

    def left(self) -> int:
        return self.steps - self.used

    def share(self, fraction: float) -> int:
        """``fraction`` of the steps left, at least :data:`FEWEST`."""
        return max(FEWEST, round(max(self.left(), 0) * fraction))

    def seconds(self) -> float:
        return max(1.0, self.net - (time.perf_counter() - self.start))

    def fraction(self) -> float:
        """How far the nesting is, below 1 (1 is told at its end)."""
        taken = self.used + sum(steps for steps, _ in self.running.values())
        expected = self.used + sum(max(steps, more) for steps, more in self.running.values()) \
            if self.last_round else self.steps
        return min(0.99, taken / max(expected, 1))

    def tick(self, packing: int | None = None, steps: int = 0, expected: int = 0) -> bool:
        """Report progress (``packing``: a counted packing under way, ``steps`` of it taken,
        ``expected`` in all); True when a stop was asked for."""
        with self.lock:
            if packing is not None:
                self.running[packing] = (steps, expected)
            fraction = self.fraction()
            if self.report is not None and fraction > self.reported:
                self.reported = fraction
                self.report(fraction)
            if not self.stopped and self.stop is not None and self.stop():
                self.stopped = True
            return self.stopped

    def spend(self, steps: int, packing: int | None = None) -> None:
        """Count ``steps`` of a packing as used (``packing``: it has ended)."""
        with self.lock:
            self.used += steps
            self.running.pop(packing, None)


def strip(shapes: Sequence[FloatArray], members: Sequence[int], height: float, spacing: float,
           orientations: Sequence[float] | None, steps: int, seed: int,
           budget: Budget, enough: float = 0.0, failures: int = 1,
           better: Callable[[Packing], None] | None = None, halt: Callable[[], bool] | None = None,
           counted: bool = True, turn: float = 0.0, workers: int | None = None) -> Packing | None:
    """Pack ``members`` into a strip of ``height`` in at most ``steps`` steps and
    ``failures`` failed attempts: {part: (angle, shift)}, or None when stopped before
    sparrow found a feasible packing. A packing no longer than ``enough`` ends the search
    at once (a sheet's length: shorter is no better).

    sparrow cannot be interrupted, so it runs in a worker process
    (:mod:`torsal.nodes.geometry.sparrow_worker`) that a stop ends at once; the best feasible
    packing it reported by then is kept. ``better`` is told each shorter packing as it
    arrives (not those of a cached job). ``halt`` (polled like ``stop``) ends this packing
    alone, keeping its best so far (another packing beside it made it of no use); the steps
    of a packing not ``counted`` are left out of the budget's (they depend on when it ended).
    ``turn``: sparrow is given each member turned by that many degrees (its search starts from
    the parts as given; free rotation only), and the angles returned are of the shapes as given.
    ``workers``: the threads sparrow searches on (:data:`WORKERS` when None; part of the job: the
    same job gives the same packing)."""
    c, s = math.cos(math.radians(turn)), math.sin(math.radians(turn))
    turned = np.array([[c, s], [-s, c]])  # counter-clockwise, as the angles sparrow reports

    def packed(rows: list) -> Packing:
        return {int(i): ((float(a) + turn) % 360.0 if turn else float(a), (float(x), float(y)))
                for i, a, x, y in rows}

    job = {
        # to a micrometre: below what sparrow's single precision holds on a sheet, and
        # rounding noise (a far site) then asks the same job
        "shapes": [[i, np.round(np.asarray(shapes[i]) @ turned if turn else shapes[i], 3).tolist()]
                   for i in members], "height": float(height),
        "spacing": float(spacing) + SLACK if spacing > 0 else None,
        "orientations": None if orientations is None else [float(a) for a in orientations],
        "steps": int(steps), "failures": int(failures), "enough": float(enough),
        "seconds": budget.seconds(), "seed": int(seed),
        "workers": WORKERS if workers is None else int(workers),
    }
    key = json.dumps({k: v for k, v in job.items() if k != "seconds"})
    if key in PACKED:
        cached, used = PACKED[key]
        budget.spend(used if counted else 0)
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
    best, used, complete, clocked, cpu = None, 0, False, False, None
    began = time.perf_counter() - budget.start
    me, expected = id(lines), steps  # this packing, and the steps it is expected to take
    untold = False  # a packing came that better has not been told
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
                        cpu = float(message[3]) if len(message) > 3 else None
                        if clocked:
                            budget.on_the_clock = True
                    else:
                        best, untold = message, True
                try:
                    line = lines.get_nowait()
                except queue.Empty:
                    break
            else:  # the worker closed its output: it has ended, or is about to
                finished = True
                with contextlib.suppress(subprocess.TimeoutExpired):
                    worker.wait(timeout=5.0)
            if untold and better is not None:  # the latest of those that came together
                better(packed(best[1]))
            untold = False
            if counted and best is not None and enough > 0:  # the steps to its end, as sparrow shortens
                expected = min(steps, used + math.ceil(math.log(max(best[0] / enough, 1.0)) / SHRINK))
            if budget.tick(me if counted else None, used, expected) or (halt is not None and halt()):
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
    budget.spend(used if counted else 0, me)
    budget.runs.append((int(seed), len(members), used, cpu, began, time.perf_counter() - budget.start))
    if ended and worker.returncode != 0 and best is None:
        last = (problem.strip().splitlines() or ["no message"])[-1]
        raise NestingFailed(f"the nesting engine (sparrow) stopped with {last}")
    packing = None if best is None else packed(best[1])
    if complete and not clocked:  # what any later run of this job would find
        while len(PACKED) >= CACHED:
            PACKED.pop(next(iter(PACKED)))
        PACKED[key] = (packing, used)
    return packing


def valid(polygons: dict[int, shapely.Polygon], room: shapely.Polygon, spacing: float) -> list[int]:
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




def strips(shapes: Sequence[FloatArray], jobs: Sequence[dict], height: float, spacing: float,
           orientations: Sequence[float] | None, budget: Budget) -> list[Packing | None]:
    """Several :func:`strip` packings side by side, one thread (and worker process) each:
    ``jobs`` are their keyword arguments (``members``, ``steps``, ``seed`` and any others);
    their packings in the same order. Each is the job it would be alone (the same packing)."""
    results: list[Packing | None] = [None] * len(jobs)
    failures: list[BaseException] = []

    def run(k: int) -> None:
        try:
            results[k] = strip(shapes, height=height, spacing=spacing, orientations=orientations,
                               budget=budget, **jobs[k])
        except BaseException as exc:  # told in the caller's thread
            failures.append(exc)

    threads = [threading.Thread(target=run, args=(k,), daemon=True) for k in range(1, len(jobs))]
    for thread in threads:
        thread.start()
    run(0)
    for thread in threads:
        thread.join()
    if failures:
        raise failures[0]
    return results
