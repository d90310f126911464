"""File safety: at least 10,000 generated or mutated ``.graph`` files.

Every case must either load to a valid graph — which then solves, saves, and loads and
saves again to the same text — or raise exactly :class:`GraphFileError` with a message.
Any other exception, or a case that hangs (``CASE_SECONDS``), fails the test.

The cases come from deterministic mutation loops over a seed corpus (truncation at every
byte, byte flips, a wrong value for every field, unknown fields, hostile special files)
and from hypothesis strategies (arbitrary JSON, plausible graphs with wrong types mixed
in, byte edits, canonical graphs that must round-trip exactly). The last test checks
that all of them together ran at least 10,000 cases.

The bugs this corpus once found (non-UTF-8 text, nesting deep enough to overflow the
stack, malformed version-0 files) are guarded by named tests at the end of this module.
"""

from __future__ import annotations

import copy
import json
import random
import time
from collections import Counter
from pathlib import Path
from typing import Any, ClassVar

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from engine import graphfile
from engine.graph import PlaceholderNode
from engine.graphfile import GraphFileError, NewerVersionError
from engine.solver import Solver
from tests.engine.nodekit import NODE_CLASSES, make_registry

REGISTRY = make_registry()
FIXTURES = Path(__file__).resolve().parents[1] / "fixtures"
# A hang guard, not a benchmark: the slowest case (the 5,000-node file, loaded, solved,
# saved, loaded and saved again) takes about 1 s, so 30 s is 30 times that. How the cost
# of loading grows is benchmarked, against a baseline, in tests/benchmarks/bench_graphfile.py.
CASE_SECONDS = 30.0
MINIMUM_CASES = 10_000

V0_SEED = b"""{
  "format": "torsal.graph",
  "version": 0,
  "nodes": [
    {"id": "s", "type": "params.NumberSlider", "x": 10.0, "y": 20.0, "settings": {"value": 2.0}},
    {"id": "add", "type": "maths.Add", "x": 200.0, "y": 20.0, "inputs": {"B": {"value": 1}}},
    {"id": "p", "type": "plugin.Missing", "x": 400.0, "y": 20.0}
  ],
  "wires": [
    {"source": "s.Value", "target": "add.A"},
    {"source": "add.Result", "target": "p.In"}
  ]
}
"""

SEEDS: dict[str, bytes] = {path.name: path.read_bytes() for path in sorted(FIXTURES.glob("engine-*.graph"))}
SEEDS["v0-draft.graph"] = V0_SEED

# per test: outcome counts, seconds, slowest case
STATS: dict[str, Counter] = {}
SECONDS: dict[str, float] = {}
SLOWEST: dict[str, float] = {}
FUZZ_TESTS = {
    "truncation",
    "byte_flips",
    "wrong_field_values",
    "unknown_fields",
    "special_files",
    "hypothesis_json_documents",
    "hypothesis_plausible_graphs",
    "hypothesis_byte_edits",
    "hypothesis_canonical_round_trip",
}


# --------------------------------------------------------------------------- harness



def as_bytes(content: bytes | str) -> bytes:
    return content if isinstance(content, bytes) else content.encode("utf-8", "surrogatepass")


def nesting_depth(content: bytes | str) -> int:
    """The deepest ``[``/``{`` nesting outside strings (works on broken JSON too)."""
    depth = deepest = 0
    in_string = escaped = False
    for byte in as_bytes(content):
        if in_string:
            if escaped:
                escaped = False
            elif byte == 0x5C:
                escaped = True
            elif byte == 0x22:
                in_string = False
        elif byte == 0x22:
            in_string = True
        elif byte in (0x5B, 0x7B):
            depth += 1
            deepest = max(deepest, depth)
        elif byte in (0x5D, 0x7D):
            depth -= 1
    return deepest


def preview(content: bytes | str) -> str:
    data = as_bytes(content)
    return repr(data[:300]) + (f" ... ({len(data)} bytes)" if len(data) > 300 else "")


def unexpected(stage: str, content: bytes | str, exc: BaseException) -> AssertionError:
    return AssertionError(
        f"{stage} raised {type(exc).__name__}: {str(exc)[:300]}\n  for file {preview(content)}"
    )


