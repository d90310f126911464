"""Hand-made hostile ``.graph`` files for the fuzz corpus, each with the outcomes allowed
(refused, loaded or newer): not graphs at all, NaN and huge numbers, deep nesting, long
strings, cycles, dangling wires, duplicates, unknown types, versions, encodings."""

from __future__ import annotations

import json
from typing import Any

from tests.support.graphfile_fuzz_harness import deep_array, deep_object


def file_with(**changes: Any) -> dict:
    data = {
        "format": "torsal.graph",
        "version": 1,
        "nodes": [
            {"id": "s", "type": "params.NumberSlider", "position": [0.0, 0.0], "settings": {"value": 2.0}},
            {"id": "a", "type": "maths.Add", "position": [100.0, 0.0]},
            {"id": "b", "type": "maths.Add", "position": [200.0, 0.0]},
            {"id": "c", "type": "maths.Add", "position": [300.0, 0.0]},
            {"id": "len", "type": "lists.ListLength", "position": [400.0, 0.0]},
            {"id": "p", "type": "plugin.Missing", "position": [500.0, 0.0]},
            {"id": "q", "type": "plugin.Missing", "position": [600.0, 0.0]},
            {"id": "pt", "type": "params.Point", "position": [0.0, 100.0]},
        ],
        "wires": [
            {"from": ["s", "Value"], "to": ["a", "A"]},
            {"from": ["a", "Result"], "to": ["b", "A"]},
            {"from": ["b", "Result"], "to": ["c", "A"]},
        ],
        "groups": [],
        "meta": {},
    }
    for key, value in changes.items():
        if key == "extra_wires":
            data["wires"] += value
        elif key == "extra_nodes":
            data["nodes"] += value
        elif key == "node0":
            data["nodes"][0].update(value)
        else:
            data[key] = value
    return data


def wire(source: str, source_port: str, target: str, target_port: str) -> dict:
    return {"from": [source, source_port], "to": [target, target_port]}


def chain(count: int, cyclic: bool) -> dict:
    nodes = [{"id": f"n{i}", "type": "maths.Add", "position": [0.0, 0.0]} for i in range(count)]
    wires = [wire(f"n{i}", "Result", f"n{i + 1}", "A") for i in range(count - 1)]
    if cyclic:
        wires.append(wire(f"n{count - 1}", "Result", "n0", "A"))
    return {"format": "torsal.graph", "version": 1, "nodes": nodes, "wires": wires}


HEAD = b'{"format": "torsal.graph", "version": 1, '
REFUSED, LOADED, NEWER = {"refused"}, {"loaded"}, {"newer"}
NODE0_RAW = '{"id": "s", "type": "params.NumberSlider", "position": [0.0, 0.0], "settings": {"value": '

