"""Solved variants kept on disk, keyed by the graph's content and the varied values.

The cache is one JSON line per solved variant, appended as it finishes, so a sweep that
is killed keeps what it solved and a re-run solves only what is missing. A torn last
line (the process killed mid-write) is skipped when read.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path
from typing import Any

from torsal.app.explore.evaluate import Job
from torsal.app.explore.variables import values_key


def graph_digest(graph_text: str) -> str:
    return hashlib.sha256(graph_text.encode("utf-8")).hexdigest()


def variant_key(digest: str, values: dict[str, Any], job: Job) -> str:
    """The key of one variant: the graph, the values, what is collected, the write policy
    and whether it is drawn."""
    text = json.dumps(
        [digest, values_key(values), [t.name for t in job.targets], job.allow_writes]
        + (["images"] if job.image_root is not None else []),
        separators=(",", ":"),
    )
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


class ResultCache:
    """A JSON-lines file of ``{"key": …, "outcome": …}``."""

    def __init__(self, path: Path) -> None:
        self.path = path
        self.entries: dict[str, dict[str, Any]] = {}
        if path.is_file():
            with path.open(encoding="utf-8", errors="replace") as handle:
                for line in handle:
                    try:
                        entry = json.loads(line)
                        self.entries[str(entry["key"])] = dict(entry["outcome"])
                    except (ValueError, KeyError, TypeError):
                        continue  # a line torn by a kill, or not ours
        self._handle = None

    def get(self, key: str) -> dict[str, Any] | None:
        return self.entries.get(key)

    def put(self, key: str, outcome: dict[str, Any]) -> None:
        self.entries[key] = outcome
        if self._handle is None:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            torn = self.path.is_file() and self.path.stat().st_size > 0
            torn = torn and not self.path.read_bytes().endswith(b"\n")
            self._handle = self.path.open("a", encoding="utf-8")
            if torn:  # end the torn line, so the next entry starts on a line of its own
                self._handle.write("\n")
        self._handle.write(json.dumps({"key": key, "outcome": outcome}, separators=(",", ":")) + "\n")
        self._handle.flush()

    def close(self) -> None:
        if self._handle is not None:
            self._handle.close()
            self._handle = None