def outcome_of(content: bytes | str) -> str:
    """``refused``, ``newer`` or ``loaded``; anything else fails."""
    try:
        graph = graphfile.loads(content, REGISTRY)
    except NewerVersionError as exc:
        assert str(exc).strip()
        return "newer"
    except GraphFileError as exc:
        assert str(exc).strip(), f"empty GraphFileError message for {preview(content)}"
        return "refused"
    except Exception as exc:
        raise unexpected("loads", content, exc) from exc
    try:
        report = Solver(graph).solve()
        text = graphfile.dumps(graph)
    except Exception as exc:
        raise unexpected("solve/dumps after a successful load", content, exc) from exc
    assert not report.cancelled
    assert set(report.solved) == set(graph.nodes)
    try:
        again = graphfile.dumps(graphfile.loads(text, REGISTRY))
    except Exception as exc:
        raise unexpected("re-loading a saved file", text, exc) from exc
    assert again == text, f"save → load → save changed the file saved from {preview(content)}"
    return "loaded"


def run_case(name: str, content: bytes | str) -> str:
    started = time.perf_counter()
    outcome = outcome_of(content)
    elapsed = time.perf_counter() - started
    assert elapsed < CASE_SECONDS, f"{elapsed:.1f} s for one file (a hang?): {preview(content)}"
    STATS.setdefault(name, Counter())[outcome] += 1
    SLOWEST[name] = max(SLOWEST.get(name, 0.0), elapsed)
    return outcome


class timed:
    """Adds the wall time of a block to ``SECONDS[name]``."""

    def __init__(self, name: str) -> None:
        self.name = name

    def __enter__(self) -> timed:
        self.started = time.perf_counter()
        return self

    def __exit__(self, *exc: object) -> None:
        SECONDS[self.name] = SECONDS.get(self.name, 0.0) + time.perf_counter() - self.started


def dump(data: Any) -> bytes:
    """JSON text for ``data``; ``Raw`` values are pasted in verbatim (NaN, 1e400 ...)."""
    text = json.dumps(data, default=lambda raw: raw.marker)
    for marker, literal in Raw.literals.items():
        text = text.replace(json.dumps(marker), literal)
    return text.encode("utf-8")


class Raw:
    """A literal that ``json.dumps`` cannot produce, e.g. ``NaN`` or 100,000 open brackets."""

    literals: ClassVar[dict[str, str]] = {}

    def __init__(self, literal: str) -> None:
        self.marker = f"@@raw{len(Raw.literals)}@@"
        Raw.literals[self.marker] = literal

    def __repr__(self) -> str:
        literal = Raw.literals[self.marker]
        return f"Raw({literal[:20]!r}{'...' if len(literal) > 20 else ''})"


def deep_array(levels: int) -> str:
    return "[" * levels + "]" * levels


def deep_object(levels: int) -> str:
    return '{"a":' * levels + "1" + "}" * levels


DELETE = object()
WRONG_VALUES: list[Any] = [
    DELETE,
    None,
    True,
    0,
    -1,
    2.5,
    1e308,
    5e-324,
    10**400,
    "",
    "graft",
    "plugin.Missing",
    "é😀\u2028\x00",
    "x" * 20_000,
    [],
    [None, "a"],
    [[1.0, 2.0]],
    {},
    {"type": "Point", "xyz": [1, 2, 3]},
    Raw("NaN"),
    Raw("-Infinity"),
    Raw("-1e400"),
    Raw("1" + "0" * 4400),
    Raw(deep_array(100_000)),
    Raw(deep_object(100_000)),
    Raw(deep_array(600)),
]


def paths_in(value: Any, prefix: tuple = ()) -> list[tuple]:
    found = [prefix]
    if isinstance(value, dict):
        for key, child in value.items():
            found += paths_in(child, (*prefix, key))
    elif isinstance(value, list):
        for index, child in enumerate(value):
            found += paths_in(child, (*prefix, index))
    return found


def replaced(data: Any, path: tuple, value: Any) -> Any:
    data = copy.deepcopy(data)
    parent = data
    for key in path[:-1]:
        parent = parent[key]
    if value is DELETE:
        del parent[path[-1]]
    else:
        parent[path[-1]] = value
    return data


# --------------------------------------------------------------------------- deterministic


@pytest.mark.timeout(120)
def test_truncation_at_every_byte_of_every_seed():
    with timed("truncation"):
        for name, seed in SEEDS.items():
            outcomes = Counter(run_case("truncation", seed[:cut]) for cut in range(len(seed)))
            # only cutting the final newline (and maybe the closing brace's whitespace) keeps it valid
            assert outcomes["loaded"] <= 2, name
            assert outcomes["refused"] >= len(seed) - 2, name


