"""The one way Torsal writes a file: through a folder held open, never through a symlink.

Everything Torsal writes — a node's export, ``--out``'s ``results.json``, a sweep's
``results.csv``, its cache and images, a saved ``.graph``, the app's autosave and bake —
goes through :func:`write_file` (or :func:`open_append` for a log that grows). It

1. opens the *base* folder once as a descriptor (``O_DIRECTORY | O_NOFOLLOW``) and checks
   it is still the folder it was when the run started (its device and inode);
2. walks down to the file's folder one name at a time with ``openat(O_NOFOLLOW)``,
   creating missing folders with ``mkdirat``: a folder that is, or becomes, a symlink is
   refused, never followed;
3. refuses a target that is a symlink, a folder, a pipe or a device (``lstat`` by
   descriptor), then creates a temporary file beside it with ``O_CREAT | O_EXCL |
   O_NOFOLLOW`` and checks it with ``fstat`` (a regular file with one link);
4. writes, flushes to disk, sets the mode (``0644`` less the umask for exports: an
   executable bit is never kept), keeps the replaced file as ``<name>.bak`` when asked (a
   hard link renamed into place, never a rewrite) and renames the temporary file over the
   target with ``renameat`` — on the same descriptors, so a folder swapped for a symlink
   in between cannot redirect it.

A writer that needs a file name (rhino3dm, ezdxf, matplotlib) writes into a private
scratch folder (:func:`scratch_folder`: the user's cache folder, mode 0700) and the
bytes are copied into the temporary file: no library ever opens a path in a folder
someone else can write.

Nothing here deletes a file it did not create: a failed write removes only its own
temporary file; a write killed with ``kill -9`` can leave a hidden
``.<name>.<pid>-<token>.tmp<suffix>`` beside the target, which is left for the user.
"""

from __future__ import annotations

import contextlib
import errno
import io
import os
import secrets
import shutil
import stat
import tempfile
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path

from torsal.engine.bounded_read import _kind

BACKUP_SUFFIX = ".bak"
EXPORT_MODE = 0o644
"""The mode of every file Torsal writes for a graph (less the umask): readable, never executable."""

_TEMP_MARK = ".tmp"
_NAME_CHARS = 120  # room for the pid, token and suffix within the usual 255-byte name limit
_DIR_FLAGS = os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC
_NEW_FLAGS = os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC
_COPY_CHUNK = 1 << 20

Produce = Callable[[Path], object] | bytes | str


class UnsafeWrite(OSError):
    """A write refused because a symlink, a swapped folder or a special file is in the way.
    Its ``strerror`` is one plain sentence."""

    def __init__(self, message: str) -> None:
        super().__init__(errno.EPERM, message)

    def __str__(self) -> str:
        return str(self.strerror)


def backup_path(path: Path) -> Path:
    """Where :func:`write_file` keeps the file it replaced: ``<name>.bak``."""
    return path.with_name(path.name + BACKUP_SUFFIX)


def folder_identity(folder: Path) -> tuple[int, int] | None:
    """The (device, inode) of ``folder`` as it is now (``None`` if it is not a folder)."""
    try:
        status = os.stat(folder)
    except OSError:
        return None
    return (status.st_dev, status.st_ino) if stat.S_ISDIR(status.st_mode) else None


def resolve_out_folder(path: Path, what: str = "--out") -> Path:
    """The folder ``path`` names, created if missing, resolved once; refused if it (the
    name given) is a symlink or not a folder. Raises :class:`UnsafeWrite`."""
    path = Path(os.path.abspath(path))
    if path.is_symlink():
        raise UnsafeWrite(f"{what} {path} is a symbolic link: give the real folder "
                          f"({os.path.realpath(path)}) if that is where results belong")
    if path.exists() and not path.is_dir():
        raise UnsafeWrite(f"{what} {path} is a file, not a folder: give a folder for the results")
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise UnsafeWrite(f"{what} {path}: cannot create that folder ({exc.strerror or exc})") from None
    return Path(os.path.realpath(path))


