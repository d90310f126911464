"""A graph writes files only with the user's consent, and only inside its own folder.

Each hostile graph here is a real ``.graph`` file solved by a real ``torsal run``
subprocess, as a user who downloaded it would: a Panel's text is the payload, an
``io.ExportCSV`` with Write = true aims it somewhere it must never land.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from torsal.engine.graph import Graph
from torsal.engine.graphfile import write_graph
from torsal.engine.writes import WriteAccess, WriteRefused
from torsal.nodes.io.data import ExportCSV
from torsal.nodes.params.panel import Panel

PAYLOAD = "echo pwned"


def hostile_graph(folder: Path, target: str, name: str = "hostile.graph") -> Path:
    """A graph that writes a Panel's text through ExportCSV to ``target``."""
    graph = Graph()
    graph.add_node(Panel({"text": PAYLOAD}), "payload")
    graph.add_node(ExportCSV(), "csv")
    graph.connect("payload", "Output", "csv", "Data")
    graph.set_input_value("csv", "Path", target)
    graph.set_input_value("csv", "Write", True)
    path = folder / name
    write_graph(graph, path)
    return path


def torsal(*args: str | Path, home: Path) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "HOME": str(home)}
    return subprocess.run(
        [sys.executable, "-m", "torsal.app.cli", *map(str, args)], capture_output=True, text=True, env=env,
        cwd=Path(__file__).resolve().parents[2], timeout=120,
    )


def run_json(graph: Path, *flags: str, home: Path) -> dict:
    done = torsal("run", graph, "--json", *flags, home=home)
    assert "Traceback" not in done.stderr, done.stderr
    return json.loads(done.stdout)


def csv_messages(report: dict) -> list[str]:
    return [m["text"] for m in report["nodes"]["csv"]["messages"]]


@pytest.fixture
def site(tmp_path):
    """A user's home, the folder a downloaded graph sits in, and a folder beside it."""
    home, project, outside = tmp_path / "home", tmp_path / "home" / "project", tmp_path / "outside"
    for folder in (home, project, outside):
        folder.mkdir(parents=True, exist_ok=True)
    (home / ".bashrc").write_text("# the user's own start-up file\n")
    return home, project, outside


def files_under(folder: Path) -> dict[str, bytes]:
    return {str(p.relative_to(folder)): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


@pytest.mark.parametrize("flags", [(), ("--allow-writes",)], ids=["plain run", "--allow-writes"])
@pytest.mark.parametrize("kind", ["home", "absolute", "dotdot", "graph", "symlink"])
def test_a_hostile_graph_writes_nothing_outside_its_folder_nor_a_graph(site, kind, flags):
    home, project, outside = site
    (project / "link").symlink_to(outside, target_is_directory=True)
    target = {
        "home": "~/.bashrc",
        "absolute": str(outside / "dropped.csv"),
        "dotdot": "../../outside/dropped.csv",
        "graph": "hostile.graph",
        "symlink": "link/dropped.csv",
    }[kind]
    graph = hostile_graph(project, target)
    before = {folder: files_under(folder) for folder in (home, outside)}

    report = run_json(graph, *flags, home=home)

    assert {folder: files_under(folder) for folder in (home, outside)} == before
    assert report["nodes"]["csv"]["state"] == "error"
    assert any("Path" in text and repr(target) in text for text in csv_messages(report))


def test_without_consent_a_run_writes_nothing_and_says_how_to_allow_it(site):
    home, project, _ = site
    graph = hostile_graph(project, "out/areas.csv")
    report = run_json(graph, home=home)
    assert not (project / "out").exists()
    assert report["nodes"]["csv"]["state"] == "warning"
    (text,) = csv_messages(report)
    assert "out/areas.csv" in text and "--allow-writes" in text


def test_allow_writes_writes_inside_the_graphs_folder_wherever_the_run_starts(site):
    home, project, _ = site
    graph = hostile_graph(project, "out/areas.csv")
    report = run_json(graph, "--allow-writes", home=home)  # the run starts in the repository
    assert report["nodes"]["csv"]["state"] == "ok"
    assert PAYLOAD in (project / "out" / "areas.csv").read_text()


def test_with_out_the_files_go_into_that_folder(site, tmp_path):
    home, project, _ = site
    graph = hostile_graph(project, "areas.csv")
    build = tmp_path / "build"
    run_json(graph, "--allow-writes", "--out", str(build), home=home)
    assert PAYLOAD in (build / "areas.csv").read_text()
    assert (build / "results.json").exists()
    assert not (project / "areas.csv").exists()


def test_a_replaced_file_keeps_a_backup(site):
    home, project, _ = site
    (project / "areas.csv").write_text("the old table\n")
    graph = hostile_graph(project, "areas.csv")
    run_json(graph, "--allow-writes", home=home)
    assert (project / "areas.csv.bak").read_text() == "the old table\n"
    assert PAYLOAD in (project / "areas.csv").read_text()
    assert not list(project.glob(".*tmp*")), "no temporary file is left behind"


def test_an_unsaved_graph_has_no_folder_and_writes_nothing():
    files = WriteAccess(None, allowed=True).for_node("csv")
    with pytest.raises(WriteRefused, match="save it first"):
        files.target("areas.csv")


@pytest.mark.parametrize("name", ["C:\\Users\\me\\x.csv", "\\\\server\\share\\x.csv", "a\0b.csv", "", "  "])
def test_windows_absolute_paths_nul_and_empty_names_are_refused(tmp_path, name):
    with pytest.raises(WriteRefused):
        WriteAccess(tmp_path, allowed=True).for_node("csv").target(name)


def test_a_dotdot_that_stays_inside_the_folder_is_fine(tmp_path):
    files = WriteAccess(tmp_path, allowed=True).for_node("csv")
    assert files.target("out/../areas.csv") == Path(os.path.realpath(tmp_path)) / "areas.csv"


def test_requests_wait_for_consent_with_their_node_and_paths(tmp_path):
    access = WriteAccess(tmp_path)
    files = access.for_node("cut")
    target = files.target("roof.dxf")
    assert files.permit([target]) is False
    (request,) = access.pending()
    assert (request.node_id, request.paths) == ("cut", (target,))
    access.allowed = True
    assert files.permit([target]) is True
    assert access.pending() == []


def plot_graph(folder: Path, file: str) -> Path:
    from torsal.nodes.display.plot import Plot

    graph = Graph()
    graph.add_node(Panel({"text": "1\n3\n2"}), "values")
    graph.add_node(Plot(), "plot")
    graph.connect("values", "Output", "plot", "Values")
    graph.set_input_value("plot", "File", file)
    path = folder / "plot.graph"
    write_graph(graph, path)
    return path


@pytest.mark.parametrize("file", ["~/.bashrc.png", "../../outside/chart.png"])
def test_a_plots_file_obeys_the_same_rules(site, file):
    home, project, outside = site
    graph = plot_graph(project, file)
    before = {folder: files_under(folder) for folder in (home, outside)}
    report = run_json(graph, "--allow-writes", home=home)
    assert {folder: files_under(folder) for folder in (home, outside)} == before
    assert report["nodes"]["plot"]["state"] == "error"


def test_a_plot_is_written_to_its_file_only_with_consent(site):
    home, project, _ = site
    graph = plot_graph(project, "charts/warp.png")
    report = run_json(graph, home=home)
    assert not (project / "charts").exists()
    assert report["nodes"]["plot"]["state"] == "warning"  # nothing written to charts/warp.png
    run_json(graph, "--allow-writes", home=home)
    assert (project / "charts" / "warp.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