@pytest.mark.timeout(120)
def test_byte_flips_of_every_seed():
    edits_per_seed = 600
    specials = b'{}[]":,0123456789.eE-+tfnul\\ \n\x00\x80\xc3\xff'
    with timed("byte_flips"):
        for name, seed in SEEDS.items():
            rng = random.Random(f"flip:{name}")
            for _ in range(edits_per_seed):
                data = bytearray(seed)
                for _ in range(rng.choice((1, 1, 1, 2, 3))):
                    at = rng.randrange(len(data))
                    kind = rng.randrange(6)
                    if kind == 0:
                        data[at] ^= 1 << rng.randrange(8)
                    elif kind == 1:
                        data[at] = rng.randrange(256)
                    elif kind == 2:
                        data[at] = rng.choice(specials)
                    elif kind == 3:
                        del data[at]
                    elif kind == 4:
                        data.insert(at, rng.choice(specials))
                    else:
                        data[at : at + 2] = data[at : at + 2][::-1]
                run_case("byte_flips", bytes(data))


@pytest.mark.timeout(300)  # a hang guard: its 11,500 cases take about 15 s
def test_a_wrong_value_for_every_field_of_every_seed():
    with timed("wrong_field_values"):
        for seed in SEEDS.values():
            data = json.loads(seed)
            for path in paths_in(data)[1:]:
                for value in WRONG_VALUES:
                    run_case("wrong_field_values", dump(replaced(data, path, value)))
        for value in WRONG_VALUES[1:]:  # the whole document replaced
            run_case("wrong_field_values", dump(value))


def record_paths(data: dict) -> list[tuple]:
    """The objects whose unknown fields must be kept: file, nodes, inputs, wires, groups, meta."""
    paths: list[tuple] = [(), ("meta",)]
    for i, node in enumerate(data["nodes"]):
        paths.append(("nodes", i))
        paths += [("nodes", i, "inputs", name) for name in node.get("inputs", {})]
    paths += [("wires", i) for i in range(len(data.get("wires", [])))]
    paths += [("groups", i) for i in range(len(data.get("groups", [])))]
    return paths


@pytest.mark.timeout(120)
@pytest.mark.parametrize("seed", [n for n in SEEDS if n.startswith("engine-")])
def test_an_unknown_field_added_to_any_object_is_kept(seed):
    data = json.loads(SEEDS[seed])
    unknown_values = [None, 0, "text", [1, {"a": []}], {"nested": {"deep": [True]}}, 1e-300]
    with timed("unknown_fields"):
        for path in record_paths(data):
            for value in unknown_values:
                mutated = copy.deepcopy(data)
                target = mutated
                for key in path:
                    target = target[key]
                target["x_fuzz_field"] = value
                text = graphfile.encode(mutated)
                assert run_case("unknown_fields", text) == "loaded"
                assert graphfile.dumps(graphfile.loads(text, REGISTRY)) == text


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


@pytest.mark.timeout(120)
@pytest.mark.parametrize("name", list(SPECIAL_FILES))
def test_special_hostile_files(name):
    content, expected = SPECIAL_FILES[name]
    if isinstance(content, dict):
        content = json.dumps(content).encode("utf-8")
    with timed("special_files"):
        outcome = run_case("special_files", content)
    assert outcome in expected, f"{name}: {outcome}, expected {expected}"


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


# --------------------------------------------------------------------------- hypothesis

HYPOTHESIS = settings(
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large, HealthCheck.large_base_example],
)

NASTY_SCALARS = [
    10**400,
    -(10**400),
    2**63,
    -(2**63) - 1,
    2**64,
    1e308,
    -1e308,
    5e-324,
    -0.0,
    "",
    "\x00",
    "é",
    "😀",
    "\u2028",
    "{0;1}",
    "graft",
    "Value",
    "params.NumberSlider",
    "x" * 300,
]
scalars = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(),
    st.floats(allow_nan=False, allow_infinity=False),
    st.text(max_size=12),
    st.sampled_from(NASTY_SCALARS),
)
json_values = st.recursive(
    scalars,
    lambda kids: st.lists(kids, max_size=5) | st.dictionaries(st.text(max_size=8), kids, max_size=5),
    max_leaves=15,
)

