"""The harness of the graph-file fuzz corpus (``test_graphfile_fuzz.py``): the seed files, the
check every case goes through, its statistics, and the hostile values mutations put in.

Every case must either load to a valid graph — which then solves, saves, and loads and
saves again to the same text — or raise exactly :class:`GraphFileError` with a message.
Any other exception, or a case that hangs (``CASE_SECONDS``), fails the case.
"""

from __future__ import annotations

import copy
import json
import time
from collections import Counter
from pathlib import Path
from typing import Any, ClassVar

from tests.support.nodekit import make_registry
from torsal.engine import graphfile
from torsal.engine.graphfile import GraphFileError, NewerVersionError
from torsal.engine.solver import Solver

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
