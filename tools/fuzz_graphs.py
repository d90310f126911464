"""Structure-aware fuzzing of ``.graph`` files: mutants of real graphs, loaded and solved.

Byte flips mostly make files that fail to parse. These mutations keep a file a graph and
change what it *means*, the way a hostile or corrupted file would:

- ``type_swap``: a node becomes another installed type (its wires now reach ports that
  may not exist, its settings belong to another node);
- ``value_kind``: an input value or setting becomes a value of another kind (text for a
  number, a list, an object, a Point, a Domain, null);
- ``hostile_number``: a number anywhere becomes 0, -1, 1e-9, 1e12, 1e308, -1e308,
  5e-324, 10^400, NaN or ±Infinity (the last three as raw JSON tokens);
- ``deep_nesting``: a value becomes a list nested 30 to 20,000 deep;
- ``duplicate_id``: a node takes another node's id, or is listed twice;
- ``missing_port``: a wire is sent to a port or node that does not exist;
- ``cycle``: a wire is added from a node's output back into one of its sources;
- ``unknown_type``: a node's type becomes one that is not installed;
- ``wire_shuffle``: a wire is removed, duplicated, reversed or given bogus modifiers;
- ``slider_bounds``: a slider's min, max and value are crossed or made huge.

Each mutant applies one to three mutations to an example from ``torsal/resources/examples`` and
is loaded and solved in a guarded worker (tools/fuzz_pool.py). The rule: a file is
refused with a :class:`~torsal.engine.graphfile.GraphFileError`, or it loads and every node
ends with a state and messages — no exception a node did not mean, no run over
``seconds``, no peak memory over ``memory``. Mutants are made from a seed, so a run is
reproducible; a failing mutant is written to ``--out`` to be run again with
``torsal run FILE``.

``python -m tools.fuzz_graphs --mutants 200`` (``make fuzz``: a larger corpus) prints a
summary and exits 1 on any failure.
"""

from __future__ import annotations

import argparse
import copy
import json
import random
import sys
import tempfile
from collections import Counter, defaultdict
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Any

EXAMPLES = Path(__file__).resolve().parent.parent / "torsal" / "resources" / "examples"

#: The kinds of mutation, those that keep a file loadable listed twice (cycles, duplicate
#: ids and missing ports are always refused on load, so they need fewer draws).
MUTATIONS = (
    "type_swap",
    "type_swap",
    "value_kind",
    "value_kind",
    "hostile_number",
    "hostile_number",
    "hostile_number",
    "deep_nesting",
    "duplicate_id",
    "missing_port",
    "cycle",
    "unknown_type",
    "wire_shuffle",
    "slider_bounds",
)

#: Numbers a mutant may hold: JSON numbers, and raw tokens JSON has no number for.
HOSTILE_NUMBERS: tuple[Any, ...] = (0, -1, 0.0, 1e-9, 1e12, 1e308, -1e308, 5e-324, 10**400, -(10**19))
RAW_TOKENS = ("NaN", "Infinity", "-Infinity", "1e400")

#: Input modifiers a mutant may give a wired input (the last two are not valid).
MODIFIERS: tuple[Any, ...] = (
    ["graft"], ["flatten", "graft", "graft"], ["simplify", "reverse"], ["bogus"], "graft",
)


class Raw:
    """A JSON token ``json.dumps`` cannot write (``NaN``, ``1e400``), pasted in verbatim."""

    def __init__(self, token: str) -> None:
        self.token = token


@dataclass(frozen=True)
class Mutant:
    """The mutant ``index`` of ``example`` under ``seed``: recreated from these alone."""

    example: str
    index: int
    seed: int = 0
    #: also describe every output as ``torsal run --json`` does (areas, lengths: slower)
    summarize: bool = False

    def __str__(self) -> str:
        return f"{self.example}#{self.index} (seed {self.seed}{', summarized' if self.summarize else ''})"


@cache
def examples() -> dict[str, str]:
    """The shipped example graphs by file name."""
    return {path.name: path.read_text(encoding="utf-8") for path in sorted(EXAMPLES.glob("*.graph"))}


@cache
def _type_ids() -> tuple[str, ...]:
    from torsal.nodes.catalogue import default_registry

    return tuple(cls.type_id for cls in default_registry(plugins=False))


# --------------------------------------------------------------------------- mutations


def _numbers(value: Any, path: tuple = ()) -> list[tuple]:
    """Paths of every number in ``value`` (bools are not numbers)."""
    found: list[tuple] = []
    if isinstance(value, dict):
        for key, child in value.items():
            found += _numbers(child, (*path, key))
    elif isinstance(value, list):
        for index, child in enumerate(value):
            found += _numbers(child, (*path, index))
    elif isinstance(value, int | float) and not isinstance(value, bool):
        found.append(path)
    return found