TYPE_IDS = [cls.type_id for cls in NODE_CLASSES]
PORT_NAMES = sorted(
    {p.name for cls in NODE_CLASSES for p in (*cls.inputs, *cls.outputs)}
    | {"x", "y", "u", "Result", "In", "Out", "", "Nope"}
)
SETTING_NAMES = sorted({s.name for cls in NODE_CLASSES for s in cls.settings_spec} | {"other"})
MODIFIER_NAMES = ["graft", "flatten", "simplify", "reverse", "graft", "sort", ""]

ids = st.sampled_from(["a", "b", "c", "d", "e", "f", "", "é"])
types = st.sampled_from([*TYPE_IDS, *TYPE_IDS, "plugin.Missing", "developable.CylindricalSurface", "", "x"])
ports = st.sampled_from(PORT_NAMES)
coordinates = st.floats(-1e16, 1e16, allow_nan=False) | st.integers(-(10**16), 10**16)
encoded_values = st.one_of(
    st.fixed_dictionaries(
        {"type": st.sampled_from(["Point", "Vector", "Domain", "Plane", "Number", "Generic", "Nope"])},
        optional={
            "xyz": st.lists(scalars, max_size=4),
            "min": scalars,
            "max": scalars,
            "origin": st.lists(scalars, max_size=4),
            "x": st.lists(scalars, max_size=4),
            "y": st.lists(scalars, max_size=4),
        },
    ),
    st.lists(st.floats(-1e6, 1e6) | st.integers(-100, 100), max_size=6),
)
setting_values = st.one_of(
    json_values,
    st.floats(allow_nan=False, allow_infinity=False),
    st.lists(st.sampled_from(["x", "y", "u", "v", "1bad", ""]), max_size=4),  # variables
    st.dictionaries(  # tree branches
        st.sampled_from(["{0}", "{1}", "{0;1}", "{-1}", "{}", "bad"]),
        st.lists(st.integers(-5, 5) | st.floats(-10, 10) | st.text(max_size=2), max_size=4),
        max_size=3,
    ),
)


input_entries = st.fixed_dictionaries(
    {},
    optional={
        "value": encoded_values | scalars,
        "modifiers": st.lists(st.sampled_from(MODIFIER_NAMES), max_size=3),
        "x_hint": scalars,
    },
)
nodes = st.fixed_dictionaries(
    {"id": ids, "type": types},
    optional={
        "label": st.text(max_size=10),
        "position": st.lists(coordinates, min_size=2, max_size=2),
        "settings": st.dictionaries(st.sampled_from(SETTING_NAMES), setting_values, max_size=4),
        "inputs": st.dictionaries(ports, input_entries, max_size=3),
        "preview": st.booleans(),
        "enabled": st.booleans(),
        "x_unknown": scalars,
        "x": scalars,  # version 0 positions
        "y": scalars,
    },
)
wires = st.fixed_dictionaries(
    {"from": st.tuples(ids, ports).map(list), "to": st.tuples(ids, ports).map(list)},
    optional={"x_style": scalars},
)
v0_wires = st.fixed_dictionaries(
    {"source": st.tuples(ids, ports).map(".".join), "target": st.tuples(ids, ports).map(".".join)}
)
groups = st.fixed_dictionaries(
    {"id": ids},
    optional={
        "title": st.text(max_size=5),
        "colour": st.text(max_size=7),
        "nodes": st.lists(ids, max_size=4),
        "x_locked": scalars,
    },
)
plausible_files = st.fixed_dictionaries(
    {
        "format": st.sampled_from(["torsal.graph"] * 15 + ["torsal.graph ", "other"]),
        "version": st.sampled_from([1] * 10 + [0, 0, 0, 2, -1, True, "1"]),
        "nodes": st.lists(nodes, max_size=7, unique_by=lambda n: n["id"]) | st.lists(nodes, max_size=4),
    },
    optional={
        "wires": st.lists(wires | v0_wires, max_size=8),
        "groups": st.lists(groups, max_size=2),
        "meta": st.dictionaries(st.text(max_size=6), scalars, max_size=3),
        "units": st.sampled_from(["m", "mm", "cm", "in", "ft", "km", ""]),
        "x_top": scalars,
    },
)
# wrong types: up to three values anywhere in a generated file replaced by any JSON value
corruptions = st.lists(st.tuples(st.integers(0, 10**6), json_values), max_size=3)


