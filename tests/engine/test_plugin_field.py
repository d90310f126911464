"""The node record's ``plugin`` field (docs/graph-format.md): written for a plug-in's node
when saving, kept by a placeholder, named in the placeholder's message, checked on reading."""

from __future__ import annotations

import json
import types

import pytest

from tests.support.nodekit import NumberSlider
from torsal.engine import graphfile
from torsal.engine import registry as registry_module
from torsal.engine.graph import Graph
from torsal.engine.node import Node, Out
from torsal.engine.registry import Registry
from torsal.engine.solver import Solver
from torsal.engine.types import NUMBER

FILE = {"format": "torsal.graph", "version": 1, "nodes": [
    {"id": "w", "type": "waves.Wave", "plugin": "torsal-waves", "settings": {"keep": [1, 2]}}]}


class Tile(Node):
    """A plug-in's node."""

    type_id = "tiles.Tile"
    outputs = (Out("Value", NUMBER, "V", "One."),)

    def solve(self) -> float:
        return 1.0


def test_a_plugin_node_is_saved_with_its_distribution_and_a_built_in_without(monkeypatch):
    dist = types.SimpleNamespace(name="torsal-tiles")
    entry = types.SimpleNamespace(name="tiles", load=lambda: Tile, dist=dist)
    monkeypatch.setattr(registry_module, "entry_points", lambda group: [entry])
    registry = Registry()
    registry.register(NumberSlider)
    registry.load_entry_points()
    graph = Graph()
    graph.add_node(registry.create("tiles.Tile"), "t")
    graph.add_node(NumberSlider(), "s")
    nodes = {n["id"]: n for n in json.loads(graphfile.dumps(graph))["nodes"]}
    assert nodes["t"]["plugin"] == "torsal-tiles"
    assert "plugin" not in nodes["s"]


def test_a_placeholder_keeps_the_field_and_its_message_names_the_package():
    graph = graphfile.loads(json.dumps(FILE), Registry())
    saved = graphfile.dumps(graph)
    assert json.loads(saved)["nodes"][0]["plugin"] == "torsal-waves"
    assert graphfile.dumps(graphfile.loads(saved, Registry())) == saved  # and kept byte for byte
    solver = Solver(graph)
    solver.solve()
    (message,) = solver.result("w").messages
    assert message.text == ("node type 'waves.Wave' is not installed (it comes from the plug-in package "
                            "'torsal-waves'); its data is kept as it is")


@pytest.mark.parametrize("bad", [5, "", ["torsal-waves"], "x" * 201])
def test_a_plugin_field_that_is_not_a_distribution_name_is_refused(bad):
    data = json.loads(json.dumps(FILE))
    data["nodes"][0]["plugin"] = bad
    with pytest.raises(graphfile.GraphFileError):
        graphfile.loads(json.dumps(data), Registry())
