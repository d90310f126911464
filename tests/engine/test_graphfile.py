"""The ``.graph`` file: exact round trip, unknown fields, placeholders, versions, atomic save.

See ``shared/spec/graph-format.md`` and the "Round trip" and "File safety" bars of issue 2.
The hostile-file corpus lives in ``test_graphfile_fuzz.py``.
"""

from __future__ import annotations

import json
import os
import re
import sys
from collections.abc import Callable
from pathlib import Path

import pytest

from engine import graphfile
from engine.graph import Graph, PlaceholderNode
from engine.graphfile import GraphFileError, NewerVersionError
from engine.registry import Registry
from engine.solver import Solver
from tests.engine.nodekit import Add, ListLength, NumberSlider

FIXTURES = Path(__file__).resolve().parents[1] / "fixtures"
EXAMPLES = Path(__file__).resolve().parents[2] / "resources" / "examples"
SPEC = Path(__file__).resolve().parents[3] / "shared" / "spec" / "graph-format.md"

ENGINE_FIXTURES = sorted(FIXTURES.glob("engine-*.graph"))  # written for the nodekit registry
ALL_FIXTURES = sorted(FIXTURES.glob("*.graph"))
ALL_EXAMPLES = sorted(EXAMPLES.glob("*.graph"))


def read(name: str) -> str:
    return (FIXTURES / name).read_text(encoding="utf-8")


def no_temporaries(directory: Path) -> list[str]:
    """Leftover temporary files of an interrupted save (``.<name>.<pid>-<token>.tmp<suffix>``)."""
    return sorted(p.name for p in directory.iterdir() if ".tmp" in p.name)


# --------------------------------------------------------------------------- round trip


@pytest.mark.parametrize("path", ENGINE_FIXTURES, ids=lambda p: p.name)
def test_every_engine_fixture_is_canonical_and_round_trips_byte_identically(path, registry):
    raw = path.read_bytes()
    text = raw.decode("utf-8")
    assert graphfile.encode(json.loads(text)) == text, "fixture is not in canonical form"
    graph = graphfile.loads(raw, registry)
    assert graphfile.dumps(graph).encode("utf-8") == raw
    # the same through the path-based reader
    assert graphfile.dumps(graphfile.read_graph(path, registry)).encode("utf-8") == raw


@pytest.mark.parametrize("path", ALL_FIXTURES + ALL_EXAMPLES, ids=lambda p: p.name)
def test_every_file_round_trips_even_with_no_node_types_installed(path):
    """With an empty registry every node is a placeholder, and still nothing changes."""
    raw = path.read_bytes()
    text = raw.decode("utf-8")
    assert graphfile.encode(json.loads(text)) == text, "file is not in canonical form"
    graph = graphfile.loads(raw, Registry())
    assert all(isinstance(r.node, PlaceholderNode) for r in graph.nodes.values())
    assert graphfile.dumps(graph).encode("utf-8") == raw


def test_round_trip_survives_solving_and_a_second_cycle(registry):
    text = read("engine-basic.graph")
    graph = graphfile.loads(text, registry)
    Solver(graph).solve()
    saved = graphfile.dumps(graph)
    assert saved == text
    assert graphfile.dumps(graphfile.loads(saved, registry)) == text


def test_canonical_layout_sorted_keys_two_space_indent_final_newline(registry):
    text = read("engine-basic.graph")
    assert text.endswith("}\n") and not text.endswith("\n\n")
    data = json.loads(text)
    assert list(data) == sorted(data)
    for node in data["nodes"]:
        assert list(node) == sorted(node)
    assert '\n  "format": "torsal.graph",\n' in text
    assert '"position": [120.0, 80.0]' in text  # short lists of plain values stay on one line
    assert "\t" not in text


