"""io.ExportCSV: any data tree as a spreadsheet, in the format of ``--export ID.PORT=x.csv``."""

from __future__ import annotations

import csv
import json

from tests.support.io_helpers import rectangle
from tests.support.node_helpers import allowed, out, run, texts, tree
from torsal.engine.solver import ERROR, OK
from torsal.engine.values import Point
from torsal.nodes.io.data import ExportCSV


def test_csv_has_one_row_per_item_with_path_and_index(tmp_path):
    target = tmp_path / "areas.csv"
    data = tree({(0, 0): [0.5, 0.25], (0, 1): ["P-003"], (1, 0): [Point(1, 2, 3)]})
    result = run(ExportCSV(), Path="areas.csv", Data=data, Write=True, writes=allowed(tmp_path))
    assert result.state == OK, texts(result)
    assert out(result) == {(0,): [str(target)]}
    rows = list(csv.reader(target.open()))
    assert rows == [
        ["path", "index", "value"],
        ["{0;0}", "0", "0.5"], ["{0;0}", "1", "0.25"], ["{0;1}", "0", "P-003"],
        ["{1;0}", "0", "1.0", "2.0", "3.0"],
    ]


def test_geometry_is_written_as_its_key_figures(tmp_path):
    target = tmp_path / "panels.csv"
    run(ExportCSV(), Path="panels.csv", Data=tree({(0,): [rectangle(0, 0, 2, 1)]}), Write=True,
        writes=allowed(tmp_path))
    (_, row) = list(csv.reader(target.open()))
    summary = json.loads(row[2])
    assert summary["type"] == "Curve" and summary["length"] == 6.0 and summary["closed"] is True


def test_nothing_is_written_while_write_is_false_and_a_folder_is_an_error(tmp_path):
    result = run(ExportCSV(), Path="x.csv", Data=tree({(0,): [1.0]}), writes=allowed(tmp_path))
    assert result.state == OK and not (tmp_path / "x.csv").exists()
    (tmp_path / "sub").mkdir()
    result = run(ExportCSV(), Path="sub", Data=tree({(0,): [1.0]}), Write=True, writes=allowed(tmp_path))
    assert result.state == ERROR and "is a folder" in texts(result)[0]
