"""The worker process of :func:`torsal.nodes.geometry.nesting.nest`: one sparrow strip packing.

Reads one JSON job on stdin (``shapes`` as ``[id, [[x, y], ...]]``, ``height``,
``spacing`` or null, ``orientations`` or null, ``steps``, ``failures``, ``enough``,
``seconds``, ``seed``) and writes one JSON line ``[width, [[id, angle, x, y], ...]]``
for each shorter feasible packing sparrow reports, ``["step", steps]`` after each step
and finally ``["end", steps, on_the_clock, cpu]`` (``cpu``: the worker's CPU seconds), then exits.

The search is measured in *steps*, not seconds, so that a job gives the same packing
on any machine, however busy: a step is one attempt of sparrow's exploration to pack
the strip shorter (its reports ``ExplFeas`` and ``ExplInfeas``; sparrow's search is
seeded and runs on one thread, so these come in the same order every time). A failed
attempt counts :data:`FAILED` steps: it searches much longer than one that succeeds.
The worker stops when ``steps`` are spent (``steps`` 0: at sparrow's first packing,
before its search), after ``failures`` failed attempts, at the first packing no longer
than ``enough``, or when sparrow ends its exploration itself (ten failed attempts in a
row); only ``seconds``, a safety net, stops it on the clock (then ``on_the_clock`` is
true and the packing may differ from run to run). sparrow's compression phase, which
shrinks the strip over time, is given no time: its end would depend on the clock. Run
with ``python -m``; the parent ends it early when the user stops.
"""

from __future__ import annotations

import json
import math
import os
import sys
import threading
import time

#: How often sparrow's progress queue is drained (s).
POLL = 0.02
#: Steps a failed attempt counts (one that succeeds counts one).
FAILED = 20


def main() -> None:
    import spyrrow

    job = json.loads(sys.stdin.read())
    items = [
        spyrrow.Item(str(i), [tuple(p) for p in shape], demand=1, allowed_orientations=job["orientations"])
        for i, shape in job["shapes"]
    ]
    instance = spyrrow.StripPackingInstance("torsal", job["height"], items)
    seconds = max(1, math.ceil(job["seconds"]))
    config = spyrrow.StripPackingConfig(
        early_termination=True, total_computation_time=None, exploration_time=seconds, compression_time=0,
        min_items_separation=job["spacing"], seed=job["seed"], num_workers=int(job.get("workers", 1)),
    )
    progress = spyrrow.ProgressQueue()
    failure: list[BaseException] = []

    def solve() -> None:
        try:
            instance.solve(config, progress=progress)
        except BaseException as exc:  # a pyo3 panic is a BaseException: told to the parent on stderr
            failure.append(exc)

    started = time.perf_counter()
    solver = threading.Thread(target=solve, daemon=True)
    solver.start()
    steps, failed, first, best = 0, 0, True, math.inf
    enough, limit, failures = float(job["enough"]), int(job["steps"]), int(job["failures"])

    def finish(on_the_clock: bool) -> None:
        print(json.dumps(["end", steps, on_the_clock, time.process_time()]), flush=True)
        os._exit(0)  # sparrow cannot be interrupted: leave it running into the exit

    while True:
        alive = solver.is_alive()
        for kind, solution in progress.drain():
            if kind == spyrrow.ReportType.ExplImproving:
                continue
            if kind == spyrrow.ReportType.Final:
                finish(time.perf_counter() - started >= seconds)
            if kind == spyrrow.ReportType.ExplFeas and solution.width < best:
                best = solution.width
                placed = [[int(p.id), p.rotation, p.translation[0], p.translation[1]]
                          for p in solution.placed_items]
                print(json.dumps([solution.width, placed]), flush=True)
            if first:  # the first report is sparrow's starting packing, not an attempt
                first = False
                if best <= enough or limit <= 0:
                    finish(False)
                continue
            failed += kind == spyrrow.ReportType.ExplInfeas
            steps += FAILED if kind == spyrrow.ReportType.ExplInfeas else 1
            print(json.dumps(["step", steps]), flush=True)
            if best <= enough or steps >= limit or failed >= failures:
                finish(False)
        if not alive:
            if failure:  # sparrow refused the parts (tiny ones, say): no packing, the parent copes
                print(f"{type(failure[0]).__name__}: {failure[0]}", file=sys.stderr, flush=True)
            finish(time.perf_counter() - started >= seconds)
        solver.join(POLL)


if __name__ == "__main__":
    main()