def test_graph_built_in_code_saves_loads_and_saves_identically(registry):
    graph = Graph()
    graph.add_node(NumberSlider({"value": 2.0}), "s", label="Span", position=(10.0, 20.0))
    graph.add_node(Add(), "add", position=(200.0, 20.0))
    graph.add_node(ListLength(), "len")
    graph.connect("s", "Value", "add", "A")
    graph.set_input_value("add", "B", [10, 20, 30])
    graph.set_modifiers("add", "B", ["reverse"])
    graph.connect("add", "Result", "len", "List")
    text = graphfile.dumps(graph)
    data = json.loads(text)
    assert data["format"] == "torsal.graph" and data["version"] == 1
    assert data["meta"]["created_with"].startswith("torsal ")
    assert data["nodes"][1]["inputs"] == {"B": {"modifiers": ["reverse"], "value": [10, 20, 30]}}
    again = graphfile.loads(text, registry)
    assert graphfile.dumps(again) == text
    assert list(again.nodes) == ["s", "add", "len"]
    assert [str(w) for w in again.wires] == [str(w) for w in graph.wires]
    assert again.nodes["add"].inputs["B"].modifiers == ["reverse"]
    solver = Solver(again)
    solver.solve()
    assert solver.result("add").output("Result").to_dict() == {"{0}": [32.0, 22.0, 12.0]}


def test_unknown_fields_at_every_level_are_kept(registry):
    text = read("engine-unknown-fields.graph")
    graph = graphfile.loads(text, registry)
    saved = graphfile.dumps(graph)
    assert saved == text
    data = json.loads(saved)
    assert data["x_future"] == {"a": [1, 2], "b": None} and data["layout"] == "grid"
    node = data["nodes"][0]
    assert node["x_note"].startswith("a note") and node["colour"] == "#ffffff"
    assert node["settings"]["x_step"] == 0.5
    inputs = data["nodes"][1]["inputs"]
    assert inputs["B"]["x_hint"] == "metres" and inputs["B"]["x_unit"] == {"si": True}
    assert inputs["A"] == {"x_only": 1}
    assert data["wires"][0]["x_style"] == {"curve": "bezier"} and data["wires"][0]["label"] == "w1"
    assert data["groups"][0]["x_locked"] is True and data["groups"][0]["collapsed"] is False
    assert data["meta"]["x_meta"] == [1, "two"]


def test_unknown_fields_survive_edits_and_only_the_edited_field_changes(registry):
    text = read("engine-unknown-fields.graph")
    graph = graphfile.loads(text, registry)
    graph.set_setting("a", "value", 7.5)
    graph.move_node("b", (250.0, 10.0))
    graph.set_input_value("b", "B", 11)
    saved = json.loads(graphfile.dumps(graph))
    before = json.loads(text)
    before["nodes"][0]["settings"]["value"] = 7.5
    before["nodes"][1]["position"] = [250.0, 10.0]
    before["nodes"][1]["inputs"]["B"]["value"] = 11
    assert saved == before


def test_removing_an_input_value_keeps_that_inputs_other_fields(registry):
    graph = graphfile.loads(read("engine-unknown-fields.graph"), registry)
    graph.set_input_value("b", "B", None, present=False)
    entry = json.loads(graphfile.dumps(graph))["nodes"][1]["inputs"]["B"]
    assert entry == {"x_hint": "metres", "x_unit": {"si": True}}


def test_missing_node_type_loads_as_a_placeholder_and_saves_back_identically(registry):
    text = read("engine-placeholder.graph")
    graph = graphfile.loads(text, registry)
    fancy = graph.nodes["fancy"]
    assert isinstance(fancy.node, PlaceholderNode)
    assert fancy.node.missing_type == "plugin.FancySurface" and fancy.type_id == "plugin.FancySurface"
    assert fancy.node.settings == {"mode": "fast", "n": 12, "nested": {"a": [1, {"b": None}], "big": 1e300}}
    assert fancy.inputs["Curve"].modifiers == ["flatten", "graft"]
    assert isinstance(graph.nodes["fancy2"].node, PlaceholderNode)
    assert sorted(str(w) for w in graph.wires if "fancy" in (w.source, w.target)) == [
        "fancy.Area → sum.A",
        "fancy.Surface → fancy2.Base",
        "fancy.Surface → len.List",
        "height.Value → fancy.Height",
    ]
    solver = Solver(graph)
    solver.solve()
    assert solver.result("fancy").state == "missing"
    assert solver.result("fancy2").state == "missing"
    assert "plugin.FancySurface" in solver.result("fancy").messages[0].text
    assert solver.result("height").state == "ok"
    assert graphfile.dumps(graph) == text


