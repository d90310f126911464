"""The optimiser's tables: every evaluation, and the Pareto front (Design Explorer CSV)."""

from __future__ import annotations

import csv
import io
from pathlib import Path

from torsal.app.explore.optimise import Evaluated, OptimiseResult
from torsal.app.explore.study import Study
from torsal.app.explore.sweep import cell, escaped
from torsal.engine.write_path import OutFolder


def _write(out: OutFolder, name: str, study: Study, rows: list[Evaluated]) -> Path:
    """One table, atomically and never through a link (the one write path); text cells
    escaped as a spreadsheet needs (:func:`torsal.app.explore.sweep.cell`)."""
    header = [v.column for v in study.variables] + [t.column for t in study.targets] + ["status"]
    handle = io.StringIO(newline="")
    writer = csv.writer(handle)
    writer.writerow(header)
    for row in rows:
        writer.writerow(
            [cell(row.values.get(v.node_id)) for v in study.variables]
            + [cell(row.outcome.outputs.get(t.name)) for t in study.targets]
            + [escaped(row.outcome.status)]
        )
    return out.write(name, handle.getvalue())


def write_evaluations(out: OutFolder, name: str, study: Study, result: OptimiseResult) -> Path:
    """Every distinct variant the optimiser solved, in the order it asked for them."""
    seen, rows = set(), []
    for evaluated in result.evaluated:
        if id(evaluated) not in seen:
            seen.add(id(evaluated))
            rows.append(evaluated)
    return _write(out, name, study, rows)


def write_front(out: OutFolder, name: str, study: Study, result: OptimiseResult) -> Path:
    """The Pareto front, sorted by the first objective."""
    return _write(out, name, study, result.front)
