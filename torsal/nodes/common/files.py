"""What every node that writes a file shares: the write rules and file errors.

A file a node *writes* must lie inside the graph's folder and needs the user's consent
(:mod:`torsal.engine.writes`): :func:`write_target` and :func:`may_write` are the two questions a
writing node asks. Every file written replaces the old one atomically and keeps it as
``<name>.bak`` (:func:`replacing`). The io palette's file nodes, the display palette's Plot
and the analysis palette's charts all write through here.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from pathlib import Path

from torsal.engine.atomic import replace_keeping_backup
from torsal.engine.node import Node


class FileFailure(ValueError):
    """A file that cannot be read or written; the message is one plain sentence."""


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


def writable(path: Path) -> Path:
    """``path`` with its folder created, or a FileFailure (a folder in the way, no permission)."""
    if path.is_dir():
        raise FileFailure(f"{path} is a folder: give a file name")
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise FileFailure(f"Cannot create the folder {path.parent}: {exc.strerror or exc}") from None
    return path
