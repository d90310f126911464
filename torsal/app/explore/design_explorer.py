"""``DIR/data.csv``: a sweep as Design Explorer (Thornton Tomasetti's CORE studio) loads it.

What Design Explorer reads, from its loading code (``index.html``: ``analyzeInputData``,
``makeUrl``; ``js/designExplorer.js``: ``loadFromUrl``, ``prepareGFolder``):

- given a folder (a web server's folder URL, a shared Google Drive or OneDrive folder) it
  loads the file called ``data.csv`` in it;
- a column whose name starts with ``in:`` is an input (a slider and an axis), ``out:`` an
  output (an axis and the radar chart), ``img`` a picture, ``threeD`` a 3D model; **any
  other column becomes an axis too** — so Torsal's ``status`` stays out of this file;
- a picture's cell that is not a full URL is looked up by *file name* among the files of
  the folder (Google Drive, OneDrive), or appended to the folder's URL (a web server): a
  bare file name of a picture beside ``data.csv`` works with all three;
- every cell of an axis is read as a number: an empty cell would be drawn as 0.

So ``data.csv`` holds the designs that solved — every varied value and every collected output
a number, status ``ok`` — with the ``in:``/``out:`` columns of ``results.csv`` and, with
``--images``, an ``img`` column naming each picture (``NNNNN.png``, beside ``data.csv``).
Variants in error or without a value stay in ``results.csv`` only, which keeps every variant
with its status.
"""

from __future__ import annotations

import csv
import io
from collections.abc import Callable
from pathlib import Path
from typing import Any

from torsal.app.explore.evaluate import Outcome
from torsal.app.explore.study import Study
from torsal.engine.write_path import OutFolder

DATA = "data.csv"
#: Design Explorer's picture column.
IMAGE = "img"


def data_rows(study: Study, outcomes: list[Outcome], cell: Callable[[Any], str], images: bool = False
              ) -> list[list[str]]:
    """The header and the rows of the designs that solved, each value written by ``cell`` (the
    sweep's own cell format, as in ``results.csv``)."""
    header = [v.column for v in study.variables] + [t.column for t in study.targets]
    rows = [header + ([IMAGE] if images else [])]
    for outcome in outcomes:
        values = [outcome.values.get(v.node_id) for v in study.variables]
        outputs = [outcome.outputs.get(t.name) for t in study.targets]
        if outcome.failed or any(v is None for v in (*values, *outputs)):
            continue
        picture = [outcome.image or ""] if images else []
        rows.append([cell(v) for v in (*values, *outputs)] + picture)
    return rows


def write_data(folder: OutFolder, study: Study, outcomes: list[Outcome], cell: Callable[[Any], str],
               images: bool = False) -> Path:
    """Write Design Explorer's ``data.csv`` in ``folder`` (atomically, through the one write path)."""
    text = io.StringIO(newline="")
    csv.writer(text).writerows(data_rows(study, outcomes, cell, images))
    return folder.write(DATA, text.getvalue())
