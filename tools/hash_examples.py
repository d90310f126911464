"""Hash every example's ``torsal run X --json`` outputs without timings, or compare two runs.

``python tools/hash_examples.py DIR [NAME ...]`` solves each example (or those named) in
``torsal/resources/examples`` headless and writes ``DIR/<example>.json`` (the results
with every ``seconds`` and ``solve_seconds`` field and the file's path dropped) and
``DIR/hashes.txt`` (one sha256 per example).
``python tools/hash_examples.py --compare BEFORE AFTER`` says, per example, whether the
two runs are identical and otherwise the largest difference between numbers at the same
place, relative to the largest magnitude among that example's numbers (its size).
"""

from __future__ import annotations

import hashlib
import json
import math
import subprocess
import sys
from pathlib import Path

EXAMPLES = Path(__file__).resolve().parent.parent / "torsal" / "resources" / "examples"
#: Dropped: the timings, and the graph file's path (two checkouts solve the same file).
DROPPED = {"seconds", "solve_seconds", "file"}


def _without_timings(value: object) -> object:
    if isinstance(value, dict):
        return {k: _without_timings(v) for k, v in value.items() if k not in DROPPED}
    if isinstance(value, list):
        return [_without_timings(v) for v in value]
    return value


def solve_all(out: Path, names: list[str]) -> None:
    out.mkdir(parents=True, exist_ok=True)
    lines = []
    for graph in sorted(EXAMPLES.glob("*.graph")):
        if names and graph.stem not in names:
            continue
        run = subprocess.run(
            [sys.executable, "-m", "torsal.app.cli", "run", str(graph), "--json"],
            capture_output=True, text=True, check=False, timeout=900)
        if not run.stdout.strip():
            sys.exit(f"{graph.stem} printed no results:\n{run.stderr}")
        text = json.dumps(_without_timings(json.loads(run.stdout)), sort_keys=True, indent=1)
        (out / f"{graph.stem}.json").write_text(text)
        lines.append(f"{hashlib.sha256(text.encode()).hexdigest()}  {graph.stem}")
        print(lines[-1], flush=True)
    (out / "hashes.txt").write_text("\n".join(lines) + "\n")


def _numbers(value: object, path: str = "") -> dict[str, object]:
    if isinstance(value, dict):
        return {k: v for key, item in value.items() for k, v in _numbers(item, f"{path}/{key}").items()}
    if isinstance(value, list):
        return {k: v for i, item in enumerate(value) for k, v in _numbers(item, f"{path}/{i}").items()}
    return {path: value}


def _real(x: object) -> bool:
    """A finite float (NaN and infinities compare as they are)."""
    return isinstance(x, float) and math.isfinite(x)


def compare(before: Path, after: Path) -> int:
    worst = 0
    for second in sorted(after.glob("*.json")):
        first = before / second.name
        a, b = _numbers(json.loads(first.read_text())), _numbers(json.loads(second.read_text()))
        if json.dumps(a, sort_keys=True) == json.dumps(b, sort_keys=True):
            print(f"identical  {second.stem}")
            continue
        if a.keys() != b.keys():
            print(f"DIFFERENT STRUCTURE  {second.stem}: {sorted(a.keys() ^ b.keys())[:5]}")
            worst = 2
            continue
        floats = [(x, b[k]) for k, x in a.items() if _real(x) and _real(b[k])]
        others = [k for k, x in a.items() if x != b[k] and not (_real(x) and _real(b[k]))]
        size = max((abs(x) for x, _ in floats), default=1.0) or 1.0
        gap = max((abs(x - y) for x, y in floats), default=0.0) / size
        print(f"differs    {second.stem}: largest gap {gap:.2e} of the size {size:.3g}; "
              f"other changes {others[:5]}")
        worst = max(worst, 1 if gap <= 1e-12 and not others else 2)
    return worst


if __name__ == "__main__":
    if len(sys.argv) < 2 or (sys.argv[1].startswith("-") and sys.argv[1] != "--compare"):
        sys.exit(__doc__)  # -h, --help or an unknown option: a folder named so is a slip
    if sys.argv[1] == "--compare":
        sys.exit(compare(Path(sys.argv[2]), Path(sys.argv[3])))
    solve_all(Path(sys.argv[1]), sys.argv[2:])
