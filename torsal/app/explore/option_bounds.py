"""Bounds on the options of ``torsal sweep`` and ``torsal optimise``, checked before any work.

- ``--seed``: a whole number from 0 to 2**32 - 1 (what numpy's and CMA-ES's generators take).
- Variants: at most :data:`MAX_VARIANTS` (a grid's product of steps, ``--samples``,
  ``--budget``): past it the sweep would take days and its table alone gigabytes.
- ``--workers``: at most the machine's cores and never more than there are variants; a
  larger number is lowered with a note (each worker is a process of ~150 MB).
- ``--scheduler``: a known scheme (``tcp://``, ``tls://``, ``ws://``, ``wss://``,
  ``ucx://``); for ``tcp://`` the address must accept a connection and greet as a dask
  scheduler does (it speaks first: an 8-byte length of a small handshake) within
  :data:`CONNECT_SECONDS`, so a silent port or an HTTP server is a message, not a hang.

Each breach is a :class:`~torsal.app.headless.UsageError` (exit 2, one line).
"""

from __future__ import annotations

import os
import socket
import struct
from typing import TYPE_CHECKING
from urllib.parse import urlsplit

from torsal.app.headless import UsageError

if TYPE_CHECKING:
    from torsal.app.explore.executors import Executor

MAX_SEED = 2**32 - 1
MAX_VARIANTS = 100_000
CONNECT_SECONDS = 5.0
SCHEMES = ("tcp", "tls", "ws", "wss", "ucx")
_HANDSHAKE_MOST = 1 << 20  # a dask handshake is a few hundred bytes


def check_seed(seed: int, flag: str = "--seed") -> int:
    if not 0 <= seed <= MAX_SEED:
        raise UsageError(f"{flag} {seed}: give a whole number from 0 to {MAX_SEED:,}")
    return seed


def check_count(count: int, what: str) -> int:
    """``count`` variants or evaluations, refused past :data:`MAX_VARIANTS`."""
    if count > MAX_VARIANTS:
        raise UsageError(f"{what} asks for {count:,} variants; at most {MAX_VARIANTS:,} are solved in "
                         "one run (split the range, or use --sampler lhs/sobol with fewer --samples)")
    return count


def grid_size(steps: list[int | None]) -> int:
    """How many variants a grid of these steps has (stops counting past the cap)."""
    total = 1
    for step in steps:
        total *= max(1, step or 1)
        if total > MAX_VARIANTS:
            break
    return total


def worker_count(workers: int | None, variants: int) -> tuple[int | None, str | None]:
    """``--workers`` lowered to the cores and the variants, with the note saying so."""
    if workers is None:
        return None, None
    if workers < 1:
        raise UsageError(f"--workers {workers}: give 1 or more worker processes")
    cores = max(1, os.cpu_count() or 1)
    most = max(1, min(cores, variants))
    if workers <= most:
        return workers, None
    reason = f"this machine has {cores} core{'s' if cores > 1 else ''}" if most == cores else \
        f"there {'is' if variants == 1 else 'are'} only {variants} variant{'s' if variants != 1 else ''}"
    return most, f"--workers {workers}: {reason}; starting {most}"


def check_scheduler(address: str) -> str:
    """``address`` if it names a reachable dask scheduler, else a UsageError saying why."""
    parts = urlsplit(address if "://" in address else f"tcp://{address}")
    if parts.scheme not in SCHEMES:
        raise UsageError(f"--scheduler {address}: unknown scheme {parts.scheme!r}; give "
                         f"tcp://HOST:PORT (or {', '.join(s + '://' for s in SCHEMES[1:])})")
    try:
        host, port = parts.hostname, parts.port
    except ValueError:
        host, port = None, None
    if parts.scheme in ("tcp", "tls") and (not host or port is None):
        raise UsageError(f"--scheduler {address}: give the scheduler as tcp://HOST:PORT, e.g. tcp://10.0.0.5:8786")
    if parts.scheme == "tcp":
        _greeting(address, host, port)
    return address


def _greeting(address: str, host: str, port: int) -> None:
    """Connect and read the first 8 bytes a dask scheduler sends: a small frame length."""
    try:
        with socket.create_connection((host, port), timeout=CONNECT_SECONDS) as connection:
            connection.settimeout(CONNECT_SECONDS)
            head = b""
            while len(head) < 8:
                chunk = connection.recv(8 - len(head))
                if not chunk:
                    break
                head += chunk
    except TimeoutError:
        raise UsageError(f"--scheduler {address}: nothing answered within {CONNECT_SECONDS:g} s; "
                         "is a dask scheduler running there?") from None
    except OSError as exc:
        raise UsageError(f"--scheduler {address}: cannot connect ({exc.strerror or exc})") from None
    size = struct.unpack("<Q", head)[0] if len(head) == 8 else 0
    if not 0 < size <= _HANDSHAKE_MOST:
        raise UsageError(f"--scheduler {address}: what answered there is not a dask scheduler")


def bounded_executor(workers: int | None, scheduler: str | None, variants: int) -> Executor:
    """The executor for ``--workers``/``--scheduler`` once both are checked (a note on
    stderr when ``--workers`` is lowered)."""
    import sys

    from torsal.app.explore.executors import make_executor

    if scheduler is not None:
        check_scheduler(scheduler)
    workers, note = worker_count(workers, variants)
    if note:
        print(f"torsal: note: {note}", file=sys.stderr)
    return make_executor(workers, scheduler)
