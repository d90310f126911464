"""Issue 24: every file Torsal writes goes through one write path that never follows a link.

Each test plants its own trap (a symlink to a file outside, a folder swapped for a link
while exports run, an executable in the way) and checks the file outside by checksum,
the exit code and the message.
"""

from __future__ import annotations

import hashlib
import os
import stat
import threading
from pathlib import Path

import pytest

from torsal.app.cli import main
from torsal.engine.graph import Graph
from torsal.engine.graphfile import write_graph
from torsal.engine.solver import ERROR, OK, Solver
from torsal.engine.write_path import UnsafeWrite, scratch_folder, write_file
from torsal.engine.writes import WriteAccess
from torsal.nodes.common.charts import plot_folder
from torsal.nodes.io.data import ExportCSV
from torsal.nodes.params.panel import Panel

PAYLOAD = "echo pwned"


def digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


@pytest.fixture
def victim(tmp_path):
    """A file outside every folder Torsal is given, standing in for ~/.bashrc."""
    outside = tmp_path / "outside"
    outside.mkdir()
    bashrc = outside / ".bashrc"
    bashrc.write_text("# the user's own start-up file\n")
    return bashrc


def export_graph(exports: dict[str, str]) -> Graph:
    """A Panel's text written by one ExportCSV per (id → Path)."""
    graph = Graph()
    graph.add_node(Panel({"text": PAYLOAD}), "payload")
    for node_id, path in exports.items():
        graph.add_node(ExportCSV(), node_id)
        graph.connect("payload", "Output", node_id, "Data")
        graph.set_input_value(node_id, "Path", path)
        graph.set_input_value(node_id, "Write", True)
    return graph


def solve(graph: Graph, folder: Path, access: WriteAccess | None = None) -> Solver:
    solver = Solver(graph, access or WriteAccess(folder, allowed=True))
    solver.solve()
    return solver


def messages(solver: Solver, node_id: str) -> str:
    return " ".join(m.text for m in solver.result(node_id).messages)


# --------------------------------------------------------------------------- --out

def test_run_out_that_is_a_symlink_is_refused_with_exit_2(tmp_path, victim, capsys):
    graph = tmp_path / "g.graph"
    write_graph(export_graph({}), graph)
    build = tmp_path / "build"
    build.symlink_to(victim.parent, target_is_directory=True)
    before = sorted(p.name for p in victim.parent.iterdir())
    assert main(["run", str(graph), "--out", str(build)]) == 2
    err = capsys.readouterr().err
    assert "is a symbolic link" in err and "Traceback" not in err
    assert sorted(p.name for p in victim.parent.iterdir()) == before


def test_run_out_results_json_planted_as_a_symlink_is_not_written_through(tmp_path, victim, capsys):
    graph = tmp_path / "g.graph"
    write_graph(export_graph({}), graph)
    build = tmp_path / "build"
    build.mkdir()
    (build / "results.json").symlink_to(victim)
    before = digest(victim)
    assert main(["run", str(graph), "--out", str(build)]) == 2
    err = capsys.readouterr().err
    assert "results.json is a symbolic link" in err and "Traceback" not in err
    assert digest(victim) == before


