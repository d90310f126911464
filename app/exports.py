"""``torsal run --export ID.PORT=PATH``: write one output's data tree to a file.

``.json`` writes the tree as in ``--json`` results; ``.csv`` writes one row per item
(path, index, then the item's fields). Geometry formats arrive with the io nodes.
"""

from __future__ import annotations

import csv
import json
from pathlib import Path
from typing import Any

from engine.datatree import DataTree, format_path
from engine.types import summarize_value


class ExportError(ValueError):
    """An export that cannot be written (unknown format, missing output)."""


def export_tree(tree: DataTree, path: Path) -> None:
    suffix = path.suffix.lower()
    path.parent.mkdir(parents=True, exist_ok=True)
    if suffix == ".json":
        data = {format_path(p): [summarize_value(v) for v in items] for p, items in tree.items()}
        path.write_text(json.dumps(data, indent=2, sort_keys=True) + "\n", encoding="utf-8")
    elif suffix == ".csv":
        with path.open("w", newline="", encoding="utf-8") as stream:
            writer = csv.writer(stream)
            writer.writerow(["path", "index", "value"])
            for p, items in tree.items():
                for i, item in enumerate(items):
                    writer.writerow([format_path(p), i, *_cells(summarize_value(item))])
    else:
        raise ExportError(f"cannot export to {suffix or 'a file without extension'} (use .json or .csv)")


def _cells(value: Any) -> list[Any]:
    if isinstance(value, dict) and "xyz" in value:
        return list(value["xyz"])
    if isinstance(value, dict | list):
        return [json.dumps(value, sort_keys=True)]
    return [value]
