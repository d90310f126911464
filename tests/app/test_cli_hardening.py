"""Issue 24: options bounded and hostile inputs answered with one line and exit 2.

Every hostile input is made here: a silent socket on loopback, a nested cluster bomb, a
cluster definition without nodes, seeds out of range, a value nested 30,000 deep, a full
disk under ``results.json``.
"""

from __future__ import annotations

import errno
import json
import os
import socket
import threading
from pathlib import Path

import pytest

from torsal.app.cli import main
from torsal.app.explore import option_bounds
from torsal.app.explore.executors import InlineExecutor
from torsal.engine.node import In, Node, Out
from torsal.engine.types import NUMBER

EXAMPLE = Path(__file__).resolve().parents[2] / "torsal" / "resources" / "examples" / "first-steps.graph"
SWEEP = ["sweep", str(EXAMPLE), "--vary", "width=1:2:3", "--collect", "total.Result"]


def one_line_exit_2(capsys, argv: list[str]) -> str:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and err.strip().splitlines()[-1].startswith("torsal: "), err
    return err


@pytest.fixture
def inline(monkeypatch):
    """Sweeps solved in this process (no worker processes to start)."""
    monkeypatch.setattr(option_bounds, "bounded_executor", lambda *args: InlineExecutor())


# --------------------------------------------------------------------------- --scheduler

@pytest.fixture
def silent_port():
    """A loopback port that accepts connections and never says a word."""
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(8)
    accepted = []
    stop = threading.Event()

    def serve() -> None:
        server.settimeout(0.1)
        while not stop.is_set():
            try:
                accepted.append(server.accept()[0])
            except OSError:
                continue

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    yield server.getsockname()[1]
    stop.set()
    thread.join()
    for connection in accepted:
        connection.close()
    server.close()


def test_a_silent_scheduler_port_is_a_message_not_a_hang(tmp_path, capsys, monkeypatch, silent_port):
    monkeypatch.setattr(option_bounds, "CONNECT_SECONDS", 0.3)  # the message proves the timeout ended it
    err = one_line_exit_2(capsys, [*SWEEP, "--out", str(tmp_path / "o"), "--scheduler",
                                   f"tcp://127.0.0.1:{silent_port}"])
    assert "nothing answered within 0.3 s" in err


def test_a_port_that_speaks_another_protocol_is_not_a_scheduler(capsys):
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(1)

    def greet() -> None:
        connection, _ = server.accept()
        connection.sendall(b"HTTP/1.1 400 Bad Request\r\n\r\n")  # 8 bytes read as 3 EiB
        connection.close()

    thread = threading.Thread(target=greet, daemon=True)
    thread.start()
    with pytest.raises(Exception, match="not a dask scheduler"):
        option_bounds.check_scheduler(f"tcp://127.0.0.1:{server.getsockname()[1]}")
    thread.join()
    server.close()


def test_an_unknown_scheme_is_exit_2_without_a_traceback(tmp_path, capsys):
    err = one_line_exit_2(capsys, [*SWEEP, "--out", str(tmp_path / "o"), "--scheduler", "nonsense://x"])
    assert "unknown scheme 'nonsense'" in err


# --------------------------------------------------------------------------- counts

def test_workers_are_capped_at_the_cores_and_the_variants():
    cores = os.cpu_count() or 1
    assert option_bounds.worker_count(1000, 2)[0] == min(cores, 2)
    count, note = option_bounds.worker_count(1000, 10**6)
    assert count == cores and note == f"--workers 1000: this machine has {cores} core{'s' * (cores > 1)}; " \
        f"starting {cores}"
    assert option_bounds.worker_count(1, 10) == (1, None)
    with pytest.raises(Exception, match="give 1 or more"):
        option_bounds.worker_count(0, 10)


@pytest.mark.parametrize("extra, words", [
    (["--sampler", "lhs", "--samples", "10000000"], "asks for 10,000,000 variants"),
    (["--seed", "-5", "--sampler", "lhs", "--samples", "3"], "--seed -5: give a whole number"),
    (["--seed", str(2**64), "--sampler", "sobol", "--samples", "3"], f"--seed {2**64}: give"),
])
def test_samples_and_seeds_out_of_range_are_refused(tmp_path, capsys, extra, words):
    argv = ["sweep", str(EXAMPLE), "--vary", "width=1:2", "--collect", "total.Result", "--out",
            str(tmp_path / "o"), *extra]
    assert words in one_line_exit_2(capsys, argv)
    assert not (tmp_path / "o").exists()


