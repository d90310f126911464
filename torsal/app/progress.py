"""What ``torsal run`` shows while a graph solves: progress where people look.

On a terminal, a live line per long node drawn by rich — the node's id, a bar, its
percent, the time it has taken and about how long it has left — kept up to date every
tenth of a second even while the node reports nothing new (the clock still moves).

Off a terminal (a CI log, a pipe), nothing for work that ends within :data:`QUIET` s;
after that one line every :data:`EVERY` s, so the log shows the run is alive::

    torsal: cut 42 % after 12 s, about 17 s left

(``still solving after 12 s`` before any node has said how far it is). The timing can be
tuned with ``TORSAL_HEARTBEAT`` (seconds; both the quiet start and the period), which
the tests use to keep short.
"""

from __future__ import annotations

import os
import sys
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager, suppress
from typing import TextIO

#: Seconds of work before a non-terminal run says anything, and between its lines.
QUIET = 5.0
EVERY = 5.0

NodeProgress = Callable[[str, float], None]


def _duration(seconds: float) -> str:
    seconds = max(0.0, seconds)
    if seconds < 60:
        return f"{seconds:.0f} s"
    minutes, rest = divmod(round(seconds), 60)
    return f"{minutes} min {rest:02d} s"


class Heartbeat:
    """Lines every ``every`` s on ``stream`` once the work has lasted ``quiet`` s."""

    def __init__(self, stream: TextIO, quiet: float = QUIET, every: float = EVERY) -> None:
        self.stream = stream
        self.quiet = quiet
        self.every = every
        self.started = time.monotonic()
        self.node: str | None = None
        self.fraction = 0.0
        self.node_started = self.started
        self._done = threading.Event()
        self._lock = threading.Lock()
        self._thread = threading.Thread(target=self._beat, name="torsal-heartbeat", daemon=True)

    def __call__(self, node_id: str, fraction: float) -> None:
        with self._lock:
            if node_id != self.node:
                self.node, self.node_started = node_id, time.monotonic()
            self.fraction = min(max(float(fraction), 0.0), 1.0)

    def line(self) -> str:
        """The heartbeat's text now."""
        now = time.monotonic()
        with self._lock:
            node, fraction, since = self.node, self.fraction, self.node_started
        if node is None or fraction >= 1.0:
            return f"torsal: still solving after {_duration(now - self.started)}"
        text = f"torsal: {node} {100 * fraction:.0f} % after {_duration(now - since)}"
        if fraction > 0.01:
            text += f", about {_duration((now - since) * (1 - fraction) / fraction)} left"
        return text

    def _beat(self) -> None:
        if self._done.wait(self.quiet):
            return
        while True:
            print(self.line(), file=self.stream, flush=True)
            if self._done.wait(self.every):
                return

    def start(self) -> Heartbeat:
        self._thread.start()
        return self

    def stop(self) -> None:
        self._done.set()
        self._thread.join(timeout=1.0)


class TerminalProgress:
    """rich's live progress display on a terminal, a task per node that reports progress."""

    def __init__(self, stream: TextIO) -> None:
        from rich.console import Console
        from rich.progress import (
            BarColumn,
            Progress,
            TaskProgressColumn,
            TextColumn,
            TimeElapsedColumn,
            TimeRemainingColumn,
        )

        self.display = Progress(
            TextColumn("{task.description}"), BarColumn(), TaskProgressColumn(),
            TimeElapsedColumn(), TextColumn("left"), TimeRemainingColumn(),
            console=Console(file=stream), refresh_per_second=10,
        )
        self.tasks: dict[str, int] = {}
        self._lock = threading.Lock()
        self._started = False

    def __call__(self, node_id: str, fraction: float) -> None:
        with self._lock:
            if not self._started:
                self.display.start()
                self._started = True
            if node_id not in self.tasks:
                self.tasks[node_id] = self.display.add_task(node_id, total=1.0)
            self.display.update(self.tasks[node_id], completed=min(max(float(fraction), 0.0), 1.0))

    def stop(self) -> None:
        with self._lock:
            if self._started:
                self.display.stop()


@contextmanager
def reporting(stream: TextIO | None = None) -> Iterator[NodeProgress]:
    """The progress callback for one run: rich's live line on a terminal, else the heartbeat."""
    stream = sys.stderr if stream is None else stream
    if stream.isatty():
        terminal = TerminalProgress(stream)
        try:
            yield terminal
        finally:
            terminal.stop()
        return
    quiet, every = QUIET, EVERY
    with suppress(ValueError):  # a malformed value keeps the defaults
        quiet = every = max(0.05, float(os.environ.get("TORSAL_HEARTBEAT", "")))
    heartbeat = Heartbeat(stream, quiet, every).start()
    try:
        yield heartbeat
    finally:
        heartbeat.stop()