@dataclass(frozen=True)
class OutFolder:
    """A results folder (``--out``) resolved once, with its (device, inode) then: Torsal's
    own files in it (results, caches, images) are written through :func:`write_file`
    relative to it, so neither it nor a folder in it can be swapped for a link."""

    path: Path
    identity: tuple[int, int] | None = None

    @classmethod
    def resolve(cls, path: Path, what: str = "--out") -> OutFolder:
        """:func:`resolve_out_folder` and the identity of what it found."""
        folder = resolve_out_folder(path, what)
        return cls(folder, folder_identity(folder))

    def __truediv__(self, name: str) -> Path:
        return self.path / name

    def write(self, name: str, produce: Produce) -> Path:
        """Replace ``name`` (a path relative to the folder) with ``produce``; no ``.bak``."""
        return write_file(self.path / name, produce, base=self.path, identity=self.identity, backup=False)

    def append(self, name: str) -> io.TextIOWrapper:
        return open_append(self.path / name, base=self.path, identity=self.identity)


# --------------------------------------------------------------------------- the folder walk

@contextlib.contextmanager
def held_folder(base: Path, parts: tuple[str, ...] = (), *, identity: tuple[int, int] | None = None,
                create: bool = True) -> Iterator[int]:
    """A descriptor on ``base/parts…``, reached one name at a time without following a
    symlink; missing folders are created when ``create``. ``identity`` is the base's
    (device, inode) when the run started: a base swapped since is refused."""
    try:
        handle = os.open(base, _DIR_FLAGS)
    except OSError as exc:
        raise _refusal(exc, base) from None
    try:
        if identity is not None:
            status = os.fstat(handle)
            if (status.st_dev, status.st_ino) != identity:
                raise UnsafeWrite(f"the folder {base} was replaced during the run: nothing is written there")
        where = base
        for part in parts:
            where = where / part
            try:
                inner = os.open(part, _DIR_FLAGS, dir_fd=handle)
            except FileNotFoundError:
                if not create:
                    raise
                with contextlib.suppress(FileExistsError):
                    os.mkdir(part, 0o777, dir_fd=handle)
                try:
                    inner = os.open(part, _DIR_FLAGS, dir_fd=handle)
                except OSError as exc:
                    raise _refusal(exc, where) from None
            except OSError as exc:
                raise _refusal(exc, where) from None
            os.close(handle)
            handle = inner
        yield handle
    finally:
        os.close(handle)


def make_folders(base: Path, parts: tuple[str, ...], identity: tuple[int, int] | None = None
                 ) -> tuple[int, int]:
    """Create ``base/parts…`` without following links; the (device, inode) of the last one."""
    with held_folder(base, parts, identity=identity) as handle:
        status = os.fstat(handle)
    return status.st_dev, status.st_ino


def _refusal(exc: OSError, where: Path) -> OSError:
    if exc.errno == errno.ELOOP or os.path.islink(where):
        return UnsafeWrite(f"{where} is a symbolic link: Torsal writes only into real folders, never "
                           "through a link")
    if exc.errno == errno.ENOTDIR:
        return UnsafeWrite(f"Cannot create the folder {where}: a file of that name is in the way")
    return exc


def _split(path: Path, base: Path | None) -> tuple[Path, tuple[str, ...], str]:
    """(base, folders below it, file name) for ``path``; without ``base``, the file's own
    folder, resolved now, is the base."""
    path = Path(os.path.abspath(path))
    if base is None:
        return Path(os.path.realpath(path.parent)), (), path.name
    base = Path(os.path.abspath(base))
    try:
        relative = path.relative_to(base)
    except ValueError:
        raise UnsafeWrite(f"{path} is outside {base}: nothing is written there") from None
    if not relative.parts or ".." in relative.parts:
        raise UnsafeWrite(f"{path} is not a file inside {base}")
    return base, relative.parts[:-1], relative.parts[-1]


def _check_target(folder: int, name: str, where: Path) -> os.stat_result | None:
    """The target's status if it is a regular file, ``None`` if absent, else refused."""
    try:
        status = os.stat(name, dir_fd=folder, follow_symlinks=False)
    except FileNotFoundError:
        return None
    if stat.S_ISLNK(status.st_mode):
        raise UnsafeWrite(f"{where} is a symbolic link: it is not written through (remove the link first)")
    kind = _kind(status.st_mode)
    if kind is not None:
        raise UnsafeWrite(f"{where} is {kind}, not a regular file; it is not replaced")
    return status


