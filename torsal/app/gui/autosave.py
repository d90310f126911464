"""Autosave to a recovery file every minute; offered back after a crash.

While a document has unsaved changes it is written (through the engine's file module,
atomically) to ``recovery/autosave-<pid>.graph`` in the config folder, with a small
JSON note saying which file it belongs to. A clean exit deletes both. At start, a
recovery file whose process is no longer running is offered back.
"""

from __future__ import annotations

import json
import os
import time
from dataclasses import dataclass
from pathlib import Path

from PySide6.QtCore import QObject, QTimer

from torsal.app.gui.document import Document
from torsal.engine.graphfile import GraphFileError, write_graph
from torsal.engine.write_path import write_file

DEFAULT_INTERVAL_S = 60.0


@dataclass
class Recovery:
    """An autosave left behind by a process that did not exit cleanly."""

    graph_path: Path
    note_path: Path
    original: Path | None
    saved_at: float

    def discard(self) -> None:
        for path in (
            self.graph_path,
            self.note_path,
            self.graph_path.with_name(self.graph_path.name + ".bak"),
        ):
            path.unlink(missing_ok=True)


def interval_seconds() -> float:
    try:
        return float(os.environ.get("TORSAL_AUTOSAVE_SECONDS", DEFAULT_INTERVAL_S))
    except ValueError:
        return DEFAULT_INTERVAL_S


class Autosaver(QObject):
    """Writes the document's recovery file on a timer while it has unsaved changes."""

    def __init__(
        self, doc: Document, folder: Path, interval_s: float | None = None, parent: QObject | None = None
    ) -> None:
        super().__init__(parent)
        self.doc = doc
        self.folder = folder / "recovery"
        self.folder.mkdir(parents=True, exist_ok=True)
        self.graph_path = self.folder / f"autosave-{os.getpid()}.graph"
        self.note_path = self.graph_path.with_suffix(".json")
        self.saves = 0
        self._saved_index: tuple[int, int] | None = None
        self.timer = QTimer(self)
        self.timer.setInterval(int((interval_s or interval_seconds()) * 1000))
        self.timer.timeout.connect(self.autosave)
        self.timer.start()
        doc.graph_replaced.connect(self._forget)

    def autosave(self) -> bool:
        """Write the recovery file if there is unsaved work not yet autosaved."""
        if not self.doc.dirty:
            self.discard()
            return False
        index = (len(self.doc.frames), self.doc.undo_stack.index())
        if index == self._saved_index and self.graph_path.exists():
            return False
        try:  # the document's own graph (edits inside a cluster not committed yet are not in it)
            write_graph(self.doc.root_graph, self.graph_path)
        except (GraphFileError, OSError):
            return False
        note = {
            "original": str(self.doc.path) if self.doc.path else None,
            "saved_at": time.time(),
            "pid": os.getpid(),
        }
        try:
            write_file(self.note_path, json.dumps(note), backup=False, mode=0o600)
        except OSError:
            return False
        self._saved_index = index
        self.saves += 1
        return True

    def _forget(self) -> None:
        self._saved_index = None

    def discard(self) -> None:
        """Remove this process's recovery files (after a save or a clean exit)."""
        Recovery(self.graph_path, self.note_path, None, 0.0).discard()
        self._saved_index = None


def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return True


def find_recoveries(folder: Path) -> list[Recovery]:
    """Recovery files left by processes that are no longer running, newest first."""
    found = []
    for note_path in (folder / "recovery").glob("autosave-*.json"):
        graph_path = note_path.with_suffix(".graph")
        try:
            note = json.loads(note_path.read_text(encoding="utf-8"))
            pid = int(note.get("pid", 0))
        except (OSError, ValueError, AttributeError):
            continue
        if not graph_path.exists() or _alive(pid):
            continue
        original = Path(note["original"]) if note.get("original") else None
        found.append(Recovery(graph_path, note_path, original, float(note.get("saved_at", 0.0))))
    found.sort(key=lambda r: r.saved_at, reverse=True)
    return found
