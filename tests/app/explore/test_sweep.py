"""``torsal sweep``: the table, error variants, the cache and resuming (solved in this process)."""

from __future__ import annotations

import csv
import itertools

import numpy as np
import pytest

from tests.support.explore_graphs import formula_graph
from torsal.app.explore.executors import InlineExecutor
from torsal.app.explore.samplers import grid, sample
from torsal.app.explore.study import open_study
from torsal.app.explore.sweep import CACHE, RESULTS, run_sweep
from torsal.engine.graph import Graph
from torsal.engine.graphfile import write_graph
from torsal.engine.solver import Solver
from torsal.nodes.lists.trees import Partition
from torsal.nodes.maths.expression import Expression
from torsal.nodes.params.sliders import IntegerSlider


@pytest.fixture
def plane(tmp_path):
    """f = 2x + 3y on x in 0 … 1, y in 0 … 2."""
    return formula_graph(tmp_path / "plane.graph", {"x": (0, 1, 0.5), "y": (0, 2, 1)}, {"f": "2*x + 3*y"})


def read_table(path):
    with path.open(newline="", encoding="utf-8") as handle:
        return list(csv.reader(handle))


def test_the_table_has_one_row_per_grid_point_in_order(plane, tmp_path):
    study = open_study(plane, ["x=0:1:3", "y=0:2:4"], ["f.Result"], steps=True)
    run_sweep(study, grid(study.variables), InlineExecutor(), tmp_path / "out")
    rows = read_table(tmp_path / "out" / RESULTS)
    assert rows[0] == ["in:x", "in:y", "out:f.Result", "status"]
    expected = list(itertools.product([0.0, 0.5, 1.0], [0.0, 2 / 3, 4 / 3, 2.0]))
    assert len(rows) - 1 == len(expected) == 12
    for row, (x, y) in zip(rows[1:], expected, strict=True):
        assert float(row[0]) == pytest.approx(x) and float(row[1]) == pytest.approx(y, abs=1e-8)
        assert float(row[2]) == pytest.approx(2 * float(row[0]) + 3 * float(row[1]), rel=1e-12)
        assert row[3] == "ok"


def test_a_variant_in_error_is_recorded_and_the_sweep_goes_on(tmp_path):
    graph = Graph()
    graph.add_node(IntegerSlider({"min": 0, "max": 3, "value": 1}), "n")
    graph.add_node(Expression({"expression": "x / x"}), "size")  # NaN at n = 0: no whole-number Size
    graph.add_node(Partition(), "part")
    graph.connect("n", "Value", "size", "x")
    graph.connect("n", "Value", "part", "List")
    graph.connect("size", "Result", "part", "Size")
    write_graph(graph, tmp_path / "chunks.graph")
    study = open_study(tmp_path / "chunks.graph", ["n=0:3:4"], ["part.Chunks:count"], steps=True)
    result = run_sweep(study, grid(study.variables), InlineExecutor(), tmp_path / "out")
    rows = read_table(tmp_path / "out" / RESULTS)
    assert [r[0] for r in rows[1:]] == ["0", "1", "2", "3"]
    assert rows[1][1] == ""  # no value, not the count 0 of an empty output (the list [n] has 1 item)
    assert rows[1][2] == "error: Partition [part]: Size is not a number (NaN)"
    assert [r[1] for r in rows[2:]] == ["1", "1", "1"] and [r[2] for r in rows[2:]] == ["ok", "ok", "ok"]
    assert result.failed == 1


def test_a_rerun_takes_every_variant_from_the_cache_and_solves_nothing(plane, tmp_path, monkeypatch):
    study = open_study(plane, ["x=0:1:3", "y=0:2:3"], ["f.Result"], steps=True)
    first = run_sweep(study, grid(study.variables), InlineExecutor(), tmp_path / "out")
    table = (tmp_path / "out" / RESULTS).read_text()
    solves = []
    original = Solver.solve
    monkeypatch.setattr(Solver, "solve", lambda self, *a, **k: solves.append(1) or original(self, *a, **k))
    executor = InlineExecutor()
    again = run_sweep(study, grid(study.variables), executor, tmp_path / "out")
    assert (first.solved, again.solved, again.cached) == (9, 0, 9)
    assert solves == [] and executor.solves == 0
    assert (tmp_path / "out" / RESULTS).read_text() == table


def test_a_killed_sweep_resumes_where_it_stopped(plane, tmp_path):
    study = open_study(plane, ["x=0:1:4", "y=0:2:3"], ["f.Result"], steps=True)
    variants = grid(study.variables)

    def kill(index, outcome):
        if index == 4:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_sweep(study, variants, InlineExecutor(), tmp_path / "out", on_outcome=kill)
    with (tmp_path / "out" / CACHE).open("a") as handle:  # the kill tore the last line
        handle.write('{"key": "ab')
    resumed = run_sweep(study, variants, InlineExecutor(), tmp_path / "out")
    assert (resumed.cached, resumed.solved) == (5, 7)
    run_sweep(study, variants, InlineExecutor(), tmp_path / "fresh")
    assert (tmp_path / "out" / RESULTS).read_text() == (tmp_path / "fresh" / RESULTS).read_text()


def test_lhs_puts_one_sample_in_each_of_n_bins_of_every_slider(plane):
    study = open_study(plane, ["x=0:1", "y=0:2"], ["f.Result"], steps=False)
    variants = sample(study.variables, "lhs", 10, seed=4)
    for name, high in (("x", 1.0), ("y", 2.0)):
        bins = np.floor(np.array([v[name] for v in variants]) / high * 10).astype(int)
        assert sorted(np.minimum(bins, 9)) == list(range(10))


def test_the_same_seed_draws_the_same_sobol_samples(plane):
    study = open_study(plane, ["x=0:1", "y=0:2"], ["f.Result"], steps=False)
    assert sample(study.variables, "sobol", 8, seed=1) == sample(study.variables, "sobol", 8, seed=1)
    assert sample(study.variables, "sobol", 8, seed=1) != sample(study.variables, "sobol", 8, seed=2)


def export_graph(folder):
    from torsal.nodes.io.data import ExportCSV

    graph = Graph()
    graph.add_node(IntegerSlider({"min": 0, "max": 3, "value": 1}), "n")
    graph.add_node(ExportCSV(), "export")
    graph.connect("n", "Value", "export", "Data")
    graph.set_input_value("export", "Path", "n.csv")
    graph.set_input_value("export", "Write", True)
    write_graph(graph, folder / "export.graph")
    return folder / "export.graph"


def test_a_swept_graph_writes_no_file_without_allow_writes(tmp_path):
    path = export_graph(tmp_path)
    study = open_study(path, ["n=0:1:2"], ["n.Value"], steps=True)
    run_sweep(study, grid(study.variables), InlineExecutor(), tmp_path / "out")
    assert sorted(p.name for p in tmp_path.rglob("*.csv")) == ["data.csv", RESULTS]


def test_with_allow_writes_each_variant_writes_into_its_own_folder(tmp_path):
    path = export_graph(tmp_path)
    study = open_study(path, ["n=0:1:2"], ["n.Value"], steps=True)
    run_sweep(study, grid(study.variables), InlineExecutor(), tmp_path / "out", allow_writes=True)
    written = sorted(p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("n.csv"))
    assert written == ["out/variants/00000/n.csv", "out/variants/00001/n.csv"]