def test_placeholder_data_is_untouched_when_the_rest_of_the_graph_is_edited(registry):
    text = read("engine-placeholder.graph")
    graph = graphfile.loads(text, registry)
    Solver(graph).solve()
    graph.set_setting("height", "value", 5.0)
    graph.remove_node("sum")
    Solver(graph).solve()
    saved = json.loads(graphfile.dumps(graph))
    original = json.loads(text)
    by_id = {n["id"]: n for n in saved["nodes"]}
    for node in original["nodes"]:
        if node["type"].startswith("plugin."):
            assert by_id[node["id"]] == node
    assert {"from": ["height", "Value"], "to": ["fancy", "Height"]} in saved["wires"]
    assert {"from": ["fancy", "Surface"], "to": ["fancy2", "Base"]} in saved["wires"]
    assert not any("sum" in (w["from"][0], w["to"][0]) for w in saved["wires"])


def test_placeholder_becomes_a_real_node_once_its_type_is_installed(registry):
    text = read("engine-placeholder.graph")
    graph = graphfile.loads(text, Registry())  # nothing installed
    assert graphfile.dumps(graph) == text
    graph = graphfile.loads(text, registry)
    assert isinstance(graph.nodes["height"].node, NumberSlider)


def test_spec_example_loads_with_a_placeholder_and_saves_back_exactly(registry):
    text = read("engine-spec-example.graph")
    graph = graphfile.loads(text, registry)
    assert isinstance(graph.nodes["height"].node, NumberSlider)
    cyl = graph.nodes["cyl"]
    assert isinstance(cyl.node, PlaceholderNode) and cyl.type_id == "developable.CylindricalSurface"
    assert cyl.inputs["Segments"].value == 24
    assert cyl.inputs["Direction"].value == {"type": "Vector", "xyz": [0, 0, 1]}
    assert [str(w) for w in graph.wires] == ["height.Value → cyl.Height"]
    solver = Solver(graph)
    solver.solve()
    assert solver.result("height").state == "ok"
    assert solver.result("height").output("Value").to_dict() == {"{0}": [3.0]}
    assert solver.result("cyl").state == "missing"
    assert graphfile.dumps(graph) == text


@pytest.mark.skipif(not SPEC.exists(), reason="shared/spec is not next to this checkout")
def test_spec_example_fixture_is_the_canonical_form_of_the_json_in_the_spec(registry):
    block = re.search(r"```json\n(.*?)```", SPEC.read_text(encoding="utf-8"), re.S)
    assert block is not None
    canonical = graphfile.encode(json.loads(block.group(1)))
    assert canonical == read("engine-spec-example.graph")
    assert graphfile.dumps(graphfile.loads(canonical, registry)) == canonical


def test_modifiers_and_persistent_values_round_trip_through_a_file(registry, tmp_path):
    graph = graphfile.loads(read("engine-basic.graph"), registry)
    graph.set_modifiers("sum", "A", ["flatten", "simplify"])
    graph.set_input_value("series", "Step", {"type": "Vector", "xyz": [0.1, 0.2, 0.3]})
    path = tmp_path / "edited.graph"
    graphfile.write_graph(graph, path)
    again = graphfile.read_graph(path, registry)
    assert again.nodes["sum"].inputs["A"].modifiers == ["flatten", "simplify"]
    assert again.nodes["series"].inputs["Step"].value == {"type": "Vector", "xyz": [0.1, 0.2, 0.3]}
    assert graphfile.dumps(again) == path.read_text(encoding="utf-8")


def test_basic_fixture_solves_as_expected(registry):
    graph = graphfile.loads(read("engine-basic.graph"), registry)
    solver = Solver(graph)
    solver.solve()
    out = {n: solver.result(n) for n in graph.nodes}
    # B is grafted to {0;0}: [4.5]; both inputs have one branch, so A (the first) is the
    # master input and the result takes A's path
    assert out["sum"].output("Result").to_dict() == {"{0}": [7.5]}
    assert out["len"].output("Length").to_dict() == {"{0}": [3], "{1}": [1]}
    assert out["values"].output("Length").to_dict() == {"{0}": [8]}
    # one call in the branch: the engine keeps the list at {0} (see test_matching.py)
    assert out["series"].output("Series").to_dict() == {"{0}": [-1.0, 0.0, 1.0, 2.0, 3.0]}
    assert out["vars"].state == "ok"
    assert out["off"].state == "disabled"
    assert graph.units == "mm"


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


