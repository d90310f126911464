"""What every file node shares: length units, where a relative path points, file errors.

Units are named as in the ``.graph`` file's ``"units"`` field: ``mm``, ``cm``, ``m``,
``in`` and ``ft`` (a few spelled-out synonyms are accepted).

Paths: a file a node *reads* may be anywhere; a relative one starts from the graph's
folder (so a graph and the files beside it move together), or from the working
directory for a graph with no file yet; ``~`` is expanded. A file a node *writes* must
lie inside the graph's folder and needs the user's consent (:mod:`engine.writes`);
:func:`write_target` and :func:`may_write` are the two questions a writing node asks.
Every file written replaces the old one atomically and keeps it as ``<name>.bak``
(:func:`replacing`).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path

from engine.atomic import replace_keeping_backup
from engine.node import Node, NodeError

#: Length of one unit in metres.
METRES: dict[str, float] = {"mm": 0.001, "cm": 0.01, "m": 1.0, "in": 0.0254, "ft": 0.3048}

_SYNONYMS = {
    "millimeter": "mm", "millimeters": "mm", "millimetre": "mm", "millimetres": "mm",
    "centimeter": "cm", "centimeters": "cm", "centimetre": "cm", "centimetres": "cm",
    "meter": "m", "meters": "m", "metre": "m", "metres": "m",
    "inch": "in", "inches": "in", '"': "in",
    "foot": "ft", "feet": "ft", "'": "ft",
}


class FileFailure(ValueError):
    """A file that cannot be read or written; the message is one plain sentence."""


def unit_name(text: str | None, what: str = "Units") -> str:
    """The canonical name (``mm``, ``cm``, ``m``, ``in``, ``ft``) of a unit, or FileFailure."""
    key = (text or "").strip().lower()
    key = _SYNONYMS.get(key, key)
    if key not in METRES:
        raise FileFailure(
            f"{what} {text!r} is not a length unit Torsal knows: use mm, cm, m, in or ft"
        )
    return key


def unit_scale(source: str, target: str) -> float:
    """The factor that turns lengths in ``source`` units into ``target`` units."""
    return METRES[unit_name(source)] / METRES[unit_name(target)]


def resolve(path: str | os.PathLike[str] | None, what: str = "Path", folder: Path | None = None) -> Path:
    """An absolute path to read: ``~`` expanded, a relative path taken from ``folder`` (the
    graph's folder) or, without one, from the working directory."""
    text = os.fspath(path).strip() if path is not None else ""
    if not text:
        raise FileFailure(f"{what} is empty: give a file name")
    expanded = os.path.expanduser(text)
    if folder is not None and not os.path.isabs(expanded):
        expanded = os.path.join(folder, expanded)
    return Path(os.path.abspath(expanded))


def read_path(node: Node, path: object, what: str = "Path") -> Path:
    """The file ``node`` is asked to read, a relative path taken from the graph's folder."""
    return resolve(None if path is None else str(path), what, node.files.folder)


def write_target(node: Node, path: object, what: str = "Path") -> Path:
    """The file ``node`` is asked to write, inside the graph's folder, or a NodeError that
    says why not (outside the folder, ``~``, an absolute path, a ``.graph`` file)."""
    return node.files.target(path, what)


def may_write(node: Node, paths: Sequence[Path]) -> bool:
    """Whether ``node`` may write ``paths`` now; if the user has not allowed this graph to
    write files, the node warns (naming the files) and the request waits for consent."""
    if node.files.permit(tuple(paths)):
        return True
    folder = node.files.folder
    names = ", ".join(_shown(p, folder) for p in paths)
    node.warn(
        f"Nothing written to {names}: this graph writes files only with your consent "
        "(torsal run --allow-writes; in the app, answer Allow when it asks)"
    )
    return False


def _shown(path: Path, folder: Path | None) -> str:
    try:
        return str(path.relative_to(os.path.realpath(folder))) if folder is not None else str(path)
    except ValueError:
        return str(path)


def replacing(path: Path, write: Callable[[Path], object]) -> Path:
    """Write ``path`` through ``write(temporary)`` and swap it in atomically, keeping the
    file it replaces as ``<name>.bak``; an OS error becomes a FileFailure naming ``path``."""
    try:
        return replace_keeping_backup(path, write)
    except OSError as exc:
        raise FileFailure(f"Cannot write {path}: {exc.strerror or exc}") from None


def readable(path: Path, kind: str) -> Path:
    """``path`` if it is a non-empty file, else a FileFailure saying what is wrong."""
    if not path.exists():
        raise FileFailure(f"There is no file {path}")
    if path.is_dir():
        raise FileFailure(f"{path} is a folder, not a {kind} file")
    if path.stat().st_size == 0:
        raise FileFailure(f"{path} is empty (0 bytes), so it holds no {kind} data")
    return path


def writable(path: Path) -> Path:
    """``path`` with its folder created, or a FileFailure (a folder in the way, no permission)."""
    if path.is_dir():
        raise FileFailure(f"{path} is a folder: give a file name")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise FileFailure(f"Cannot create the folder {path.parent}: {exc.strerror or exc}") from None
    return path


def numbered(path: Path, count: int) -> list[Path]:
    """``[path]`` for one file, else ``stem-1.ext`` … ``stem-N.ext`` beside it, the numbers
    zero-padded to the same width (``stem-01`` … ``stem-12``) so they sort."""
    if count <= 1:
        return [path]
    width = len(str(count))
    return [path.with_name(f"{path.stem}-{i:0{width}d}{path.suffix}") for i in range(1, count + 1)]


@contextmanager
def file_errors() -> Iterator[None]:
    """Turn a :class:`FileFailure` (or an OS error) into a :class:`~engine.node.NodeError`:
    a file that cannot be read or written puts the node in error with the reason."""
    try:
        yield
    except FileFailure as exc:
        raise NodeError(str(exc).rstrip(".")) from None
    except OSError as exc:
        where = f" {exc.filename}" if exc.filename else ""
        raise NodeError(f"Cannot use the file{where}: {exc.strerror or exc}") from None