def test_a_grid_of_more_variants_than_the_cap_is_refused(tmp_path, capsys):
    argv = ["sweep", str(EXAMPLE), "--vary", "width=0.2:3:101", "--vary", "count=1:50:50", "--vary",
            "wave=0:2:101", "--collect", "total.Result", "--out", str(tmp_path / "o")]
    assert "the grid asks for 510,050 variants" in one_line_exit_2(capsys, argv)


def test_optimise_seed_and_budget_out_of_range(capsys):
    base = ["optimise", str(EXAMPLE), "--vary", "width=1:2", "--minimise", "total.Result"]
    assert "--seed -5" in one_line_exit_2(capsys, [*base, "--seed", "-5"])
    assert "--budget 1000000" in one_line_exit_2(capsys, [*base, "--budget", "1000000"])


def test_a_value_nested_30000_deep_is_refused(capsys):
    deep = "[" * 30_000 + "]" * 30_000
    err = one_line_exit_2(capsys, ["run", str(EXAMPLE), "--set", f"width.Value={deep}"])
    assert "more than 32 deep" in err


# --------------------------------------------------------------------------- clusters

def cluster_bomb(path: Path, levels: int = 16, fan: int = 10) -> Path:
    """``fan`` instances per level, ``levels`` deep, the bottom definition empty (the
    issue's 10**16 instances that counted as 0 nodes)."""
    clusters = []
    for level in range(levels):
        nodes = [] if level == 0 else [
            {"id": f"c{j}", "type": "cluster.Cluster", "position": [0, 0],
             "settings": {"definition": f"d{level - 1}"}} for j in range(fan)]
        clusters.append({"id": f"d{level}", "nodes": nodes, "wires": [], "inputs": [], "outputs": []})
    top = [{"id": f"t{j}", "type": "cluster.Cluster", "position": [0, 0],
            "settings": {"definition": f"d{levels - 1}"}} for j in range(fan)]
    path.write_text(json.dumps({"format": "torsal.graph", "version": 1, "nodes": top, "wires": [],
                                "clusters": clusters}))
    return path


def test_check_refuses_a_nested_cluster_bomb_of_empty_definitions(tmp_path, capsys):
    """(How fast: tests/benchmarks/bench_hardening.py.)"""
    bomb = cluster_bomb(tmp_path / "bomb.graph")
    err = one_line_exit_2(capsys, ["check", str(bomb)])
    assert "expand to more than 200,000 nodes" in err
    assert "expand to more than" in one_line_exit_2(capsys, ["run", str(bomb)])


def test_a_cluster_definition_without_nodes_is_a_message(tmp_path, capsys):
    path = tmp_path / "bare.graph"
    path.write_text('{"format":"torsal.graph","version":1,"nodes":[],"clusters":[{"id":"a"}]}')
    assert 'has no "nodes" list' in one_line_exit_2(capsys, ["check", str(path)])


# --------------------------------------------------------------------------- full disks

def test_a_full_disk_leaves_results_json_whole_and_exits_2(tmp_path, capsys, monkeypatch):
    out = tmp_path / "build"
    out.mkdir()
    (out / "results.json").write_text('{"the": "previous results"}\n')

    def no_space(*args):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(os, "fsync", no_space)
    err = one_line_exit_2(capsys, ["run", str(EXAMPLE), "--out", str(out)])
    assert "cannot write results.json: No space left on device" in err
    assert (out / "results.json").read_text() == '{"the": "previous results"}\n'
    assert sorted(p.name for p in out.iterdir()) == ["results.json"]


def test_a_sweep_on_a_full_out_exits_2_with_one_line(tmp_path, capsys, monkeypatch, inline):
    def no_space(*args):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(os, "fsync", no_space)
    err = one_line_exit_2(capsys, [*SWEEP, "--out", str(tmp_path / "o")])
    assert "No space left on device" in err


# --------------------------------------------------------------------------- call budgets

def point(*xyz: float) -> dict:
    return {"type": "Point", "xyz": [float(c) for c in xyz]}


