"""``torsal sweep``: solve many variants and write them as a Design Explorer table.

``DIR/results.csv`` has one row per variant, in the sampler's order: an ``in:ID`` column
per varied slider, an ``out:NODE.OUTPUT`` column per collected output, with ``--images``
an ``img:perspective`` column (the variant's picture, ``images/NNNNN.png`` beside the table:
see :mod:`torsal.app.explore.images`), and a ``status`` column (``ok``, or the message of the node
in error). The solved variants are also kept
in ``DIR/cache.jsonl``: a re-run takes them from there, and a killed sweep resumes.
"""

from __future__ import annotations

import csv
import os
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from torsal.app.explore.cache import ResultCache, graph_digest, variant_key
from torsal.app.explore.evaluate import Job, Outcome
from torsal.app.explore.executors import WORKER_FAILED, Executor
from torsal.app.explore.progress import Progress
from torsal.app.explore.study import Study

RESULTS = "results.csv"
CACHE = "cache.jsonl"
IMAGES = "images"
#: The header of the pictures' column (Design Explorer shows ``img:`` columns as pictures).
IMAGE_COLUMN = "img:perspective"


@dataclass
class SweepResult:
    """The finished sweep: one outcome per variant, in order, and how many were solved."""

    outcomes: list[Outcome]
    solved: int
    cached: int
    csv_path: Path | None = None

    @property
    def failed(self) -> int:
        return sum(1 for o in self.outcomes if o.failed)


def run_sweep(
    study: Study,
    variants: list[dict[str, Any]],
    executor: Executor,
    out: Path | None = None,
    *,
    allow_writes: bool = False,
    images: bool = False,
    progress: Progress | None = None,
    on_outcome: Callable[[int, Outcome], None] | None = None,
) -> SweepResult:
    """Solve every variant not in ``out``'s cache, then write ``out/results.csv`` (with
    ``images``, each variant's picture in ``out/images`` and its column in the table)."""
    job = Job(tuple(study.targets), allow_writes, str((out / "variants").resolve()) if out else None,
              str((out / IMAGES).resolve()) if out is not None and images else None,
              str(Path(study.path).resolve().parent))
    cache = ResultCache(out / CACHE) if out is not None else None
    digest = graph_digest(study.text)
    keys = [variant_key(digest, values, job) for values in variants]
    outcomes: list[Outcome | None] = [None] * len(variants)
    pending = []
    for index, values in enumerate(variants):
        hit = cache.get(keys[index]) if cache is not None else None
        if hit is not None:
            outcomes[index] = Outcome.from_json(hit)
            if progress is not None:
                progress.advance(cached=True)
        else:
            pending.append((index, values))
    solved = 0
    try:
        for index, data in executor.run(study.text, job, pending):
            outcome = Outcome.from_json(data)
            outcomes[index] = outcome
            solved += 1
            if cache is not None and not outcome.status.startswith(WORKER_FAILED):
                cache.put(keys[index], data)
            if progress is not None:
                progress.advance(note="" if not outcome.failed else f"variant {index + 1} in error")
            if on_outcome is not None:
                on_outcome(index, outcome)
    finally:
        if cache is not None:
            cache.close()
    result = SweepResult([o for o in outcomes if o is not None], solved, len(variants) - len(pending))
    if out is not None:
        result.csv_path = write_table(out / RESULTS, study, result.outcomes, images=images)
    return result


def cell(value: Any) -> str:
    """A table cell: numbers exactly (``repr``), nothing for a missing value (never 0)."""
    if value is None:
        return ""
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, float):
        return repr(value)
    return str(value)


def table_rows(study: Study, outcomes: list[Outcome], images: bool = False) -> list[list[str]]:
    header = [v.column for v in study.variables] + [t.column for t in study.targets]
    header += [IMAGE_COLUMN] if images else []
    rows = [[*header, "status"]]
    for outcome in outcomes:
        picture = [f"{IMAGES}/{outcome.image}" if outcome.image else ""] if images else []
        rows.append(
            [cell(outcome.values.get(v.node_id)) for v in study.variables]
            + [cell(outcome.outputs.get(t.name)) for t in study.targets]
            + picture
            + [outcome.status]
        )
    return rows


def write_table(path: Path, study: Study, outcomes: list[Outcome], images: bool = False) -> Path:
    """Write the Design Explorer CSV (atomically: a reader never sees half a table)."""
    temporary = path.with_name(path.name + ".part")
    with temporary.open("w", encoding="utf-8", newline="") as handle:
        csv.writer(handle).writerows(table_rows(study, outcomes, images))
    os.replace(temporary, path)
    return path
