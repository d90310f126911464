"""How the cost of a ``.graph`` file grows with its size (``make bench``).

Run alone with::

    .venv/bin/python -m pytest tests/benchmarks/bench_graphfile.py \\
        -o python_files='bench_*.py' -o norecursedirs='.*' -s

The baseline of each figure is the same work on a file half the size, measured in the
same run: linear work doubles (ratio 2), a search of the file per node or wire makes
it about 4. The bars: a 2,000-wire chain loads in well under half a second, and the
fuzz corpus's slowest file (5,000 nodes) goes through load, solve, save, load and save
in about a second. ``make test`` checks the same growth by counting function calls
(``tests/engine/test_graphfile.py``) and keeps only a hang guard on the corpus.
"""

from __future__ import annotations

import json

from engine import graphfile
from engine.solver import Solver
from tests.benchmarks.timing import ratio_to_baseline
from tests.engine.nodekit import make_registry

REGISTRY = make_registry()


def chain_text(count: int) -> str:
    """``count`` maths.Add nodes, each wired into the next."""
    nodes = [{"id": f"n{i}", "type": "maths.Add", "position": [0.0, 0.0]} for i in range(count)]
    wires = [{"from": [f"n{i}", "Result"], "to": [f"n{i + 1}", "A"]} for i in range(count - 1)]
    return graphfile.encode(
        {"format": "torsal.graph", "version": 1, "nodes": nodes, "wires": wires, "groups": [], "meta": {}}
    )


def unwired_file(count: int) -> bytes:
    """The fuzz corpus's "5,000 nodes" file, for any count."""
    nodes = [{"id": f"n{i}", "type": "maths.Add"} for i in range(count)]
    return json.dumps({"format": "torsal.graph", "version": 1, "nodes": nodes}).encode("utf-8")


def round_trip(content: bytes | str) -> None:
    """What the fuzz corpus does with a file that loads: load, solve, save, load, save."""
    graph = graphfile.loads(content, REGISTRY)
    Solver(graph).solve()
    text = graphfile.dumps(graph)
    assert graphfile.dumps(graphfile.loads(text, REGISTRY)) == text


def test_loading_a_chain_of_4000_wires_costs_twice_2000():
    half, full = chain_text(2000), chain_text(4000)
    ratio = ratio_to_baseline(
        "load a 4,000-node chain",
        lambda: graphfile.loads(full, REGISTRY),
        "load a 2,000-node chain",
        lambda: graphfile.loads(half, REGISTRY),
        15,
    )
    assert ratio <= 3.0


def test_the_fuzz_corpus_slowest_file_costs_twice_one_half_its_size():
    half, full = unwired_file(2500), unwired_file(5000)
    ratio = ratio_to_baseline(
        "round trip of 5,000 unwired nodes",
        lambda: round_trip(full),
        "the same with 2,500 nodes",
        lambda: round_trip(half),
        7,
    )
    assert ratio <= 3.0