def _temporary(folder: int, name: str, suffix: str) -> tuple[str, int]:
    """A new file beside ``name`` created exclusively, never through a link; its name and
    an open descriptor."""
    while True:
        temp = f".{name[:_NAME_CHARS]}.{os.getpid()}-{secrets.token_hex(4)}{_TEMP_MARK}{suffix}"
        try:
            handle = os.open(temp, _NEW_FLAGS, 0o600, dir_fd=folder)
        except FileExistsError:
            continue
        status = os.fstat(handle)
        if not stat.S_ISREG(status.st_mode) or status.st_nlink != 1:  # pragma: no cover - O_EXCL
            os.close(handle)
            raise UnsafeWrite(f"the temporary file {temp} is not a new regular file")
        return temp, handle


# --------------------------------------------------------------------------- writing

def write_file(path: Path, produce: Produce, *, base: Path | None = None,
               identity: tuple[int, int] | None = None, backup: bool = True,
               mode: int | None = EXPORT_MODE, create_folders: bool = True) -> Path:
    """Replace ``path`` atomically with what ``produce`` gives; returns ``path``.

    ``produce`` is the content (bytes, or text written as UTF-8) or a callable that writes
    the whole content to the file name it is given (a scratch file with ``path``'s suffix,
    in a private folder). ``base`` is the folder the run may write in, resolved when it
    started (``identity``: its device and inode then); the folders between it and the file
    are walked without following links. Without ``base`` the file's folder, resolved now,
    is the base (the user's own choice of file). ``backup`` keeps a replaced file as
    ``<name>.bak``; ``mode`` is the new file's mode less the umask (``None``: the replaced
    file's mode, for a saved graph). A failure leaves the file and its ``.bak`` as they
    were and removes only the temporary file this call made.
    """
    path = Path(os.path.abspath(path))
    root, parts, name = _split(path, base)
    with held_folder(root, parts, identity=identity, create=create_folders) as folder:
        existing = _check_target(folder, name, path)
        temp, handle = _temporary(folder, name, path.suffix)
        try:
            with os.fdopen(handle, "wb", closefd=False) as stream:
                _produce_into(stream, produce, path.suffix)
                stream.flush()
                os.fsync(handle)
            if mode is None:
                final_mode = (existing.st_mode & 0o7777) if existing is not None else 0o666 & ~_umask()
            else:
                final_mode = mode & ~_umask()
            os.fchmod(handle, final_mode)
            os.close(handle)
            handle = -1
            if existing is not None and backup:
                _keep_backup(folder, name)
            os.rename(temp, name, src_dir_fd=folder, dst_dir_fd=folder)
        except BaseException:
            if handle >= 0:
                os.close(handle)
            with contextlib.suppress(OSError):
                os.unlink(temp, dir_fd=folder)
            raise
        with contextlib.suppress(OSError):
            os.fsync(folder)
    return path


def _produce_into(stream: io.BufferedWriter, produce: Produce, suffix: str) -> None:
    if isinstance(produce, str):
        stream.write(produce.encode("utf-8"))
    elif isinstance(produce, bytes | bytearray | memoryview):
        stream.write(produce)
    else:
        with scratch_file(suffix) as scratch:
            produce(scratch)
            try:
                source = os.open(scratch, os.O_RDONLY | os.O_NOFOLLOW | os.O_CLOEXEC)
            except FileNotFoundError:
                return  # the writer wrote nothing: an empty file
            with os.fdopen(source, "rb") as copy:
                shutil.copyfileobj(copy, stream, _COPY_CHUNK)


def _keep_backup(folder: int, name: str) -> None:
    """Make the current ``name`` the ``.bak``, atomically: a hard link renamed into place
    (or, where there are no hard links, a flushed copy)."""
    backup = name + BACKUP_SUFFIX
    with contextlib.suppress(OSError):
        now = os.stat(name, dir_fd=folder, follow_symlinks=False)
        old = os.stat(backup, dir_fd=folder, follow_symlinks=False)
        if (now.st_dev, now.st_ino) == (old.st_dev, old.st_ino):
            return  # a save killed after its backup step: the backup already is this file
    staged, handle = _temporary(folder, backup, BACKUP_SUFFIX)
    try:
        os.close(handle)
        os.unlink(staged, dir_fd=folder)
        try:
            os.link(name, staged, src_dir_fd=folder, dst_dir_fd=folder, follow_symlinks=False)
        except OSError:  # no hard links here (FAT, some network shares): a flushed copy instead
            _copy_within(folder, name, staged)
        os.rename(staged, backup, src_dir_fd=folder, dst_dir_fd=folder)
    finally:
        with contextlib.suppress(OSError):
            os.unlink(staged, dir_fd=folder)


