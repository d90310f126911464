"""Solved variants kept on disk, keyed by the graph's content and the varied values.

The cache is one JSON line per solved variant, appended as it finishes, so a sweep that
is killed keeps what it solved and a re-run solves only what is missing. A torn last
line (the process killed mid-write) is skipped when read.

A cache is trusted only when this user's Torsal wrote it for this graph: every line
carries a signature (HMAC-SHA256) made with a secret key kept in the user's data folder
(mode 0600) over the graph's hash, Torsal's version and the line itself. A line without
a valid signature — a cache planted in ``--out``, written for another graph, or by
another version — is ignored, and the sweep says how many it ignored; those variants are
solved again.
"""

from __future__ import annotations

import contextlib
import hashlib
import hmac
import json
import os
import secrets
import stat
from pathlib import Path
from typing import Any

from torsal.app.explore.evaluate import Job
from torsal.app.explore.variables import values_key
from torsal.engine.write_path import OutFolder, read_own

_CACHE_LIMIT = 512 * 2**20  # a cache larger than this is not read (512 MB)
_KEY_NAME = "cache-key"


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


def secret_key() -> bytes:
    """This user's key for signing caches: 32 random bytes in the user's data folder, made
    once (exclusively, mode 0600) and read only if it is a regular file of this user's
    that no one else can read."""
    import platformdirs

    folder = Path(platformdirs.user_data_dir("torsal", appauthor=False))
    folder.mkdir(mode=0o700, parents=True, exist_ok=True)
    path = folder / _KEY_NAME
    flags = os.O_RDONLY | os.O_NOFOLLOW | os.O_CLOEXEC
    for _ in range(2):
        try:
            handle = os.open(path, flags)
        except FileNotFoundError:
            with contextlib.suppress(FileExistsError):
                new = os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC
                fresh = os.open(path, new, 0o600)
                with os.fdopen(fresh, "wb") as stream:
                    stream.write(secrets.token_bytes(32))
                    stream.flush()
                    os.fsync(stream.fileno())
            continue
        with os.fdopen(handle, "rb") as stream:
            status = os.fstat(stream.fileno())
            key = stream.read(64)
        if (stat.S_ISREG(status.st_mode) and status.st_mode & 0o077 == 0 and len(key) == 32
                and status.st_uid == os.getuid()):
            return key
        break
    raise OSError(f"the cache key {path} is not a private file of this user's: caches are not used")


def signer(digest: str) -> bytes:
    """The signing key of caches of the graph with hash ``digest`` in this Torsal version."""
    from torsal import __version__

    return hmac.new(secret_key(), f"{digest}\n{__version__}".encode(), hashlib.sha256).digest()


def _sign(key: bytes, variant: str, outcome_text: str) -> str:
    return hmac.new(key, f"{variant}\n{outcome_text}".encode(), hashlib.sha256).hexdigest()


class ResultCache:
    """A JSON-lines file of ``{"key": …, "outcome": …, "sig": …}`` in an ``--out`` folder."""

    def __init__(self, out: OutFolder, name: str, digest: str) -> None:
        self.out = out
        self.name = name
        self.entries: dict[str, dict[str, Any]] = {}
        self.ignored = 0  # lines not signed by this user's Torsal for this graph
        try:
            self._key: bytes | None = signer(digest)
        except OSError:
            self._key = None
        data = read_own(out / name, _CACHE_LIMIT)
        self._torn = bool(data) and not data.endswith(b"\n")
        for line in (data or b"").decode("utf-8", errors="replace").splitlines():
            self._read_line(line)
        self._handle = None

    def _read_line(self, line: str) -> None:
        try:
            entry = json.loads(line)
            key, outcome, signature = str(entry["key"]), entry["outcome"], str(entry["sig"])
            if not isinstance(outcome, dict):
                raise TypeError
        except (ValueError, KeyError, TypeError, RecursionError):
            return  # a line torn by a kill
        text = json.dumps(outcome, separators=(",", ":"), sort_keys=True)
        if self._key is None or not hmac.compare_digest(signature, _sign(self._key, key, text)):
            self.ignored += 1
            return
        self.entries[key] = dict(outcome)

    def get(self, key: str) -> dict[str, Any] | None:
        return self.entries.get(key)

    def put(self, key: str, outcome: dict[str, Any]) -> None:
        self.entries[key] = outcome
        if self._key is None:
            return
        if self._handle is None:
            self._handle = self.out.append(self.name)
            if self._torn:  # end the torn line, so the next entry starts on a line of its own
                self._handle.write("\n")
        text = json.dumps(outcome, separators=(",", ":"), sort_keys=True)
        line = {"key": key, "outcome": outcome, "sig": _sign(self._key, key, text)}
        self._handle.write(json.dumps(line, separators=(",", ":")) + "\n")
        self._handle.flush()

    def close(self) -> None:
        if self._handle is not None:
            self._handle.close()
            self._handle = None
