"""Data trees as spreadsheets (CSV) and as JSON, item by item.

CSV: a header ``path,index,value``, then one row per item: the branch path (``{0;1}``),
the item's index in its branch, then the item — a number, text or boolean as it is;
a point or vector as three cells x, y, z; anything else (a curve's summary, a domain)
as one cell of JSON. JSON: the tree as ``torsal run --json`` shows an output.
"""

from __future__ import annotations

import csv
import json
from pathlib import Path
from typing import Any

from torsal.engine.datatree import DataTree, format_path
from torsal.engine.types import summarize_value
from torsal.nodes.io.common import replacing, writable


def cells(value: Any) -> list[Any]:
    """An item's summary as CSV cells."""
    if isinstance(value, dict) and "xyz" in value:
        return list(value["xyz"])
    if isinstance(value, dict | list):
        return [json.dumps(value, sort_keys=True)]
    return [value]


def write_csv(tree: DataTree, path: Path) -> Path:
    """Write ``tree`` as CSV (see the module) and return the path."""
    writable(path)

    def write(temporary: Path) -> None:
        with temporary.open("w", newline="", encoding="utf-8") as stream:
            writer = csv.writer(stream)
            writer.writerow(["path", "index", "value"])
            for p, items in tree.items():
                for i, item in enumerate(items):
                    writer.writerow([format_path(p), i, *cells(summarize_value(item))])

    return replacing(path, write)


def write_json(tree: DataTree, path: Path) -> Path:
    """Write ``tree`` as JSON (paths to lists of item summaries) and return the path."""
    data = {format_path(p): [summarize_value(v) for v in items] for p, items in tree.items()}
    writable(path)
    text = json.dumps(data, indent=2, sort_keys=True) + "\n"
    return replacing(path, lambda temporary: temporary.write_text(text, encoding="utf-8"))
