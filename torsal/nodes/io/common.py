"""What every file node shares: length units, where a relative path points, file errors.

Units are named as in the ``.graph`` file's ``"units"`` field: ``mm``, ``cm``, ``m``,
``in`` and ``ft`` (a few spelled-out synonyms are accepted).

Paths: a file a node *reads* may be anywhere; a relative one starts from the graph's
folder (so a graph and the files beside it move together), or from the working
directory for a graph with no file yet; ``~`` is expanded. A file a node *writes* must
lie inside the graph's folder and needs the user's consent (:mod:`torsal.engine.writes`);
:func:`write_target` and :func:`may_write` are the two questions a writing node asks.
Every file written replaces the old one atomically and keeps it as ``<name>.bak``
(:func:`replacing`).
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

from torsal.engine.bounded_read import kind_of
from torsal.engine.node import Node, NodeError
from torsal.nodes.common.files import FileFailure, may_write, replacing, writable, write_target
from torsal.nodes.common.units import METRES, unit_name, unit_scale

__all__ = ["METRES", "FileFailure", "file_errors", "may_write", "numbered", "read_path", "readable",
           "replacing", "resolve", "unit_name", "unit_scale", "writable", "write_target"]


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
    return resolve(None if path is None else str(path), what, node.files.read_folder)


def readable(path: Path, kind: str) -> Path:
    """``path`` if it is a non-empty file, else a FileFailure saying what is wrong."""
    if not path.exists():
        raise FileFailure(f"There is no file {path}")
    found = kind_of(path)  # by type: a pipe would hang a reader, a device never ends
    if found is not None:
        raise FileFailure(f"{path} is {found}, not a {kind} file: only regular files are read")
    if path.stat().st_size == 0:
        raise FileFailure(f"{path} is empty (0 bytes), so it holds no {kind} data")
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
    """Turn a :class:`FileFailure` (or an OS error) into a :class:`~torsal.engine.node.NodeError`:
    a file that cannot be read or written puts the node in error with the reason."""
    try:
        yield
    except FileFailure as exc:
        raise NodeError(str(exc).rstrip(".")) from None
    except OSError as exc:
        where = f" {exc.filename}" if exc.filename else ""
        raise NodeError(f"Cannot use the file{where}: {exc.strerror or exc}") from None
