"""Foreign parsers run fenced: in a child process with a memory and a time limit.

A reader backed by a C/C++ library (rhino3dm) can crash on a hostile or damaged file, or
allocate without end. :class:`FencedReader` runs such a reader as a child process —
``python -P -m MODULE MEMORY SECONDS``, started from the folder that holds this ``torsal``
(``-P``: the current folder, which may hold a user's own ``torsal`` or ``numpy``, is never
searched) — and talks to it over its stdin and stdout in length-prefixed msgpack frames
(:mod:`msgspec`; never pickle). Whatever happens there, the calling process lives:

- the child dies (SIGSEGV, SIGABRT, killed by its memory limit): :class:`ReaderCrashed`;
- it takes longer than ``seconds`` for one file: it is killed, :class:`ReaderCrashed`;
- its reply is not a well-formed frame: :class:`ReaderCrashed`.

One child serves many requests (a fuzz run, a graph with several imports) and is started
again after a crash. A child belongs to the process that started it (a forked worker
starts its own) and is stopped when that process exits.
"""

from __future__ import annotations

import atexit
import os
import queue
import signal
import struct
import subprocess
import sys
import threading
import time
from pathlib import Path
from typing import Any

import msgspec

#: The address space a reader child may use (bytes): python, numpy and rhino3dm take ~130 MB.
MEMORY = 2 << 30

#: The longest one request may take (seconds of wall time); a request may ask for less.
SECONDS = 600.0

#: The longest a child may take to start (import its modules) before its first request.
STARTUP = 60.0

#: The largest reply a child may send (bytes), so a confused child cannot make us allocate.
LARGEST_REPLY = 1 << 30

#: The folder that holds this ``torsal`` package, first on the child's path.
ROOT = str(Path(__file__).resolve().parents[4])


class ReaderCrashed(Exception):
    """The child died, hung or sent nonsense; the message says which, in a few words."""


class FencedReader:
    """A child process running ``module``'s ``main``, limited to ``memory`` bytes and
    ``seconds`` per request. Thread-safe: requests are served one at a time."""

    def __init__(self, module: str, memory: int = MEMORY, seconds: float = SECONDS) -> None:
        self.module, self.memory, self.seconds = module, memory, seconds
        self._child: subprocess.Popen[bytes] | None = None
        self._owner = 0
        self._lock = threading.Lock()
        self._frames: queue.Queue[bytes | int | None] = queue.Queue()
        self.started = 0  #: how many children this reader has started (a crash starts another)

    def _start(self) -> subprocess.Popen[bytes]:
        child = self._child
        if child is not None and self._owner == os.getpid() and child.poll() is None:
            return child
        path = os.pathsep.join(filter(None, [ROOT, os.environ.get("PYTHONPATH")]))
        env = {**os.environ, "PYTHONPATH": path, "OPENBLAS_NUM_THREADS": "1", "OMP_NUM_THREADS": "1"}
        cpu = max(60, int(self.seconds * 4))  # a backstop over the child's life; the clock is ours
        self._child = subprocess.Popen(
            [sys.executable, "-P", "-m", self.module, str(self.memory), str(cpu)],
            stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, env=env, cwd=ROOT,
        )
        self._owner = os.getpid()
        self.started += 1
        self._frames = queue.Queue()
        threading.Thread(target=_pump, args=(self._child.stdout, self._frames), daemon=True).start()
        try:  # the child says it is ready once its imports are done: that time is not a request's
            msgspec.msgpack.decode(self._frame(self._child, time.monotonic() + STARTUP, STARTUP))
        except (ReaderCrashed, msgspec.DecodeError):
            self._stop(self._child)
            raise ReaderCrashed("the reader could not start") from None
        return self._child

    def request(self, message: dict[str, Any], seconds: float | None = None) -> dict[str, Any]:
        """Send ``message``, return the child's reply; :class:`ReaderCrashed` if it has none
        within ``seconds`` (default: the reader's own limit, the smaller of the two)."""
        limit = self.seconds if seconds is None else min(seconds, self.seconds)
        with self._lock:
            child = self._start()  # (a ReaderCrashed if it cannot)
            try:
                body = msgspec.msgpack.encode(message)
                assert child.stdin is not None
                child.stdin.write(struct.pack("<I", len(body)) + body)
                child.stdin.flush()
                reply = msgspec.msgpack.decode(self._frame(child, time.monotonic() + limit, limit))
            except (BrokenPipeError, ConnectionError):
                why = self._why(child)
                self._stop(child)
                raise ReaderCrashed(why) from None
            except msgspec.DecodeError:
                self._stop(child)
                raise ReaderCrashed("the reader sent a malformed reply") from None
            except ReaderCrashed:
                self._stop(child)
                raise
            if not isinstance(reply, dict):
                self._stop(child)
                raise ReaderCrashed("the reader sent a malformed reply")
            return reply

    def _frame(self, child: subprocess.Popen[bytes], deadline: float, limit: float) -> bytes:
        """The child's next message, read by its pump thread (portable: no select on pipes)."""
        try:
            item = self._frames.get(timeout=max(0.0, deadline - time.monotonic()))
        except queue.Empty:
            self._stop(child)
            raise ReaderCrashed(f"the reader took longer than {limit:g} s") from None
        if item is None:
            raise ReaderCrashed(self._why(child))
        if isinstance(item, int):
            raise ReaderCrashed(f"the reader sent a reply of {item:,} bytes")
        return item

    def _why(self, child: subprocess.Popen[bytes]) -> str:
        try:
            code = child.wait(timeout=5.0)
        except subprocess.TimeoutExpired:
            self._stop(child)
            return "the reader stopped answering"
        if code < 0:
            try:
                name = signal.Signals(-code).name
            except ValueError:
                name = f"signal {-code}"
            return f"the reader crashed ({name})"
        return f"the reader crashed (exit {code})"

    def _stop(self, child: subprocess.Popen[bytes]) -> None:
        if child.poll() is None:
            child.kill()
        child.wait()
        for stream in (child.stdin, child.stdout):
            if stream is not None:
                stream.close()
        if self._child is child:
            self._child = None

    def close(self) -> None:
        """Stop the child (it also ends by itself when our end of its stdin closes)."""
        with self._lock:
            child = self._child
            if child is not None and self._owner == os.getpid():
                self._stop(child)
            self._child = None


def _pump(stream: Any, frames: queue.Queue[bytes | int | None]) -> None:
    """Read the child's frames into ``frames``: each body, the size of one too large (then
    stop), and None at the end of its output."""
    try:
        while len(head := stream.read(4)) == 4:
            (size,) = struct.unpack("<I", head)
            if size > LARGEST_REPLY:
                frames.put(size)
                return
            body = stream.read(size)
            if len(body) < size:
                break
            frames.put(body)
    except (OSError, ValueError):  # the pipe closed under us: the child was stopped
        pass
    frames.put(None)


_READERS: dict[str, FencedReader] = {}
_READERS_LOCK = threading.Lock()


def reader(module: str) -> FencedReader:
    """The shared fenced reader of this process for ``module``."""
    with _READERS_LOCK:
        found = _READERS.get(module)
        if found is None:
            found = _READERS[module] = FencedReader(module)
        return found


@atexit.register
def _close_all() -> None:
    for found in list(_READERS.values()):
        found.close()