def test_run_out_on_a_read_only_folder_is_exit_2_and_one_line(tmp_path, capsys):
    if os.geteuid() == 0:
        pytest.skip("root writes into read-only folders")
    graph = tmp_path / "g.graph"
    write_graph(export_graph({}), graph)
    build = tmp_path / "build"
    build.mkdir(mode=0o500)
    assert main(["run", str(graph), "--out", str(build)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("torsal: --out") and "Traceback" not in err


# --------------------------------------------------------------------------- node exports

def test_an_export_replacing_an_executable_is_written_0644(tmp_path):
    script = tmp_path / "build.sh"
    script.write_text("#!/bin/sh\necho original\n")
    script.chmod(0o755)
    solver = solve(export_graph({"csv": "build.sh"}), tmp_path)
    assert solver.result("csv").state == OK, messages(solver, "csv")
    assert PAYLOAD in script.read_text()
    assert stat.S_IMODE(script.stat().st_mode) & 0o111 == 0
    assert stat.S_IMODE(script.stat().st_mode) == 0o644 & ~current_umask()
    assert (tmp_path / "build.sh.bak").read_text() == "#!/bin/sh\necho original\n"


def current_umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


@pytest.mark.parametrize("path, why", [
    (".git/hooks/pre-commit", "dot"),
    (".hg/hgrc", "dot"),
    ("cfg/.hidden/x.csv", "dot"),
    (".envrc", "dot"),
    ("g.graph.bak", ".bak"),
    ("notes.csv.bak", ".bak"),
])
def test_a_node_never_writes_into_dot_folders_dot_files_or_backups(tmp_path, path, why):
    (tmp_path / ".git" / "hooks").mkdir(parents=True)
    hook = tmp_path / ".git" / "hooks" / "pre-commit"
    hook.write_text("#!/bin/sh\n")
    before = digest(hook)
    solver = solve(export_graph({"csv": path}), tmp_path)
    assert solver.result("csv").state == ERROR
    assert why in messages(solver, "csv")
    assert digest(hook) == before
    assert not (tmp_path / path).exists() or (tmp_path / path) == hook


def test_a_symlink_inside_the_folder_is_refused_even_when_it_points_inside(tmp_path):
    (tmp_path / "real").mkdir()
    (tmp_path / "alias").symlink_to(tmp_path / "real", target_is_directory=True)
    (tmp_path / "table.csv").symlink_to(tmp_path / "real" / "t.csv")
    for path in ("alias/x.csv", "table.csv"):
        solver = solve(export_graph({"csv": path}), tmp_path)
        assert solver.result("csv").state == ERROR
        assert "symbolic link" in messages(solver, "csv")
    assert list((tmp_path / "real").iterdir()) == []


def test_two_exporters_with_one_path_the_second_is_refused_and_the_original_kept(tmp_path):
    (tmp_path / "areas.csv").write_text("the user's original\n")
    solver = solve(export_graph({"a": "areas.csv", "b": "areas.csv"}), tmp_path)
    states = {solver.result("a").state, solver.result("b").state}
    assert states == {OK, ERROR}
    refused = "a" if solver.result("a").state == ERROR else "b"
    assert "also written by node" in messages(solver, refused)
    assert (tmp_path / "areas.csv.bak").read_text() == "the user's original\n"


def test_only_the_first_write_of_a_run_makes_the_backup(tmp_path):
    (tmp_path / "areas.csv").write_text("the user's original\n")
    graph = export_graph({"csv": "areas.csv"})
    access = WriteAccess(tmp_path, allowed=True)
    solver = solve(graph, tmp_path, access)
    graph.set_setting("payload", "text", "second")
    solver.solve()
    assert "second" in (tmp_path / "areas.csv").read_text()
    assert (tmp_path / "areas.csv.bak").read_text() == "the user's original\n"


def test_a_fifo_or_a_folder_at_the_target_is_refused_by_type(tmp_path):
    os.mkfifo(tmp_path / "pipe.csv")
    (tmp_path / "folder.csv").mkdir()
    solver = solve(export_graph({"a": "pipe.csv", "b": "folder.csv"}), tmp_path)
    assert "named pipe" in messages(solver, "a")
    assert "folder" in messages(solver, "b")


def test_a_folder_swapped_for_a_symlink_during_100_exports_writes_nothing_outside(tmp_path, victim,
                                                                                   monkeypatch):
    """The race the issue measured (6–13 of 20–40 writes escaped): a thread swaps
    ``project/out`` between a real folder and a link to the victim's folder while the
    graph is solved 100 times; every write lands inside or is refused. Each write waits
    a moment after the path was checked (as a large export does while it is produced),
    so the swap often lands between the check and the write."""
    import random
    import time

    from torsal.nodes.common import files

    jitter = random.Random(24)
    real_write = files.write_file

    def slow_write(*args, **kwargs):
        time.sleep(jitter.uniform(0.0, 0.002))
        return real_write(*args, **kwargs)

    monkeypatch.setattr(files, "write_file", slow_write)
    project = tmp_path / "project"
    project.mkdir()
    (victim.parent / "areas.csv").write_text("not yours\n")
    watched = {p: digest(p) for p in victim.parent.iterdir()}
    graph = export_graph({"csv": "out/areas.csv"})
    access = WriteAccess(project, allowed=True)
    solver = Solver(graph, access)
    real, link, parked = project / "out", project / "out-link", project / "out-parked"
    real.mkdir()
    link.symlink_to(victim.parent, target_is_directory=True)
    stop = threading.Event()

    swaps = [0]

    def place(source: Path, name: Path) -> None:
        """Rename ``source`` to ``name``; a folder the exporter made meanwhile is moved aside."""
        while True:
            try:
                os.rename(source, name)
                return
            except OSError:
                os.rename(name, project / f"made-{swaps[0]}-{len(list(project.iterdir()))}")

    def swap() -> None:
        while not stop.is_set():
            place(real, parked)
            place(link, real)  # project/out is now a link to the outside
            place(real, link)
            place(parked, real)
            swaps[0] += 1

    swapper = threading.Thread(target=swap, daemon=True)
    swapper.start()
    states = []
    try:
        for i in range(100):
            graph.set_setting("payload", "text", f"{PAYLOAD} {i}")
            solver.solve()
            states.append(solver.result("csv").state)
    finally:
        stop.set()
        swapper.join()
    assert {p: digest(p) for p in victim.parent.iterdir()} == watched
    assert len(states) == 100 and set(states) <= {OK, ERROR}
    print(f"\n100 exports during {swaps[0]} swaps: {states.count(OK)} written inside, "
          f"{states.count(ERROR)} refused, 0 outside")


def test_write_file_refuses_a_target_that_is_a_symlink(tmp_path, victim):
    (tmp_path / "x.json").symlink_to(victim)
    before = digest(victim)
    with pytest.raises(UnsafeWrite, match="symbolic link"):
        write_file(tmp_path / "x.json", b"{}")
    assert digest(victim) == before


# --------------------------------------------------------------------------- scratch

def test_plots_and_scratch_files_go_to_a_private_per_user_folder():
    folder = scratch_folder()
    assert stat.S_IMODE(os.lstat(folder).st_mode) == 0o700
    assert os.lstat(folder).st_uid == os.getuid()
    assert plot_folder().parent == folder
    import tempfile

    assert not folder.is_relative_to(tempfile.gettempdir())


def test_without_a_usable_cache_folder_scratch_is_a_fresh_private_folder(tmp_path, monkeypatch):
    import platformdirs

    from torsal.engine import write_path

    blocker = tmp_path / "home-is-a-file"
    blocker.write_text("")
    monkeypatch.setattr(platformdirs, "user_cache_dir", lambda *args, **kwargs: str(blocker / "torsal"))
    monkeypatch.setattr(write_path, "_fallback", None)
    folder = scratch_folder()
    assert folder.is_dir() and stat.S_IMODE(os.lstat(folder).st_mode) == 0o700
    assert folder.name.startswith("torsal-") and folder.name != "torsal"
    assert scratch_folder() == folder  # one per process
    folder.rmdir()
