"""The ``.graph`` file's versions: a newer file is refused (and never overwritten), a
version-0 file migrates to the same graph as its version-1 twin, unusable versions are
refused. See ``docs/graph-format.md``.
"""

from __future__ import annotations

import json
import os

import pytest

from tests.support.graphfile_files import (
    read,
)
from torsal.engine import graphfile
from torsal.engine.graph import Graph
from torsal.engine.graphfile import GraphFileError, NewerVersionError
from torsal.engine.solver import Solver

# --------------------------------------------------------------------------- versions


def newer_text(version: int = 2) -> str:
    data = json.loads(read("engine-basic.graph"))
    data["version"] = version
    data["x_from_the_future"] = {"feature": True}
    return graphfile.encode(data)


@pytest.mark.parametrize("version", [2, 17, 10**400])
def test_newer_version_is_refused_naming_both_versions(registry, version):
    with pytest.raises(NewerVersionError) as caught:
        graphfile.loads(newer_text(version), registry)
    message = str(caught.value)
    assert isinstance(caught.value, GraphFileError)
    assert f"version {version}" in message
    assert f"version {graphfile.VERSION}" in message
    assert "newer" in message


def test_newer_version_file_is_refused_by_read_graph(registry, tmp_path):
    path = tmp_path / "future.graph"
    path.write_text(newer_text(), encoding="utf-8")
    with pytest.raises(NewerVersionError, match="version 2"):
        graphfile.read_graph(path, registry)


def test_write_graph_refuses_to_overwrite_a_newer_file_and_leaves_it_unchanged(registry, tmp_path):
    path = tmp_path / "future.graph"
    original = newer_text().encode("utf-8")
    path.write_bytes(original)
    stamp = os.stat(path).st_mtime_ns
    graph = graphfile.loads(read("engine-basic.graph"), registry)
    with pytest.raises(NewerVersionError) as caught:
        graphfile.write_graph(graph, path)
    assert "version 2" in str(caught.value)
    assert path.read_bytes() == original
    assert os.stat(path).st_mtime_ns == stamp
    assert not (tmp_path / "future.graph.bak").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["future.graph"]


def test_write_graph_overwrites_an_unreadable_or_current_file(registry, tmp_path):
    """Only a *newer* file is protected; garbage or a v1 file is replaced (and backed up)."""
    graph = graphfile.loads(read("engine-basic.graph"), registry)
    for old in (b"not json at all", b"[1, 2]", read("engine-spec-example.graph").encode()):
        path = tmp_path / "target.graph"
        path.write_bytes(old)
        graphfile.write_graph(graph, path)
        assert path.read_text(encoding="utf-8") == read("engine-basic.graph")
        assert (tmp_path / "target.graph.bak").read_bytes() == old


V0_TEXT = """{
  "format": "torsal.graph",
  "version": 0,
  "nodes": [
    {"id": "height", "type": "params.NumberSlider", "x": 120.0, "y": 80.0,
     "settings": {"value": 3.0}, "x_extra": "kept"},
    {"id": "add", "type": "maths.Add", "x": 300.5, "y": -40.0, "inputs": {"B": {"value": 2}}},
    {"id": "fancy", "type": "plugin.Missing", "x": 500.0, "y": 0.0},
    {"id": "len", "type": "lists.ListLength", "position": [600.0, 100.0]}
  ],
  "wires": [
    {"source": "height.Value", "target": "add.A"},
    {"source": "add.Result", "target": "fancy.In", "x_style": "dashed"},
    {"source": "add.Result", "target": "len.List"}
  ],
  "groups": [],
  "meta": {"created_with": "torsal 0.0.1", "description": "draft"}
}
"""

V1_TEXT = """{
  "format": "torsal.graph",
  "version": 1,
  "nodes": [
    {"id": "height", "type": "params.NumberSlider", "position": [120.0, 80.0],
     "settings": {"value": 3.0}, "x_extra": "kept"},
    {"id": "add", "type": "maths.Add", "position": [300.5, -40.0], "inputs": {"B": {"value": 2}}},
    {"id": "fancy", "type": "plugin.Missing", "position": [500.0, 0.0]},
    {"id": "len", "type": "lists.ListLength", "position": [600.0, 100.0]}
  ],
  "wires": [
    {"from": ["height", "Value"], "to": ["add", "A"]},
    {"from": ["add", "Result"], "to": ["fancy", "In"], "x_style": "dashed"},
    {"from": ["add", "Result"], "to": ["len", "List"]}
  ],
  "groups": [],
  "meta": {"created_with": "torsal 0.0.1", "description": "draft"}
}
"""


def graph_summary(graph: Graph) -> dict:
    return {
        "nodes": [
            (
                r.id,
                r.type_id,
                r.position,
                r.label,
                r.node.settings,
                {k: (s.value, s.has_value, s.modifiers) for k, s in r.inputs.items()},
            )
            for r in graph.nodes.values()
        ],
        "wires": [str(w) for w in graph.wires],
        "groups": [(g.id, g.title, g.nodes) for g in graph.groups],
        "meta": graph.meta,
        "units": graph.units,
    }


def test_version_0_migrates_to_the_same_graph_as_the_equivalent_version_1_file(registry):
    old = graphfile.loads(V0_TEXT, registry)
    new = graphfile.loads(V1_TEXT, registry)
    assert graph_summary(old) == graph_summary(new)
    assert graphfile.dumps(old) == graphfile.dumps(new)
    saved = json.loads(graphfile.dumps(old))
    assert saved["version"] == 1
    assert saved["wires"][1] == {"from": ["add", "Result"], "to": ["fancy", "In"], "x_style": "dashed"}
    assert saved["nodes"][0]["x_extra"] == "kept" and "x" not in saved["nodes"][0]
    solver_old, solver_new = Solver(old), Solver(new)
    solver_old.solve()
    solver_new.solve()
    assert solver_old.result("len").output("Length").to_dict() == {"{0}": [1]}
    assert {n: r.outputs for n, r in solver_old.results.items()} == {
        n: r.outputs for n, r in solver_new.results.items()
    }


def test_migration_is_one_pure_step_per_version():
    data = json.loads(V0_TEXT)
    before = json.dumps(data, sort_keys=True)
    migrated = graphfile._migrate_0_to_1(data)
    assert json.dumps(data, sort_keys=True) == before, "a migration must not change its input"
    assert migrated["version"] == 1
    assert migrated == json.loads(V1_TEXT)
    assert sorted(graphfile.MIGRATIONS) == list(range(graphfile.VERSION))
    assert graphfile.migrate(json.loads(V1_TEXT)) == json.loads(V1_TEXT)


def test_version_0_wire_without_a_port_is_refused_clearly(registry):
    data = json.loads(V0_TEXT)
    data["wires"][0]["source"] = "height"
    with pytest.raises(GraphFileError):
        graphfile.loads(json.dumps(data), registry)


@pytest.mark.parametrize("version", [-1, "1", 1.0, True, None, [1], {"v": 1}])
def test_unusable_version_numbers_are_refused(registry, version):
    data = json.loads(read("engine-spec-example.graph"))
    data["version"] = version
    with pytest.raises(GraphFileError) as caught:
        graphfile.loads(json.dumps(data), registry)
    assert not isinstance(caught.value, NewerVersionError)


def test_missing_version_is_refused(registry):
    data = json.loads(read("engine-spec-example.graph"))
    del data["version"]
    with pytest.raises(GraphFileError, match="version"):
        graphfile.loads(json.dumps(data), registry)
