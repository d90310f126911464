"""Shared by the ``.graph`` file tests (``test_graphfile_*.py``): the fixture and example
files, a fixture's text, leftover temporaries of a save, a chain of Add nodes, and a count
of the function calls something makes (its work, which the machine's load cannot change)."""

from __future__ import annotations

import sys
from collections.abc import Callable
from pathlib import Path

from torsal.engine import graphfile

FIXTURES = Path(__file__).resolve().parents[1] / "fixtures"
EXAMPLES = Path(__file__).resolve().parents[2] / "torsal" / "resources" / "examples"
SPEC = Path(__file__).resolve().parents[2] / "docs" / "graph-format.md"

ENGINE_FIXTURES = sorted(FIXTURES.glob("engine-*.graph"))  # written for the nodekit registry
ALL_FIXTURES = sorted(FIXTURES.glob("*.graph"))
ALL_EXAMPLES = sorted(EXAMPLES.glob("*.graph"))


def read(name: str) -> str:
    return (FIXTURES / name).read_text(encoding="utf-8")


def no_temporaries(directory: Path) -> list[str]:
    """Leftover temporary files of an interrupted save (``.<name>.<pid>-<token>.tmp<suffix>``)."""
    return sorted(p.name for p in directory.iterdir() if ".tmp" in p.name)


def chain_text(count: int) -> str:
    nodes = [{"id": f"n{i}", "type": "maths.Add", "position": [0.0, 0.0]} for i in range(count)]
    wires = [{"from": [f"n{i}", "Result"], "to": [f"n{i + 1}", "A"]} for i in range(count - 1)]
    return graphfile.encode(
        {"format": "torsal.graph", "version": 1, "nodes": nodes, "wires": wires, "groups": [], "meta": {}}
    )


def calls_made(function: Callable[[], object]) -> int:
    """How many Python and C functions ``function()`` calls: a count of its work that,
    unlike its time, the machine's load cannot change."""
    calls = 0

    def count(frame: object, event: str, arg: object) -> None:
        nonlocal calls
        if event in ("call", "c_call"):
            calls += 1

    sys.setprofile(count)
    try:
        function()
    finally:
        sys.setprofile(None)
    return calls
