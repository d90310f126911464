"""Reading a ``.graph`` file in bounded work: a newer or foreign file is refused before the
full parse, numbers are decoded in C to the floats ``json`` reads, nesting is capped, and a
named pipe is refused at once.
"""

from __future__ import annotations

import json
import os

import pytest

from tests.support.graphfile_files import (
    calls_made,
)
from torsal.engine import graphfile
from torsal.engine.graphfile import GraphFileError, NewerVersionError

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
