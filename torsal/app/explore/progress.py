"""Progress of a sweep or an optimisation on stderr: a bar on a terminal, lines otherwise."""

from __future__ import annotations

import sys
import time
from typing import TextIO


def _clock(seconds: float) -> str:
    seconds = max(0, round(seconds))
    hours, rest = divmod(seconds, 3600)
    minutes, secs = divmod(rest, 60)
    return f"{hours}:{minutes:02d}:{secs:02d}" if hours else f"{minutes}:{secs:02d}"


class Progress:
    """Counts finished variants and prints how many, how fast and the ETA.

    Variants taken from the cache count as done but do not enter the rate, so the ETA
    of a resumed sweep is the time its remaining solves will take; the rate is measured
    from the first solved variant on, so starting the workers does not inflate it.
    """

    def __init__(self, what: str, total: int, stream: TextIO | None = None, quiet: bool = False) -> None:
        self.what = what
        self.total = total
        self.stream = stream if stream is not None else sys.stderr
        self.quiet = quiet
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self.done = 0
        self.cached = 0
        self.solved = 0
        self.start = time.monotonic()
        self._first: float | None = None  # when the first solved variant came back
        self._last = 0.0

    def advance(self, cached: bool = False, note: str = "") -> None:
        self.done += 1
        if cached:
            self.cached += 1
        else:
            self.solved += 1
        now = time.monotonic()
        if not cached and self._first is None:
            self._first = now
        if self.done == self.total or now - self._last >= (0.2 if self.tty else 5.0):
            self._last = now
            self._print(note)

    def eta(self) -> float | None:
        if self.done >= self.total:
            return 0.0
        if self.solved < 2 or self._first is None:
            return None
        seconds = time.monotonic() - self._first
        if seconds <= 0:
            return None
        return (self.total - self.done) * seconds / (self.solved - 1)

    def line(self, note: str = "") -> str:
        eta = self.eta()
        parts = [f"{self.what}: {self.done}/{self.total}"]
        if self.cached:
            parts.append(f"{self.cached} from the cache")
        parts.append(f"elapsed {_clock(time.monotonic() - self.start)}")
        parts.append("ETA " + (_clock(eta) if eta is not None else "…"))
        if note:
            parts.append(note)
        return " · ".join(parts)

    def _print(self, note: str) -> None:
        if self.quiet:
            return
        if self.tty:
            width = 24
            filled = int(width * self.done / max(self.total, 1))
            bar = "█" * filled + "░" * (width - filled)
            end = "\n" if self.done == self.total else ""
            self.stream.write(f"\r{bar} {self.line(note)}\033[K{end}")
        else:
            self.stream.write(self.line(note) + "\n")
        self.stream.flush()