def _copy_within(folder: int, name: str, copy: str) -> None:
    source = os.open(name, os.O_RDONLY | os.O_NOFOLLOW | os.O_CLOEXEC, dir_fd=folder)
    with os.fdopen(source, "rb") as reader:
        status = os.fstat(reader.fileno())
        target = os.open(copy, _NEW_FLAGS, status.st_mode & 0o777, dir_fd=folder)
        with os.fdopen(target, "wb") as writer:
            shutil.copyfileobj(reader, writer, _COPY_CHUNK)
            writer.flush()
            os.fsync(writer.fileno())


def open_append(path: Path, *, base: Path | None = None,
                identity: tuple[int, int] | None = None) -> io.TextIOWrapper:
    """``path`` opened for appending text (created with mode 0644 less the umask if new),
    reached without following a link; a link, pipe or device there is refused."""
    path = Path(os.path.abspath(path))
    root, parts, name = _split(path, base)
    with held_folder(root, parts, identity=identity) as folder:
        _check_target(folder, name, path)
        flags = os.O_WRONLY | os.O_APPEND | os.O_CREAT | os.O_NOFOLLOW | os.O_CLOEXEC | os.O_NONBLOCK
        try:
            handle = os.open(name, flags, EXPORT_MODE, dir_fd=folder)
        except OSError as exc:
            raise _refusal(exc, path) from None
    if not stat.S_ISREG(os.fstat(handle).st_mode):
        os.close(handle)
        raise UnsafeWrite(f"{path} is not a regular file; nothing is appended to it")
    os.set_blocking(handle, True)
    return open(handle, "a", encoding="utf-8")


def read_own(path: Path, limit: int) -> bytes | None:
    """The bytes of one of Torsal's own files (a cache, a results file) if it is a regular
    file reached without a link and at most ``limit`` bytes; ``None`` otherwise."""
    try:
        handle = os.open(path, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC)
    except OSError:
        return None
    with os.fdopen(handle, "rb") as stream:
        status = os.fstat(handle)
        if not stat.S_ISREG(status.st_mode) or status.st_size > limit:
            return None
        data = stream.read(limit + 1)
    return data if len(data) <= limit else None


# --------------------------------------------------------------------------- scratch

def scratch_folder() -> Path:
    """This user's private folder for scratch files (plots without a file, writers that
    need a name): the user cache folder (platformdirs), created with mode 0700 and checked
    to be a real folder owned by this user and closed to others. Where that cannot be made
    (a read-only home), a folder of this process's own made by :func:`tempfile.mkdtemp`
    (mode 0700, a fresh random name): never a shared, predictable path."""
    global _fallback
    import platformdirs

    folder = Path(platformdirs.user_cache_dir("torsal", appauthor=False))
    try:
        folder.mkdir(mode=0o700, parents=True, exist_ok=True)
        status = os.lstat(folder)
        if not stat.S_ISDIR(status.st_mode) or (hasattr(os, "getuid") and status.st_uid != os.getuid()):
            raise UnsafeWrite(f"the scratch folder {folder} is not a folder of this user's")
        if status.st_mode & 0o077:
            os.chmod(folder, 0o700)
        return folder
    except OSError:
        if _fallback is None:
            _fallback = Path(tempfile.mkdtemp(prefix="torsal-"))
        return _fallback


_fallback: Path | None = None


@contextlib.contextmanager
def scratch_file(suffix: str = "") -> Iterator[Path]:
    """A file name with ``suffix`` in a new private folder under :func:`scratch_folder`;
    the folder and whatever is in it are removed afterwards."""
    own = tempfile.mkdtemp(prefix="w-", dir=scratch_folder())  # mode 0700, made exclusively
    try:
        yield Path(own) / f"file{suffix}"
    finally:
        shutil.rmtree(own, ignore_errors=True)


def _umask() -> int:
    """The process's umask, read without changing it where the system says (Linux)."""
    with contextlib.suppress(OSError, ValueError), open("/proc/self/status", encoding="ascii") as status:
        for line in status:
            if line.startswith("Umask:"):
                return int(line.split()[1], 8)
    mask = os.umask(0o022)  # elsewhere: set and put back at once
    os.umask(mask)
    return mask