# --------------------------------------------------------------------------- saving


def test_write_graph_creates_a_new_file_without_a_backup(registry, tmp_path):
    graph = graphfile.loads(read("engine-basic.graph"), registry)
    path = tmp_path / "new.graph"
    graphfile.write_graph(graph, path)
    assert path.read_text(encoding="utf-8") == read("engine-basic.graph")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["new.graph"]


def test_write_graph_keeps_the_previous_content_as_bak(registry, tmp_path):
    path = tmp_path / "design.graph"
    first = graphfile.loads(read("engine-basic.graph"), registry)
    graphfile.write_graph(first, path)
    first.set_setting("height", "value", 6.0)
    graphfile.write_graph(first, path)
    backup = tmp_path / "design.graph.bak"
    assert backup.read_text(encoding="utf-8") == read("engine-basic.graph")
    assert json.loads(path.read_text(encoding="utf-8"))["nodes"][0]["settings"]["value"] == 6.0
    # a third save moves the second version into the backup
    second = path.read_bytes()
    first.set_setting("height", "value", 7.0)
    graphfile.write_graph(first, path)
    assert backup.read_bytes() == second
    assert no_temporaries(tmp_path) == []


@pytest.mark.parametrize("failing", ["replace", "fsync"])
def test_a_failure_mid_save_leaves_the_original_untouched_and_no_temporary_files(
    registry, tmp_path, monkeypatch, failing
):
    path = tmp_path / "design.graph"
    original = read("engine-spec-example.graph").encode("utf-8")
    path.write_bytes(original)
    graph = graphfile.loads(read("engine-basic.graph"), registry)

    def boom(*args, **kwargs):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, failing, boom)
    with pytest.raises(OSError, match="No space left"):
        graphfile.write_graph(graph, path)
    monkeypatch.undo()
    assert path.read_bytes() == original
    assert no_temporaries(tmp_path) == []
    assert set(p.name for p in tmp_path.iterdir()) <= {"design.graph", "design.graph.bak"}
    # and the next save works
    graphfile.write_graph(graph, path)
    assert path.read_text(encoding="utf-8") == read("engine-basic.graph")


def test_an_interrupted_save_leaves_no_temporary_files(registry, tmp_path, monkeypatch):
    path = tmp_path / "design.graph"
    graph = graphfile.loads(read("engine-basic.graph"), registry)

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(os, "replace", interrupted)
    with pytest.raises(KeyboardInterrupt):
        graphfile.write_graph(graph, path)
    assert not path.exists()
    assert no_temporaries(tmp_path) == []


def test_an_unsaveable_graph_does_not_touch_the_file(registry, tmp_path):
    path = tmp_path / "design.graph"
    original = read("engine-basic.graph").encode("utf-8")
    path.write_bytes(original)
    graph = graphfile.loads(original, registry)
    graph.set_setting("height", "value", float("nan"))  # JSON cannot hold NaN
    with pytest.raises(GraphFileError):
        graphfile.write_graph(graph, path)
    assert path.read_bytes() == original
    assert sorted(p.name for p in tmp_path.iterdir()) == ["design.graph"]


def test_saving_keeps_the_files_permissions(registry, tmp_path):
    path = tmp_path / "shared.graph"
    path.write_text(read("engine-spec-example.graph"), encoding="utf-8")
    os.chmod(path, 0o644)
    graphfile.write_graph(graphfile.loads(path.read_bytes(), registry), path)
    assert os.stat(path).st_mode & 0o777 == 0o644


def test_read_graph_errors_are_graph_file_errors(registry, tmp_path):
    with pytest.raises(GraphFileError, match="cannot read"):
        graphfile.read_graph(tmp_path / "absent.graph", registry)
    with pytest.raises(GraphFileError):
        graphfile.read_graph(tmp_path, registry)  # a directory
    big = tmp_path / "big.graph"
    with open(big, "wb") as stream:
        stream.truncate(graphfile.MAX_FILE_BYTES + 1)  # sparse: cheap to make
    with pytest.raises(GraphFileError, match="64 MB"):
        graphfile.read_graph(big, registry)