SPECIAL_FILES: dict[str, tuple[bytes | str | dict, set[str]]] = {
    # not a graph at all
    "empty file": (b"", REFUSED),
    "whitespace only": (b" \n\t\r\n", REFUSED),
    "top-level array": (b"[]", REFUSED),
    "top-level array of graphs": (b'[{"format": "torsal.graph", "version": 1, "nodes": []}]', REFUSED),
    "top-level number": (b"42", REFUSED),
    "top-level huge number": (b"1e400", REFUSED),
    "top-level string": (b'"torsal.graph"', REFUSED),
    "top-level null": (b"null", REFUSED),
    "top-level true": (b"true", REFUSED),
    "empty object": (b"{}", REFUSED),
    "format only": (b'{"format": "torsal.graph"}', REFUSED),
    "no nodes": (b'{"format": "torsal.graph", "version": 1}', REFUSED),
    "wrong format": ({"format": "torsal.graph2", "version": 1, "nodes": []}, REFUSED),
    "format in wrong case": ({"format": "Torsal.Graph", "version": 1, "nodes": []}, REFUSED),
    "minimal graph": ({"format": "torsal.graph", "version": 1, "nodes": []}, LOADED),
    "two documents": (b'{"format": "torsal.graph", "version": 1, "nodes": []} {}', REFUSED),
    "trailing comma": (b'{"format": "torsal.graph", "version": 1, "nodes": [],}', REFUSED),
    "comment": (b'{"format": "torsal.graph", "version": 1, // hi\n "nodes": []}', REFUSED),
    "single quotes": (b"{'format': 'torsal.graph', 'version': 1, 'nodes': []}", REFUSED),
    "duplicate keys, last wins": (
        b'{"format": "x", "format": "torsal.graph", "version": 1, "nodes": []}',
        LOADED,
    ),
    # NaN / Infinity literals
    "NaN version": (b'{"format": "torsal.graph", "version": NaN, "nodes": []}', REFUSED),
    "NaN setting": (
        b'{"format": "torsal.graph", "version": 1, "nodes": [' + NODE0_RAW.encode() + b"NaN}}]}",
        REFUSED,
    ),
    "Infinity setting": (
        b'{"format": "torsal.graph", "version": 1, "nodes": [' + NODE0_RAW.encode() + b"Infinity}}]}",
        REFUSED,
    ),
    "-Infinity position": (
        HEAD + b'"nodes": [{"id": "a", "type": "maths.Add", "position": [-Infinity, 0]}]}',
        REFUSED,
    ),
    "nan lowercase in meta": (
        b'{"format": "torsal.graph", "version": 1, "nodes": [], "meta": {"a": nan}}',
        REFUSED,
    ),
    # huge numbers
    "1e308 setting": (file_with(node0={"settings": {"value": 1e308}}), LOADED),
    "-1e308 setting": (file_with(node0={"settings": {"value": -1e308}}), LOADED),
    "5e-324 setting": (file_with(node0={"settings": {"value": 5e-324}}), LOADED),
    "1e400 setting": (
        b'{"format": "torsal.graph", "version": 1, "nodes": [' + NODE0_RAW.encode() + b"1e400}}]}",
        REFUSED,
    ),
    "1e400 version": (b'{"format": "torsal.graph", "version": 1e400, "nodes": []}', REFUSED),
    "10**400 setting": (file_with(node0={"settings": {"value": 10**400}}), LOADED),
    "-10**400 setting": (file_with(node0={"settings": {"value": -(10**400)}}), LOADED),
    "10**400 decimals": (file_with(node0={"settings": {"decimals": 10**400}}), LOADED),
    "10**400 position": (file_with(node0={"position": [10**400, 0]}), REFUSED),
    "1e308 position": (file_with(node0={"position": [1e308, 0.0]}), REFUSED),
    "10**400 version": ({"format": "torsal.graph", "version": 10**400, "nodes": []}, NEWER),
    "-10**400 version": ({"format": "torsal.graph", "version": -(10**400), "nodes": []}, REFUSED),
    "4400-digit integer": (
        b'{"format": "torsal.graph", "version": 1, "nodes": [], "meta": {"n": 1' + b"0" * 4400 + b"}}",
        REFUSED,
    ),
    "huge input value": (
        file_with(
            extra_nodes=[
                {"id": "big", "type": "maths.Add", "inputs": {"A": {"value": [10**400, 1e308, -1e308]}}}
            ]
        ),
        LOADED,
    ),
    # deep nesting
    "100,000 nested arrays": (deep_array(100_000).encode(), REFUSED),
    "100,000 nested objects": (deep_object(100_000).encode(), REFUSED),
    "100,000 nested arrays in a setting": (
        b'{"format": "torsal.graph", "version": 1, "nodes": ['
        + NODE0_RAW.encode()
        + deep_array(100_000).encode()
        + b"}}]}",
        REFUSED,
    ),
    "100,000 nested arrays in an input value": (
        HEAD
        + b'"nodes": [{"id": "a", "type": "maths.Add", "inputs": {"A": {"value": '
        + deep_array(100_000).encode()
        + b"}}}]}",
        REFUSED,
    ),
    "100,000 nested objects in meta": (
        b'{"format": "torsal.graph", "version": 1, "nodes": [], "meta": '
        + deep_object(100_000).encode()
        + b"}",
        REFUSED,
    ),
    "unclosed 100,000 arrays": (b"[" * 100_000, REFUSED),
    "20 nested arrays in a setting": (
        file_with(node0={"settings": {"value": json.loads(deep_array(20))}}),
        LOADED,
    ),
    "50 nested arrays in an input value": (
        file_with(
            extra_nodes=[
                {
                    "id": "d",
                    "type": "lists.ListLength",
                    "inputs": {"List": {"value": json.loads(deep_array(50))}},
                }
            ]
        ),
        LOADED,
    ),
    # long strings and big files
    "1 MB label": (file_with(node0={"label": "L" * 1_000_000}), LOADED),
    "10 MB setting text": (file_with(node0={"settings": {"value": "v" * 10_000_000}}), LOADED),
    "1 MB meta key": (
        {"format": "torsal.graph", "version": 1, "nodes": [], "meta": {"k" * 1_000_000: 1}},
        LOADED,
    ),
    "200-character id": (file_with(node0={"id": "i" * 200}, wires=[]), LOADED),
    "201-character id": (file_with(node0={"id": "i" * 201}, wires=[]), REFUSED),
    "10,000-character type": (file_with(node0={"type": "t" * 10_000}), REFUSED),
    "1 MB port name": (file_with(extra_wires=[wire("c", "R" * 1_000_000, "p", "In")]), REFUSED),
    "5,000 nodes": (
        {
            "format": "torsal.graph",
            "version": 1,
            "nodes": [{"id": f"n{i}", "type": "maths.Add"} for i in range(5_000)],
        },
        LOADED,
    ),
    "200-node chain": (chain(200, cyclic=False), LOADED),
    # cycles
    "self loop": (file_with(extra_wires=[wire("len", "Length", "len", "List")]), REFUSED),
    "self loop on an item input": (file_with(wires=[wire("a", "Result", "a", "A")]), REFUSED),
    "two-node cycle": (
        file_with(wires=[wire("a", "Result", "b", "A"), wire("b", "Result", "a", "A")]),
        REFUSED,
    ),
    "three-node cycle": (file_with(extra_wires=[wire("c", "Result", "a", "B")]), REFUSED),
    "cycle through placeholders": (
        file_with(
            extra_wires=[
                wire("c", "Result", "p", "In"),
                wire("p", "Out", "q", "In"),
                wire("q", "Out", "a", "B"),
            ]
        ),
        REFUSED,
    ),
    "placeholder self loop": (file_with(extra_wires=[wire("p", "Out", "p", "In")]), REFUSED),
    "200-node cycle": (chain(200, cyclic=True), REFUSED),
    # dangling wires
    "wire from a missing node": (file_with(extra_wires=[wire("ghost", "Value", "b", "B")]), REFUSED),
    "wire to a missing node": (file_with(extra_wires=[wire("s", "Value", "ghost", "A")]), REFUSED),
    "wire from a missing output": (file_with(extra_wires=[wire("s", "Nope", "b", "B")]), REFUSED),
    "wire to a missing input": (file_with(extra_wires=[wire("s", "Value", "b", "Nope")]), REFUSED),
    "wire to an output": (file_with(extra_wires=[wire("s", "Value", "b", "Result")]), REFUSED),
    "wire from an input": (file_with(extra_wires=[wire("b", "B", "c", "B")]), REFUSED),
    "wire with empty ends": (file_with(extra_wires=[{"from": [], "to": []}]), REFUSED),
    "wire with one-element ends": (file_with(extra_wires=[{"from": ["s"], "to": ["b"]}]), REFUSED),
    "wire with three-element ends": (
        file_with(extra_wires=[{"from": ["s", "Value", "x"], "to": ["b", "B", "y"]}]),
        REFUSED,
    ),
    "wire ends as strings": (file_with(extra_wires=[{"from": "s.Value", "to": "b.B"}]), REFUSED),
    "wire without to": (file_with(extra_wires=[{"from": ["s", "Value"]}]), REFUSED),
    "wire with empty port": (file_with(extra_wires=[wire("s", "", "b", "B")]), REFUSED),
    "wire to a placeholder's unknown port": (
        file_with(extra_wires=[wire("c", "Result", "p", "Anything")]),
        LOADED,
    ),
    "wire from a placeholder into a real input": (
        file_with(extra_wires=[wire("p", "Out", "b", "B")]),
        LOADED,
    ),
    "Point into a Number input": (file_with(extra_wires=[wire("pt", "Point", "b", "B")]), REFUSED),
    "Point into a Generic list input": (file_with(extra_wires=[wire("pt", "Point", "len", "List")]), LOADED),
    # duplicates
    "duplicate node ids": (file_with(extra_nodes=[{"id": "a", "type": "maths.Add"}]), REFUSED),
    "duplicate ids of different types": (
        file_with(extra_nodes=[{"id": "s", "type": "plugin.Other"}]),
        REFUSED,
    ),
    "duplicate wire": (file_with(extra_wires=[wire("s", "Value", "a", "A")]), REFUSED),
    "two wires into an item input": (file_with(extra_wires=[wire("s", "Value", "b", "A")]), REFUSED),
    "two wires into a list input": (
        file_with(extra_wires=[wire("s", "Value", "len", "List"), wire("a", "Result", "len", "List")]),
        LOADED,
    ),
    "duplicate group ids": (
        file_with(groups=[{"id": "g", "nodes": ["a"]}, {"id": "g", "nodes": ["b"]}]),
        LOADED,
    ),
    "group of missing nodes": (file_with(groups=[{"id": "g", "nodes": ["ghost", "a", "a"]}]), LOADED),
    # unknown types
    "unknown type": (file_with(node0={"type": "plugin.Unknown"}, wires=[]), LOADED),
    "type without a palette": (file_with(node0={"type": "NoDot"}, wires=[]), LOADED),
    "empty type": (file_with(node0={"type": ""}), REFUSED),
    "type in wrong case": (file_with(node0={"type": "params.numberslider"}, wires=[]), LOADED),
    "unknown modifier": (
        file_with(extra_nodes=[{"id": "m", "type": "maths.Add", "inputs": {"A": {"modifiers": ["sort"]}}}]),
        REFUSED,
    ),
    "unknown units": (file_with(units="km"), REFUSED),
    "settings-defined ports": (
        file_with(
            extra_nodes=[{"id": "v", "type": "maths.Variables", "settings": {"variables": ["u", "w"]}}],
            extra_wires=[wire("c", "Result", "v", "w")],
        ),
        LOADED,
    ),
    "wire to a port the settings do not define": (
        file_with(
            extra_nodes=[{"id": "v", "type": "maths.Variables", "settings": {"variables": ["u"]}}],
            extra_wires=[wire("c", "Result", "v", "x")],
        ),
        REFUSED,
    ),
    "settings a node rejects": (
        file_with(extra_nodes=[{"id": "v", "type": "maths.Variables", "settings": {"variables": 7}}]),
        REFUSED,
    ),
    "malformed encoded input value": (
        file_with(
            extra_nodes=[{"id": "m", "type": "maths.Add", "inputs": {"A": {"value": {"type": "Point"}}}}]
        ),
        LOADED,
    ),
    "unknown encoded value type": (
        file_with(
            extra_nodes=[{"id": "m", "type": "maths.Add", "inputs": {"A": {"value": {"type": "Nope"}}}}]
        ),
        LOADED,
    ),
    "node that raises": (file_with(extra_nodes=[{"id": "f", "type": "debug.Fail"}]), LOADED),
    # versions
    "version 2": ({"format": "torsal.graph", "version": 2, "nodes": []}, NEWER),
    "version 999 with unknown shape": (
        {"format": "torsal.graph", "version": 999, "nodes": "new shape"},
        NEWER,
    ),
    "version -1": ({"format": "torsal.graph", "version": -1, "nodes": []}, REFUSED),
    "version as text": ({"format": "torsal.graph", "version": "1", "nodes": []}, REFUSED),
    "version 1.0": ({"format": "torsal.graph", "version": 1.0, "nodes": []}, REFUSED),
    "version true": ({"format": "torsal.graph", "version": True, "nodes": []}, REFUSED),
    "version 0 minimal": ({"format": "torsal.graph", "version": 0, "nodes": []}, LOADED),
    "version 0 with null nodes": ({"format": "torsal.graph", "version": 0, "nodes": None}, REFUSED),
    "version 0 with numeric wires": (
        {"format": "torsal.graph", "version": 0, "nodes": [], "wires": 5},
        REFUSED,
    ),
    "version 0 wire to a bare id": (
        {
            "format": "torsal.graph",
            "version": 0,
            "nodes": [{"id": "a", "type": "maths.Add"}],
            "wires": [{"source": "a", "target": "a"}],
        },
        REFUSED,
    ),
    # encodings
    "latin-1 label": (
        HEAD + b'"nodes": [{"id": "a", "type": "maths.Add", "label": "caf\xe9"}]}',
        REFUSED,
    ),
    "0xff in an id": (
        b'{"format": "torsal.graph", "version": 1, "nodes": [{"id": "\xff", "type": "maths.Add"}]}',
        REFUSED,
    ),
    "encoded surrogate bytes": (
        b'{"format": "torsal.graph", "version": 1, "nodes": [], "meta": {"a": "\xed\xa0\x80"}}',
        REFUSED,
    ),
    "0xff outside strings": (b'{"format": "torsal.graph", "version": 1, \xff "nodes": []}', REFUSED),
    "UTF-16 file": ('{"format": "torsal.graph", "version": 1, "nodes": []}'.encode("utf-16"), REFUSED),
    "UTF-8 byte order mark": (b'\xef\xbb\xbf{"format": "torsal.graph", "version": 1, "nodes": []}', LOADED),
    "lone surrogate escape": (
        b'{"format": "torsal.graph", "version": 1, "nodes": [], "meta": {"a": "\\ud800"}}',
        REFUSED,
    ),
    "escaped surrogate pair": (
        b'{"format": "torsal.graph", "version": 1, "nodes": [], "meta": {"a": "\\ud83d\\ude00"}}',
        LOADED,
    ),
    "NUL characters": (file_with(node0={"label": "a\x00b"}, meta={"\x00": "\x00"}), LOADED),
    "text with a lone surrogate": (
        '{"format": "torsal.graph", "version": 1, "nodes": [], "meta": {"a": "\ud800"}}',
        REFUSED,
    ),
}
