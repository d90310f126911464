"""The worked example plug-in (examples/plugin, distribution ``torsal-waves``), installed
into a scratch folder as pip installs it: listed, solved, swept on local dask workers, and
recorded in the files it is used in; a graph needing it where it is not installed exits 2
naming it; a plug-in that reuses a type id is refused, a broken one reported, by every
command, once. (The app's palette: tests/app/gui/test_plugin_palette.py.)"""

from __future__ import annotations

import csv
import json
import math
import subprocess
import sys
from pathlib import Path

import pytest
from scipy.special import ellipe

from tests.support.plugin_install import EXAMPLE, environment, install, torsal, write_plugin

GRAPH_SCRIPT = """
import sys
from torsal.engine.graph import Graph
from torsal.engine.graphfile import write_graph
from torsal.nodes.catalogue import default_registry

registry = default_registry()
graph = Graph()
slider = {"min": 0.0, "max": 1.0, "value": 0.25, "decimals": 4}
graph.add_node(registry.create("params.NumberSlider", slider), "x")
graph.add_node(registry.create("waves.Wave"), "wave")
graph.add_node(registry.create("waves.Corrugation"), "sheet")
graph.connect("x", "Value", "wave", "X")
write_graph(graph, sys.argv[1])
"""


@pytest.fixture(scope="module")
def waves(tmp_path_factory) -> Path:
    """The example plug-in, installed (about 3 s)."""
    return install([EXAMPLE], tmp_path_factory.mktemp("plugins") / "waves")


@pytest.fixture(scope="module")
def graph(waves, tmp_path_factory) -> Path:
    """A graph made with the plug-in installed: a slider x into waves.Wave, and a waves.Corrugation."""
    path = tmp_path_factory.mktemp("graph") / "waves.graph"
    done = subprocess.run([sys.executable, "-P", "-c", GRAPH_SCRIPT, str(path)], capture_output=True,
                          text=True, env=environment(waves), cwd=path.parent, timeout=120)
    assert done.returncode == 0, done.stderr
    return path


def developed_width(width: float, pitch: float, depth: float) -> float:
    """Arc length of z = depth/2 · sin(2π x / pitch) over 0 … width (whole periods): per
    period 4 √(1 + a²b²) / b · E(a²b² / (1 + a²b²)), with a = depth/2, b = 2π / pitch."""
    a, b = depth / 2, 2 * math.pi / pitch
    m = (a * b) ** 2 / (1 + (a * b) ** 2)
    return width / pitch * 4 * math.sqrt(1 + (a * b) ** 2) / b * ellipe(m)


def test_the_plugin_is_listed_with_its_help(waves, tmp_path):
    done = torsal(tmp_path, "nodes", plugins=(waves,))
    assert done.returncode == 0 and done.stderr == ""
    listed = {line.split()[0]: line for line in done.stdout.splitlines()}
    assert "sine wave" in listed["waves.Wave"] and "corrugated sheet" in listed["waves.Corrugation"]
    without = torsal(tmp_path, "nodes")
    assert "waves.Wave" not in without.stdout
    listed_json = torsal(tmp_path, "nodes", "--json", plugins=(waves,)).stdout
    catalogue = {entry["type"]: entry for entry in json.loads(listed_json)}
    assert catalogue["waves.Wave"]["plugin"] == "torsal-waves"
    assert "plugin" not in catalogue["maths.Expression"]


def test_a_saved_graph_records_the_distribution_of_each_plugin_node(graph):
    nodes = {n["id"]: n for n in json.loads(graph.read_text(encoding="utf-8"))["nodes"]}
    assert nodes["wave"]["plugin"] == nodes["sheet"]["plugin"] == "torsal-waves"
    assert "plugin" not in nodes["x"]  # Torsal's own


def test_run_solves_the_plugins_nodes(waves, graph, tmp_path):
    done = torsal(tmp_path, "run", str(graph), "--json", plugins=(waves,))
    assert done.returncode == 0, done.stderr
    nodes = json.loads(done.stdout)["nodes"]
    assert nodes["wave"]["outputs"]["Height"]["{0}"] == [pytest.approx(1.0, abs=1e-12)]  # sin(2π · 0.25)
    (developed,) = nodes["sheet"]["outputs"]["Developed"]["{0}"]
    # a polyline of 2001 points through the sine: shorter than the arc by 6.5e-6 of it
    assert developed == pytest.approx(developed_width(1.0, 0.1, 0.02), rel=1e-5)
    assert developed < developed_width(1.0, 0.1, 0.02)


