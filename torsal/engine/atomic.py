"""Replacing a file without ever leaving it half-written, keeping the old one as ``.bak``.

A save that is killed at any moment leaves the file and its ``.bak`` each a complete
version: the new content is written to a temporary file in the same folder, flushed to
disk, and only then swapped in with :func:`os.replace` (atomic on one file system). The
previous file becomes the ``.bak`` the same way — through a hard link, or a flushed copy
where the file system has no hard links — so the backup is never rewritten in place.

Temporary files are named ``.<name>.<pid>-<token>.tmp<suffix>``: the target's suffix is
kept (exporters that choose a format by suffix still work), and the process id lets the
next save remove what a killed save left behind.

Example, from an io node::

    def write(temporary: Path) -> None:
        temporary.write_text(csv_text, encoding="utf-8")

    replace_keeping_backup(target, write)   # target.csv, and target.csv.bak if it existed
"""

from __future__ import annotations

import contextlib
import errno
import glob
import os
import secrets
import shutil
import time
from collections.abc import Callable
from pathlib import Path

from torsal.engine.bounded_read import kind_of

BACKUP_SUFFIX = ".bak"
_TEMP_MARK = ".tmp"
_STALE_SECONDS = 24 * 3600  # a temporary file this old is left over, whatever its process id says
_NAME_CHARS = 120  # room for the pid, token and suffix within the usual 255-byte name limit


def backup_path(path: Path) -> Path:
    """Where :func:`replace_keeping_backup` keeps the replaced file: ``<name>.bak``."""
    return path.with_name(path.name + BACKUP_SUFFIX)


def replace_keeping_backup(path: Path, write: Callable[[Path], None]) -> Path:
    """Replace ``path`` with what ``write`` puts in a temporary file; returns ``path``.

    ``write(temporary)`` is called with a path in the same folder whose suffix is
    ``path``'s; it must write the whole new content there. Then the temporary file is
    flushed to disk, given the replaced file's permissions, the current ``path`` (if any)
    becomes ``<name>.bak`` atomically, and the temporary file takes ``path``'s place
    atomically. If ``write`` (or anything after it) fails, the temporary file is removed
    and ``path`` and its ``.bak`` are as they were. Left-overs of earlier saves that were
    killed are removed first.
    """
    path = Path(path)
    kind = kind_of(path)
    if kind is not None:
        raise OSError(errno.EINVAL, f"{path} is {kind}, not a regular file; it is not replaced")
    backup = backup_path(path)
    remove_stale_temporaries(path)
    remove_stale_temporaries(backup)
    temporary = _create_temporary(path)
    try:
        write(temporary)
        _flush(temporary)
        with contextlib.suppress(FileNotFoundError):
            os.chmod(temporary, path.stat().st_mode & 0o7777)
        if path.exists():
            _replace_backup(path, backup)
        os.replace(temporary, path)
    except BaseException:
        temporary.unlink(missing_ok=True)
        raise
    _flush_folder(path.parent)
    return path


def temporary_pattern(path: Path) -> str:
    """The glob pattern of the temporary files made for ``path`` (in its folder)."""
    return f".{glob.escape(_stem_for(path))}.*{_TEMP_MARK}{glob.escape(path.suffix)}"


def remove_stale_temporaries(path: Path) -> list[Path]:
    """Remove temporary files for ``path`` whose process is gone (or that are a day old).

    Those of live processes are left alone: another save may be under way. Returns the
    files removed.
    """
    removed = []
    folder = path.parent if str(path.parent) else Path(".")
    with contextlib.suppress(OSError):
        for candidate in folder.glob(temporary_pattern(path)):
            if _is_stale(candidate, path):
                with contextlib.suppress(OSError):
                    candidate.unlink()
                    removed.append(candidate)
    return removed


# --------------------------------------------------------------------------- internals

def _stem_for(path: Path) -> str:
    return path.name[:_NAME_CHARS]


def _create_temporary(path: Path) -> Path:
    """A new empty file next to ``path``, created exclusively (mode 0666 less the umask)."""
    folder = path.parent if str(path.parent) else Path(".")
    while True:
        name = f".{_stem_for(path)}.{os.getpid()}-{secrets.token_hex(4)}{_TEMP_MARK}{path.suffix}"
        candidate = folder / name
        try:
            handle = os.open(candidate, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
        except FileExistsError:
            continue
        os.close(handle)
        return candidate


def _replace_backup(path: Path, backup: Path) -> None:
    """Make the current ``path`` the ``.bak`` in one atomic step."""
    with contextlib.suppress(OSError):
        if os.path.samefile(path, backup):
            return  # a save killed after its backup step: the backup already is this file
    staged = _create_temporary(backup)
    try:
        staged.unlink()
        try:
            os.link(path, staged)  # the old file itself becomes the backup: nothing is copied
        except OSError:  # no hard links here (FAT, some network shares): a flushed copy instead
            shutil.copy2(path, staged)
            _flush(staged)
        os.replace(staged, backup)
    finally:
        # gone after a rename, unless ``backup`` was already a link to the same file (then
        # rename does nothing and leaves ``staged`` in place)
        staged.unlink(missing_ok=True)


def _flush(path: Path) -> None:
    handle = os.open(path, os.O_RDONLY)
    try:
        os.fsync(handle)
    finally:
        os.close(handle)


def _flush_folder(folder: Path) -> None:
    """Make the renames durable too (not possible on every system: skipped where not)."""
    with contextlib.suppress(OSError, AttributeError):
        handle = os.open(folder if str(folder) else ".", os.O_RDONLY | os.O_DIRECTORY)
        try:
            os.fsync(handle)
        finally:
            os.close(handle)


def _is_stale(candidate: Path, path: Path) -> bool:
    middle = candidate.name[len(_stem_for(path)) + 2:-len(_TEMP_MARK + path.suffix)]
    pid_text = middle.split("-", 1)[0]
    try:
        if time.time() - candidate.stat().st_mtime > _STALE_SECONDS:
            return True
    except OSError:
        return False
    if not pid_text.isdigit():
        return False  # not one of ours after all
    pid = int(pid_text)
    if pid == os.getpid() or os.name != "posix":  # os.kill(pid, 0) is only a probe on POSIX
        return False  # this process's own save, perhaps in another thread
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return True
    except OSError:  # alive, owned by someone else
        return False
    return False