def _set(data: Any, path: tuple, value: Any) -> None:
    for key in path[:-1]:
        data = data[key]
    data[path[-1]] = value


def _value_slots(data: dict) -> list[tuple]:
    """Paths of every input value and setting in the file."""
    slots = []
    for i, node in enumerate(data.get("nodes", [])):
        for name, entry in (node.get("inputs") or {}).items():
            if isinstance(entry, dict) and "value" in entry:
                slots.append(("nodes", i, "inputs", name, "value"))
        for name in node.get("settings") or {}:
            slots.append(("nodes", i, "settings", name))
    return slots


def _other_value(rng: random.Random) -> Any:
    return rng.choice([
        "text", "", "1e999", "nan", "-5", "x" * 5000, None, True, False, [], [1, 2, 3],
        [[1.0, 2.0], "a", None], {}, {"type": "Point", "xyz": [1e308, 0, 0]},
        {"type": "Point", "xyz": [1, 2]}, {"type": "Domain", "min": 0, "max": 1e308},
        {"type": "Vector", "xyz": [0, 0, 0]}, {"type": "Plane", "origin": [0, 0, 0]}, {"type": "Nope"},
        [{"type": "Point", "xyz": [0, 0, 0]}] * 3, list(range(8)),
    ])


def _hostile(rng: random.Random) -> Any:
    if rng.random() < 0.3:
        return Raw(rng.choice(RAW_TOKENS))
    return rng.choice(HOSTILE_NUMBERS)


def _deep(rng: random.Random) -> Raw:
    levels = rng.choice((30, 63, 65, 200, 1000, 20_000))
    return Raw("[" * levels + "1" + "]" * levels)


def _fitting_types(data: dict, node: dict) -> list[str]:
    """Other node types with every port ``node``'s wires use (so the file still loads and
    the swapped node is solved with data meant for another)."""
    from torsal.nodes.catalogue import default_registry

    ins = {w["to"][1] for w in data.get("wires", []) if w["to"][0] == node.get("id")}
    outs = {w["from"][1] for w in data.get("wires", []) if w["from"][0] == node.get("id")}
    fitting = []
    for cls in default_registry(plugins=False):
        if cls.type_id != node.get("type") and ins <= {p.name for p in cls.inputs} and outs <= {
                p.name for p in cls.outputs}:
            fitting.append(cls.type_id)
    return fitting


def _node_ids(data: dict) -> list[str]:
    return [n.get("id") for n in data.get("nodes", []) if isinstance(n, dict)]


def _downstream(data: dict, start: str) -> set[str]:
    targets: dict[str, set[str]] = {}
    for wire in data.get("wires", []):
        try:
            targets.setdefault(wire["from"][0], set()).add(wire["to"][0])
        except (KeyError, TypeError, IndexError):
            continue
    seen, stack = set(), [start]
    while stack:
        for nxt in targets.get(stack.pop(), ()):
            if nxt not in seen:
                seen.add(nxt)
                stack.append(nxt)
    return seen


