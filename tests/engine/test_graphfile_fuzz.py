"""File safety: at least 10,000 generated or mutated ``.graph`` files.

Every case must either load to a valid graph — which then solves, saves, and loads and
saves again to the same text — or raise exactly :class:`GraphFileError` with a message.
Any other exception, or a case that hangs (``CASE_SECONDS``), fails the test.

The cases come from deterministic mutation loops over a seed corpus (truncation at every
byte, byte flips, a wrong value for every field, unknown fields, hostile special files)
and from hypothesis strategies (arbitrary JSON, plausible graphs with wrong types mixed
in, byte edits, canonical graphs that must round-trip exactly). The last test checks
that all of them together ran at least 10,000 cases.

The harness is in ``graphfile_fuzz_harness.py``, the hand-made hostile files in
``hostile_graph_files.py``, the strategies in ``graph_file_strategies.py``. The bugs this
corpus once found (non-UTF-8 text, nesting deep enough to overflow the stack, malformed
version-0 files) are guarded by named tests in ``test_graphfile_refusals.py``.
"""

from __future__ import annotations

import copy
import json
import random
from collections import Counter

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from tests.support.graph_file_strategies import (
    HYPOTHESIS,
    canonical_files,
    corrupt,
    corruptions,
    json_values,
    plausible_files,
)
from tests.support.graphfile_fuzz_harness import (
    FUZZ_TESTS,
    MINIMUM_CASES,
    REGISTRY,
    SECONDS,
    SEEDS,
    SLOWEST,
    STATS,
    WRONG_VALUES,
    dump,
    paths_in,
    replaced,
    run_case,
    timed,
)
from tests.support.hostile_graph_files import SPECIAL_FILES
from torsal.engine import graphfile

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


@pytest.mark.timeout(120)
@pytest.mark.parametrize("name", list(SPECIAL_FILES))
def test_special_hostile_files(name):
    content, expected = SPECIAL_FILES[name]
    if isinstance(content, dict):
        content = json.dumps(content).encode("utf-8")
    with timed("special_files"):
        outcome = run_case("special_files", content)
    assert outcome in expected, f"{name}: {outcome}, expected {expected}"


# --------------------------------------------------------------------------- hypothesis


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