# --------------------------------------------------------------------------- load cost


def chain_text(count: int) -> str:
    nodes = [{"id": f"n{i}", "type": "maths.Add", "position": [0.0, 0.0]} for i in range(count)]
    wires = [{"from": [f"n{i}", "Result"], "to": [f"n{i + 1}", "A"]} for i in range(count - 1)]
    return graphfile.encode(
        {"format": "torsal.graph", "version": 1, "nodes": nodes, "wires": wires, "groups": [], "meta": {}}
    )


def test_a_500_node_chain_loads_and_round_trips(registry):
    text = chain_text(500)
    graph = graphfile.loads(text, registry)
    assert graphfile.dumps(graph) == text
    solver = Solver(graph)
    assert len(solver.solve().solved) == 500


def calls_made(function: Callable[[], object]) -> int:
    """How many Python and C functions ``function()`` calls: a count of its work that,
    unlike its time, the machine's load cannot change."""
    calls = 0

    def count(frame: object, event: str, arg: object) -> None:
        nonlocal calls
        if event in ("call", "c_call"):
            calls += 1

    sys.setprofile(count)
    try:
        function()
    finally:
        sys.setprofile(None)
    return calls


@pytest.mark.timeout(60)
def test_loading_scales_linearly_with_the_number_of_wires(registry):
    """Twice the wires, twice the work: a search of the wires per wire (a loop check, a
    list lookup) made it about 4×. The time is benchmarked in bench_graphfile.py."""
    small, large = chain_text(1000), chain_text(2000)
    graphfile.loads(small, registry)  # first-use work (imports, caches) is not counted
    ratio = calls_made(lambda: graphfile.loads(large, registry)) / calls_made(
        lambda: graphfile.loads(small, registry)
    )
    assert ratio < 2.2


# --------------------------------------------------------------------------- bounded reading


class CountingDecoder:
    """Stands in for the full-document decoder and counts its uses."""

    def __init__(self, decoder):
        self.decoder, self.calls = decoder, 0

    def decode(self, content):
        self.calls += 1
        return self.decoder.decode(content)


@pytest.fixture
def full_parses(monkeypatch) -> CountingDecoder:
    counter = CountingDecoder(graphfile._DOCUMENT)
    monkeypatch.setattr(graphfile, "_DOCUMENT", counter)
    return counter


def bulky(version: object, where: str = "sorted") -> bytes:
    """A graph of 20,000 nodes (~1 MB) whose ``version`` stands after the nodes (as in a saved
    file, whose keys are sorted), first, or between the other top-level fields."""
    nodes = [{"id": f"n{i}", "type": "maths.Add", "position": [1.5, 2.5]} for i in range(20_000)]
    fields = {"format": "torsal.graph", "meta": {"version": 1}, "nodes": nodes, "version": version}
    order = {
        "sorted": ["format", "meta", "nodes", "version"],
        "first": ["version", "nodes", "format", "meta"],
        "middle": ["nodes", "version", "meta", "format"],
    }[where]
    return json.dumps({key: fields[key] for key in order}).encode("utf-8")


@pytest.mark.parametrize("where", ["sorted", "first", "middle"])
def test_a_newer_version_is_refused_before_the_file_is_parsed(registry, full_parses, where):
    with pytest.raises(NewerVersionError, match="version 99"):
        graphfile.loads(bulky(99, where), registry)
    assert full_parses.calls == 0


def test_a_current_version_goes_on_to_the_full_parse(registry, full_parses):
    graph = graphfile.loads(bulky(1), registry)
    assert len(graph.nodes) == 20_000
    assert full_parses.calls == 1


def test_a_version_key_inside_the_document_is_not_the_files_version(registry):
    text = json.dumps({"format": "torsal.graph", "meta": {"version": 99}, "nodes": [], "version": 1})
    assert graphfile.loads(text, registry).meta == {"version": 99}


@pytest.mark.parametrize(
    "content",
    [
        b"[1, 2, 3]",
        b'"torsal.graph"',
        b'{"format": "other.app", "version": 1, "nodes": []}',
        b'{"nodes": []}',
    ],
    ids=["list", "string", "foreign format", "no format"],
)
def test_a_document_that_is_not_a_torsal_graph_is_refused_before_the_full_parse(
    registry, full_parses, content
):
    with pytest.raises(GraphFileError, match="not a Torsal graph file"):
        graphfile.loads(content, registry)
    assert full_parses.calls == 0