def test_a_sweep_on_local_dask_workers_solves_the_plugin_there(waves, graph, tmp_path):
    out = tmp_path / "sweep"
    done = torsal(tmp_path, "sweep", str(graph), "--vary", "x=0:1:5", "--collect", "wave.Height",
                  "--out", str(out), "--workers", "1", plugins=(waves,))
    assert done.returncode == 0, done.stderr[-3000:]
    with (out / "results.csv").open(newline="", encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    assert [float(r["in:x"]) for r in rows] == [0.0, 0.25, 0.5, 0.75, 1.0]
    for row in rows:
        expected = math.sin(2 * math.pi * float(row["in:x"]))
        assert float(row["out:wave.Height"]) == pytest.approx(expected, abs=1e-12)


def test_workers_without_the_plugin_report_it_and_cache_nothing(waves, graph, tmp_path):
    """A cluster whose workers lack the plug-in (started here, without it on their path): each
    variant fails naming the package, and is not cached, so a re-run once it is installed solves."""
    import logging

    from distributed import LocalCluster

    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address="127.0.0.1:0", silence_logs=logging.CRITICAL) as cluster:
        out = tmp_path / "sweep"
        done = torsal(tmp_path, "sweep", str(graph), "--vary", "x=0:1:2", "--collect", "wave.Height",
                      "--out", str(out), "--scheduler", cluster.scheduler_address, plugins=(waves,))
    assert done.returncode == 1, done.stderr[-3000:]
    with (out / "results.csv").open(newline="", encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    assert len(rows) == 2
    for row in rows:
        assert row["out:wave.Height"] == ""
        assert row["status"].startswith("error: the worker failed")
        assert "'waves.Wave'" in row["status"] and "pip install torsal-waves" in row["status"]
    assert not (out / "cache.jsonl").exists() or (out / "cache.jsonl").read_text() == ""


@pytest.mark.parametrize("command", ["run", "check"])
def test_without_the_plugin_a_graph_needing_it_exits_2_naming_type_and_package(graph, tmp_path, command):
    done = torsal(tmp_path, command, str(graph))
    assert done.returncode == 2
    assert "'waves.Wave' (node wave)" in done.stderr and "'waves.Corrugation' (node sheet)" in done.stderr
    assert "'torsal-waves'" in done.stderr and "pip install torsal-waves" in done.stderr
    assert "Traceback" not in done.stderr


CLASH = """
from torsal.api import NUMBER, Node, Out

class Expression(Node):
    \"\"\"Not Torsal's Expression.\"\"\"
    type_id = "maths.Expression"
    outputs = (Out("Result", NUMBER, "R", "Nothing."),)

class Fine(Node):
    \"\"\"A type of its own, refused with the rest of the plug-in.\"\"\"
    type_id = "clash.Fine"
    outputs = (Out("Result", NUMBER, "R", "Nothing."),)
"""
BROKEN = "raise RuntimeError('the broken plug-in fails on import')\n"


@pytest.fixture(scope="module")
def bad_plugins(tmp_path_factory) -> Path:
    folder = tmp_path_factory.mktemp("bad")
    clash = write_plugin(folder / "clash", "torsal-clash", "torsal_clash", CLASH)
    broken = write_plugin(folder / "broken", "torsal-broken", "torsal_broken", BROKEN)
    return install([clash, broken], folder / "site")


def test_a_plugin_reusing_a_type_id_is_refused_and_a_broken_one_reported_by_every_command_once(
        bad_plugins, waves, graph, tmp_path):
    commands = {
        "nodes": ["nodes"],
        "check": ["check", str(graph)],
        "run": ["run", str(graph)],
        "sweep": ["sweep", str(graph), "--vary", "x=0:1:2", "--collect", "wave.Height", "--out",
                  str(tmp_path / "o"), "--workers", "1"],
    }
    for name, args in commands.items():
        done = torsal(tmp_path, *args, plugins=(bad_plugins, waves))
        assert done.returncode == 0, (name, done.stderr[-3000:])
        refused = [line for line in done.stderr.splitlines() if "'torsal-clash'" in line]
        assert len(refused) == 1, (name, done.stderr)
        assert "'maths.Expression'" in refused[0] and "already provided by 'torsal'" in refused[0]
        broken = [line for line in done.stderr.splitlines() if "'torsal-broken'" in line]
        assert len(broken) == 1 and "the broken plug-in fails on import" in broken[0], (name, done.stderr)
        if name == "nodes":  # the built-in is kept, and nothing of the refused plug-in is half-loaded
            assert "clash.Fine" not in done.stdout
            assert "Work out a formula" in next(
                line for line in done.stdout.splitlines() if line.startswith("maths.Expression "))