def corrupt(document: dict, changes: list[tuple[int, Any]]) -> Any:
    for where, value in changes:
        paths = paths_in(document)
        path = paths[where % len(paths)]
        document = value if not path else replaced(document, path, value)
    return document


@pytest.mark.timeout(120)
@settings(HYPOTHESIS, max_examples=300)
@given(
    document=json_values
    | st.dictionaries(
        st.sampled_from(["format", "version", "nodes", "wires", "groups", "meta", "units"]), json_values
    )
    | st.fixed_dictionaries(
        {"format": st.just("torsal.graph"), "version": st.just(1)},
        optional={
            "nodes": json_values,
            "wires": json_values,
            "groups": json_values,
            "meta": json_values,
            "units": json_values,
        },
    )
)
def test_hypothesis_arbitrary_json_documents(document):
    with timed("hypothesis_json_documents"):
        run_case("hypothesis_json_documents", json.dumps(document).encode("utf-8"))


@pytest.mark.timeout(120)
@settings(HYPOTHESIS, max_examples=700)
@given(document=plausible_files, changes=corruptions)
def test_hypothesis_plausible_graphs_with_wrong_types_mixed_in(document, changes):
    document = corrupt(document, changes)
    with timed("hypothesis_plausible_graphs"):
        run_case("hypothesis_plausible_graphs", json.dumps(document).encode("utf-8"))


@pytest.mark.timeout(120)
@settings(HYPOTHESIS, max_examples=800)
@given(
    seed=st.sampled_from(sorted(SEEDS)),
    edits=st.lists(
        st.tuples(
            st.sampled_from(["set", "insert", "delete", "cut"]),
            st.floats(0, 1),
            st.binary(min_size=1, max_size=4),
        ),
        min_size=1,
        max_size=4,
    ),
)
def test_hypothesis_byte_edits_of_seeds(seed, edits):
    data = bytearray(SEEDS[seed])
    for kind, where, payload in edits:
        at = min(int(where * len(data)), max(len(data) - 1, 0))
        if kind == "set":
            data[at : at + len(payload)] = payload
        elif kind == "insert":
            data[at:at] = payload
        elif kind == "delete":
            del data[at : at + len(payload)]
        else:
            del data[at:]
    with timed("hypothesis_byte_edits"):
        run_case("hypothesis_byte_edits", bytes(data))


finite_json = st.recursive(
    st.none()
    | st.booleans()
    | st.integers()
    | st.floats(allow_nan=False, allow_infinity=False)
    | st.text(max_size=10)
    | st.sampled_from([10**400, 1e308, 5e-324, -0.0, "é😀\u2028"]),
    lambda kids: st.lists(kids, max_size=4) | st.dictionaries(st.text(max_size=6), kids, max_size=4),
    max_leaves=10,
)
unknown_keys = st.text(max_size=6).map(lambda s: "x_" + s)


