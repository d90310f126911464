"""Files a graph reads are found from the graph's folder, with or without ``--out``; an
exporter with nothing to write leaves the file already there (and its ``.bak``) alone.

Real ``.graph`` files solved by a real ``torsal run`` subprocess, as in the README's CI recipe
(``torsal run g.graph --allow-writes --out build``).
"""

from __future__ import annotations

import hashlib
import json
import subprocess
import sys
from pathlib import Path

import rhino3dm as rh

from torsal.app.explore.evaluate import Job, solve_variant
from torsal.engine.graph import Graph
from torsal.engine.graphfile import write_graph
from torsal.nodes.io.data import ExportCSV
from torsal.nodes.io.meshes import ExportMesh
from torsal.nodes.io.rhino import Export3dm, Import3dm

ROOT = Path(__file__).resolve().parents[3]


def design_file(path: Path) -> Path:
    """A .3dm holding one line, made with rhino3dm (not with the code under test)."""
    model = rh.File3dm()
    model.Settings.ModelUnitSystem = rh.UnitSystem.Meters
    model.Objects.AddLine(rh.Point3d(0, 0, 0), rh.Point3d(3, 4, 0))
    assert model.Write(str(path), 7)
    return path


def copy_graph(folder: Path, source: str) -> Path:
    """Import3dm reads ``source``; Export3dm, CSV and mesh exporters write what it found."""
    graph = Graph()
    graph.add_node(Import3dm(), "read")
    graph.set_input_value("read", "Path", source)
    for node_id, node, port, name in (("rhino", Export3dm(), "Curves", "copy.3dm"),
                                      ("csv", ExportCSV(), "Data", "copy.csv"),
                                      ("mesh", ExportMesh(), "Meshes", "copy.obj")):
        graph.add_node(node, node_id)
        graph.connect("read", "Meshes" if node_id == "mesh" else "Curves", node_id, port)
        graph.set_input_value(node_id, "Path", name)
        graph.set_input_value(node_id, "Write", True)
    path = folder / "copy.graph"
    write_graph(graph, path)
    return path


def run(graph: Path, *flags: str, cwd: Path) -> tuple[int, dict]:
    done = subprocess.run([sys.executable, "-P", "-m", "torsal.app.cli", "run", str(graph), "--json", *flags],
                          capture_output=True, text=True, cwd=cwd, timeout=120,
                          env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"})
    assert "Traceback" not in done.stderr, done.stderr
    return done.returncode, json.loads(done.stdout)


def digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def test_with_out_a_file_the_graph_reads_is_still_found_beside_the_graph(tmp_path):
    project, build, elsewhere = tmp_path / "project", tmp_path / "build", tmp_path / "elsewhere"
    for folder in (project, elsewhere):
        folder.mkdir()
    design_file(project / "design.3dm")
    graph = copy_graph(project, "design.3dm")
    code, report = run(graph, "--allow-writes", "--out", str(build), cwd=elsewhere)
    assert report["nodes"]["read"]["state"] == "ok", report["nodes"]["read"]
    assert code == 0
    copied = rh.File3dm.Read(str(build / "copy.3dm"))
    (obj,) = list(copied.Objects)
    end = obj.Geometry.PointAtEnd
    assert (end.X, end.Y, end.Z) == (3.0, 4.0, 0.0)  # the line came through
    assert not (project / "copy.3dm").exists()


def test_an_exporter_with_nothing_to_write_leaves_the_file_and_its_backup_alone(tmp_path):
    project = tmp_path / "project"
    project.mkdir()
    graph = copy_graph(project, "missing.3dm")  # Import3dm refuses: no such file
    before = {}
    for name in ("copy.3dm", "copy.csv", "copy.obj"):
        for suffix in ("", ".bak"):
            path = project / f"{name}{suffix}"
            path.write_bytes(f"the user's good {name}{suffix}\n".encode())
            before[path] = digest(path)
    code, report = run(graph, "--allow-writes", cwd=tmp_path)
    assert code == 1 and report["nodes"]["read"]["state"] == "error"
    assert "missing.3dm" in report["nodes"]["read"]["messages"][0]["text"]
    for node_id in ("rhino", "csv", "mesh"):
        node = report["nodes"][node_id]
        assert node["state"] == "warning", node
        text = node["messages"][0]["text"]
        assert "nothing to write" in text or "collected no data" in text, text
    assert {path: digest(path) for path in before} == before
    assert sorted(p.name for p in project.iterdir()) == sorted(
        ["copy.graph", *(p.name for p in before)]), "no file was added or removed"


def test_a_sweep_variant_reads_from_the_graphs_folder_not_its_variant_folder(tmp_path):
    project = tmp_path / "project"
    project.mkdir()
    design_file(project / "design.3dm")
    graph = copy_graph(project, "design.3dm")
    job = Job((), allow_writes=True, write_root=str(tmp_path / "variants"), read_root=str(project))
    outcome = solve_variant(graph.read_text(), {}, job, 3)
    assert not outcome["status"].startswith("error"), outcome["status"]
    assert (tmp_path / "variants" / "00003" / "copy.3dm").exists()