def test_text_that_is_not_json_is_still_reported_as_not_json(registry):
    with pytest.raises(GraphFileError, match="not valid JSON"):
        graphfile.loads(b'{"format": "torsal.graph", "version": 1, "nodes": [', registry)


NUMBER_TOKENS = [
    "1e308", "-1e308", "1.7976931348623157e308", "5e-324", "2.2250738585072014e-308", "1e23",
    "0.1", "-0.0", "1E5", "123456789012345678901234567890", "1e-400", "0." + "3" * 400,
]


def test_every_number_decodes_to_the_float_the_json_module_reads(registry):
    tokens = ", ".join(NUMBER_TOKENS)
    text = f'{{"format": "torsal.graph", "version": 1, "nodes": [], "meta": {{"x": [{tokens}]}}}}'
    expected = json.loads(text)["meta"]["x"]
    got = graphfile.loads(text, registry).meta["x"]
    assert [repr(v) for v in got] == [repr(v) for v in expected]  # repr tells -0.0 from 0.0


@pytest.mark.parametrize("token", ["1e400", "-1e309", "1" + "0" * 400 + ".0"])
def test_a_number_too_large_for_a_float_is_refused(registry, token):
    text = (
        '{"format": "torsal.graph", "version": 1, "nodes": '
        f'[{{"id": "a", "type": "maths.Add", "inputs": {{"A": {{"value": [[1.5, {token}]]}}}}}}]}}'
    )
    with pytest.raises(GraphFileError, match="number Torsal cannot read"):
        graphfile.loads(text, registry)


def numbers_file(token: str, count: int) -> bytes:
    items = ", ".join([token] * count)
    return f'{{"format": "torsal.graph", "version": 1, "nodes": [], "meta": {{"x": [{items}]}}}}'.encode()


@pytest.mark.parametrize("token", ["1", "1.5", "1e308"])
def test_no_python_work_is_done_per_number(registry, token):
    """A thousand times the numbers, the same Python calls: each number is decoded,
    checked and copied in C. (How the time grows is benchmarked in bench_graphfile.py.)"""
    few, many = numbers_file(token, 100), numbers_file(token, 100_000)
    graphfile.loads(few, registry)  # first-use work is not counted
    assert calls_made(lambda: graphfile.loads(many, registry)) <= calls_made(
        lambda: graphfile.loads(few, registry)
    ) + 10


def test_nesting_depth_counts_levels_of_lists_and_objects():
    assert graphfile.nesting_depth(1) == 0
    assert graphfile.nesting_depth([]) == 1
    assert graphfile.nesting_depth({"a": [1, {"b": [2.0]}], "c": 3}) == 4
    assert graphfile.nesting_depth([[1]] * 10 + [[[[]]]]) == 4


def test_a_file_nested_past_the_limit_is_refused(registry):
    value = "1"
    for _ in range(graphfile.MAX_DEPTH):
        value = f"[{value}]"
    text = f'{{"format": "torsal.graph", "version": 1, "nodes": [], "meta": {{"x": {value}}}}}'
    with pytest.raises(GraphFileError, match=f"nested more than {graphfile.MAX_DEPTH} levels"):
        graphfile.loads(text, registry)


@pytest.mark.timeout(20)
@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes here")
def test_read_graph_refuses_a_named_pipe_at_once(registry, tmp_path):
    fifo = tmp_path / "pipe.graph"
    os.mkfifo(fifo)
    with pytest.raises(GraphFileError, match=r"it is a named pipe \(FIFO\), not a graph file"):
        graphfile.read_graph(fifo, registry)


@pytest.mark.timeout(20)
@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes here")
def test_write_graph_does_not_replace_a_named_pipe(registry, tmp_path):
    fifo = tmp_path / "pipe.graph"
    os.mkfifo(fifo)
    graph = graphfile.loads(read("engine-basic.graph"), registry)
    with pytest.raises(OSError, match="named pipe"):
        graphfile.write_graph(graph, fifo)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["pipe.graph"]
