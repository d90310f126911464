"""``torsal sweep``: solve many variants and write them as tables.

``DIR/results.csv`` has one row per variant, in the sampler's order: an ``in:ID`` column
per varied slider, an ``out:NODE.OUTPUT`` column per collected output, with ``--images``
an ``img:perspective`` column (the variant's picture, ``NNNNN.png`` beside the table:
see :mod:`torsal.app.explore.images`), and a ``status`` column (``ok``, or the message of the node
in error). ``DIR/data.csv`` is the same for Design Explorer: the designs that solved, without
the status (:mod:`torsal.app.explore.design_explorer`); with ``--images`` the pictures lie
beside both tables. The solved variants are also kept in ``DIR/cache.jsonl``: a re-run takes
them from there, and a killed sweep resumes (only lines this user's Torsal signed for this
graph are used: :mod:`torsal.app.explore.cache`). Every file goes through the one write path
(:mod:`torsal.engine.write_path`): ``DIR`` is resolved once and nothing in it is written
through a link. Text cells that a spreadsheet would run as a formula are escaped (:func:`cell`).
"""

from __future__ import annotations

import csv
import io
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from torsal.app.explore.cache import ResultCache, graph_digest, variant_key
from torsal.app.explore.design_explorer import write_data
from torsal.app.explore.evaluate import Job, Outcome
from torsal.app.explore.executors import WORKER_FAILED, Executor
from torsal.app.explore.progress import Progress
from torsal.app.explore.study import Study
from torsal.engine.write_path import OutFolder

RESULTS = "results.csv"
CACHE = "cache.jsonl"
#: The header of the pictures' column (Design Explorer shows ``img:`` columns as pictures).
IMAGE_COLUMN = "img:perspective"


@dataclass
class SweepResult:
    """The finished sweep: one outcome per variant, in order, and how many were solved."""

    outcomes: list[Outcome]
    solved: int
    cached: int
    csv_path: Path | None = None
    notes: list[str] = field(default_factory=list)  #: what the command prints as notes

    @property
    def failed(self) -> int:
        return sum(1 for o in self.outcomes if o.failed)


def run_sweep(
    study: Study,
    variants: list[dict[str, Any]],
    executor: Executor,
    out: Path | OutFolder | None = None,
    *,
    allow_writes: bool = False,
    images: bool = False,
    progress: Progress | None = None,
    on_outcome: Callable[[int, Outcome], None] | None = None,
) -> SweepResult:
    """Solve every variant not in ``out``'s cache, then write ``out/results.csv`` and
    ``out/data.csv`` (with ``images``, each variant's picture beside them and its column in
    the tables: Design Explorer finds pictures beside its ``data.csv``)."""
    folder = out if isinstance(out, OutFolder) or out is None else OutFolder.resolve(out)
    job = Job(tuple(study.targets), allow_writes, str(folder / "variants") if folder else None,
              str(folder.path) if folder is not None and images else None,
              str(Path(study.path).resolve().parent))
    digest = graph_digest(study.text)
    cache = ResultCache(folder, CACHE, digest) if folder is not None else None
    notes = []
    if cache is not None and cache.ignored:
        notes.append(f"{cache.ignored} line(s) of {CACHE} were not signed by your Torsal for this graph "
                     "and version: ignored, those variants are solved again")
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
    result = SweepResult([o for o in outcomes if o is not None], solved, len(variants) - len(pending),
                         notes=notes)
    if folder is not None:
        result.csv_path = write_table(folder, RESULTS, study, result.outcomes, images=images)
        write_data(folder, study, result.outcomes, cell, images=images)
    return result


#: What a spreadsheet takes for the start of a formula (OWASP's list for CSV injection).
FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")


def cell(value: Any) -> str:
    """A table cell: numbers exactly (``repr``), nothing for a missing value (never 0);
    text that starts like a formula (``=``, ``+``, ``-``, ``@``, tab, CR) gets a leading
    ``'`` as OWASP recommends, so a spreadsheet shows it rather than running it."""
    if value is None:
        return ""
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, int):
        return str(value)
    return escaped(str(value))


def escaped(text: str) -> str:
    """``text`` made safe for a spreadsheet cell (see :func:`cell`)."""
    return "'" + text if text.startswith(FORMULA_STARTS) else text


def table_rows(study: Study, outcomes: list[Outcome], images: bool = False) -> list[list[str]]:
    header = [v.column for v in study.variables] + [t.column for t in study.targets]
    header += [IMAGE_COLUMN] if images else []
    rows = [[*header, "status"]]
    for outcome in outcomes:
        picture = [outcome.image or ""] if images else []
        rows.append(
            [cell(outcome.values.get(v.node_id)) for v in study.variables]
            + [cell(outcome.outputs.get(t.name)) for t in study.targets]
            + picture
            + [escaped(outcome.status)]
        )
    return rows


def write_table(out: OutFolder, name: str, study: Study, outcomes: list[Outcome],
                images: bool = False) -> Path:
    """Write the Design Explorer CSV (atomically: a reader never sees half a table)."""
    text = io.StringIO(newline="")
    csv.writer(text).writerows(table_rows(study, outcomes, images))
    return out.write(name, text.getvalue())
