"""Data for spreadsheets: ExportCSV."""

from __future__ import annotations

from typing import Any

from engine.datatree import DataTree
from engine.node import TREE, In, Node, Out
from engine.types import BOOLEAN, GENERIC, TEXT
from nodes.io import tables
from nodes.io.common import file_errors, resolve


class ExportCSV(Node):
    """Write any data tree to a CSV file, one row per item, for a spreadsheet.

    The columns are path, index, value: the item's branch ({0;2}), its place in the
    branch, and the item itself — numbers and text as they are, a point or vector
    as three cells x, y, z, geometry as its key figures in JSON (a curve's length,
    a surface's area). Wire rulings' warp angles or panel areas in. The same format
    as ``torsal run --export ID.PORT=file.csv``. Nothing is written until Write is
    true; a relative Path starts from the working directory.
    """

    type_id = "io.ExportCSV"
    inputs = (
        In("Path", TEXT, "P", "The .csv file to write.", default=""),
        In("Data", GENERIC, "D", "The data tree to write.", access=TREE),
        In("Write", BOOLEAN, "W", "Set to true to write the file; while false nothing is written.",
           default=False),
    )
    outputs = (Out("Path", TEXT, "P", "The file written, as an absolute path (empty while Write is false)."),)

    def solve(self, path: Any, data: DataTree, write: Any) -> Any:
        if not write:
            self.remark("Write is false: nothing written")
            return None
        with file_errors():
            return str(tables.write_csv(data, resolve(path)))
