"""No module of the project is over 700 lines (issue 14's bar): a module that large mixes ideas."""

from __future__ import annotations

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LIMIT = 700


def _sizes() -> dict[str, int]:
    return {
        str(path.relative_to(ROOT)): len(path.read_text(encoding="utf-8").splitlines())
        for package in ("torsal/engine", "torsal/nodes", "torsal/app")
        for path in sorted((ROOT / package).rglob("*.py"))
    }


def test_the_walk_finds_the_modules():
    sizes = _sizes()
    assert "torsal/engine/solver.py" in sizes and len(sizes) > 100


def test_no_module_is_over_700_lines():
    over = {name: lines for name, lines in _sizes().items() if lines > LIMIT}
    assert not over, f"modules over {LIMIT} lines: {over}"
