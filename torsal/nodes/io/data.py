"""Data for spreadsheets: ExportCSV."""

from __future__ import annotations

from typing import Any

from torsal.engine.datatree import DataTree
from torsal.engine.node import TREE, In, Node, Out
from torsal.engine.types import BOOLEAN, GENERIC, TEXT
from torsal.nodes.io.common import file_errors, may_write, write_target
from torsal.nodes.io.formats import tables


class ExportCSV(Node):
    """Write any data tree to a CSV file, one row per item, for a spreadsheet.

    The columns are path, index, value: the item's branch ({0;2}), its place in the
    branch, and the item itself — numbers and text as they are, a point or vector
    as three cells x, y, z, geometry as its key figures in JSON (a curve's length,
    a surface's area). Wire rulings' warp angles or panel areas in. The same format
    as ``torsal run --export ID.PORT=file.csv``. Nothing is written until Write is
    true and you have allowed the graph to write files; Path is relative to the graph's
    folder and must stay inside it. A file it replaces is kept as ``<name>.bak``.
    """

    type_id = "io.ExportCSV"
    nickname, aliases = "CSV", ("Write File", "spreadsheet", "excel")
    inputs = (
        In("Path", TEXT, "P", "The .csv file to write, relative to the graph's folder.", default=""),
        In("Data", GENERIC, "D", "The data tree to write.", access=TREE),
        In("Write", BOOLEAN, "W", "Set to true to write the file; while false nothing is written.",
           default=False),
    )
    outputs = (Out("Path", TEXT, "P", "The file written, as an absolute path (empty while Write is false)."),)

    def solve(self, path: Any, data: DataTree, write: Any) -> Any:
        if not write:
            self.remark("Write is false: nothing written")
            return None
        if not data.item_count:  # e.g. an upstream node refused: the file already there stays as it is
            self.warn("There is nothing to write: Data is empty, so the file (and its .bak) is left "
                      "as it was")
            return None
        with file_errors():
            target = write_target(self, path)
            if not may_write(self, [target]):
                return None
            return str(tables.write_csv(data, target))
