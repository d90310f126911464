"""The optimiser's tables: every evaluation, and the Pareto front (Design Explorer CSV)."""

from __future__ import annotations

import csv
import os
from pathlib import Path

from torsal.app.explore.optimise import Evaluated, OptimiseResult
from torsal.app.explore.study import Study
from torsal.app.explore.sweep import cell


def _write(path: Path, study: Study, rows: list[Evaluated]) -> Path:
    header = [v.column for v in study.variables] + [t.column for t in study.targets] + ["status"]
    temporary = path.with_name(path.name + ".part")
    with temporary.open("w", encoding="utf-8", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(header)
        for row in rows:
            writer.writerow(
                [cell(row.values.get(v.node_id)) for v in study.variables]
                + [cell(row.outcome.outputs.get(t.name)) for t in study.targets]
                + [row.outcome.status]
            )
    os.replace(temporary, path)
    return path


def write_evaluations(path: Path, study: Study, result: OptimiseResult) -> Path:
    """Every distinct variant the optimiser solved, in the order it asked for them."""
    seen, rows = set(), []
    for evaluated in result.evaluated:
        if id(evaluated) not in seen:
            seen.add(id(evaluated))
            rows.append(evaluated)
    return _write(path, study, rows)


def write_front(path: Path, study: Study, result: OptimiseResult) -> Path:
    """The Pareto front, sorted by the first objective."""
    return _write(path, study, result.front)
