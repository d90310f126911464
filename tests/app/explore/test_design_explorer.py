"""``DIR/data.csv`` read as Design Explorer reads a folder (its loading code: ``index.html``'s
``analyzeInputData`` and ``makeUrl``, ``js/designExplorer.js``'s ``loadFromUrl``), column by
column: the file it asks a folder for, how it sorts columns by their name, how it finds a
picture, and that every axis cell is a number."""

from __future__ import annotations

import csv
import itertools
import math

import pytest
from matplotlib.image import imread

from tests.app.explore.test_sweep_images import torus  # noqa: F401 - the fixture
from tests.support.explore_graphs import formula_graph
from torsal.app.explore.design_explorer import DATA
from torsal.app.explore.executors import InlineExecutor
from torsal.app.explore.samplers import grid
from torsal.app.explore.study import open_study
from torsal.app.explore.sweep import RESULTS, run_sweep


def design_explorer_columns(header: list[str]) -> dict[str, list[str]]:
    """The columns sorted as Design Explorer's analyzeInputData sorts them (by the upper-cased
    name's start: IN:, OUT:, IMG, THREED; anything else is an axis of its own)."""
    kinds: dict[str, list[str]] = {"in": [], "out": [], "img": [], "threeD": [], "other": []}
    for key in header:
        name = key.strip().upper()
        kind = next((k for k, start in (("in", "IN:"), ("out", "OUT:"), ("img", "IMG"), ("threeD", "THREED"))
                     if name.startswith(start)), "other")
        kinds[kind].append(key)
    return kinds


def read(path):
    with path.open(newline="", encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


def sweep(path, out, vary, collect, **options):
    study = open_study(path, vary, collect, steps=True)
    return run_sweep(study, grid(study.variables), InlineExecutor(), out, **options)


def test_data_csv_has_inputs_and_outputs_and_no_other_axis(tmp_path):
    plane = formula_graph(tmp_path / "plane.graph", {"x": (0, 1, 0.5), "y": (0, 2, 1)}, {"f": "2*x + 3*y"})
    sweep(plane, tmp_path / "out", ["x=0:1:3", "y=0:2:2"], ["f.Result"])
    rows = read(tmp_path / "out" / DATA)  # the file Design Explorer loads from a folder
    kinds = design_explorer_columns(list(rows[0]))
    assert kinds["in"] == ["in:x", "in:y"] and kinds["out"] == ["out:f.Result"]
    assert kinds["other"] == [] and kinds["img"] == [] and kinds["threeD"] == []  # no status axis
    expected = list(itertools.product([0.0, 0.5, 1.0], [0.0, 2.0]))
    assert [(float(r["in:x"]), float(r["in:y"])) for r in rows] == expected
    assert [float(r["out:f.Result"]) for r in rows] == [2 * x + 3 * y for x, y in expected]


def test_every_axis_cell_is_a_number_so_a_variant_in_error_is_left_out(tmp_path):
    # sqrt of a negative number has no value: x = 0 and 0.25 give none, 0.75 and 1 do
    graph = formula_graph(tmp_path / "g.graph", {"x": (0, 1, 0.5)}, {"f": "sqrt(x - 0.5)"})
    sweep(graph, tmp_path / "out", ["x=0:1:5"], ["f.Result"])
    table = read(tmp_path / "out" / RESULTS)
    data = read(tmp_path / "out" / DATA)
    solved = [r for r in table if r["status"] == "ok" and r["out:f.Result"] != ""]
    assert len(table) == 5 and 0 < len(solved) < 5
    assert [r["in:x"] for r in data] == [r["in:x"] for r in solved]
    for row in data:
        for key, value in row.items():
            assert math.isfinite(float(value)), (key, value)  # Design Explorer reads an empty cell as 0
        assert float(row["out:f.Result"]) == pytest.approx(math.sqrt(float(row["in:x"]) - 0.5), abs=1e-12)


def test_pictures_are_named_by_file_beside_data_csv(torus, tmp_path):  # noqa: F811 - the fixture
    sweep(torus, tmp_path / "out", ["r=0.2:0.8:3"], ["torus.Torus:count"], images=True)
    rows = read(tmp_path / "out" / DATA)
    kinds = design_explorer_columns(list(rows[0]))
    assert kinds["img"] == ["img"] and kinds["other"] == []
    for index, row in enumerate(rows):
        # makeUrl: a cloud folder's pictures are found by file name, a server folder's by its
        # URL followed by the cell: a bare name of a picture in the same folder works for both
        assert row["img"] == f"{index:05d}.png" and "/" not in row["img"]
        assert imread(tmp_path / "out" / row["img"]).shape[2] in (3, 4)
