"""The worker process of :func:`nodes.geometry.nesting.nest`: one sparrow strip packing.

Reads one JSON job on stdin (``shapes`` as ``[id, [[x, y], ...]]``, ``height``,
``spacing`` or null, ``orientations`` or null, ``seconds``, ``seed``) and writes one JSON
line ``[width, [[id, angle, x, y], ...]]`` for each shorter feasible packing sparrow
reports, the last one being its final packing. Run with ``python -m``; the parent ends
it when it has what it needs or the user stops.
"""

from __future__ import annotations

import json
import math
import sys
import threading

#: How often sparrow's progress queue is drained (s).
POLL = 0.05


def main() -> None:
    import spyrrow

    job = json.loads(sys.stdin.read())
    items = [
        spyrrow.Item(str(i), [tuple(p) for p in shape], demand=1, allowed_orientations=job["orientations"])
        for i, shape in job["shapes"]
    ]
    instance = spyrrow.StripPackingInstance("torsal", job["height"], items)
    config = spyrrow.StripPackingConfig(
        early_termination=True, total_computation_time=job["seconds"],
        min_items_separation=job["spacing"], seed=job["seed"], num_workers=1,
    )
    progress = spyrrow.ProgressQueue()
    done: list[object] = []
    worker = threading.Thread(target=lambda: done.append(instance.solve(config, progress=progress)))
    worker.start()
    feasible = (spyrrow.ReportType.ExplFeas, spyrrow.ReportType.CmprFeas, spyrrow.ReportType.Final)
    best = math.inf

    def send(solutions: list) -> None:  # type: ignore[type-arg]
        nonlocal best
        for solution in solutions:
            if solution.width < best:
                best = solution.width
                placed = [[int(p.id), p.rotation, p.translation[0], p.translation[1]]
                          for p in solution.placed_items]
                print(json.dumps([solution.width, placed]), flush=True)

    while worker.is_alive():
        worker.join(POLL)
        send([solution for kind, solution in progress.drain() if kind in feasible])
    send([solution for kind, solution in progress.drain() if kind in feasible] + done)


if __name__ == "__main__":
    main()
