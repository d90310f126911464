"""Graph files the fuzz corpus once broke the loader with — non-UTF-8 text, nesting deep
enough to overflow the stack, malformed version-0 files — and the messages a refused file
gets: each refused with :class:`GraphFileError`, a message saying what is wrong."""

from __future__ import annotations

import json

import pytest

from tests.support.graphfile_fuzz_harness import REGISTRY, deep_array
from tests.support.hostile_graph_files import HEAD, SPECIAL_FILES
from torsal.engine import graphfile
from torsal.engine.graph import PlaceholderNode
from torsal.engine.graphfile import MAX_DEPTH, GraphFileError
from torsal.engine.solver import Solver


def test_cycle_and_dangling_wire_messages_say_what_is_wrong():
    cases = {
        "two-node cycle": "loop",
        "wire from a missing node": "ghost",
        "wire to a missing input": "Nope",
        "duplicate node ids": "'a'",
        "Point into a Number input": "Point",
        "unknown units": "units",
    }
    for name, needle in cases.items():
        content = json.dumps(SPECIAL_FILES[name][0])
        with pytest.raises(GraphFileError) as caught:
            graphfile.loads(content, REGISTRY)
        assert needle in str(caught.value), (name, str(caught.value))


def test_placeholders_in_the_corpus_really_are_placeholders():
    graph = graphfile.loads(json.dumps(SPECIAL_FILES["unknown type"][0]), REGISTRY)
    assert isinstance(graph.nodes["s"].node, PlaceholderNode)
    solver = Solver(graph)
    solver.solve()
    assert solver.result("s").state == "missing"


@pytest.mark.parametrize(
    "content",
    [
        HEAD + b'"nodes": [{"id": "a", "type": "maths.Add", "label": "caf\xe9"}]}',
        '{"format": "torsal.graph", "version": 1, "nodes": [], "meta": {"a": "\ud800"}}',
    ],
    ids=["latin-1-bytes", "str-with-lone-surrogate"],
)
def test_invalid_utf8_is_a_graph_file_error(content):
    with pytest.raises(GraphFileError):
        graphfile.loads(content, REGISTRY)


def nested_setting(levels: int) -> str:
    """A one-node file whose setting is ``levels`` nested lists: the file is ``levels + 4``
    deep (file, nodes, node, settings, then the lists)."""
    return (
        '{"format": "torsal.graph", "version": 1, "nodes": [{"id": "a", "type": "plugin.X", '
        '"settings": {"v": ' + deep_array(levels) + "}}]}"
    )


@pytest.mark.parametrize("levels", [400, 600, 900, 5_000])
def test_deep_but_decodable_nesting_is_a_graph_file_error(levels):
    with pytest.raises(GraphFileError, match="nested"):
        graphfile.loads(nested_setting(levels), REGISTRY)


def test_nesting_to_max_depth_loads_and_one_level_more_is_refused():
    graph = graphfile.loads(nested_setting(MAX_DEPTH - 4), REGISTRY)
    assert graph.nodes["a"].node.settings["v"] == json.loads(deep_array(MAX_DEPTH - 4))
    with pytest.raises(GraphFileError, match=f"nested more than {MAX_DEPTH} levels deep"):
        graphfile.loads(nested_setting(MAX_DEPTH - 3), REGISTRY)


@pytest.mark.parametrize("field,value", [("nodes", None), ("nodes", 3), ("wires", 5), ("wires", None)])
def test_version_0_file_with_non_list_parts_is_a_graph_file_error(field, value):
    data = {"format": "torsal.graph", "version": 0, "nodes": []}
    data[field] = value
    with pytest.raises(GraphFileError):
        graphfile.loads(json.dumps(data), REGISTRY)
