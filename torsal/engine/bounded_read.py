"""Reading a file whose name came from a user or a graph, without stalls or huge allocations.

Only regular files are read. A folder, a device (``/dev/zero`` never ends), a named pipe
(opening one waits for a writer, forever) or a socket is refused at once, before it is
opened. The size limit is enforced on the bytes actually read, never on the size the
file system reports (0 for devices, and it can change while reading).
"""

from __future__ import annotations

import os
import stat
from pathlib import Path

_CHUNK = 1 << 20


class UnreadableFileError(ValueError):
    """A file that is not read: not a regular file, too large, or not readable. The
    message is one sentence, to follow the file's name ("plan.graph: it is a folder, ...")."""


def _kind(mode: int) -> str | None:
    """What a non-regular file is, in words; ``None`` for a regular file."""
    if stat.S_ISREG(mode):
        return None
    if stat.S_ISDIR(mode):
        return "a folder"
    if stat.S_ISFIFO(mode):
        return "a named pipe (FIFO)"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "a special file"


def kind_of(path: str | os.PathLike[str]) -> str | None:
    """``"a folder"``, ``"a device"``, ``"a named pipe (FIFO)"``, ``"a socket"`` or ``"a
    special file"`` for what is not a regular file at ``path``; ``None`` for a regular file
    or nothing at all. Symbolic links are followed."""
    try:
        return _kind(os.stat(path).st_mode)
    except OSError:
        return None


def _refuse(kind: str, what: str) -> UnreadableFileError:
    return UnreadableFileError(f"it is {kind}, not {what}: only regular files are read")


def read_bounded(path: str | os.PathLike[str], limit: int, what: str = "a file") -> bytes:
    """The bytes of the regular file ``path``, at most ``limit`` of them.

    ``what`` names the expected kind of file in messages ("a graph file"). Raises
    :class:`UnreadableFileError` for a folder, device, named pipe or socket (checked with
    ``stat`` before opening, and again on the open file in case it was swapped in
    between), for a file longer than ``limit`` bytes (at most ``limit + 1`` bytes are
    read to find out), and for any operating-system error.
    """
    path = Path(path)
    try:
        kind = _kind(os.stat(path).st_mode)
        if kind is not None:
            raise _refuse(kind, what)
        # O_NONBLOCK: if a named pipe is swapped in after the check, opening it does not wait
        flags = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_BINARY", 0)
        handle = os.open(path, flags | getattr(os, "O_CLOEXEC", 0))
        try:
            status = os.fstat(handle)
            kind = _kind(status.st_mode)
            if kind is not None:
                raise _refuse(kind, what)
            # the reported size is only a hint for the first read (one read for most files)
            chunks, total, want = [], 0, max(_CHUNK, status.st_size + 1)
            while total <= limit:
                chunk = os.read(handle, min(want, limit + 1 - total))
                want = _CHUNK
                if not chunk:
                    break
                chunks.append(chunk)
                total += len(chunk)
        finally:
            os.close(handle)
    except OSError as exc:
        raise UnreadableFileError(f"cannot read {path}: {exc.strerror or exc}") from None
    if total > limit:
        raise UnreadableFileError(
            f"it is larger than {_size(limit)}; {what} is at most {_size(limit)}"
        )
    return b"".join(chunks)


def _size(count: int) -> str:
    if count >= 2**20 and count % 2**20 == 0:
        return f"{count // 2**20} MB"
    if count >= 2**10 and count % 2**10 == 0:
        return f"{count // 2**10} kB"
    return f"{count} bytes"
