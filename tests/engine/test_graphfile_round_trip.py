"""The ``.graph`` file: exact round trip, unknown fields, placeholders, and a long chain's load
cost. See ``docs/graph-format.md`` and the "Round trip" and "File safety" bars of
issue 2. Versions, saving and bounded reading have their own ``test_graphfile_*.py``; the
hostile-file corpus lives in ``test_graphfile_fuzz.py``.
"""

from __future__ import annotations

import json
import re

import pytest

from tests.support.graphfile_files import (
    ALL_EXAMPLES,
    ALL_FIXTURES,
    ENGINE_FIXTURES,
    SPEC,
    calls_made,
    chain_text,
    read,
)
from tests.support.nodekit import Add, ListLength, NumberSlider
from torsal.engine import graphfile
from torsal.engine.graph import Graph, PlaceholderNode
from torsal.engine.registry import Registry
from torsal.engine.solver import Solver

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


# --------------------------------------------------------------------------- load cost

def test_a_500_node_chain_loads_and_round_trips(registry):
    text = chain_text(500)
    graph = graphfile.loads(text, registry)
    assert graphfile.dumps(graph) == text
    solver = Solver(graph)
    assert len(solver.solve().solved) == 500


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