def warp_series_graph(path: Path, count: int) -> Path:
    """Two lines into RulingDevelopable, its WarpTolerance fed by a Series of ``count``."""
    from torsal.engine.graph import Graph
    from torsal.engine.graphfile import write_graph
    from torsal.nodes.catalogue import default_registry

    registry = default_registry()
    graph = Graph()
    lines = (("a", point(0, 0, 0), point(10, 0, 0)), ("b", point(0, 3, 1), point(10, 4, 2)))
    for node_id, start, end in lines:
        graph.add_node(registry.get("curves.Line")(), node_id)
        graph.set_input_value(node_id, "Start", start)
        graph.set_input_value(node_id, "End", end)
    graph.add_node(registry.get("maths.Series")(), "tol")
    for port, value in (("Start", 0.001), ("Step", 1e-9), ("Count", count)):
        graph.set_input_value("tol", port, value)
    graph.add_node(registry.get("developable.RulingDevelopable")(), "strip")
    graph.connect("a", "Line", "strip", "CurveA")
    graph.connect("b", "Line", "strip", "CurveB")
    graph.connect("tol", "Series", "strip", "WarpTolerance")
    write_graph(graph, path)
    return path


def test_check_refuses_a_million_strip_solves(tmp_path, capsys):
    """The issue's 12 KB graph: a Series of 1,000,000 into WarpTolerance (~80 min of solves);
    how fast: tests/benchmarks/bench_hardening.py."""
    small = warp_series_graph(tmp_path / "small.graph", 3)
    assert main(["check", str(small)]) == 0  # imports warmed; three strips are fine
    assert "calls of the solve's 5,000,000" in capsys.readouterr().out
    bomb = warp_series_graph(tmp_path / "million.graph", 1_000_000)
    err = one_line_exit_2(capsys, ["check", str(bomb)])
    assert "strip: WarpTolerance has 1,000,000 values: RulingDevelopable would run 1,000,000 times; " \
           "at most 2,000 at once" in err


def test_run_refuses_the_million_strip_solves_naming_node_and_input(tmp_path):
    from torsal.app.headless import run_file

    run = run_file(warp_series_graph(tmp_path / "million.graph", 1_000_000))
    assert run.exit_code == 1
    (message,) = run.solver.result("strip").messages
    assert message.text.startswith("WarpTolerance has 1,000,000 values: RulingDevelopable would run")


class Doubled(Node):
    """Twice a number, one call per item."""

    type_id = "test.Doubled"
    inputs = (In("x", NUMBER, "x", "A number."),)
    outputs = (Out("Result", NUMBER, "R", "Twice x."),)

    def solve(self, x: float) -> float:
        return 2 * x


def test_the_solves_total_budget_names_the_node_that_passes_it():
    from torsal.engine.call_budget import SolveBudget
    from torsal.engine.graph import Graph
    from torsal.engine.solver import ERROR, Solver
    from torsal.nodes.maths.sequences import Series

    graph = Graph()
    graph.add_node(Series(), "numbers")
    graph.set_input_value("numbers", "Count", 40)
    graph.add_node(Doubled(), "twice")
    graph.connect("numbers", "Series", "twice", "x")
    solver = Solver(graph, budget=SolveBudget(limit=30))
    solver.solve()
    assert solver.result("twice").state == ERROR
    (text,) = [m.text for m in solver.result("twice").messages]
    assert text.startswith("x has 40 values: Doubled would run 40 times")
    assert "budget of 30 calls in all" in text
    assert solver.refused == [("twice", text)]


def test_optimise_on_a_full_out_exits_2_with_one_line(tmp_path, capsys, monkeypatch, inline):
    real_fsync = os.fsync

    def no_space(handle):
        if os.path.isdir(f"/proc/self/fd/{handle}"):
            return real_fsync(handle)
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(os, "fsync", no_space)
    argv = ["optimise", str(EXAMPLE), "--vary", "width=1:2", "--minimise", "total.Result", "--budget", "4",
            "--out", str(tmp_path / "o")]
    err = one_line_exit_2(capsys, argv)
    assert "cannot write" in err or "No space left on device" in err
    assert list((tmp_path / "o").iterdir()) == []


def test_rationalise_fed_a_list_of_60_tolerances_is_refused_before_any_work():
    from tests.support.node_helpers import run, tree
    from torsal.engine.solver import ERROR
    from torsal.nodes.developable.rationalise import Rationalise
    from torsal.nodes.geometry.parametric_surface import cylinder
    from torsal.nodes.limits import MAX_RATIONALISE_CALLS

    result = run(Rationalise(), Surface=tree({(0,): [cylinder(1.0, 2.0)]}),
                 Tolerance=tree({(0,): [0.01 + 0.001 * i for i in range(60)]}))
    assert result.state == ERROR  # before any of the 60 designs (seconds each) was solved
    assert result.messages[0].text == (f"Tolerance has 60 values: Rationalise would run 60 times; "
                                       f"at most {MAX_RATIONALISE_CALLS:,} at once")