def mutate(data: dict, kind: str, rng: random.Random) -> str:
    """Apply one mutation of ``kind`` to ``data`` in place; returns what was done."""
    nodes = data.get("nodes", [])
    wires = data.setdefault("wires", [])
    if not nodes:
        return "no nodes"
    node = rng.choice(nodes)
    if kind == "type_swap":
        fitting = _fitting_types(data, node)
        node["type"] = rng.choice(fitting if fitting and rng.random() < 0.7 else _type_ids())
        return f"{node['id']} became {node['type']}"
    if kind == "unknown_type":
        node["type"] = rng.choice(["plugin.Nope", "maths.Nope", "io.ExportCSV2", "x"])
        return f"{node['id']} became {node['type']}"
    if kind in ("value_kind", "deep_nesting"):
        slots = _value_slots(data)
        if not slots:
            return "no values"
        slot = rng.choice(slots)
        value = _other_value(rng) if kind == "value_kind" else _deep(rng)
        _set(data, slot, value)
        return f"{'/'.join(map(str, slot))} set to a {type(value).__name__}"
    if kind == "hostile_number":
        paths = _numbers(data)
        if not paths:
            return "no numbers"
        # prefer the values a node computes with over positions and versions
        values = [p for p in paths if "inputs" in p or "settings" in p] or paths
        path = rng.choice(values if rng.random() < 0.85 else paths)
        value = _hostile(rng)
        _set(data, path, value)
        return f"{'/'.join(map(str, path))} set to {getattr(value, 'token', value)!r}"[:200]
    if kind == "duplicate_id":
        if rng.random() < 0.5 and len(nodes) > 1:
            other = rng.choice([n for n in nodes if n is not node])
            node["id"] = other["id"]
            return f"a node took the id {other['id']!r}"
        nodes.append(copy.deepcopy(node))
        return f"{node['id']} listed twice"
    if kind == "missing_port":
        if not wires:
            return "no wires"
        wire = rng.choice(wires)
        end = rng.choice(["from", "to"])
        if rng.random() < 0.7:
            wire[end] = [wire[end][0], rng.choice(["Nope", "", "value", "Result ", "é"])]
        else:
            wire[end] = [rng.choice(["ghost", "", node["id"] + "_"]), wire[end][1]]
        return f"a wire's {end} end moved to {wire[end]}"
    if kind == "cycle":
        if not wires:
            return "no wires"
        wire = rng.choice(wires)
        source, target = wire["from"][0], wire["to"][0]
        later = sorted(_downstream(data, target) | {target})
        back_from = rng.choice(later)
        outs = [w["from"][1] for w in wires if w["from"][0] == back_from] or ["Result", "Value", "Curve"]
        ins = [w["to"][1] for w in wires if w["to"][0] == source] or ["A", "Curve", "x"]
        wires.append({"from": [back_from, rng.choice(outs)], "to": [source, rng.choice(ins)]})
        return f"a wire from {back_from} back into {source}"
    if kind == "wire_shuffle":
        if not wires:
            return "no wires"
        i = rng.randrange(len(wires))
        action = rng.choice(["remove", "duplicate", "reverse", "modifiers"])
        if action == "remove":
            wires.pop(i)
        elif action == "duplicate":
            wires.append(copy.deepcopy(wires[i]))
        elif action == "reverse":
            wires[i] = {"from": wires[i]["to"], "to": wires[i]["from"]}
        else:
            target, port = wires[i]["to"]
            for n in nodes:
                if n.get("id") == target:
                    n.setdefault("inputs", {}).setdefault(port, {})["modifiers"] = rng.choice(MODIFIERS)
        return f"wire {i}: {action}"
    if kind == "slider_bounds":
        sliders = [n for n in nodes if "Slider" in str(n.get("type"))]
        if not sliders:
            return "no sliders"
        settings = rng.choice(sliders).setdefault("settings", {})
        low, high = rng.choice([(10, -10), (0, 1e308), (-1e308, 1e308), (5, 5), (0, 1e12)])
        settings.update({"min": low, "max": high, "value": rng.choice([low, high, 1e308, -1, 0])})
        return f"slider bounds {low}..{high}"
    raise ValueError(f"unknown mutation {kind!r}")


def _dumps(data: Any) -> str:
    """JSON text of ``data`` with :class:`Raw` tokens pasted in."""
    tokens: dict[str, str] = {}

    def placeholder(value: Any) -> str:
        if isinstance(value, Raw):
            key = f"@@raw{len(tokens)}@@"
            tokens[key] = value.token
            return key
        raise TypeError(f"cannot write {type(value).__name__}")

    text = json.dumps(data, default=placeholder, indent=1)
    for key, token in tokens.items():
        text = text.replace(json.dumps(key), token)
    return text


def make(mutant: Mutant) -> tuple[str, list[str]]:
    """The text of ``mutant`` and the mutations applied to it, from its seed alone."""
    rng = random.Random(f"{mutant.seed}:{mutant.example}:{mutant.index}")
    data = json.loads(examples()[mutant.example])
    done = []
    for _ in range(rng.choice((1, 1, 2, 3))):
        kind = rng.choice(MUTATIONS)
        done.append(f"{kind}: {mutate(data, kind, rng)}")
    return _dumps(data), done


# --------------------------------------------------------------------------- running


def run_mutant(mutant: Mutant) -> dict[str, Any]:
    """Load and solve ``mutant``, describe its outputs, then save it (in a guarded worker)."""
    from tools.fuzz_pool import solve_guarded
    from torsal.engine import graphfile
    from torsal.engine.graphfile import GraphFileError
    from torsal.nodes.catalogue import default_registry

    text, _ = make(mutant)
    try:
        graph = graphfile.loads(text, default_registry(plugins=False))
    except GraphFileError as exc:
        if not str(exc).strip():
            raise AssertionError("a GraphFileError without a message") from None
        return {"outcome": "refused", "bytes": len(text)}
    solved = solve_guarded(graph, summarize=mutant.summarize)
    graphfile.dumps(graph)  # what was loaded can be saved
    states = Counter(state for state, _ in solved["nodes"].values())
    return {"outcome": "solved", "bytes": len(text), "states": dict(states)}


@dataclass
class Summary:
    """What a fuzzing run found."""

    cases: int = 0
    outcomes: Counter = None  # type: ignore[assignment]
    failures: list[str] = None  # type: ignore[assignment]
    written: list[Path] = None  # type: ignore[assignment]
    slowest: float = 0.0
    largest: int = 0
    seconds: float = 0.0
    by_kind: dict[str, Counter] = None  # type: ignore[assignment]
    slowest_cases: list[tuple[float, str]] = None  # type: ignore[assignment]