@st.composite
def canonical_files(draw: st.DrawFn) -> dict:
    """Files as Torsal writes them (every field Torsal always writes is present)."""
    count = draw(st.integers(0, 6))
    node_ids = draw(st.lists(st.text(min_size=1, max_size=8), min_size=count, max_size=count, unique=True))
    file_nodes = []
    for node_id in node_ids:
        node = {
            "id": node_id,
            "type": draw(
                st.sampled_from(
                    [
                        "params.NumberSlider",
                        "maths.Add",
                        "lists.ListLength",
                        "plugin.Missing",
                        "other.Thing",
                        "x",
                    ]
                )
            ),
            "position": draw(
                st.lists(st.floats(-1e15, 1e15) | st.integers(-(10**15), 10**15), min_size=2, max_size=2)
            ),
        }
        optional = {
            "label": st.text(max_size=12),
            "settings": st.dictionaries(st.text(max_size=8), finite_json, max_size=4),
            "inputs": st.dictionaries(
                st.text(max_size=6),
                st.fixed_dictionaries(
                    {},
                    optional={
                        "value": finite_json,
                        "modifiers": st.lists(
                            st.sampled_from(["graft", "flatten", "simplify", "reverse"]), max_size=3
                        ),
                        "x_hint": finite_json,
                    },
                ),
                max_size=3,
            ),
            "preview": st.booleans(),
            "enabled": st.booleans(),
        }
        for key, strategy in optional.items():
            if draw(st.booleans()):
                node[key] = draw(strategy)
        for key in draw(st.lists(unknown_keys, max_size=2)):
            node[key] = draw(finite_json)
        file_nodes.append(node)
    placeholders = [n["id"] for n in file_nodes if n["type"] in ("plugin.Missing", "other.Thing", "x")]
    file_wires, seen = [], set()
    for _ in range(draw(st.integers(0, 6))):
        if len(placeholders) < 2:
            break
        i, j = sorted(
            draw(st.lists(st.integers(0, len(placeholders) - 1), min_size=2, max_size=2, unique=True))
        )
        ends = (
            placeholders[i],
            draw(st.text(min_size=1, max_size=5)),
            placeholders[j],
            draw(st.text(min_size=1, max_size=5)),
        )
        if ends in seen:
            continue
        seen.add(ends)
        entry = {"from": [ends[0], ends[1]], "to": [ends[2], ends[3]]}
        for key in draw(st.lists(unknown_keys, max_size=1)):
            entry[key] = draw(finite_json)
        file_wires.append(entry)
    file_groups = [
        {
            "id": draw(st.text(min_size=1, max_size=5)),
            "title": draw(st.text(max_size=8)),
            "colour": draw(st.text(max_size=8)),
            "nodes": draw(st.lists(st.sampled_from(node_ids), max_size=3)) if node_ids else [],
        }
        for _ in range(draw(st.integers(0, 2)))
    ]
    data = {
        "format": "torsal.graph",
        "version": 1,
        "nodes": file_nodes,
        "wires": file_wires,
        "groups": file_groups,
        "meta": draw(st.dictionaries(st.text(max_size=8), finite_json, max_size=3)),
    }
    if draw(st.booleans()):
        data["units"] = draw(st.sampled_from(["m", "mm", "cm", "in", "ft"]))
    for key in draw(st.lists(unknown_keys, max_size=2)):
        data[key] = draw(finite_json)
    return data


@pytest.mark.timeout(120)
@settings(HYPOTHESIS, max_examples=200)
@given(data=canonical_files())
def test_hypothesis_canonical_files_round_trip_exactly(data):
    text = graphfile.encode(data)
    with timed("hypothesis_canonical_round_trip"):
        assert run_case("hypothesis_canonical_round_trip", text) == "loaded"
        graph = graphfile.loads(text, REGISTRY)
        assert graphfile.dumps(graph) == text


# --------------------------------------------------------------------------- the total


def test_at_least_10000_files_were_checked():
    ran = {name for name in STATS}
    if ran != FUZZ_TESTS:
        pytest.skip(f"run the whole module to count the cases (missing: {sorted(FUZZ_TESTS - ran)})")
    total = sum(sum(c.values()) for c in STATS.values())
    lines = [f"{'corpus':34} {'cases':>6} {'seconds':>8} {'slowest':>8}  outcomes"]
    for name in sorted(STATS):
        counts = STATS[name]
        lines.append(
            f"{name:34} {sum(counts.values()):6d} {SECONDS.get(name, 0.0):8.2f} "
            f"{SLOWEST[name]:8.3f}  {dict(sorted(counts.items()))}"
        )
    lines.append(f"{'total':34} {total:6d} {sum(SECONDS.values()):8.2f}")
    print("\n" + "\n".join(lines))
    assert total >= MINIMUM_CASES
    everything = sum((c for c in STATS.values()), Counter())
    assert everything["loaded"] >= 1000, "the corpus should also exercise solving and saving"
    assert everything["refused"] >= 1000


# --------------------------------------------------------------------------- once bugs, now guarded


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


@pytest.mark.parametrize("levels", [400, 600, 900])
def test_deep_but_decodable_nesting_is_a_graph_file_error(levels):
    text = (
        '{"format": "torsal.graph", "version": 1, "nodes": [{"id": "a", "type": "plugin.X", '
        '"settings": {"v": ' + deep_array(levels) + "}}]}"
    )
    try:
        graph = graphfile.loads(text, REGISTRY)
    except GraphFileError:
        return
    graphfile.dumps(graph)


@pytest.mark.parametrize("field,value", [("nodes", None), ("nodes", 3), ("wires", 5), ("wires", None)])
def test_version_0_file_with_non_list_parts_is_a_graph_file_error(field, value):
    data = {"format": "torsal.graph", "version": 0, "nodes": []}
    data[field] = value
    with pytest.raises(GraphFileError):
        graphfile.loads(json.dumps(data), REGISTRY)