def fuzz(mutants_per_example: int, seed: int = 0, workers: int = 2, seconds: float = 20.0,
         memory: int = 1 << 30, out: Path | None = None, names: list[str] | None = None,
         summarize: bool = False) -> Summary:
    """Run ``mutants_per_example`` mutants of every example; failing ones are written to ``out``.

    ``summarize`` also describes every output as ``torsal run --json`` does.
    """
    import time

    from tools.fuzz_pool import GuardedPool, node_modules

    started = time.perf_counter()
    chosen = names or list(examples())
    cases = [Mutant(name, i, seed, summarize) for name in chosen for i in range(mutants_per_example)]
    summary = Summary(outcomes=Counter(), failures=[], written=[], by_kind=defaultdict(Counter),
                      slowest_cases=[])
    with tempfile.TemporaryDirectory(prefix="torsal-fuzz-") as scratch:  # io nodes' relative paths land here
        # headroom over ``memory`` so that a case just past it is measured, not killed
        pool = GuardedPool(workers=workers, memory_bytes=memory + (256 << 20), seconds=seconds, cwd=scratch,
                           preload=(*node_modules(), "tools.fuzz_graphs"))
        for mutant, result in pool.run(run_mutant, cases):
            summary.cases += 1
            summary.slowest = max(summary.slowest, result.seconds)
            summary.slowest_cases = sorted([*summary.slowest_cases, (result.seconds, str(mutant))])[-5:]
            summary.largest = max(summary.largest, result.peak_bytes)
            problems = list(result.unexpected)
            if result.stalled or result.seconds > seconds:
                problems.append(f"ran {result.seconds:.1f} s (limit {seconds:g} s)")
            if result.peak_bytes > memory:
                problems.append(f"peak memory {result.peak_bytes / 2**20:.0f} MiB "
                                f"(limit {memory / 2**20:.0f})")
            outcome = result.info["outcome"] if result.info else "failed"
            summary.outcomes[outcome] += 1
            for kind in {line.split(":")[0] for line in make(mutant)[1]}:
                summary.by_kind[kind][outcome] += 1
            if problems:
                text, done = make(mutant)
                where = ""
                if out is not None:
                    out.mkdir(parents=True, exist_ok=True)
                    path = out / f"{Path(mutant.example).stem}-seed{mutant.seed}-{mutant.index}.graph"
                    path.write_text(text, encoding="utf-8")
                    summary.written.append(path)
                    where = f" -> {path}"
                summary.failures.append(
                    f"{mutant}{where}\n    mutations: {done}\n    " + "\n    ".join(problems)
                )
    summary.seconds = time.perf_counter() - started
    return summary


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m tools.fuzz_graphs", description=__doc__.split("\n\n")[0])
    parser.add_argument("--mutants", type=int, default=200, help="mutants per example (default 200)")
    parser.add_argument("--seed", type=int, default=0, help="seed of the corpus (default 0)")
    parser.add_argument("--workers", type=int, default=2, help="worker processes (default 2)")
    parser.add_argument("--seconds", type=float, default=20.0, help="time limit per mutant (default 20)")
    parser.add_argument("--memory-mb", type=int, default=1024, help="peak memory limit per mutant, MiB")
    parser.add_argument("--out", type=Path, default=Path(tempfile.gettempdir()) / "torsal-fuzz",
                        help="folder for failing mutants (default: $TMPDIR/torsal-fuzz)")
    parser.add_argument("--summarize", action="store_true",
                        help="also describe every output as torsal run --json does (slower)")
    parser.add_argument("examples", nargs="*", help="example file names (default: all)")
    args = parser.parse_args(argv)
    summary = fuzz(args.mutants, args.seed, args.workers, args.seconds, args.memory_mb << 20, args.out,
                   args.examples or None, args.summarize)
    for failure in summary.failures:
        print("FAIL", failure)
    for kind in sorted(summary.by_kind):
        print(f"  {kind:15} {dict(summary.by_kind[kind])}")
    for seconds, mutant in reversed(summary.slowest_cases):
        print(f"  slow: {seconds:6.2f} s {mutant}")
    print(f"{summary.cases} mutants of {len(args.examples or examples())} examples (seed {args.seed}) in "
          f"{summary.seconds:.1f} s: {dict(summary.outcomes)}; slowest {summary.slowest:.2f} s, "
          f"largest {summary.largest / 2**20:.0f} MiB; {len(summary.failures)} failed")
    return 1 if summary.failures else 0


if __name__ == "__main__":
    sys.exit(main())
